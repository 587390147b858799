"""Study(...).run() in-process and Results (issue 28, item 5): the same results and tables as `pounding run`."""
import os
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, need

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = os.path.join(HERE, "..", "..", "..", "studies", "quick.toml")


def test_study_from_python_gives_the_clis_tables(tmp_path):
    need("pandas")
    h5py = need("h5py")
    py_out, cli_out = tmp_path / "py.h5", tmp_path / "cli.h5"
    res = pounding.Study(QUICK).run(out=str(py_out), progress=False)
    assert res.exit_code == 0 and py_out.exists()
    run = subprocess.run([cli(), "run", QUICK, "--out", str(cli_out), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    csv = subprocess.run([cli(), "report", str(cli_out), "--csv"], capture_output=True, text=True).stdout
    assert pounding._core.report(str(py_out), True) == csv  # every CSV table, to the digit
    md = subprocess.run([cli(), "report", str(cli_out)], capture_output=True, text=True).stdout
    cli_tables = pounding.study.markdown_tables(md)
    assert list(res.sections) == list(cli_tables)
    for heading, table in cli_tables.items():
        assert res.sections[heading].equals(table), heading
    with h5py.File(py_out) as a, h5py.File(cli_out) as b:
        for key in a["uncoupled"]:
            assert np.array_equal(a["uncoupled"][key][()], b["uncoupled"][key][()], equal_nan=True), key
    t3 = res.table3
    assert list(t3.columns) == ["gap_ratio", "hits", "n", "probability"] and t3["n"].dtype == np.int64
    assert (t3["probability"] == (t3["hits"] / t3["n"]).round(6)).all()
    assert res.table2.shape == (25, len(t3))
    assert res.code_rules["rule"].iloc[0] == "Standard 2800"
    m = res.period_pair(0.3)
    cp = res.csv_tables["period_pair"]
    assert m.shape == (11, 11) and m.loc[1.0, 1.05] == cp[(cp["gap_ratio"] == 0.3) & (cp["T1"] == 1.0)
                                                          & (cp["T2"] == 1.05)]["probability"].item()
    assert "uncoupled" in res.groups() and res.arrays("uncoupled")["peak_closing"].size > 0


def test_bad_study_text_is_a_value_error(tmp_path):
    text = open(QUICK).read().replace("[gaps]", "[gaps]\nbogus_key = 1", 1)
    with pytest.raises(ValueError, match="bogus_key"):
        pounding.Study(text, base_dir=str(tmp_path)).run(out=str(tmp_path / "x.h5"), progress=False)
    assert not (tmp_path / "x.h5").exists() and os.listdir(tmp_path) == []
    with pytest.raises(ValueError, match="not found"):
        pounding.Results(str(tmp_path / "missing.h5"))


def test_fragility_study_numbers_are_the_bindings(tmp_path):
    """A fragility study's /fragility and /hazard (written by the study's own analysis) against fragility.fit and
    hazard.rate on the file's observed stripes: the same C++ code, so the same bits."""
    need("h5py")
    studies = os.path.join(HERE, "..", "..", "..", "studies")
    text = open(os.path.join(studies, "fragility-pair.toml")).read()
    text = text.replace("samples_per_pair = 200", "samples_per_pair = 20").replace("bootstrap = 2000", "bootstrap = 50")
    (tmp_path / "frag.toml").write_text(text)
    (tmp_path / "example-hazard.csv").write_text(open(os.path.join(studies, "example-hazard.csv")).read())
    res = pounding.Study(str(tmp_path / "frag.toml")).run(out=str(tmp_path / "frag.h5"), progress=False)
    f, h = res.arrays("fragility"), res.arrays("hazard")
    ok = 0
    for g in range(len(f["gaps"])):
        fit = pounding.fragility.fit(f["levels"], f["observed_n"][g], f["observed_z"][g])
        stored = f["status"][g].decode() if isinstance(f["status"][g], bytes) else str(f["status"][g])
        if not fit.ok:
            assert np.isnan(f["theta"][g]), (g, fit.status, stored)
            continue
        ok += 1
        assert fit.theta == f["theta"][g] and fit.beta == f["beta"][g], g
        lam = pounding.hazard.rate(fit.theta, fit.beta, (h["im"], h["rate"]))
        assert lam["rate"] == h["annual_rate"][g], g
    assert ok >= 3
    assert any(k.startswith("Fragility per gap") for k in res.sections)
    fr, hz = res.fragility, res.hazard
    assert fr["theta"].tolist() == f["theta"].tolist() and (fr["status"] == "ok").sum() == ok
    assert hz["annual_rate"].tolist() == h["annual_rate"].tolist() and hz["gap"].tolist() == f["gaps"].tolist()
    assert len(res.hazard_curve) == len(h["curve_gap"]) and "rate" in res.hazard_curve


def test_ctrl_c_stops_a_study_and_resume_finishes_it(tmp_path):
    import signal
    out = tmp_path / "q.h5"
    calls = []

    def progress(phase, done, total, elapsed, final):
        calls.append(done)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C while the study runs

    with pytest.raises(KeyboardInterrupt, match="resume=True"):
        pounding.Study(QUICK).run(out=str(out), progress=progress)
    assert not out.exists() and (tmp_path / "q.h5.ckpt").exists()  # no results, the checkpoint kept
    res = pounding.Study(QUICK).run(out=str(out), progress=False, resume=True)
    assert res.exit_code == 0 and res.table3["n"].iloc[0] == 96800
    whole = pounding.Study(QUICK).run(out=str(tmp_path / "whole.h5"), progress=False)
    assert pounding._core.report(str(out), True) == pounding._core.report(str(whole.path), True)
    with pytest.raises(RuntimeError, match="callback failed"):
        pounding.Study(QUICK).run(out=str(tmp_path / "r.h5"), progress=lambda *a: 1 / 0)


def test_study_threads_give_the_same_bits(tmp_path):
    """Study.run(threads=2) writes the same results as threads=1 (each thread its own unit computer, results
    stored by unit id); the thread count is provenance in /timing, not a setting."""
    h5py = need("h5py")
    one, two = tmp_path / "t1.h5", tmp_path / "t2.h5"
    pounding.Study(QUICK).run(out=str(one), progress=False, threads=1)
    pounding.Study(QUICK).run(out=str(two), progress=False, threads=2)
    with h5py.File(one) as a, h5py.File(two) as b:
        assert a["timing"].attrs["threads"] == 1 and b["timing"].attrs["threads"] == 2
        for group in ("uncoupled", "models"):
            for key in a[group]:
                x, y = a[group][key][()], b[group][key][()]
                assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), (group, key)
    compare = os.path.join(HERE, "..", "..", "cli", "compare_results.py")
    run = subprocess.run(["/usr/bin/python3", compare, str(one), str(two)], capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


@pytest.mark.parametrize("bad", [-1, 1025, 1.5, "2", True])
def test_bad_threads_is_a_value_error(tmp_path, bad):
    with pytest.raises(ValueError, match=r"threads"):
        pounding.Study(QUICK).run(out=str(tmp_path / "x.h5"), progress=False, threads=bad)
    assert os.listdir(tmp_path) == []
