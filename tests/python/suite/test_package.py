"""The package layout (issue 28, item 1): pounding is a package (compiled core + Python files) importable from the
build tree and installable with `cmake --install` into a site directory."""
import os
import subprocess
import sys

import pytest

import pounding
from conftest import in_ci


def test_layout():
    assert os.path.basename(pounding.__file__) == "__init__.py"
    assert pounding._core.__name__ == "pounding._core"
    for name in ("analyze", "simulate", "read_record", "spectrum", "design_spectrum", "Status", "run_batch"):
        assert hasattr(pounding, name), name
    assert pounding.fragility.fit and pounding.hazard.rate and pounding.analysis.ddc_rho


def test_cmake_install(tmp_path):
    build = os.environ.get("POUNDING_BUILD_DIR")
    if not build:
        if in_ci():
            pytest.fail("POUNDING_BUILD_DIR is not set (CI is set, so not skipped)")
        pytest.skip("POUNDING_BUILD_DIR (the build tree) is not set")
    cache = open(os.path.join(build, "CMakeCache.txt")).read()
    site = next(line.split("=", 1)[1] for line in cache.splitlines()
                if line.startswith("POUNDING_PYTHON_INSTALL_DIR:"))
    out = subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix", str(tmp_path)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    where = tmp_path / site / "pounding"
    assert (where / "__init__.py").exists() and (where / "fragility.py").exists()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(tmp_path / site)
    code = ("import pounding; print(pounding.__file__); "
            "print(pounding.fragility.fit([0.5, 1.0], [40, 40], [10, 30]).status)")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == [str(where / "__init__.py"), "ok"]
