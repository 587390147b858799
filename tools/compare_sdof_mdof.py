#!/usr/bin/python3
"""When is an SDOF enough? (issue 25 §6, docs/sdof-vs-mdof.md) Compares two results files of the same study, one
run with SDOF buildings (the paper's model) and one with shear buildings ([structures] model = "shear"), e.g.
studies/stochastic-pounding.toml and studies/stochastic-pounding-storeys.toml.

Refuses (exit 2, one ERROR line) unless the two files hold the same records (id, source, step, length, PGA,
polarity) and the same sampled structures (every /models dataset, exactly: periods, heights, masses, damping,
yield, code gaps), the same seed and gap ratios, the first file SDOF buildings only and the second at least
one shear building.

Prints (Markdown):
  - Table 3 side by side: per gap ratio the models with at least one impact and the probability of each model
    (counted as `pounding report` counts them: uncoupled peak closing D > x d over the analyses with status 0),
    the difference MDOF - SDOF in percentage points and the ratio, the analyses that touch in one model only
    (over the analyses valid in both), and a first-mode reading of the SDOF: D_SDOF x Gamma1 phi1,roof (the
    roof of the building's first mode, uniform shear building of equal floor masses);
  - the T1 x T2 matrix of the difference at one gap ratio, its extremes and the median ratio of the peak
    closings D_MDOF / D_SDOF per period pair.
The gap ratio of the matrix and the map defaults to the SDOF study's 10 % advice point (the exact order statistic
of the report's "Separation advice" table: the smallest x that at most floor(0.1 n) analyses exceed); any x > 0
may be given, since D answers every gap.
Figures (--figure PREFIX): PREFIX-map.png, the T1 x T2 map of MDOF - SDOF (diverging colour map, labelled colour
bar), and PREFIX-curves.png, the probability against the gap ratio of both models (continuous curves from D);
200 dpi PNG plus each --format (svg, pdf).
Usage: tools/compare_sdof_mdof.py SDOF.h5 MDOF.h5 [--ratio X] [--figure PREFIX] [--format svg ...]"""
import argparse
import math
import sys
import textwrap

import h5py
import numpy as np

DPI = 200
ADVICE_TARGET = 0.10
# the closing ratio D_MDOF / D_SDOF is taken where the SDOF closes by more than 1 % of the code gap: two SDOFs of
# one period move together until one yields (D ~ 1e-15 m), which makes the ratio meaningless there
RATIO_FLOOR = 0.01


def fail(what, where, fix):
    print(f" ERROR: {what}, {where}, {fix}", file=sys.stderr)
    sys.exit(2)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def load(path, option):
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail(f"cannot read the results file {path!r} ({e})", option, "give a results file written by pounding run")
    need = ["uncoupled/peak_closing", "uncoupled/status", "models/code_gap", "models/i1", "models/i2",
            "models/periods1", "models/periods2", "gaps/ratios", "records/id", "settings/structures"]
    for n in need:
        if n not in f:
            fail(f"{path!r} has no /{n} (not a grid study's results file)", option,
                 "give the results of a study with a period grid (studies/stochastic-pounding*.toml)")
    s = f["settings"]
    models = []
    for b in ("structures.building1", "structures.building2"):
        models.append(text(s[b].attrs.get("model", "sdof")) if b in s else "sdof")
    return {
        "path": path, "f": f, "models": models,
        "D": f["uncoupled/peak_closing"][()], "status": f["uncoupled/status"][()],
        "d": f["models/code_gap"][()], "i1": f["models/i1"][()], "i2": f["models/i2"][()],
        "p1": f["models/periods1"][()], "p2": f["models/periods2"][()], "ratios": f["gaps/ratios"][()],
        "seed": f.attrs.get("seed"), "title": text(f.attrs.get("title", "")),
        "commit": text(f.attrs.get("git_commit", "")), "wall": f.attrs.get("wall_time_s"),
        "ranks": f.attrs.get("ranks"), "substeps": f.attrs.get("substeps"),
        "storey_height": [float(s[b].attrs.get("storey_height", 3.2)) for b in
                          ("structures.building1", "structures.building2")],
        "profile": [text(s[b].attrs.get("stiffness_profile", "uniform")) for b in
                    ("structures.building1", "structures.building2")],
    }


def same(a, b):
    if a.shape != b.shape:
        return False, f"shape {list(a.shape)} against {list(b.shape)}"
    if a.dtype.kind == "f":
        eq = (a == b) | (np.isnan(a) & np.isnan(b))
    else:
        eq = a == b
    if eq.all():
        return True, ""
    k = int(np.flatnonzero(~eq.reshape(-1))[0])
    return False, f"entry {k}: {a.reshape(-1)[k]!r} against {b.reshape(-1)[k]!r}"


def check_shared(S, M):
    """Refuses two files that are not the same records and samples; returns the names of what was compared."""
    where = f"{S['path']} against {M['path']}"
    fix = "run both studies from the same file apart from [structures] model (same seed, [records], [structures] sampling keys)"
    if any(m != "sdof" for m in S["models"]):
        fail(f"the first file {S['path']!r} has shear buildings (model {S['models']})", "argument SDOF.h5",
             "give the SDOF study's results first and the shear study's second")
    if all(m == "sdof" for m in M["models"]):
        fail(f"the second file {M['path']!r} has SDOF buildings only", "argument MDOF.h5",
             "give the results of the study run with [structures] model = \"shear\" second")
    if S["seed"] != M["seed"]:
        fail(f"the seeds differ ({S['seed']} against {M['seed']})", where, fix)
    ok, why = same(S["ratios"], M["ratios"])
    if not ok:
        fail(f"the gap ratios differ (/gaps/ratios {why})", where, "give both studies the same [gaps] ratios")
    compared = {"models": [], "records": []}
    for group in ("models", "records"):
        a, b = S["f"][group], M["f"][group]
        if set(a.keys()) != set(b.keys()):
            fail(f"/{group} holds different datasets ({sorted(set(a.keys()) ^ set(b.keys()))})", where, fix)
        for k in sorted(a.keys()):
            if not isinstance(a[k], h5py.Dataset):
                continue
            ok, why = same(a[k][()], b[k][()])
            if not ok:
                what = "sampled structures" if group == "models" else "records"
                fail(f"the two results do not share their {what}: /{group}/{k} differs ({why})", where, fix)
            compared[group].append(k)
    if S["D"].shape != M["D"].shape:
        fail(f"/uncoupled/peak_closing has shape {list(S['D'].shape)} against {list(M['D'].shape)}", where, fix)
    return compared


def gamma_phi_roof(n):
    """Gamma1 phi1,roof of a uniform shear building of n equal floors and n equal storeys (M = I, K tridiagonal)."""
    if n <= 1:
        return 1.0
    K = 2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    K[-1, -1] = 1.0
    w, v = np.linalg.eigh(K)
    phi = v[:, 0]
    return float(phi.sum() / (phi @ phi) * phi[-1])


def first_mode_factor(S, M):
    """Per model the mean over the two buildings of Gamma1 phi1,roof of the shear building each sample becomes
    (storeys max(1, round(h / storey_height)), uniform profile); None unless both buildings are uniform shear."""
    if M["models"] != ["shear", "shear"] or M["profile"] != ["uniform", "uniform"]:
        return None
    f = M["f"]["models"]
    cache = {}
    out = np.zeros(len(M["d"]))
    for b, h in enumerate((f["h1"][()], f["h2"][()])):
        n = np.maximum(1, np.rint(h / M["storey_height"][b]).astype(int))
        for k in set(n.tolist()):
            cache.setdefault(k, gamma_phi_roof(k))
        out += np.array([cache[k] for k in n]) / 2
    return out


def advice_point(X, ok, target):
    """The smallest gap ratio that at most floor(target n) of the n valid analyses exceed (report's definition)."""
    x = np.sort(X[ok])[::-1]
    k = int(math.floor(target * len(x) + 1e-9))
    return float(x[k]) if k < len(x) else 0.0


def pct(k, n):
    return 100.0 * k / n if n else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sdof", metavar="SDOF.h5")
    ap.add_argument("mdof", metavar="MDOF.h5")
    ap.add_argument("--ratio", type=float, help="gap ratio x of the matrix and the map (default: the SDOF 10 %% advice point)")
    ap.add_argument("--figure", metavar="PREFIX", help="write PREFIX-map.png and PREFIX-curves.png")
    ap.add_argument("--format", nargs="*", default=[], help="extra figure formats (svg, pdf)")
    a = ap.parse_args()
    if a.ratio is not None and not (a.ratio > 0 and math.isfinite(a.ratio) and a.ratio <= 10):
        fail(f"--ratio {a.ratio} is not a gap ratio", "--ratio", "give a ratio x in (0, 10] of the code gap d")
    for fmt in a.format:
        if fmt not in ("svg", "pdf", "png"):
            fail(f"unknown figure format {fmt!r}", "--format", "give svg, pdf or png")
    S, M = load(a.sdof, "argument SDOF.h5"), load(a.mdof, "argument MDOF.h5")
    compared = check_shared(S, M)

    R = S["D"].shape[0]
    d = S["d"][None, :]
    okS, okM = S["status"] == 0, M["status"] == 0
    both = okS & okM
    XS, XM = S["D"] / d, M["D"] / d  # peak closing in units of the code gap: touches at x exactly when X > x
    gf = first_mode_factor(S, M)
    XF = XS * gf[None, :] if gf is not None else None
    x_adv = advice_point(XS, okS, ADVICE_TARGET)
    x = a.ratio if a.ratio is not None else round(x_adv, 3)  # as the report prints it
    p1, p2 = S["p1"], S["p2"]
    out = print

    out(f"# SDOF against shear buildings: {S['title']}\n")
    out(f"- SDOF: `{S['path']}` (commit {S['commit'][:12]}, {S['ranks']} rank(s), {S['wall']:.1f} s, substeps {S['substeps']})")
    out(f"- MDOF: `{M['path']}` (commit {M['commit'][:12]}, {M['ranks']} rank(s), {M['wall']:.1f} s, substeps {M['substeps']};"
        f" building models {M['models'][0]}, {M['models'][1]})")
    out(f"- samples: identical -- {len(compared['models'])} datasets of /models ({len(S['d'])} models: "
        f"{', '.join(compared['models'])}) and {len(compared['records'])} of /records ({R} records) compared exactly; seed {S['seed']}")
    out(f"- analyses: {okS.sum()} valid of {okS.size} (SDOF), {okM.sum()} of {okM.size} (MDOF), {both.sum()} valid in both\n")

    out("## Table 3 side by side: probability of at least one impact\n")
    out("Counted as `pounding report` counts Table 3 (uncoupled peak closing D > x d, analyses with status 0). "
        "Only MDOF / only SDOF: analyses (valid in both) that touch in one model and not the other. SDOF x Gamma phi_roof: "
        "the SDOF's closing scaled by the first mode's roof participation of the shear buildings (mean of the two).\n")
    out("| gap ratio | SDOF impacts | SDOF | MDOF impacts | MDOF | MDOF - SDOF (pp) | MDOF / SDOF | only MDOF | only SDOF | SDOF x Gamma phi_roof |")
    out("|---|---|---|---|---|---|---|---|---|---|")
    for r in S["ratios"]:
        hs, ns = int((XS[okS] > r).sum()), int(okS.sum())
        hm, nm = int((XM[okM] > r).sum()), int(okM.sum())
        ps, pm = pct(hs, ns), pct(hm, nm)
        onlyM = int(((XM > r) & ~(XS > r) & both).sum())
        onlyS = int(((XS > r) & ~(XM > r) & both).sum())
        ratio = f"{pm / ps:.2f}" if ps > 0 else "-"
        first = f"{pct(int((XF[okS] > r).sum()), ns):.2f}%" if XF is not None else "-"
        out(f"| {r:g} | {hs} / {ns} | {ps:.2f}% | {hm} / {nm} | {pm:.2f}% | {pm - ps:+.2f} | {ratio} | {onlyM} | {onlyS} | {first} |")

    # per period pair
    nP1, nP2 = len(p1), len(p2)
    PS, PM, Q = np.full((nP1, nP2), np.nan), np.full((nP1, nP2), np.nan), np.full((nP1, nP2), np.nan)
    for i in range(nP1):
        for j in range(nP2):
            sel = ((S["i1"] == i) & (S["i2"] == j))[None, :]
            if not sel.any():
                continue
            s_ok, m_ok = sel & okS, sel & okM
            PS[i, j] = pct(int((XS[s_ok] > x).sum()), int(s_ok.sum()))
            PM[i, j] = pct(int((XM[m_ok] > x).sum()), int(m_ok.sum()))
            bb = sel & both & (XS > RATIO_FLOOR)
            if bb.any():
                Q[i, j] = float(np.median(M["D"][bb] / S["D"][bb]))
    diff = PM - PS
    how = "the SDOF study's 10 % advice point" if a.ratio is None else "--ratio"
    out(f"\n## MDOF - SDOF by period pair at gap ratio x = {x:.3f} ({how}), percentage points (rows T1, columns T2)\n")
    out("| T1 \\ T2 |" + "".join(f" {T:.2f} |" for T in p2))
    out("|---|" + "---|" * nP2)
    for i in range(nP1):
        out(f"| {p1[i]:.2f} |" + "".join(f" {v:+.1f} |" if np.isfinite(v) else " - |" for v in diff[i]))
    hs, ns = int((XS[okS] > x).sum()), int(okS.sum())
    hm, nm = int((XM[okM] > x).sum()), int(okM.sum())
    out(f"\nAt x = {x:.3f}: SDOF {pct(hs, ns):.2f}%, MDOF {pct(hm, nm):.2f}% ({pct(hm, nm) - pct(hs, ns):+.2f} pp).")
    if np.isfinite(diff).any():
        lo = np.unravel_index(np.nanargmin(diff), diff.shape)
        hi = np.unravel_index(np.nanargmax(diff), diff.shape)
        out(f"Largest over-estimate by the SDOF: T1 {p1[lo[0]]:.2f} s, T2 {p2[lo[1]]:.2f} s, {diff[lo]:+.1f} pp "
            f"(SDOF {PS[lo]:.1f}%, MDOF {PM[lo]:.1f}%).")
        out(f"Largest under-estimate by the SDOF: T1 {p1[hi[0]]:.2f} s, T2 {p2[hi[1]]:.2f} s, {diff[hi]:+.1f} pp "
            f"(SDOF {PS[hi]:.1f}%, MDOF {PM[hi]:.1f}%).")
        out(f"Period pairs where the MDOF is higher / lower / equal: {int((diff > 0).sum())} / {int((diff < 0).sum())} / "
            f"{int((diff == 0).sum())} of {int(np.isfinite(diff).sum())}.")
    out("\n## Median peak closing D_MDOF / D_SDOF by period pair (rows T1, columns T2; analyses with D_SDOF > 0.01 d)\n")
    out("| T1 \\ T2 |" + "".join(f" {T:.2f} |" for T in p2))
    out("|---|" + "---|" * nP2)
    for i in range(nP1):
        out(f"| {p1[i]:.2f} |" + "".join(f" {v:.2f} |" if np.isfinite(v) else " - |" for v in Q[i]))
    bb = both & (XS > RATIO_FLOOR)
    if bb.any():
        q = M["D"][bb] / S["D"][bb]
        out(f"\nOver all analyses with D_SDOF > 0.01 d: median D_MDOF / D_SDOF {np.median(q):.3f} (10-90 %: {np.quantile(q, 0.1):.3f}-"
            f"{np.quantile(q, 0.9):.3f})" + (f"; mean Gamma1 phi1,roof of the shear buildings {gf.mean():.3f} "
                                             f"({gf.min():.3f}-{gf.max():.3f})." if gf is not None else "."))
    if a.figure:
        figures(a, S, M, x, how, diff, XS, XM, okS, okM, XF)


def figures(a, S, M, x, how, diff, XS, XM, okS, okM, XF):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def save(fig, base):
        names = [base + ".png"]
        fig.savefig(names[0], dpi=DPI)
        for ext in a.format:
            if ext != "png":
                names.append(base + "." + ext)
                fig.savefig(names[-1], dpi=DPI)
        plt.close(fig)
        for n in names:
            print(f"figure: {n}")

    p1, p2 = S["p1"], S["p2"]

    def edges(p):
        if len(p) == 1:
            return np.array([p[0] - 0.05, p[0] + 0.05])
        mid = (p[1:] + p[:-1]) / 2
        return np.concatenate([[2 * p[0] - mid[0]], mid, [2 * p[-1] - mid[-1]]])

    R, N = S["D"].shape
    title = textwrap.fill(f"Shear buildings minus SDOFs: probability of pounding at gap {x:.3f} d "
                          f"({R} records, {N:,} models per record)", 60)
    fig, ax = plt.subplots(figsize=(6.4, 5.4), layout="constrained")
    vmax = max(5.0, 5.0 * math.ceil(np.nanmax(np.abs(diff)) / 5.0)) if np.isfinite(diff).any() else 5.0
    mesh = ax.pcolormesh(edges(p2), edges(p1), diff, cmap="RdBu_r", vmin=-vmax, vmax=vmax, shading="flat")
    cb = fig.colorbar(mesh, ax=ax)
    cb.set_label("MDOF − SDOF probability (percentage points)\nred: the SDOF under-estimates")
    ax.set_xlabel("T2, period of building 2 (s)")
    ax.set_ylabel("T1, period of building 1 (s)")
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=10)
    save(fig, a.figure + "-map")

    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    xs = np.linspace(0.0, max(1.0, float(S["ratios"].max())), 201)
    for X, ok, label, style in ((XS, okS, "SDOF (the paper's model)", "-"), (XM, okM, "shear buildings", "--")):
        v = np.sort(X[ok])
        ax.plot(xs, 100.0 * (1.0 - np.searchsorted(v, xs, side="right") / len(v)), style, lw=2, label=label)
    if XF is not None:
        v = np.sort(XF[okS])
        ax.plot(xs, 100.0 * (1.0 - np.searchsorted(v, xs, side="right") / len(v)), ":", lw=1.5,
                label="SDOF × Γ₁φ₁,roof")
    ax.axvline(x, color="0.5", lw=0.8)
    ax.set_xlabel("gap ratio x (gap = x d, d = Standard 2800's code gap)")
    ax.set_ylabel("probability of at least one impact (%)")
    ax.set_ylim(0, 100)
    ax.set_xlim(xs[0], xs[-1])
    ax.legend(loc="upper right")
    ax.set_title(textwrap.fill(f"Probability of pounding: SDOFs and shear buildings, same samples (grey: x = {x:.3f})", 60),
                 fontsize=10)
    save(fig, a.figure + "-curves")


if __name__ == "__main__":
    main()
