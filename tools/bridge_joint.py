#!/usr/bin/env python3
"""The bridge paper's five spatial-variation cases (issue 26 section 2, studies/bridge-joint): probability of
pounding at one expansion joint versus the gap, with spatially varying and with uniform input, side by side.

Runs `pounding motions` for the five cases of Lindsay et al. (2011) (../shared/research/seeds-models.md 1.5):
  1 D-high, 2 D-medium, 3 D-low (soft soil, high/medium/low coherency loss), 4 C-high, 5 A-high;
  2 supports 100 m apart, apparent velocity 500 m/s, Sobczyk coherency (our choice: the paper names no model),
  NZS 1170.5 spectra with Z R = 0.7 (the paper's "PGA 0.7 g", read as the standard's cap on Z R; Z = 0.5, R = 1.4),
  20 realisations per case (seeds 1..5, one per case),
then, for two elastic SDOF spans (span k on support k, period T_k, damping zeta; default the prototype's
0.98 Hz segment for both), the total displacement x_k = u_k + u_gk (u_k the response to support k's record, exact
for a piecewise-linear record: scipy.signal.cont2discrete 'foh'; u_gk the ground displacement, integrated from the
baseline-corrected record) and the joint closing delta(t) = x_1 - x_2 (the paper's u1 - u2 - g_p with g_p = 0).
Pounding at gap g: max delta > g -- the UNCOUPLED criterion the engine's studies count (peak closing of the
analysis without contact). Uniform input: both spans on support 1's record.

NOT the coupled bridge analysis: no contact, restrainers, bearings or abutments. With --study STUDY.toml (a bridge
study on two supports, e.g. studies/bridge-joint.toml) every case is also run COUPLED through the study runner
(`pounding run`, [records] directory = the case's folder, supports = 2 in place of the study's [records.motions];
uniform input: the same study without `support = 2`), and the table gains the study's answers beside this script's: the median peak closing (the study's
/uncoupled/peak_closing, its central-difference run of the same segments) and the gap for P = 10 % (the same
definition, np.quantile(closing, 0.9)), the largest relative difference of the per-realisation closings, and the
study's mean joint impact count at the gap for P = 10 %.

  bridge_joint.py --pounding build/pounding --out DIR [--realisations 20] [--period1 1.0204 --period2 1.0204]
                  [--zeta 0.05] [--gaps 0,0.01,...] [--study studies/bridge-joint.toml]
writes DIR/bridge-joint.csv (case, gap_m, p_svgm, p_uniform, n) and DIR/bridge-joint.md (the table, the gap for a
10 % probability of pounding in each case, the settings); prints the Markdown.
"""
import argparse
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_spatial import read_set  # noqa: E402  (the AT2/MANIFEST reader of the independent check)

CASES = [("1 D-high", "D", "high"), ("2 D-medium", "D", "medium"), ("3 D-low", "D", "low"),
         ("4 C-high", "C", "high"), ("5 A-high", "A", "high")]


def sdof_relative(acc, dt, period, zeta):
    """u(t) of u'' + 2 zeta w u' + w^2 u = -ag for every row of acc (R x n), exact for ag linear between samples."""
    from scipy import signal
    w = 2 * np.pi / period
    A = np.array([[0.0, 1.0], [-w * w, -2 * zeta * w]])
    B = np.array([[0.0], [-1.0]])
    Ad, Bd, Cd, Dd, _ = signal.cont2discrete((A, B, np.array([[1.0, 0.0]]), np.zeros((1, 1))), dt, method="foh")
    x = np.zeros((2, acc.shape[0]))
    u = np.zeros_like(acc)
    for k in range(acc.shape[1]):
        a = acc[:, k]
        u[:, k] = (Cd @ x)[0] + Dd[0, 0] * a
        x = Ad @ x + Bd * a
    return u


def ground_displacement(acc, dt):
    """u_g with the acceleration linear between samples (the integrals of records.hpp)."""
    v = np.zeros_like(acc)
    d = np.zeros_like(acc)
    for k in range(acc.shape[1] - 1):
        d[:, k + 1] = d[:, k] + dt * v[:, k] + dt * dt * (acc[:, k] / 3 + acc[:, k + 1] / 6)
        v[:, k + 1] = v[:, k] + dt * (acc[:, k] + acc[:, k + 1]) / 2
    return d


def peak_closing(a1, a2, dt, t1, t2, zeta):
    x1 = sdof_relative(a1, dt, t1, zeta) + ground_displacement(a1, dt)
    x2 = sdof_relative(a2, dt, t2, zeta) + ground_displacement(a2, dt)
    return np.max(x1 - x2, axis=1)


def run_study(pounding, study, folder, out, uniform):
    """The bridge study on the case's folder (absolute), SVGM or uniform; its /uncoupled/peak_closing per realisation
    (recorded sign), the impact counts [R, G] and the gap axis (m)."""
    import h5py
    text = open(study).read()
    lines, table = [], ""
    for line in text.splitlines():
        if line.startswith("["):
            table = line.strip()
        if table == "[records.motions]":  # the study's own generator gives way to the case's folder
            continue
        if table == "[records]" and (line.startswith("directory = ") or line.startswith("supports = ")):
            continue
        if uniform and line.strip() == "support = 2":
            continue
        lines.append(line)
        if line.strip() == "[records]":
            lines += [f'directory = "{os.path.abspath(folder)}"', "supports = 2"]
    path = out + (".uniform" if uniform else ".svgm")
    with open(path + ".toml", "w") as f:
        f.write("\n".join(lines) + "\n")
    subprocess.run([pounding, "run", path + ".toml", "--out", path + ".h5", "--quiet", "--force"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    h = h5py.File(path + ".h5", "r")
    D = h["uncoupled/peak_closing"][()][:, 0]
    gaps = None if "impacts" not in h else h["impacts/gap_axis"][()] if "impacts/gap_axis" in h else \
        h["impacts/gap_ratios"][()] * h["models/code_gap"][0]  # [gaps] metres: gap_axis is metres already
    count = h["impacts/impact_count"][()].reshape(len(D), -1) if "impacts" in h else None
    return D, count, gaps


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--pounding", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--realisations", type=int, default=20)
    p.add_argument("--period1", type=float, default=1 / 0.98)
    p.add_argument("--period2", type=float, default=1 / 0.98)
    p.add_argument("--zeta", type=float, default=0.05)
    p.add_argument("--gaps", default=",".join(f"{g:g}" for g in np.arange(0, 0.3001, 0.01)))
    p.add_argument("--z", type=float, default=0.5)
    p.add_argument("--r", type=float, default=1.4)
    p.add_argument("--study", help="a bridge study on two supports to run coupled per case (studies/bridge-joint.toml)")
    a = p.parse_args()
    gaps = np.array([float(x) for x in a.gaps.split(",")])
    os.makedirs(a.out, exist_ok=True)
    rows, summary, studies = [], [], []
    for i, (name, soil, loss) in enumerate(CASES):
        folder = os.path.join(a.out, name.replace(" ", "-"))
        if not os.path.exists(os.path.join(folder, "MANIFEST.tsv")):
            subprocess.run([a.pounding, "motions", "--supports", "2", "--spacing", "100", "--velocity", "500",
                            "--coherency", "sobczyk", "--loss", loss, "--spectrum", "nzs1170.5", "--soil", soil,
                            "--z", str(a.z), "--r", str(a.r), "--realisations", str(a.realisations),
                            "--seed", str(i + 1), "--label", name, "--quiet", "--out", folder], check=True,
                           stdout=subprocess.DEVNULL)
        dt, sets, _ = read_set(folder)
        a1 = np.array([sets[r][1] for r in sorted(sets)])
        a2 = np.array([sets[r][2] for r in sorted(sets)])
        svgm = peak_closing(a1, a2, dt, a.period1, a.period2, a.zeta)
        uniform = peak_closing(a1, a1, dt, a.period1, a.period2, a.zeta)
        n = len(svgm)
        for g in gaps:
            rows.append((name, g, float(np.mean(svgm > g)), float(np.mean(uniform > g)), n))
        summary.append((name, np.median(svgm), np.quantile(svgm, 0.9), np.median(uniform), np.quantile(uniform, 0.9)))
        if a.study:
            Ds, cs, gs = run_study(a.pounding, a.study, folder, os.path.join(a.out, name.replace(" ", "-")), False)
            Du, cu, _ = run_study(a.pounding, a.study, folder, os.path.join(a.out, name.replace(" ", "-")), True)
            rel = float(np.max(np.abs(Ds - svgm) / svgm))
            g10 = np.quantile(Ds, 0.9)
            k = int(np.argmin(np.abs(gs - g10))) if gs is not None else None
            imp = float(np.mean(cs[:, k][cs[:, k] > 0])) if k is not None and (cs[:, k] > 0).any() else 0.0
            studies.append((name, np.median(Ds), g10, np.median(Du), np.quantile(Du, 0.9), rel,
                            gs[k] if k is not None else float("nan"), imp))
    with open(os.path.join(a.out, "bridge-joint.csv"), "w") as f:
        f.write("case,gap_m,p_svgm,p_uniform,n\n")
        for r in rows:
            f.write(f"{r[0]},{r[1]:g},{r[2]:.4f},{r[3]:.4f},{r[4]}\n")
    md = [f"Two elastic spans, T1 = {a.period1:.4g} s, T2 = {a.period2:.4g} s, zeta = {a.zeta:g}; supports 100 m apart, "
          f"500 m/s, Sobczyk coherency, NZS 1170.5 Z = {a.z:g}, R = {a.r:g}; {a.realisations} realisations per case. "
          "Probability of pounding = share of realisations whose uncoupled peak joint closing exceeds the gap.", "",
          "| case | median peak closing, SVGM (mm) | gap for P = 10 %, SVGM (mm) | median, uniform (mm) | gap for P = 10 %, uniform (mm) |",
          "|---|---|---|---|---|"]
    for s in summary:
        md.append(f"| {s[0]} | {1e3 * s[1]:.1f} | {1e3 * s[2]:.1f} | {1e3 * s[3]:.1f} | {1e3 * s[4]:.1f} |")
    show = [g for g in gaps if abs(g * 1000 % 50) < 1e-6]
    md += ["", "| case | " + " | ".join(f"P at {1e3 * g:.0f} mm SVGM / uniform" for g in show) + " |",
           "|---|" + "---|" * len(show)]
    for name, *_ in CASES:
        cells = [f"{r[2]:.2f} / {r[3]:.2f}" for r in rows if r[0] == name and r[1] in show]
        md.append(f"| {name} | " + " | ".join(cells) + " |")
    if studies:
        md += ["", f"Coupled through the study runner ({a.study}: Hertzdamp joint, one record per support, the study's "
               "central-difference step), beside the uncoupled closing above:", "",
               "| case | median peak closing, study (mm) | gap for P = 10 %, study (mm) | median, uniform (mm) | "
               "gap for P = 10 %, uniform (mm) | largest rel. difference of the closings, study vs exact | mean "
               "impacts at the study gap nearest the 10 % gap (mm) |", "|---|---|---|---|---|---|---|"]
        for s_ in studies:
            md.append(f"| {s_[0]} | {1e3 * s_[1]:.1f} | {1e3 * s_[2]:.1f} | {1e3 * s_[3]:.1f} | {1e3 * s_[4]:.1f} | "
                      f"{s_[5]:.1e} | {s_[7]:.1f} at {1e3 * s_[6]:.0f} |")
    text = "\n".join(md) + "\n"
    with open(os.path.join(a.out, "bridge-joint.md"), "w") as f:
        f.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
