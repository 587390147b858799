"""Shared set-up of the pytest suite of the Python package (ctest python.pytest, tests/python/run_pytest.py).

The environment names what the suite needs: PYTHONPATH holds build/python, POUNDING_EXE the CLI (the suite compares
the module with it), POUNDING_BUILD_DIR the build tree (the install test). need() imports an optional module (scipy,
pandas, h5py) or skips with the reason -- a failure under CI=true, like every other test's missing data.
"""
import importlib
import os
import shutil

import pytest


def in_ci():
    return os.environ.get("CI", "") not in ("", "0", "false", "no")


def need(name):
    try:
        return importlib.import_module(name)
    except ImportError as e:
        if in_ci():
            pytest.fail(f"{name} is needed (CI is set, so not skipped): {e}")
        pytest.skip(f"needs {name} ({e})")


def cli():
    exe = os.environ.get("POUNDING_EXE") or shutil.which("pounding")
    if not exe or not os.path.exists(exe):
        if in_ci():
            pytest.fail("POUNDING_EXE does not name the pounding CLI (CI is set, so not skipped)")
        pytest.skip("the pounding CLI is not known (set POUNDING_EXE)")
    return exe


def write_at2(path, acc_g, dt, units_line="UNITS OF G"):
    """A PEER NGA-West2 AT2 file written here, not by the engine (5 values a line, %15.7E)."""
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "Test record written by tests/python/suite, 1 Jan 2026",
             f"ACCELERATION TIME SERIES IN {units_line}",
             f"NPTS=  {len(acc_g)}, DT=   {dt:.4f} SEC"]
    for i in range(0, len(acc_g), 5):
        lines.append("".join(f"{v:15.7E}" for v in acc_g[i:i + 5]))
    path.write_text("\n".join(lines) + "\n")
    return path
