#!/usr/bin/python3
"""Per-position amplification statistics of a row of buildings (issue 25 step 8, docs/rows.md;
../shared/research/systems-and-bridges.md §4, Anagnostopoulos 1988: "the end buildings of a row almost always suffer
substantial response increases, while interior buildings often respond less than alone").

Reads a results file of an impacts-scene study ([structures] buildings = n >= 2; scene = "impacts") and forms, for
every analysis (record x model) that ran without failure, each building's amplification

    A_b = peak |u| of building b with contact / peak |u| of building b without contact

(its largest floor relative to the ground: impacts/peak_u{b} over uncoupled/peak_u{b} of the same record and
model), grouped by position in the row: end-left (building 1), interior (2 .. n-1; none in a pair) and end-right
(building n). Per gap ratio and position it prints the number of values, the median, the 16th and 84th percentiles,
the mean and P(A > 1), over all analyses and over those where the row pounds at that gap (any joint touches: an
untouched analysis has A = 1 exactly).

Usage: row_amplification.py RESULTS.h5 [--json]
  --json   one JSON object {"buildings": n, "gap_ratios": [...], "positions": [{"position", "buildings": [1-based],
           "gaps": [{"ratio", "n", "median", "p16", "p84", "mean", "p_amplified", "n_pounding", "median_pounding",
           "p_amplified_pounding"}]}]} instead of the table.
Exit 2 with one ERROR line for a file that is not an impacts-scene study.
"""
import json
import signal
import sys

import h5py
import numpy as np


def fail(what, fix):
    print(f" ERROR: {what}, {sys.argv[1]}, {fix}", file=sys.stderr)
    sys.exit(2)


def stats(a):
    if a.size == 0:
        return dict(n=0, median=None, p16=None, p84=None, mean=None, p_amplified=None)
    return dict(n=int(a.size), median=float(np.median(a)), p16=float(np.percentile(a, 16)),
                p84=float(np.percentile(a, 84)), mean=float(np.mean(a)), p_amplified=float(np.mean(a > 1.0)))


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        f = h5py.File(args[0], "r")
    except OSError as e:
        fail(f"cannot read the results file ({e})", "give a results file written by pounding run")
    if "impacts" not in f or "impact_count" not in f["impacts"]:
        fail("the file has no /impacts results", 'run the study with scene = "impacts"')
    u, imp = f["uncoupled"], f["impacts"]
    n = 2
    while f"peak_u{n + 1}" in u:
        n += 1
    R, M = u["peak_closing"].shape
    x = imp["gap_ratios"][()] if "gap_ratios" in imp else imp["gap_axis"][()]  # [gaps] metres: the gaps in m
    G = len(x)
    ok_u = u["status"][()].reshape(R, M) == 0
    ok_c = imp["status"][()].reshape(R, M, G) == 0
    ok = ok_u[:, :, None] & ok_c
    pounds = imp["impact_count"][()].reshape(R, M, G) > 0
    amp = {}
    for b in range(1, n + 1):
        c = imp[f"peak_u{b}"][()].reshape(R, M, G)
        un = u[f"peak_u{b}"][()].reshape(R, M)
        amp[b] = c / un[:, :, None]
    positions = [("end-left", [1])]
    if n > 2:
        positions.append(("interior", list(range(2, n))))
    positions.append(("end-right", [n]))
    out = dict(buildings=n, gap_ratios=[float(v) for v in x], positions=[])
    for name, bs in positions:
        gaps = []
        for g in range(G):
            sel = ok[:, :, g]
            a = np.concatenate([amp[b][:, :, g][sel] for b in bs])
            ap = np.concatenate([amp[b][:, :, g][sel & pounds[:, :, g]] for b in bs])
            s = stats(a)
            sp = stats(ap)
            s.update(ratio=float(x[g]), n_pounding=sp["n"], median_pounding=sp["median"],
                     p_amplified_pounding=sp["p_amplified"])
            gaps.append(s)
        out["positions"].append(dict(position=name, buildings=bs, gaps=gaps))
    if "--json" in sys.argv:
        json.dump(out, sys.stdout, indent=1)
        print()
        return 0
    print(f"{args[0]}: a row of {n} buildings, {R} records x {M} models; amplification A = peak |u| with contact / "
          f"without (per building, its largest floor)")
    fmt = lambda v: "-" if v is None else f"{v:.3f}"
    print(f"{'gap ratio':>9}  {'position':<9} {'n':>6} {'median':>7} {'p16':>7} {'p84':>7} {'P(A>1)':>7}   "
          f"{'pounding: n':>11} {'median':>7} {'P(A>1)':>7}")
    for g in range(G):
        for p in out["positions"]:
            s = p["gaps"][g]
            print(f"{x[g]:>9.3g}  {p['position']:<9} {s['n']:>6} {fmt(s['median']):>7} {fmt(s['p16']):>7} "
                  f"{fmt(s['p84']):>7} {fmt(s['p_amplified']):>7}   {s['n_pounding']:>11} "
                  f"{fmt(s['median_pounding']):>7} {fmt(s['p_amplified_pounding']):>7}")
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the output quietly, not with a BrokenPipe traceback
    sys.exit(main())
