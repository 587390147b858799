#!/usr/bin/python3
"""Two of the report's numbers rebuilt from a pounding results file with h5py alone (docs/results-format.md):

  (a) Table 3: the probability of at least one impact at each of the study's gap ratios x -- the fraction of the
      ok analyses (status 0) whose uncoupled peak closing exceeds the gap x d (d = /models/code_gap), pooled over
      records and models. A pair touches at a gap g exactly when its peak closing max(u1 - u2) exceeds g.
  (b) the separation in metres at target probabilities t: the smallest gap that at most floor(t n) of the n ok
      analyses exceed, i.e. the (floor(t n) + 1)-th largest peak closing.

Reads format 2 (status [records, models], /gaps) and format 1 (status flat, no /gaps).
Usage: tools/results_example.py RESULTS.h5 [--targets 10 5 1]   (targets in %)"""
import argparse

import h5py
import numpy as np


def ok_closings(f):
    """The peak closing (m) of every ok analysis, [records, models], and the mask of the ok ones."""
    pc = f["uncoupled/peak_closing"][()]  # [records, models], m
    ok = f["uncoupled/status"][()].reshape(pc.shape) == 0  # format 1 stored the status flat
    return pc, ok


def table3(f):
    """Rows (x, analyses that touch, ok analyses) for each gap ratio x of the study."""
    pc, ok = ok_closings(f)
    if "gaps" in f:
        ratios = f["gaps/ratios"][()]
        metres = f["gaps/metres"][()]  # [models, gaps] = x * code_gap
    else:  # format 1
        ratios = np.asarray(f["settings/gaps"].attrs["ratios"])
        metres = f["models/code_gap"][()][:, None] * ratios[None, :]
    n = int(ok.sum())
    return [(x, int(((pc > metres[None, :, g]) & ok).sum()), n) for g, x in enumerate(ratios)]


def separation(f, t):
    """The smallest gap (m) that at most floor(t n) of the n ok analyses exceed (t a fraction)."""
    pc, ok = ok_closings(f)
    z_desc = np.sort(pc[ok])[::-1]
    n = z_desc.size
    if n == 0:
        return float("nan")
    j = int(np.floor(t * n))
    return z_desc[min(j, n - 1)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--targets", type=float, nargs="*", default=[10.0, 5.0, 1.0], help="target probabilities (%%)")
    a = ap.parse_args()
    with h5py.File(a.results, "r") as f:
        print(f"{a.results}: format {int(f.attrs['format_version'])}, {f.attrs['title']}\n")
        print("Table 3: probability of at least one impact\n")
        print("| gap ratio | models with impact | probability |\n|---|---|---|")
        for x, k, n in table3(f):
            print(f"| {x:g} | {k} / {n} | " + (f"{100.0 * k / n:.2f}%" if n else "n/a") + " |")
        print("\nSeparation in metres: the smallest gap that at most floor(t n) of the n ok analyses exceed\n")
        print("| target | separation (m) |\n|---|---|")
        for t in a.targets:
            print(f"| {t:g}% | {separation(f, t / 100.0):.4f} |")


if __name__ == "__main__":
    main()
