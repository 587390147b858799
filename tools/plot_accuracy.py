#!/usr/bin/python3
"""Error versus cost of every stepper x dt x contact law (docs/accuracy_chart.csv from `pounding accuracy chart`).

Draws, per contact law, the 99th-percentile relative peak-force error (peak closing for the stereomechanical
law, which has no force) and the largest probability-table error against the wall time per analysis, log-log,
one curve per stepper (points k = 0..5, dt = record dt / 2^k), the Pareto front (cheapest for its error) in
black. Prints the front and, per law, the cheapest setting meeting the study tolerance (probability-table error
< 0.1 percentage point at every gap ratio and peak-force error < 1 %).

    /usr/bin/python3 tools/plot_accuracy.py docs/accuracy_chart.csv docs/img/accuracy_chart.png
"""
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

FLOOR = 1e-9  # zero errors are drawn at this floor on the log axis


def main():
    src, out = sys.argv[1], sys.argv[2]
    rows = list(csv.DictReader(open(src)))
    for r in rows:
        for k in ("ms_per_analysis", "ns_per_pair_step", "closing_median", "closing_p99", "force_median",
                  "force_p99", "amp_p99", "count_differs", "verdict_differs", "prob_error_max_pp"):
            r[k] = float(r[k])
        r["k"] = int(r["k"])
        r["diverged"] = int(r["diverged"])
        stereo = r["law"] in ("stereomechanical", "none")
        r["err"] = r["closing_p99"] if stereo else r["force_p99"]
    laws = list(dict.fromkeys(r["law"] for r in rows))
    steppers = list(dict.fromkeys(r["stepper"] for r in rows))
    colors = dict(zip(steppers, ["C0", "C1", "C2", "C3", "C4", "C5"]))
    fig, axes = plt.subplots(2, len(laws), figsize=(4.2 * len(laws), 7.2), squeeze=False)
    print("Pareto front (error = p99 peak-force error; stereomechanical: p99 peak-closing error)")
    for j, law in enumerate(laws):
        lr = [r for r in rows if r["law"] == law]
        for i, (key, label) in enumerate([("err", "p99 rel. error of peak " + ("closing" if law in ("stereomechanical", "none")
                                                                                else "force")),
                                          ("prob_error_max_pp", "max probability-table error (pp)")]):
            ax = axes[i][j]
            for s in steppers:
                pts = sorted([r for r in lr if r["stepper"] == s], key=lambda r: r["k"])
                xs = [r["ms_per_analysis"] for r in pts if math.isfinite(r[key])]
                ys = [max(r[key], FLOOR) for r in pts if math.isfinite(r[key])]
                ax.plot(xs, ys, "o-", color=colors[s], ms=3.5, lw=1.2, label=s)
                for r in pts:
                    if r["diverged"]:
                        ax.plot(r["ms_per_analysis"], 1.0, "x", color=colors[s], ms=7)
            # Pareto front: sorted by cost, keep points whose error is below every cheaper point's
            fin = sorted([r for r in lr if math.isfinite(r[key])], key=lambda r: r["ms_per_analysis"])
            front, best = [], math.inf
            for r in fin:
                if r[key] < best:
                    front.append(r)
                    best = r[key]
            ax.plot([r["ms_per_analysis"] for r in front], [max(r[key], FLOOR) for r in front], "k--", lw=1.0,
                    label="Pareto front" if j == 0 and i == 0 else None)
            if i == 0:
                print("  %s: %s" % (law, ", ".join("%s k=%d (%.3g ms, %.2g)" % (r["stepper"], r["k"],
                                                                                r["ms_per_analysis"], r[key])
                                                  for r in front)))
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(law if i == 0 else "", fontsize=10)
            ax.set_xlabel("wall time per analysis (ms, 15 s record)", fontsize=8)
            ax.set_ylabel(label, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="both", lw=0.3, alpha=0.5)
            if key == "prob_error_max_pp":
                ax.axhline(0.1, color="grey", lw=0.8, ls=":")
            else:
                ax.axhline(0.01, color="grey", lw=0.8, ls=":")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Error vs cost: 50 sampled models x 3 real records (15 s), gap ratio 0.1; "
                 "x = diverged; dotted = study tolerance", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    print("\nCheapest setting meeting probability error < 0.1 pp and peak-force (closing) p99 error < 1 %:")
    for law in laws:
        ok = [r for r in rows if r["law"] == law and r["prob_error_max_pp"] < 0.1 and r["err"] < 0.01
              and r["diverged"] == 0]
        if not ok:
            print("  %s: none" % law)
            continue
        b = min(ok, key=lambda r: r["ms_per_analysis"])
        print("  %s: %s, dt = %.5g s (k = %d): %.3g ms/analysis, %.3g ns/pair-step, force p99 %.2g, closing p99 "
              "%.2g, count differs %.3f, prob error %.3g pp" % (law, b["stepper"], float(b["dt"]), b["k"],
                                                              b["ms_per_analysis"], b["ns_per_pair_step"],
                                                              b["force_p99"], b["closing_p99"], b["count_differs"],
                                                              b["prob_error_max_pp"]))


if __name__ == "__main__":
    main()
