#!/usr/bin/python3
"""Plots from a pounding results file (h5py + matplotlib, Debian's python3 packages).
Pair studies (/settings/structures heights_specified == 1, both buildings' heights given):
  <prefix>-separation.png   probability of at least one impact versus separation in metres, with the bootstrap
                            band, the code rules and the separation advice -- all read from the engine's own
                            `pounding report RESULTS.h5 --csv`, so the figure and the report agree
Grid studies:
  <prefix>-probability.png  probability of at least one impact versus gap ratio: the continuous curve,
                            the study's gap ratios with 95 % Wilson intervals, the cubic fit, and (when the study
                            compares with "stochastic-pounding", or does not say) the paper's Table 3 and eq. 10
  <prefix>-periods.png      T1 x T2 heat map of the probability at one gap ratio
Every figure: PNG at 200 dpi, plus each --format given (svg, pdf).
Usage: tools/plot_study.py RESULTS.h5 [--prefix out/study] [--ratio 0.3] [--format svg pdf] [--pounding BIN]"""
import argparse
import csv
import io
import os
import shutil
import subprocess
import textwrap

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


DPI = 200


def save(fig, base, formats):
    """base.png at 200 dpi plus base.<ext> for each extra format; returns the names written."""
    names = [base + ".png"]
    fig.savefig(names[0], dpi=DPI)
    for ext in formats:
        names.append(base + "." + ext)
        fig.savefig(names[-1], dpi=DPI)
    plt.close(fig)
    return names


def wrap_title(title, fig, share=1.0, fontsize=10):
    """The title broken into lines that fit `share` of the figure's width (a long one was clipped on both sides)."""
    chars = int(share * fig.get_figwidth() * 72 / (0.55 * fontsize))
    return textwrap.fill(title, max(chars, 20))


def attr_str(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def find_pounding(given):
    """--pounding, else $POUNDING, else <repo>/build/pounding next to this script, else `pounding` on PATH."""
    if given:
        cands = [given]
    elif os.environ.get("POUNDING"):
        cands = [os.environ["POUNDING"]]
    else:
        here = os.path.dirname(os.path.abspath(__file__))
        cands = [os.path.join(here, "..", "build", "pounding"), shutil.which("pounding")]
    for c in cands:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    tried = ", ".join(str(c) for c in cands if c) or "nothing"
    raise SystemExit(f"plot_study.py: cannot find an executable pounding binary (tried {tried}; none on PATH "
                     "either unless listed); give it with --pounding BIN or $POUNDING")


def report_rows(binary, results):
    r = subprocess.run([binary, "report", results, "--csv"], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"plot_study.py: `{binary} report {results} --csv` failed ({r.returncode}): {r.stderr}")
    return list(csv.DictReader(io.StringIO(r.stdout)))


def plot_pair(f, a, prefix):
    rows = report_rows(find_pounding(a.pounding), a.results)
    conf = float(f["settings/report"].attrs.get("confidence", 0.95)) if "settings/report" in f else 0.95
    band = [r for r in rows if r["table"] == "curve_band"]
    if not band:
        raise SystemExit(f"plot_study.py: the report of {a.results} has no curve_band rows; nothing to plot")
    g = np.array([float(r["gap_m"]) for r in band])
    p = 100 * np.array([float(r["probability"]) for r in band])
    lo = 100 * np.array([float(r["lo"]) for r in band])
    hi = 100 * np.array([float(r["hi"]) for r in band])
    n = band[0]["n"]

    fig, ax = plt.subplots(figsize=(10, 5.5))
    ax.fill_between(g, lo, hi, color="C0", alpha=0.25,
                    label=f"{100 * conf:g} % bootstrap band over records and models")
    ax.plot(g, p, "C0", lw=2, label=f"this study (n = {n})")

    # code rules: rules with equal separations share one line; named in the legend (a label inside the axes was
    # crossed by the other rules' lines)
    rules = {}
    for r in rows:
        if r["table"] == "code_rule":
            key = round(float(r["gap_m"]), 6)
            rules.setdefault(key, [float(r["probability"]), []])[1].append(r["name"])
    for i, (gm, (prob, names)) in enumerate(sorted(rules.items())):
        ax.axvline(gm, color=f"C{2 + i % 8}", lw=1.2, alpha=0.9,
                   label=textwrap.fill(" / ".join(names), 44) + f":\n  {gm:.3f} m, P = {100 * prob:.1f} %")

    # separation advice: the estimate (dot) with its interval, and the advised separation (its upper end, a
    # diamond on a dashed line up to the target) labelled right beside that diamond
    # a target the records do not resolve (floor(t N) = 0: "not resolved by N records") is advised at the upper end
    # of the report's lognormal estimate instead, drawn hollow and labelled so (issue 23 item 2)
    lognormal = {r["probability"]: float(r["hi"]) for r in rows if r["table"] == "separation_lognormal"}
    first, first_ln = True, True
    ends = []
    for r in rows:
        if r["table"] != "separation":
            continue
        s, t = float(r["gap_m"]), 100 * float(r["probability"])
        slo, shi = float(r["lo"]), float(r["hi"])
        unresolved = r["name"].startswith("not resolved") and r["probability"] in lognormal
        adv = lognormal[r["probability"]] if unresolved else shi
        ends.append(max(shi, adv))
        ax.errorbar([s], [t], xerr=[[s - slo], [shi - s]], fmt="o", color="k", capsize=3, ms=5,
                    mfc="white" if unresolved else "k",
                    label="separation for a target probability (interval)" if first else None)
        ax.plot([adv, adv], [0, t], color="k", ls="--" if not unresolved else ":", lw=1)
        if unresolved:
            ax.plot([adv], [t], "D", color="k", mfc="white", ms=5,
                    label="target not resolved by the records: lognormal estimate's upper end" if first_ln else None)
            first_ln = False
        else:
            ax.plot([adv], [t], "D", color="k", ms=5,
                    label="advised separation (upper end of the interval)" if first else None)
        ax.annotate(f"{t:g} %: {adv:.3f} m" + (" (lognormal)" if unresolved else ""), (adv, t),
                    textcoords="offset points", xytext=(6, 0), fontsize=7,
                    va="center", ha="left", gid="advice", zorder=5,
                    bbox=dict(facecolor="white", edgecolor="none", alpha=0.95, pad=1))
        first = False

    # the x-axis ends a little past the last thing to read: the advice, the code rules, or where the band's
    # upper edge falls below 0.5 % (the curve runs on to the study's curve_max, far past the data)
    tail = g[hi >= 0.5]
    x_end = max([tail.max() if tail.size else g.max()] + ends + list(rules))
    ax.set_xlim(0, min(g.max(), 1.15 * x_end))
    ax.set_ylim(0, 100)
    ax.set_xlabel("separation between the buildings (m)")
    ax.set_ylabel("probability of at least one impact (%)")
    ax.set_title(wrap_title(attr_str(f.attrs["title"]), fig, 0.62), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    return save(fig, prefix + "-separation", a.format)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--prefix", default=None)
    ap.add_argument("--ratio", type=float, default=0.3)
    ap.add_argument("--fit-min", type=float, default=0.1)
    ap.add_argument("--fit-max", type=float, default=1.0)
    ap.add_argument("--format", nargs="+", default=[], choices=["svg", "pdf"],
                    help="extra formats besides the 200 dpi PNG")
    ap.add_argument("--pounding", default=None, help="the pounding binary (pair studies run its report --csv)")
    a = ap.parse_args()
    prefix = a.prefix or a.results.rsplit(".", 1)[0]
    f = h5py.File(a.results, "r")
    st = f["settings/structures"].attrs if "settings/structures" in f else {}
    if int(st.get("heights_specified", 0)) == 1:
        print(*plot_pair(f, a, prefix))
        return
    rep = f["settings/report"].attrs if "settings/report" in f else {}
    paper = "compare_with" not in rep or attr_str(rep["compare_with"]) == "stochastic-pounding"
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
    if paper:
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
    ax.set_title(wrap_title(attr_str(f.attrs["title"]), fig), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    written = save(fig, prefix + "-probability", a.format)

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
    written += save(fig, prefix + "-periods", a.format)
    print(*written)


if __name__ == "__main__":
    main()
