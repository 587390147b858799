#!/usr/bin/python3
"""Exit 0 when two pounding results files hold bit-identical results (NaN == NaN), else list the
differences and exit 1. Compares, in both directions, every dataset and every attribute of the file, its
groups and datasets, except provenance that legitimately differs between runs (date, wall time, ranks,
commit, program version, build, study path, the machine: host, cpu_model, cpu_cores); string datasets of record sources and notes are compared too.
The /timing group (issue 27: each phase's seconds) is provenance like wall_time_s: its seconds (rank0_s, max_s,
wall_s) and units_resumed are compared in shape only, its phase names exactly, and a file without it (written
before issue 27) matches one with it.

Usage: compare_results.py A.h5 B.h5 [--allow-added] [--ignore=NAME,NAME...]
  --ignore       attributes deliberately different between the two runs (e.g. study_text,batch when the
                 batch width is what the comparison varies)
  --allow-added  items present only in B are reported but not counted (B written by a newer format that
                 adds datasets or attributes, e.g. an old build's file against a new build's)."""
import sys

import h5py
import numpy as np

PROVENANCE = {"date", "wall_time_s", "ranks", "git_commit", "program_version", "build", "study_path", "host", "cpu_model",
              "cpu_cores"}
TIMING = "/timing"  # seconds that differ run to run: like wall_time_s
TIMING_PROVENANCE = {"wall_s", "units_resumed", "units", "threads"}  # units: the work units, a function of the batch width; threads: per rank
TIMING_SECONDS = {"rank0_s", "max_s"}
args = [x for x in sys.argv[1:] if not x.startswith("--")]
allow_added = "--allow-added" in sys.argv
for x in sys.argv[1:]:
    if x.startswith("--ignore="):
        PROVENANCE |= set(x.split("=", 1)[1].split(","))
a, b = h5py.File(args[0], "r"), h5py.File(args[1], "r")
bad, added = 0, 0


def equal(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.shape != y.shape:
        return False
    if x.dtype.kind == "f" and y.dtype.kind == "f":
        return np.array_equal(x, y, equal_nan=True)
    if x.dtype.kind in "OSU" or y.dtype.kind in "OSU":
        dec = lambda v: v.decode() if isinstance(v, bytes) else str(v)
        return [dec(v) for v in x.ravel()] == [dec(v) for v in y.ravel()]
    return np.array_equal(x, y)


def compare_attrs(path, x, y):
    global bad, added
    for k in sorted(set(x.attrs) | set(y.attrs)):
        if k in PROVENANCE or (path == TIMING and k in TIMING_PROVENANCE):
            continue
        if k not in y.attrs:
            print(f"{path} attribute {k} only in A")
            bad += 1
        elif k not in x.attrs:
            print(f"{path} attribute {k} only in B")
            added += 1
        elif not equal(x.attrs[k], y.attrs[k]):
            print(f"{path} attribute {k} differs")
            bad += 1


def walk(path, x, y):
    global bad, added
    compare_attrs(path or "/", x, y)
    for name in sorted(set(x) | set(y)):
        p = f"{path}/{name}"
        if p == TIMING and (name not in x or name not in y):
            continue  # a file written before /timing existed
        if path == TIMING and name in TIMING_SECONDS and name in x and name in y:
            if np.shape(x[name]) != np.shape(y[name]):
                print(f"{p} shape differs")
                bad += 1
            continue
        if name not in y:
            print(f"{p} only in A")
            bad += 1
        elif name not in x:
            print(f"{p} only in B")
            added += 1
        elif isinstance(x[name], h5py.Group) != isinstance(y[name], h5py.Group):
            print(f"{p} is a group in one file only")
            bad += 1
        elif isinstance(x[name], h5py.Group):
            walk(p, x[name], y[name])
        else:
            if not equal(x[name][()], y[name][()]):
                print(f"{p} differs")
                bad += 1
            compare_attrs(p, x[name], y[name])


walk("", a, b)
total = bad + (0 if allow_added else added)
print(f"compared {args[0]} and {args[1]}: {total} differences" + (f" ({added} items only in B allowed)" if allow_added and added else ""))
assert total == 0, f"{total} differences"
