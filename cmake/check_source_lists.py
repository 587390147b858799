#!/usr/bin/env python3
"""ctest build.source_lists: the explicit file lists of CMakeLists.txt cannot go stale.

Fails when a source, header or test script in src/, include/, tests/ or bench/ is not named in
CMakeLists.txt (the manifest CMake writes at configure time), when a named file no longer exists, or when a
shell test runs mpirun without being in POUNDING_MPI_TESTS (a serial build would then run it and fail).
Test data (tests/data, tests/sanitize) are not sources and are not checked.
"""
import argparse
import os
import sys

CHECKED_DIRS = ("src", "include", "tests", "bench")
EXTENSIONS = (".cpp", ".cc", ".c", ".hpp", ".h", ".sh", ".py", ".cmake", ".txt")
NOT_SOURCES = ("tests/data/", "tests/sanitize/")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--listed", required=True, help="manifest written by CMakeLists.txt")
    ap.add_argument("--mpi-tests", required=True, help="POUNDING_MPI_TESTS, one test name a line")
    a = ap.parse_args()
    listed = {l.strip() for l in open(a.listed) if l.strip()}
    mpi_tests = {l.strip() for l in open(a.mpi_tests) if l.strip()}

    present = set()
    for top in CHECKED_DIRS:
        for root, dirs, files in os.walk(os.path.join(a.source_dir, top)):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            for f in files:
                rel = os.path.relpath(os.path.join(root, f), a.source_dir).replace(os.sep, "/")
                if rel.endswith(EXTENSIONS) and not rel.startswith(NOT_SOURCES):
                    present.add(rel)

    problems = []
    for rel in sorted(present - listed):
        problems.append(f"{rel}: not listed in CMakeLists.txt (add it to its target's or test list)")
    for rel in sorted(listed):
        if not os.path.exists(os.path.join(a.source_dir, rel)):
            problems.append(f"{rel}: listed in CMakeLists.txt but missing")
    for rel in sorted(present):
        parts = rel.split("/")
        if len(parts) == 3 and parts[0] == "tests" and parts[1] in ("cli", "faults") and rel.endswith(".sh"):
            name = f"{parts[1]}.{parts[2][:-3]}"
            text = open(os.path.join(a.source_dir, rel), errors="replace").read()
            if ("mpirun" in text or "mpiexec" in text) and name not in mpi_tests:
                problems.append(f"{rel}: runs mpirun but {name} is not in POUNDING_MPI_TESTS")
    for p in problems:
        print("FAIL:", p)
    print(f"{len(present)} files checked, {len(listed)} listed, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
