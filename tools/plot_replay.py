#!/usr/bin/python3
"""The force history and force-penetration loop of `pounding replay --out forces.csv` (issue 26 §3): the law's force
(and the measured force, when the kinematics file had one) against time, and the force against the penetration
(the loop's area is the energy dissipated per impact).

    pounding replay --law hertzdamp --kh 2e9 --input kin.csv --out forces.csv
    /usr/bin/python3 tools/plot_replay.py forces.csv replay.png
"""
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_replay.py FORCES.csv OUT.png")
    rows = list(csv.DictReader(open(sys.argv[1])))
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    t = [float(r["time_s"]) for r in rows]
    d = [float(r["penetration_m"]) * 1e3 for r in rows]
    f = [float(r["force_N"]) * 1e-3 for r in rows]
    m = [float(r["measured_force_N"]) * 1e-3 for r in rows]
    measured = not all(math.isnan(x) for x in m)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.0, 4.4))
    if measured:
        ax.plot(t, m, color="0.55", lw=1.6, label="measured")
    ax.plot(t, f, color="C0", lw=1.1, label="law")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("contact force (kN)")
    ax.set_title("Force history", fontsize=10)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8, loc="upper right")
    inside = [(di, fi, mi) for di, fi, mi in zip(d, f, m) if di > 0]
    if inside:
        if measured:
            bx.plot([x[0] for x in inside], [x[2] for x in inside], ".", color="0.55", ms=2, label="measured")
        bx.plot([x[0] for x in inside], [x[1] for x in inside], ".-", color="C0", ms=2, lw=0.6, label="law")
        bx.legend(fontsize=8, loc="upper left")
    bx.set_xlabel("penetration (mm)")
    bx.set_ylabel("contact force (kN)")
    bx.set_title("Force-penetration loop (area = energy dissipated)", fontsize=10)
    bx.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=80)


if __name__ == "__main__":
    main()
