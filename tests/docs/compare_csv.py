#!/usr/bin/env python3
"""Compare a freshly regenerated (partial) CSV with the stored evidence CSV it came from.

Every row of NEW must match the row of STORED with the same key columns; every compared column must agree
within its tolerance. Used by the tests/docs ctests: a docs/*.csv that no longer matches what the current
engine prints fails the suite (issue 12: evidence that cannot go stale).

  compare_csv.py STORED NEW --key stepper,law,k [--cols a,b | --ignore ns_per_pair_step,ms_per_analysis]
                 [--rtol 1e-9] [--atol 0] [--tol force_p99=0.02:1e-6 ...] [--min-rows N]
                 [--resolved status=ok]

Numbers: |new - stored| <= atol + rtol * |stored| (nan equals nan, inf equals inf of the same sign).
Other cells: exact string equality. Exit 0 agree, 1 differ, 2 usage or unreadable input.
--resolved COL=VALUE: a row whose stored COL is not VALUE (an unresolved row: a lane the resolution guard marked
coarse, or one that diverged) is compared on COL alone. Its numbers follow the last bits of every contraction
the compiler picks (a chattering contact at h omega_c ~ 1.6 gives 36,530 N in one build and 19,269 N in
another), so they are evidence of nothing but the status, which is what the stored row claims.
Standard library only (runs on any python3).
"""
import argparse
import csv
import math
import sys


def number(s):
    try:
        return float(s)
    except ValueError:
        return None


def same(a, b, rtol, atol):
    x, y = number(a), number(b)
    if x is None or y is None:
        return a.strip() == b.strip()
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    if math.isinf(x) or math.isinf(y):
        return x == y
    return abs(x - y) <= atol + rtol * abs(x)


def read(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as err:
        print(f"compare_csv: cannot read {path}: {err}", file=sys.stderr)
        sys.exit(2)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("stored")
    ap.add_argument("new")
    ap.add_argument("--key", required=True, help="comma-separated key columns")
    ap.add_argument("--cols", default="", help="columns to compare (default: all but key and --ignore)")
    ap.add_argument("--ignore", default="", help="columns not compared (timings)")
    ap.add_argument("--rtol", type=float, default=1e-9)
    ap.add_argument("--atol", type=float, default=0.0)
    ap.add_argument("--tol", action="append", default=[], help="COL=RTOL[:ATOL] for one column")
    ap.add_argument("--min-rows", type=int, default=1, help="NEW must hold at least this many rows")
    ap.add_argument("--resolved", default="", help="COL=VALUE: rows whose stored COL differs compare COL only")
    a = ap.parse_args()
    stored, new = read(a.stored), read(a.new)
    key = [k for k in a.key.split(",") if k]
    if not stored or not new:
        print(f"compare_csv: empty input ({len(stored)} stored rows, {len(new)} new rows)", file=sys.stderr)
        return 2
    for k in key:
        if k not in stored[0] or k not in new[0]:
            print(f"compare_csv: key column '{k}' missing", file=sys.stderr)
            return 2
    ignore = set(c for c in a.ignore.split(",") if c)
    cols = [c for c in a.cols.split(",") if c] or [c for c in new[0] if c not in key and c not in ignore]
    for c in cols:
        if c not in stored[0] or c not in new[0]:
            print(f"compare_csv: column '{c}' missing in {'stored' if c not in stored[0] else 'new'}", file=sys.stderr)
            return 2
    tol = {}
    for t in a.tol:
        name, _, val = t.partition("=")
        r, _, at = val.partition(":")
        tol[name] = (float(r), float(at) if at else a.atol)
    resolved_col, _, resolved_value = a.resolved.partition("=")
    if resolved_col and (resolved_col not in stored[0] or resolved_col not in new[0]):
        print(f"compare_csv: --resolved column '{resolved_col}' missing", file=sys.stderr)
        return 2
    index = {tuple(r[k] for k in key): r for r in stored}
    bad = 0
    unresolved = 0
    for r in new:
        k = tuple(r[c] for c in key)
        s = index.get(k)
        if s is None:
            print(f"DIFF {dict(zip(key, k))}: no such row in {a.stored}")
            bad += 1
            continue
        row_cols = cols
        if resolved_col and s[resolved_col] != resolved_value:
            row_cols = [resolved_col]
            unresolved += 1
        for c in row_cols:
            rt, at = tol.get(c, (a.rtol, a.atol))
            if not same(s[c], r[c], rt, at):
                print(f"DIFF {dict(zip(key, k))} {c}: stored {s[c]}, now {r[c]} (rtol {rt:g}, atol {at:g})")
                bad += 1
    if len(new) < a.min_rows:
        print(f"DIFF only {len(new)} rows regenerated, at least {a.min_rows} expected")
        bad += 1
    if resolved_col:
        print(f"{len(new) - unresolved} resolved rows ({resolved_col} {resolved_value}) x {len(cols)} columns and "
              f"{unresolved} unresolved rows x {resolved_col} compared with {a.stored}: {bad} differences")
    else:
        print(f"{len(new)} rows x {len(cols)} columns compared with {a.stored}: {bad} differences")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
