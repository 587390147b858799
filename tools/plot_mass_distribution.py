#!/usr/bin/python3
"""Structural mass distribution per period, like Fig. 3 of stochastic-pounding-monte-carlo.txt.

Reads the dump of `pounding sample STUDY.toml --out FILE.csv|FILE.h5` and draws, for every period T of
the grid, the distribution of the sampled mass m = mbar rho r^2 h (both structures of every pair pooled:
they are independent draws). Left: histograms (density, log-spaced bins) per period; right: median,
interquartile range and 5-95 % range per period. Prints the same statistics as a table.

    tools/plot_mass_distribution.py structures.csv --out mass_distribution.png
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_samples(path):
    """Returns (T, m) arrays with both structures pooled."""
    if path.endswith(".h5"):
        import h5py

        with h5py.File(path, "r") as f:
            g = f["samples"]
            cols = {k: np.asarray(g[k][:]) for k in ("T1", "T2", "m1", "m2")}
    else:
        with open(path) as f:
            lines = [ln for ln in f if not ln.startswith("#") and ln.strip()]
        names = lines[0].strip().split(",")
        data = np.loadtxt(lines[1:], delimiter=",", ndmin=2) if len(lines) > 1 else np.empty((0, len(names)))
        cols = {k: data[:, names.index(k)] for k in ("T1", "T2", "m1", "m2")}
    T = np.concatenate([cols["T1"], cols["T2"]])
    m = np.concatenate([cols["m1"], cols["m2"]])
    if T.size == 0:
        sys.exit(f" ERROR: {path} holds no samples, {path}, run `pounding sample` with --n >= 1")
    return T, m


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("samples", help="CSV or HDF5 written by `pounding sample`")
    ap.add_argument("--out", default="mass_distribution.png", help="PNG to write")
    ap.add_argument("--bins", type=int, default=40, help="histogram bins (log-spaced)")
    a = ap.parse_args()

    T, m = read_samples(a.samples)
    m_t = m / 1000.0  # tonnes
    periods = np.unique(np.round(T, 9))
    edges = np.logspace(np.log10(m_t.min()), np.log10(m_t.max()), a.bins + 1)
    cmap = plt.get_cmap("viridis")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5.2))
    print(f"{'T (s)':>6} {'n':>7} {'mean (t)':>11} {'median (t)':>11} {'5 % (t)':>10} {'95 % (t)':>11}")
    stats = []
    for j, t in enumerate(periods):
        x = m_t[np.isclose(T, t, atol=1e-9)]
        colour = cmap(j / max(1, len(periods) - 1))
        dens, _ = np.histogram(x, bins=edges, density=True)
        ax1.stairs(dens * np.diff(edges), edges, color=colour, label=f"T = {t:.2f} s")
        q = np.percentile(x, [5, 25, 50, 75, 95])
        stats.append(q)
        print(f"{t:6.2f} {x.size:7d} {x.mean():11.4g} {q[2]:11.4g} {q[0]:10.4g} {q[4]:11.4g}")
    ax1.set_xscale("log")
    ax1.set_xlabel("structural mass m (t)")
    ax1.set_ylabel("fraction of models per bin")
    ax1.set_title("Distribution of structural mass per period")
    ax1.legend(fontsize=7, ncol=2)
    ax1.grid(alpha=0.3, which="both")

    stats = np.array(stats)
    ax2.fill_between(periods, stats[:, 0], stats[:, 4], alpha=0.2, color="C0", label="5-95 %")
    ax2.fill_between(periods, stats[:, 1], stats[:, 3], alpha=0.4, color="C0", label="25-75 %")
    ax2.plot(periods, stats[:, 2], "o-", color="C0", label="median")
    ax2.set_yscale("log")
    ax2.set_xlabel("period T (s)")
    ax2.set_ylabel("structural mass m (t)")
    ax2.set_title(f"Mass versus period ({m.size} structures)")
    ax2.legend()
    ax2.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
