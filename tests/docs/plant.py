#!/usr/bin/env python3
"""Plant the smallest printed change in one cell of a stored evidence CSV (a temporary copy), so that a
tests/docs ctest can show its comparison fails when the stored evidence and the engine disagree.

  plant.py IN OUT --where col=value[,col=value...] --col COL [--digit N]

Adds one unit of the last printed significant digit to the cell (e.g. 0.004108 -> 0.004109; a cell of 0
becomes 1e-06), or with --digit N one unit of the N-th significant digit (--digit 6: 0.63032968 ->
0.63033068, a change of 1e-6..1e-5 relative), and writes the rest unchanged. Exit 2 when no row matches.
Standard library only.
"""
import argparse
import math
import csv
import sys


def bump(s, digit=None):
    x = float(s)
    if x == 0:
        return "1e-06"
    if digit:
        unit = 10.0 ** (math.floor(math.log10(abs(x))) - digit + 1)
        return repr(float(f"{x + math.copysign(unit, x):.{digit + 2}g}"))
    mant = s.lower().split("e")[0].lstrip("+-")
    digits = mant.replace(".", "").lstrip("0")
    frac = len(mant.split(".")[1]) if "." in mant else 0
    exp = int(s.lower().split("e")[1]) if "e" in s.lower() else 0
    unit = 10.0 ** (exp - frac)  # one unit of the last printed digit
    new = x + unit if x > 0 else x - unit
    return repr(float(f"{new:.{max(len(digits), 1) + 1}g}"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("inp")
    ap.add_argument("out")
    ap.add_argument("--where", required=True)
    ap.add_argument("--col", required=True)
    ap.add_argument("--digit", type=int, default=None, help="bump this significant digit (default: the last printed)")
    a = ap.parse_args()
    cond = dict(kv.split("=", 1) for kv in a.where.split(","))
    with open(a.inp, newline="") as f:
        rd = csv.DictReader(f)
        fields, rows = rd.fieldnames, list(rd)
    hit = 0
    for r in rows:
        if all(r[k] == v for k, v in cond.items()):
            old = r[a.col]
            r[a.col] = bump(old, a.digit)
            print(f"planted {cond} {a.col}: {old} -> {r[a.col]}")
            hit += 1
    if not hit:
        print(f"plant: no row with {cond}", file=sys.stderr)
        return 2
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
