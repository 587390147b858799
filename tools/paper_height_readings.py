#!/usr/bin/python3
"""Two readings of the paper's heights (stochastic-pounding-monte-carlo.txt, "adjacent structures with equal
heights") side by side with its Tables 2 and 3: results of studies/stochastic-pounding.toml run with
[structures] equal_heights = false (each building its own height from the period-height rule) and = true (one
height valid for both periods). Prints Markdown for docs/paper-heights.md.

  tools/paper_height_readings.py INDEPENDENT.h5 EQUAL.h5

Regenerate both files as docs/paper-heights.md says."""
import sys

import h5py
import numpy as np

RATIOS = [0.1, 0.2, 0.3, 0.5, 0.7, 1.0]
PAPER_TOTAL = [71.09, 45.56, 25.26, 6.12, 1.14, 0.0]
# Table 2 (counts of 30,976 analyses) for the records present in ../shared/records/real
PAPER_TABLE2 = {
    "EQ2": [26624, 21504, 11776, 0, 0, 0],
    "EQ3": [27904, 23552, 20224, 8192, 4352, 0],
    "EQ6": [0, 0, 0, 0, 0, 0],
    "EQ15": [19712, 9216, 768, 0, 0, 0],
}
# every count of Table 2 as printed (EQ1-EQ25, 0.1d ... d), for the multiples-of-256 check
PAPER_ALL = [20736, 8704, 26624, 21504, 11776, 27904, 23552, 20224, 8192, 4352, 26832, 21248, 15872, 256, 26980,
             21760, 17152, 5888, 16640, 21248, 5120, 512, 19712, 23808, 18176, 7680, 25856, 18688, 13568, 2304,
             25088, 19200, 13056, 1280, 24320, 17664, 11264, 5888, 768, 19712, 9216, 768, 24128, 17408, 7936, 22784,
             14336, 2304, 23780, 16384, 8960, 27684, 24064, 19968, 11008, 3228, 22016, 7936, 1280, 23040, 12288,
             3072, 27136, 22784, 19456, 9728, 512, 26880, 21504, 16384, 2816, 22528, 12800, 25088, 18432, 4352]


def load(path):
    f = h5py.File(path, "r")
    pc = f["uncoupled/peak_closing"][()]
    ok = f["uncoupled/status"][()].reshape(pc.shape) == 0
    d = f["models/code_gap"][()]
    ids = [x.decode() if isinstance(x, bytes) else x for x in f["records/id"][()]]
    synth = f["records/synthetic"][()]
    pair = f["models/i1"][()] * 1000 + f["models/i2"][()]
    return pc, ok, d, ids, synth, pair


def main():
    runs = {"own heights": load(sys.argv[1]), "equal heights": load(sys.argv[2])}
    print("| gap ratio | paper | " + " | ".join(runs) + " |\n|---|---|" + "---|" * len(runs))
    for j, x in enumerate(RATIOS):
        cells = []
        for pc, ok, d, *_ in runs.values():
            hit = (pc > x * d[None, :]) & ok
            cells.append(f"{100 * hit.sum() / ok.sum():.2f}%")
        print(f"| {x} | {PAPER_TOTAL[j]:.2f}% | " + " | ".join(cells) + " |")
    print("\nPer record (analyses with at least one impact, of 30,976), real records only:\n")
    print("| record | reading | " + " | ".join(f"{x}d" for x in RATIOS) + " |\n|---|---|" + "---|" * len(RATIOS))
    for rid, paper in PAPER_TABLE2.items():
        print(f"| {rid} | paper | " + " | ".join(str(v) for v in paper) + " |")
        for name, (pc, ok, d, ids, synth, _) in runs.items():
            k = ids.index(rid)
            assert not synth[k], f"{rid} is a synthetic stand-in in {name}: run with real_dir"
            print(f"| {rid} | {name} | " + " | ".join(str(int(((pc[k] > x * d) & ok[k]).sum())) for x in RATIOS) + " |")
    print("\nMultiples of 256 and unanimous period pairs:\n")
    print("| | Table 2 counts that are multiples of 256 (non-zero ones) | (record, period pair, gap) cells with an impact in "
          "which all 256 samples impact |\n|---|---|---|")
    nz = [v for v in PAPER_ALL if v]
    print(f"| paper | {sum(v % 256 == 0 for v in nz)} of {len(nz)} | - |")
    for name, (pc, ok, d, ids, synth, pair) in runs.items():
        counts, unanimous, cells = [], 0, 0
        for x in RATIOS:
            hit = (pc > x * d[None, :]) & ok
            counts += [int(v) for v in hit.sum(axis=1) if v]
            for p in np.unique(pair):
                h = hit[:, pair == p]
                touched = h.any(axis=1)
                unanimous += int(np.sum(h.all(axis=1)))
                cells += int(np.sum(touched))
        print(f"| {name} | {sum(c % 256 == 0 for c in counts)} of {len(counts)} | {unanimous} of {cells} "
              f"({100 * unanimous / cells:.1f} %) |")


if __name__ == "__main__":
    main()
