#!/usr/bin/python3
"""Plots from a pounding results file (h5py + matplotlib, Debian's python3 packages):
  <prefix>-probability.png  probability of at least one impact versus gap ratio: the continuous curve,
                            the study's gap ratios with 95 % Wilson intervals, the cubic fit, the paper's eq. 10
  <prefix>-periods.png      T1 x T2 heat map of the probability at one gap ratio
Usage: tools/plot_study.py RESULTS.h5 [--prefix out/study] [--ratio 0.3]"""
import argparse

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def wilson(k, n, z=1.959963984540054):
    """95 % Wilson score interval of k in n. Exactly, lo <= k/n <= hi, lo = 0 at k = 0 and hi = 1 at k = n;
    in floating point centre - half can land a few ulp above 0 (k = 0) or centre + half below 1 (k = n), which
    gave a negative error bar that matplotlib rejects -- so the bounds are clipped to [0, k/n] and [k/n, 1]."""
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return min(max(centre - half, 0.0), p), max(min(centre + half, 1.0), p)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--prefix", default=None)
    ap.add_argument("--ratio", type=float, default=0.3)
    ap.add_argument("--fit-min", type=float, default=0.1)
    ap.add_argument("--fit-max", type=float, default=1.0)
    a = ap.parse_args()
    prefix = a.prefix or a.results.rsplit(".", 1)[0]
    f = h5py.File(a.results, "r")
    pc = f["uncoupled/peak_closing"][()]
    R, M = pc.shape
    ok = f["uncoupled/status"][()].reshape(R, M) == 0  # [records, models]; format 1 stored it flat
    d = f["models/code_gap"][()]
    z = (pc / d[None, :])[ok]
    n = z.size
    if n == 0:
        raise SystemExit(f"plot_study.py: {a.results} has no valid analysis (all {pc.size} excluded); nothing to plot")
    x = np.linspace(0.005, 1.5, 300)
    zs = np.sort(z)
    p = 100.0 * (n - np.searchsorted(zs, x, side="right")) / n
    sel = (x >= a.fit_min - 1e-12) & (x <= a.fit_max + 1e-12)
    c = np.polyfit(x[sel], p[sel], 3)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(x, p, lw=2, label=f"this study, continuous (n = {n})")
    ax.plot(x[sel], np.polyval(c, x[sel]), "--", label="cubic fit: {:.1f}x³ {:+.1f}x² {:+.1f}x {:+.1f}".format(*c))
    paper_x = np.array([0.1, 0.2, 0.3, 0.5, 0.7, 1.0])
    ax.plot(paper_x, [71.09, 45.56, 25.26, 6.12, 1.14, 0.0], "ks", label="paper, Table 3")
    xx = np.linspace(0.1, 1.0, 100)
    ax.plot(xx, -213.7 * xx**3 + 510.3 * xx**2 - 403.4 * xx + 106.8, "k:", label="paper, eq. 10")
    for r in paper_x:
        k = int(np.sum(z > r))
        lo, hi = wilson(k, n)
        ax.errorbar([r], [100 * k / n], yerr=[[100 * (k / n - lo)], [100 * (hi - k / n)]], fmt="o", color="C3",
                    capsize=3)
    ax.set_xlabel("gap ratio g / d  (d = 0.005 (h1 + h2))")
    ax.set_ylabel("probability of at least one impact (%)")
    ax.set_title(f.attrs["title"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "-probability.png", dpi=120)

    # each building its own grid (files before periods1/periods2: one grid for both)
    g = f["models"]
    p1 = g["periods1"][()] if "periods1" in g else g["periods"][()]
    p2 = g["periods2"][()] if "periods2" in g else g["periods"][()]
    i1, i2 = g["i1"][()], g["i2"][()]
    hit = (pc > a.ratio * d[None, :]) & ok
    mat = np.full((len(p1), len(p2)), np.nan)
    for a1 in range(len(p1)):
        for a2 in range(len(p2)):
            m = (i1 == a1) & (i2 == a2)
            mat[a1, a2] = 100.0 * hit[:, m].sum() / max(1, ok[:, m].sum())
    fig, ax = plt.subplots(figsize=(6, 5))
    im = ax.imshow(mat, origin="lower", cmap="viridis",
                   extent=[p2[0] - 0.025, p2[-1] + 0.025, p1[0] - 0.025, p1[-1] + 0.025])
    fig.colorbar(im, label="probability of at least one impact (%)")
    ax.set_xlabel("T2 (s), right structure")
    ax.set_ylabel("T1 (s), left structure")
    ax.set_title(f"gap ratio {a.ratio}")
    fig.tight_layout()
    fig.savefig(prefix + "-periods.png", dpi=120)
    print(prefix + "-probability.png", prefix + "-periods.png")


if __name__ == "__main__":
    main()
