#!/usr/bin/python3
"""Stiff steel-frame contact (docs/stiff_contact.csv from `pounding accuracy stability`): peak contact force
against h * omega_c (omega_c = sqrt(k / meff) of the 20,660 N/mm contact) for every stepper and law; lanes the
kernel marked diverged are drawn as crosses at the top, lanes the resolution guard marked coarse (ran, but h omega_c
over the accuracy limit of the stepper x law) as open circles, ok lanes filled. The measured stability limits (docs/stability.csv)
are printed.

    /usr/bin/python3 tools/plot_stability.py docs/stability.csv docs/stiff_contact.csv docs/img/stability.png
"""
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    stab, stiff, out = sys.argv[1], sys.argv[2], sys.argv[3]
    for r in csv.DictReader(open(stab)):
        print("%-20s zeta %-5s measured %-10s theory %s" % (r["stepper"], r["zeta"], r["measured_h_omega"],
                                                            r["theory_h_omega"]))
    rows = list(csv.DictReader(open(stiff)))
    laws = list(dict.fromkeys(r["law"] for r in rows))
    steppers = list(dict.fromkeys(r["stepper"] for r in rows))
    fig, axes = plt.subplots(1, len(laws), figsize=(4.3 * len(laws), 3.8), squeeze=False)
    for j, law in enumerate(laws):
        ax = axes[0][j]
        ran = ("ok", "coarse")
        top = max(float(r["peak_force"]) for r in rows if r["law"] == law and r["status"] in ran) * 1.6
        for i, s in enumerate(steppers):
            pts = [r for r in rows if r["law"] == law and r["stepper"] == s]
            line = [(float(r["h_omega_contact"]), float(r["peak_force"])) for r in pts if r["status"] in ran]
            ok = [(float(r["h_omega_contact"]), float(r["peak_force"])) for r in pts if r["status"] == "ok"]
            coarse = [(float(r["h_omega_contact"]), float(r["peak_force"])) for r in pts if r["status"] == "coarse"]
            bad = [float(r["h_omega_contact"]) for r in pts if r["status"] not in ran]
            if line:
                ax.plot(*zip(*sorted(line)), "-", color="C%d" % i, lw=0.8, label=s)
            if ok:
                ax.plot(*zip(*ok), "o", color="C%d" % i, ms=4)
            if coarse:
                ax.plot(*zip(*coarse), "o", mfc="none", color="C%d" % i, ms=5)
            if bad:
                ax.plot(bad, [top * (1 + 0.05 * i)] * len(bad), "x", color="C%d" % i, ms=8)
        ax.axvline(2.0, color="grey", ls=":", lw=0.8)
        ax.axvline(2.83, color="grey", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel("h * omega_c (contact)")
        ax.set_ylabel("peak contact force (N)")
        ax.set_title("%s (x diverged, open = coarse, filled = ok)" % law, fontsize=9)
        ax.grid(True, lw=0.3)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
