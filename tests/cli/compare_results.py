#!/usr/bin/python3
"""Exit 0 when two pounding results files hold bit-identical model results (NaN == NaN), else list the
differences and exit 1. Usage: compare_results.py A.h5 B.h5"""
import sys

import h5py
import numpy as np

a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
bad = 0
for group in ("models", "uncoupled", "impacts", "records"):
    if (group in a) != (group in b):
        print(f"group {group} only in one file")
        bad += 1
        continue
    if group not in a:
        continue
    for name in a[group]:
        x, y = a[group][name][()], b[group][name][()]
        if x.dtype.kind == "O":  # strings (paths, notes) may differ; results may not
            continue
        if x.dtype.kind == "f":
            same = x.shape == y.shape and np.array_equal(x, y, equal_nan=True)
        else:
            same = x.shape == y.shape and np.array_equal(x, y)
        if not same:
            print(f"{group}/{name} differs")
            bad += 1
print(f"compared {sys.argv[1]} and {sys.argv[2]}: {bad} differences")
assert bad == 0, f"{bad} result datasets differ"
