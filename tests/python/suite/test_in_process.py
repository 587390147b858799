"""What an in-process user sees: the wall time of a Study run in Python (it read "wall time 0.00 s": the process's
clock started at the run's end), and docs/python.md's first blocks pasted as they are (they read "0 records" when
Python was not started in the repository root; now they stop naming the folder)."""
import os
import re
import subprocess
import sys

import pytest

import pounding
from conftest import need

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
QUICK = os.path.join(ROOT, "studies", "quick.toml")


def test_in_process_wall_time_is_the_runs(tmp_path):
    h5py = need("h5py")
    out = tmp_path / "quick.h5"
    res = pounding.Study(QUICK).run(out=str(out), progress=False)
    assert res.exit_code == 0
    with h5py.File(out) as f:
        t = f["timing"]
        phases = [p.decode() if isinstance(p, bytes) else p for p in t["phase"][()]]
        units = t["rank0_s"][()][phases.index("units")]
        wall = t.attrs["wall_s"]
        assert units > 0 and wall >= units, (wall, units)  # it was 0.0000x: the clock started at the end
    report = pounding._core.report(str(out), False)
    times = re.findall(r"wall time ([0-9.]+) s", report)
    assert times and float(times[0]) > 0, times


def _blocks(n):
    text = open(os.path.join(ROOT, "docs", "python.md")).read()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)[:n]


def test_docs_records_block_reads_the_records(tmp_path):
    """docs/python.md's blocks 1 and 2 as pasted (from the repository root): every .AT2 file of the records folder
    read, eight kept; started elsewhere, the first block stops naming the folder instead of reading 0 records."""
    real = os.environ.get("POUNDING_REAL_RECORDS_DIR", os.path.join(ROOT, "..", "shared", "records", "real"))
    count = len([f for f in os.listdir(real) if f.endswith(".AT2")]) if os.path.isdir(real) else 0
    if count == 0:
        pytest.skip(f"no real records in {real}")
    script = tmp_path / "blocks.py"
    script.write_text("\n".join(_blocks(2)))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    env.pop("POUNDING_REAL_RECORDS_DIR", None)
    # as pasted in the repository root: the default ../shared/records/real where it is there, else the variable
    pasted = env if os.path.isdir(os.path.join(ROOT, "..", "shared", "records", "real")) else dict(
        env, POUNDING_REAL_RECORDS_DIR=real)
    run = subprocess.run([sys.executable, str(script)], cwd=ROOT, capture_output=True, text=True, env=pasted)
    assert run.returncode == 0, run.stderr
    assert f"{count} records read" in run.stdout, run.stdout
    assert len(run.stdout.splitlines()) == 1 + 8, run.stdout  # the eight records of step 2
    script.write_text(_blocks(1)[0])
    away = subprocess.run([sys.executable, str(script)], cwd=str(tmp_path), capture_output=True, text=True, env=env)
    assert away.returncode != 0 and "0 records" not in away.stdout, away.stdout
    assert "no .AT2 files in" in away.stderr and "repository root" in away.stderr, away.stderr
