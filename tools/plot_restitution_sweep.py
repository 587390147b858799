#!/usr/bin/python3
"""Delivered against target restitution over the approach velocity, per damping law (issue 26 §3): the CSV of
`pounding collide --sweep-v0 lo,hi,n` with a restitution curve e(v0) (e.g. --restitution-preset lindsay2011).
Top: the target e(v0) (the curve, clamped) and the e each law delivers in one free impact; the curve's valid
(calibrated) range shaded. Bottom: delivered - target.

    pounding collide --law hertzdamp --restitution-preset lindsay2011 --sweep-v0 0.1,4,40 > sweep.csv
    /usr/bin/python3 tools/plot_restitution_sweep.py sweep.csv sweep.png
Prints the largest |delivered - target| per law.
"""
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_restitution_sweep.py SWEEP.csv OUT.png")
    src, out = sys.argv[1], sys.argv[2]
    rows = list(csv.DictReader(open(src)))
    if not rows:
        sys.exit(f"{src}: no rows")
    name = lambda r: r["damping_law"] if r["damping_law"] != "-" else r["law"]  # noqa: E731
    laws = list(dict.fromkeys(name(r) for r in rows))
    first = [r for r in rows if name(r) == laws[0]]
    v = [float(r["v0_mps"]) for r in first]
    target = [float(r["e_target"]) for r in first]
    vlo, vhi = float(first[0]["valid_min_mps"]), float(first[0]["valid_max_mps"])
    shaded = vlo == vlo and vlo > min(v) or vhi == vhi and vhi < max(v)  # a finite range inside the sweep
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7.0, 7.6), height_ratios=[2.2, 1])
    if shaded:
        for a in (ax, bx):
            a.axvspan(max(vlo, min(v)), min(vhi, max(v)), color="0.9", zorder=0)
    for law in laws:
        sel = [r for r in rows if name(r) == law]
        vs = [float(r["v0_mps"]) for r in sel]
        ax.plot(vs, [float(r["e_effective"]) for r in sel], "o-", ms=2.5, lw=1.0, label=law)
        bx.plot(vs, [float(r["e_miss"]) for r in sel], "o-", ms=2.5, lw=1.0)
        print(f"{law}: max |delivered - target| = {max(abs(float(r['e_miss'])) for r in sel):.3g}")
    ax.plot(v, target, color="black", lw=1.6, ls="--", zorder=5, label="target e(v0)")
    ax.set_ylabel("restitution e")
    bx.set_ylabel("delivered - target")
    bx.set_xlabel("approach velocity v0 (m/s)")
    bx.axhline(0.0, color="black", lw=0.8)
    for a in (ax, bx):
        a.grid(True, lw=0.3)
        a.set_xlim(min(v), max(v))
    ax.set_xlabel("approach velocity v0 (m/s)")
    shade = f" (shaded: valid {vlo:g}-{vhi:g} m/s)" if shaded else ""
    ax.set_title(f"Restitution delivered by one free impact vs e(v0){shade}", fontsize=9)
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
