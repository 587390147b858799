#!/usr/bin/env python3
"""Plot response spectra written by `pounding records spectrum` with the suite's mean, like Fig. 4 of
stochastic-pounding-monte-carlo.txt (5 %-damped elastic pseudo-acceleration spectra and their mean).

    pounding records spectrum --suite default --records-dir ../shared/records/real -o suite.csv
    tools/plot_spectra.py suite.csv -o suite.png [--normalize] [--logx]

Real records are drawn solid, synthetic stand-ins dashed (the CSV's `#kind` row says which); the mean
(arithmetic, as in the paper) is thick black, the mean +- one standard deviation shaded.

A selection written by `pounding records select ... -o selection.csv` (detected from its header
`period_s,target_g,mean_g,...`) is drawn as the target (thick), each scaled record (thin), the mean of the
scaled records (thick black), the rule's line (90 % or 100 % of the target, dashed) and the period range
(shaded); --loglog for logarithmic axes:

    pounding records select --asce7 1.0,0.6,8 --period 1.0 --directory ../shared/records/real -o sel.csv
    tools/plot_spectra.py sel.csv -o sel.png --loglog

A results file (.h5) of a study with [records] select = N and [target_spectrum] is drawn the same way from its
/selection group (target, each chosen record scaled by f_i F, their mean, the rule's line); h5py reads it:

    pounding run studies/fragility-select.toml && tools/plot_spectra.py fragility-select.h5 -o sel.png --loglog
"""
import argparse
import csv
import sys

import numpy as np


def read_csv(path):
    names, kinds, rows, quantity = None, None, [], "psa"
    with open(path, newline="") as f:
        for row in csv.reader(f):
            if not row:
                continue
            if row[0].startswith("# "):
                quantity = row[0][2:].split()[0]
            elif row[0] == "#kind":
                kinds = row[1:]
            elif row[0] == "period_s":
                names = row[1:]
            elif not row[0].startswith("#"):
                rows.append([float(x) for x in row])
    if names is None or not rows:
        sys.exit(f"{path}: not a `pounding records spectrum` CSV (no period_s header or no rows)")
    data = np.array(rows)
    return quantity, names, kinds or ["real"] * len(names), data[:, 0], data[:, 1:]


def read_selection(path):
    """The "# key: value" header and the table of a `records select` CSV, or None for another CSV."""
    meta, header, rows = {}, None, []
    with open(path, newline="") as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("# ") and ": " in line:
                key, value = line[2:].split(": ", 1)
                meta[key] = value
            elif line.startswith("period_s,"):
                header = line.split(",")
            elif line and not line.startswith("#") and header is not None:
                rows.append([float(x) for x in line.split(",")])
    if header is None or header[1:3] != ["target_g", "mean_g"]:
        return None
    if not rows:
        sys.exit(f"{path}: a `records select` CSV without rows")
    return meta, header[3:], np.array(rows)


def is_hdf5(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89HDF\r\n\x1a\n"


def read_results_selection(path):
    """The /selection group of a results file as read_selection() returns a CSV: (meta, names, table)."""
    import h5py

    with h5py.File(path, "r") as f:
        if "selection" not in f:
            sys.exit(f"{path}: a results file without /selection (the study has no [records] select = N)")
        g = f["selection"]
        at = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
        names = [x.decode() if isinstance(x, bytes) else str(x) for x in g["records"][()]]
        periods, target, mean = g["periods"][()], g["target"][()], g["mean"][()]
        spectra = g["spectra"][()]  # [records, periods], scaled by f_i F
    meta = {"rule": str(at["rule_text"]), "rule_fraction": str(at["rule_fraction"]),
            "range_s": f"{at['t_min']} {at['t_max']}", "suite_factor": str(at["suite_factor"]),
            "condition_holds": "yes" if int(at["meets"]) else "no", "target": str(at["target_description"])}
    return meta, names, np.column_stack([periods, target, mean, spectra.T])


def wrap(title, fig, share=1.0, fontsize=10):
    """The title broken into lines that fit `share` of the figure's width (a long one was clipped)."""
    import textwrap

    return "\n".join(textwrap.fill(line, max(20, int(share * fig.get_figwidth() * 72 / (0.55 * fontsize))))
                     for line in title.split("\n"))


def plain_log_ticks(axis):
    """Numbers at 1, 2 and 5 of every decade (0.1, 0.2, 0.5, 1, 2, 5 g), none at the minor ticks: on the few
    decades a spectrum spans, decade labels alone left Sa above 1 g without a number."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def plot_selection(a, meta, names, data, plt):
    T, target, mean, S = data[:, 0], data[:, 1], data[:, 2], data[:, 3:]
    fig, ax = plt.subplots(figsize=(11, 5.5))
    for j in range(S.shape[1]):  # each record named (the legend beside the axes)
        name = names[j] if j < len(names) else f"record {j + 1}"
        ax.plot(T, S[:, j], lw=0.8, alpha=0.7, color=plt.cm.tab20(j % 20), label=name)
    ax.plot(T, target, color="tab:red", lw=3, label="target")
    ax.plot(T, mean, color="k", lw=2.5, label=f"mean of {S.shape[1]} scaled")
    frac = float(meta.get("rule_fraction", "0"))
    if frac > 0:
        ax.plot(T, frac * target, color="tab:red", lw=1.5, ls="--", label=f"{frac * 100:g} % of the target")
    if "range_s" in meta:
        lo, hi = (float(x) for x in meta["range_s"].split())
        ax.axvspan(lo, hi, color="tab:orange", alpha=0.1, label=f"period range {lo:g}-{hi:g} s")
    if a.loglog:
        ax.set_xscale("log")
        ax.set_yscale("log")
        plain_log_ticks(ax.xaxis)
        plain_log_ticks(ax.yaxis)
    elif a.logx:
        ax.set_xscale("log")
        plain_log_ticks(ax.xaxis)
    ax.set_xlabel("period T (s)")
    ax.set_ylabel("pseudo-acceleration Sa (g)")
    ax.set_title(a.title or wrap(f"{meta.get('rule', 'selection')}", fig, 0.6, 9) +
                 f"\nsuite factor {float(meta.get('suite_factor', 1)):.3f}, "
                 f"condition holds: {meta.get('condition_holds', '?')}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              ncol=2 if S.shape[1] > 16 else 1)
    fig.tight_layout()
    fig.savefig(a.output, dpi=150)
    print(f"wrote {a.output}: selection of {S.shape[1]} records, min mean/target {np.min(mean / target):.4f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="a `records spectrum` or `records select` CSV, or a results file with /selection")
    ap.add_argument("-o", "--output", default="spectra.png")
    ap.add_argument("--normalize", action="store_true", help="divide each spectrum by its value at T = 0 (PGA)")
    ap.add_argument("--logx", action="store_true", help="logarithmic period axis")
    ap.add_argument("--loglog", action="store_true", help="logarithmic period and Sa axes (selection CSVs)")
    ap.add_argument("--title", default="")
    a = ap.parse_args()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    selection = read_results_selection(a.csv) if is_hdf5(a.csv) else read_selection(a.csv)
    if selection is not None:
        plot_selection(a, *selection, plt)
        return
    quantity, names, kinds, T, S = read_csv(a.csv)
    unit = {"psa": "g", "psv": "m/s", "sd": "m"}.get(quantity, "")
    if a.normalize:
        if T[0] != 0:
            sys.exit("--normalize needs the T = 0 row (PGA) in the CSV")
        S = S / S[0, :]
    keep = T > 0 if a.logx else np.ones_like(T, dtype=bool)
    fig, ax = plt.subplots(figsize=(11, 5.5))
    named = len(names) <= 30  # a suite of up to 30 records is named record by record in the legend
    for j, (n, k) in enumerate(zip(names, kinds)):
        ax.plot(T[keep], S[keep, j], lw=0.8, alpha=0.6, ls="--" if k == "synthetic" else "-",
                color=plt.cm.tab20(j % 20) if named else ("tab:blue" if k == "synthetic" else "tab:red"),
                label=n if named else None)
    mean, sd = S.mean(axis=1), S.std(axis=1, ddof=1) if S.shape[1] > 1 else np.zeros(len(T))
    ax.fill_between(T[keep], (mean - sd)[keep], (mean + sd)[keep], color="k", alpha=0.12, label="mean ± 1 sd")
    ax.plot(T[keep], mean[keep], color="k", lw=2.5, label=f"mean of {S.shape[1]}")
    nsyn = sum(k == "synthetic" for k in kinds)
    ax.plot([], [], color="0.3", label=f"real ({len(kinds) - nsyn}, solid)")
    ax.plot([], [], color="0.3", ls="--", label=f"synthetic ({nsyn}, dashed)")
    if a.logx:
        ax.set_xscale("log")
        plain_log_ticks(ax.xaxis)
    ax.set_xlabel("period T (s)")
    label = {"psa": "pseudo-acceleration", "psv": "pseudo-velocity", "sd": "deformation"}.get(quantity, quantity)
    ax.set_ylabel(f"{label} / PGA" if a.normalize else f"{label} ({unit})")
    ax.set_title(a.title or wrap(f"5 %-damped elastic spectra ({a.csv})", fig, 0.6), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6 if named else 8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              ncol=2 if named and len(names) > 15 else 1)
    fig.tight_layout()
    fig.savefig(a.output, dpi=150)
    print(f"wrote {a.output}: {S.shape[1]} spectra ({nsyn} synthetic), peak mean {mean.max():.3f} at T = {T[mean.argmax()]:.3g} s")


if __name__ == "__main__":
    main()
