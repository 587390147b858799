#!/usr/bin/python3
"""Plots of a fragility study (a study with [intensity], optionally [hazard]): reads the results file with h5py
only -- the engine is not needed. Debian's python3-numpy, python3-h5py and python3-matplotlib.
  <prefix>-fragility.png  per gap, P(pound | IM = x) = Phi(ln(x / theta) / beta) over the IM, the observed fractions
                          z / n at the stripes with 95 % Wilson intervals, and the curves at theta_lo and theta_hi
                          (beta fixed; the bootstrap interval of theta, NOT a band for the curve). Gaps whose fit is
                          not ok show the observed points only, marked "(no fit: status)".
  <prefix>-fit.png        goodness of fit: observed fraction versus fitted P at every (gap, stripe), 1:1 line
  <prefix>-rate.png       (when /hazard exists) annual rate of pounding and P(pounding in `years`) versus the
                          separation (metres for a pair study, ratio of d otherwise): the rate-versus-separation
                          curve, the per-gap rates with their bootstrap intervals, the target line and the
                          risk-targeted separation with its interval; beside it the hazard curve, log-log
Every figure: PNG at 200 dpi, plus each --format given (svg, pdf).
Usage: tools/plot_fragility.py RESULTS.h5 [-o out/study] [--format svg pdf] [--gaps 0.5 1.0] [--linear]"""
import argparse
import math
import textwrap
import os
import sys

PROG = "plot_fragility.py"
try:
    import h5py
    import matplotlib
    import matplotlib.lines
    import matplotlib.patches
    import matplotlib.ticker

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as e:  # a clear line instead of a traceback
    raise SystemExit(f"{PROG}: {sys.executable} lacks {e.name} (Debian: apt-get install python3-numpy python3-h5py "
                     "python3-matplotlib; tools/setup.sh installs them)")

DPI = 200
Z95 = 1.959963984540054


def wilson(k, n, z=Z95):
    """95 % Wilson score interval of k in n, clipped to [0, k/n] and [k/n, 1] (as tools/plot_study.py: in floating
    point the bounds can land a few ulp on the wrong side of k/n, a negative error bar matplotlib rejects)."""
    k = np.asarray(k, float)
    n = np.asarray(n, float)
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return np.minimum(np.maximum(centre - half, 0.0), p), np.maximum(np.minimum(centre + half, 1.0), p)


def phi(u):
    return 0.5 * (1.0 + np.vectorize(math.erf)(np.asarray(u, float) / math.sqrt(2.0)))


def lognormal_cdf(x, theta, beta):
    """P(pound | IM = x) = Phi(ln(x / theta) / beta); beta = 0 is the step at theta."""
    x = np.asarray(x, float)
    if beta <= 0:
        return (x >= theta).astype(float)
    return phi(np.log(x / theta) / beta)


def save(fig, base, formats):
    """base.png at 200 dpi plus base.<ext> for each extra format; returns the names written."""
    names = [base + ".png"]
    fig.savefig(names[0], dpi=DPI)
    for ext in formats:
        if ext != "png":
            names.append(base + "." + ext)
            fig.savefig(names[-1], dpi=DPI)
    plt.close(fig)
    return names


def text(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.size == 1:
        return text(v.item())
    return str(v)


def open_results(path):
    """The file, or exit non-zero naming it and what to run."""
    if not os.path.exists(path):
        raise SystemExit(f"{PROG}: {path}: no such file; make it with `pounding run STUDY.toml --out {path}` "
                         "(a study with an [intensity] section, e.g. studies/fragility-pair.toml)")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise SystemExit(f"{PROG}: {path}: not a readable HDF5 results file ({e}); make it with `pounding run`")
    if "fragility" not in f:
        f.close()
        raise SystemExit(f"{PROG}: {path} has no /fragility group: it is not a fragility study. Run a study with an "
                         "[intensity] section (stripes of an intensity measure), e.g. `pounding run "
                         "studies/fragility-pair.toml`, and plot that; for other studies use tools/plot_study.py")
    return f


class Fragility:
    """The /fragility and /intensity datasets the figures need, and the gap labels."""

    def __init__(self, f):
        g = f["fragility"]
        self.gaps = g["gaps"][()]
        self.gaps_m = g["gaps_m"][()] if "gaps_m" in g else np.full(self.gaps.shape, np.nan)
        self.pair = bool(np.all(np.isfinite(self.gaps_m)))
        self.levels = g["levels"][()]
        self.theta, self.beta = g["theta"][()], g["beta"][()]
        self.theta_lo, self.theta_hi = g["theta_lo"][()], g["theta_hi"][()]
        self.beta_lo, self.beta_hi = g["beta_lo"][()], g["beta_hi"][()]
        self.status = [text(s) for s in g["status"][()]]
        self.note = [text(s) for s in g["note"][()]] if "note" in g else [""] * len(self.gaps)
        self.n, self.z = g["observed_n"][()], g["observed_z"][()]
        self.fitted = g["fitted"][()]
        self.confidence = float(g.attrs.get("confidence", 0.95))
        method = text(g.attrs.get("method", "msa"))
        self.ida = text(g.attrs.get("ida", "")) if method == "ida" else ""
        self.fit_words = {"": "maximum likelihood over the stripes",
                          "linear": "IDA capacities of a linear pair, by moments",
                          "bisection": "bisection-IDA capacities, by moments"}.get(self.ida, "IDA capacities")
        self.replicates = int(g.attrs.get("replicates", 0))
        it = f["intensity"].attrs if "intensity" in f else {}
        self.units = text(it.get("units", g.attrs.get("im_units", "")))
        self.im_label = text(it.get("description", text(it.get("measure", "IM")) + ", " + self.units))
        self.measure = text(it.get("measure", "IM"))

    def label(self, i):
        if self.pair:
            return f"{self.gaps[i]:g} d = {self.gaps_m[i]:.3f} m"
        return f"{self.gaps[i]:g} d"

    def chosen(self, wanted):
        """Indices of the --gaps (ratios of d), all gaps without it; exits naming the gaps there are."""
        if not wanted:
            return list(range(len(self.gaps)))
        out = []
        for w in wanted:
            hit = np.flatnonzero(np.isclose(self.gaps, w, rtol=1e-9, atol=1e-9))
            if hit.size == 0:
                have = " ".join(f"{x:g}" for x in self.gaps)
                raise SystemExit(f"{PROG}: --gaps {w:g} is not a gap of this study (its gaps, ratios of d: {have})")
            out.append(int(hit[0]))
        return out


def im_axis(fr, log):
    top = fr.levels.max()
    ok = np.isfinite(fr.theta)
    if ok.any():  # show the medians of the fitted curves, but never more than 4x past the last stripe
        top = max(top, min(1.5 * np.nanmax(fr.theta[ok]), 4 * fr.levels.max()))
    lo = fr.levels.min() / 2 if log else 0.0
    x = np.geomspace(fr.levels.min() / 2, top * 1.25, 400) if log else np.linspace(1e-6 * top, top * 1.25, 400)
    return x, lo, top * 1.25


def plot_fragility(fr, sel, a, prefix, title):
    ncol = 1 if len(sel) == 1 else (2 if len(sel) in (2, 4) else 3)
    nrow = math.ceil(len(sel) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(max(4.2 * ncol + 0.6, 9.0), 3.4 * nrow + (1.6 if ncol == 3 else 2.2)), sharex=True, sharey=True,
                             squeeze=False)
    x, xlo, xhi = im_axis(fr, not a.linear)
    lmin, lmax = fr.levels.min(), fr.levels.max()
    x = np.unique(np.concatenate([x, [lmin, lmax]]))
    conf = f"{100 * fr.confidence:g} %"
    for k, i in enumerate(sel):
        ax = axes[k // ncol][k % ncol]
        n, z = fr.n[i], fr.z[i]
        has = n > 0  # a stripe every record of which was dropped has no observation
        p = np.where(has, z / np.maximum(n, 1), np.nan)
        lo, hi = wilson(z[has], n[has])
        ok = fr.status[i] == "ok" and np.isfinite(fr.theta[i]) and np.isfinite(fr.beta[i])
        if ok:
            # within the stripes the fit is drawn in full; below and above them it is an extrapolation, drawn
            # faint over a grey band (legend: "beyond the stripes")
            inside = (x >= lmin) & (x <= lmax)
            for part, style in ((inside, dict(lw=2, alpha=1.0)), (x <= lmin, dict(lw=1.5, alpha=0.45)),
                                (x >= lmax, dict(lw=1.5, alpha=0.45))):
                gid = None if part is inside else "extrapolated"
                ax.plot(x[part], lognormal_cdf(x[part], fr.theta[i], fr.beta[i]), "C0", gid=gid, **style)
                if np.isfinite(fr.theta_lo[i]) and np.isfinite(fr.theta_hi[i]):
                    thin = dict(lw=1, alpha=style["alpha"])
                    ax.plot(x[part], lognormal_cdf(x[part], fr.theta_lo[i], fr.beta[i]), "C0", ls="--", gid=gid, **thin)
                    ax.plot(x[part], lognormal_cdf(x[part], fr.theta_hi[i], fr.beta[i]), "C0", ls=":", gid=gid, **thin)
            ax.text(0.03, 0.96, f"theta = {fr.theta[i]:.3g} {fr.units} [{fr.theta_lo[i]:.3g}, {fr.theta_hi[i]:.3g}]\n"
                    f"beta = {fr.beta[i]:.2f} [{fr.beta_lo[i]:.2f}, {fr.beta_hi[i]:.2f}]", transform=ax.transAxes,
                    ha="left", va="top", fontsize=7,
                    bbox=dict(facecolor="white", edgecolor="0.8", alpha=0.85, pad=2))
            head = fr.label(i)
        else:
            head = f"{fr.label(i)}  (no fit: {fr.status[i]})"
            ax.text(0.03, 0.96, f"no fit: {fr.status[i]}\n{fr.note[i]}", transform=ax.transAxes, ha="left",
                    va="top", fontsize=7, color="C3")
        ax.errorbar(fr.levels[has], p[has], yerr=[p[has] - lo, hi - p[has]], fmt="o", color="C3", ms=4, capsize=2)
        ax.set_title(head, fontsize=9)
        ax.set_xscale("linear" if a.linear else "log")
        ax.set_xlim(xlo, xhi)
        for span in ((xlo, lmin), (lmax, xhi)):
            if span[1] > span[0]:
                ax.axvspan(*span, color="0.88", alpha=0.6, lw=0, zorder=0, gid="beyond-stripes")
        ax.tick_params(labelbottom=True, labelleft=True, labelsize=8)  # numbers on every panel, shared or not
        if not a.linear:
            ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
            ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3, which="both")
    handles = [
        matplotlib.lines.Line2D([], [], color="C0", lw=2,
                                label=f"fitted lognormal ({fr.fit_words}), theta [and beta] "
                                      f"with their {conf} bootstrap intervals"),
        matplotlib.lines.Line2D([], [], color="C0", lw=1, ls="--",
                                label="same beta at theta_lo (dashed) ..."),
        matplotlib.lines.Line2D([], [], color="C0", lw=1, ls=":",
                                label=f"... and at theta_hi (dotted): the {conf} bootstrap interval of theta only, "
                                      "NOT a confidence band of the curve"),
        matplotlib.patches.Patch(color="0.88", alpha=0.6,
                                 label=f"beyond the stripes ({lmin:g}-{lmax:g} {fr.units}): the fit extrapolated, "
                                       "drawn faint"),
        matplotlib.lines.Line2D([], [], color="C3", marker="o", ls="none", ms=4,
                                label="observed z / n at each stripe, 95 % Wilson interval (analyses taken as independent; the "
                                      "models of one record are not, so it is too narrow)"),
    ]
    fig.legend(handles=handles, loc="lower center", ncol=2 if ncol == 3 else 1, fontsize=7, frameon=False)
    for k in range(len(sel), nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    for k in range(max(0, len(sel) - ncol), len(sel)):  # the lowest visible panel of each column
        axes[k // ncol][k % ncol].set_xlabel(textwrap.fill(fr.im_label, 48), fontsize=8)
    for row in axes:
        row[0].set_ylabel("P(pounding | IM)")
    fig.suptitle(f"{title}\nfragility per gap: P = Phi(ln(x / theta) / beta)" + ("" if fr.pair else
                 " (gaps as ratios of each model's code gap d)"), fontsize=9)
    fig.tight_layout(rect=(0, 0.07 if ncol == 3 and nrow > 1 else (0.12 if ncol == 3 else 0.36 / (1 + nrow)), 1, 1))
    return save(fig, prefix + "-fragility", a.format)


def plot_fit(fr, sel, a, prefix, title):
    fig, ax = plt.subplots(figsize=(6, 6))
    outside = total = 0
    for c, i in enumerate(sel):
        has = (fr.n[i] > 0) & np.isfinite(fr.fitted[i])
        if fr.status[i] != "ok" or not has.any():
            continue
        n, z, fit = fr.n[i][has], fr.z[i][has], fr.fitted[i][has]
        p = z / n
        lo, hi = wilson(z, n)
        outside += int(np.sum((fit < lo) | (fit > hi)))
        total += int(has.sum())
        ax.errorbar(fit, p, yerr=[p - lo, hi - p], fmt="o", ms=4, capsize=2, color=f"C{c % 10}", label=fr.label(i))
    ax.plot([0, 1], [0, 1], "k-", lw=1, label="1:1")
    ax.set_xlim(-0.02, 1.02)
    ax.set_ylim(-0.02, 1.02)
    ax.set_aspect("equal")
    ax.set_xlabel("fitted P(pounding | IM) at the stripe")
    ax.set_ylabel("observed fraction z / n (95 % Wilson interval)")
    ax.set_title(f"{title}\nobserved versus fitted at every (gap, stripe): the fitted P lies outside the Wilson "
                 f"interval at {outside} of {total}\n(Wilson treats the n analyses as independent; the models of one "
                 "record are not, so the true intervals are wider)", fontsize=7)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    return save(fig, prefix + "-fit", a.format)


def plot_rate(f, fr, sel, a, prefix, title):
    h = f["hazard"]
    at = h.attrs
    years = float(at["years"])
    target = float(at["target_percent"])
    lam = float(at["lambda_target"])
    rate, rlo, rhi = h["annual_rate"][()], h["rate_lo"][()], h["rate_hi"][()]
    prob, plo, phi_ = h["probability"][()], h["probability_lo"][()], h["probability_hi"][()]
    cg, cr, cp = h["curve_gap"][()], h["curve_rate"][()], h["curve_probability"][()]
    if fr.pair:
        d = float(np.median(fr.gaps_m / fr.gaps))
        xs, cx, unit = fr.gaps_m, cg * d, "m"
        xlabel = f"separation between the buildings (m); d = {d:.3f} m"
        tg, tlo, thi = (float(at.get(k, np.nan)) for k in ("target_gap_m", "target_gap_m_lo", "target_gap_m_hi"))
        jlo, jhi, adv = (float(at.get(k, np.nan)) for k in ("target_gap_m_jack_lo", "target_gap_m_jack_hi",
                                                             "target_gap_m_advice"))
    else:
        xs, cx, unit = fr.gaps, cg, "d"
        xlabel = "gap as a ratio of each model's code gap d"
        tg, tlo, thi = (float(at.get(k, np.nan)) for k in ("target_gap", "target_gap_lo", "target_gap_hi"))
        jlo, jhi, adv = (float(at.get(k, np.nan)) for k in ("target_gap_jack_lo", "target_gap_jack_hi",
                                                             "target_gap_advice"))
    status = text(at.get("target_status", ""))
    conf = f"{100 * fr.confidence:g} %"

    fig = plt.figure(figsize=(12, 7.5))
    gs = fig.add_gridspec(2, 3)
    ax_r = fig.add_subplot(gs[0, :2])
    ax_p = fig.add_subplot(gs[1, :2], sharex=ax_r)
    ax_h = fig.add_subplot(gs[:, 2])
    ax_r.plot(cx, cr, "C0", lw=1.5,
              label="rate at the study's gaps, ln-linear between them (bisection IDA)" if fr.ida == "bisection"
              else "rate versus separation (fragility refitted at each gap, point estimate)")
    ax_p.plot(cx, 100 * cp, "C0", lw=1.5, label=f"P(pounding in {years:g} years) = 1 - exp(-rate {years:g})")
    s = np.array(sel)
    ax_r.errorbar(xs[s], rate[s], yerr=[rate[s] - rlo[s], rhi[s] - rate[s]], fmt="o", color="C3", capsize=3,
                  label=f"the study's gaps, {conf} bootstrap interval over records")
    ax_p.errorbar(xs[s], 100 * prob[s], yerr=[100 * (prob[s] - plo[s]), 100 * (phi_[s] - prob[s])], fmt="o",
                  color="C3", capsize=3, label=f"the study's gaps, {conf} bootstrap interval")
    if "rate_jack_hi" in h:  # files written before the jackknife have none
        jl, jh = h["rate_jack_lo"][()][s], h["rate_jack_hi"][()][s]
        pjl, pjh = h["probability_jack_lo"][()][s], h["probability_jack_hi"][()][s]
        ok = np.isfinite(jl) & np.isfinite(jh)
        dx = 0.012 * (cx.max() if len(cx) else xs.max())  # beside the bootstrap bars
        ax_r.errorbar(xs[s][ok] + dx, rate[s][ok], yerr=[rate[s][ok] - jl[ok], jh[ok] - rate[s][ok]], fmt="none",
                      ecolor="C1", capsize=3, label=f"{conf} jackknife interval over records")
        ax_p.errorbar(xs[s][ok] + dx, 100 * prob[s][ok], yerr=[100 * (prob[s][ok] - pjl[ok]), 100 * (pjh[ok] - prob[s][ok])],
                      fmt="none", ecolor="C1", capsize=3, label=f"{conf} jackknife interval")
    tlabel = f"{target:g} % in {years:g} years"
    ax_r.axhline(lam, color="k", ls="--", lw=1, label=f"{tlabel}: lambda = {lam:.3g} per year")
    ax_p.axhline(target, color="k", ls="--", lw=1, label=tlabel)
    if status == "ok" and np.isfinite(tg):
        for ax in (ax_r, ax_p):
            if np.isfinite(tlo) and np.isfinite(thi):
                ax.axvspan(tlo, thi, color="C2", alpha=0.2,
                           label=f"bootstrap {conf} interval [{tlo:.3g}, {thi:.3g}] {unit}" if ax is ax_r else None)
            ax.axvline(tg, color="C2", lw=1.5,
                       label=f"risk-targeted separation {tg:.3g} {unit} ({tlabel})" if ax is ax_r else None)
            if np.isfinite(jhi):  # files written before the jackknife have none
                ax.axvline(jlo, color="C2", ls=":", lw=1.2,
                           label=f"jackknife {conf} interval [{jlo:.3g}, {jhi:.3g}] {unit}" if ax is ax_r else None)
                ax.axvline(jhi, color="C2", ls=":", lw=1.2)
            if np.isfinite(adv):
                ax.axvline(adv, color="C1", ls="--", lw=1.5,
                           label=f"advice: at least {adv:.3g} {unit} (the larger upper end)" if ax is ax_r else None)
        head = f"risk-targeted separation for {tlabel}: {tg:.3g} {unit}, {conf} interval [{tlo:.3g}, {thi:.3g}]"
        if np.isfinite(adv):
            head += f", advice {adv:.3g} {unit}"
    else:
        head = f"no risk-targeted separation ({status}: {text(at.get('target_note', ''))})"
    ax_r.set_yscale("log")
    ax_r.set_ylabel("annual rate of pounding (1/year)")
    ax_r.set_title(f"{title}\n{head}", fontsize=8)
    ax_r.grid(alpha=0.3, which="both")
    ax_r.legend(fontsize=6.5, loc="upper right")
    ax_p.set_ylabel(f"P(pounding in {years:g} years) (%)")
    ax_p.set_xlabel(xlabel)
    ax_p.set_yscale("log")
    pos = np.concatenate([cp[cp > 0], plo[s][plo[s] > 0], [target / 100]])
    ax_p.set_ylim(max(100 * pos.min() / 2, 1e-4), 150)
    ax_p.set_xlim(0, max(cx.max(), 1.04 * xs.max()))  # the largest gap's marker and bar in view
    ax_p.grid(alpha=0.3, which="both")
    ax_p.legend(fontsize=6.5, loc="upper right")

    im, hr = h["im"][()], h["rate"][()]
    ax_h.loglog(im, hr, "k.-", lw=1, ms=3, label="hazard curve used")
    ax_h.axhline(lam, color="k", ls="--", lw=1, label=tlabel)
    ax_h.axvspan(fr.levels.min(), fr.levels.max(), color="C3", alpha=0.12, label="the stripes' IM range")
    ax_h.set_xlabel(textwrap.fill(fr.im_label, 40))
    ax_h.set_ylabel("annual rate of exceedance (1/year)")
    src = text(at.get("source", ""))
    ax_h.set_title("site hazard" + (f"\n{src[:60]}{'...' if len(src) > 60 else ''}" if src else ""), fontsize=7)
    ax_h.grid(alpha=0.3, which="both")
    ax_h.legend(fontsize=6.5, loc="lower left")
    fig.tight_layout()
    return save(fig, prefix + "-rate", a.format)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("results", help="results file of a study with [intensity] (pounding run)")
    ap.add_argument("-o", "--prefix", default=None, help="output prefix (default: the results file without .h5)")
    ap.add_argument("--format", nargs="+", default=[], choices=["png", "svg", "pdf"],
                    help="extra formats besides the 200 dpi PNG (always written)")
    ap.add_argument("--gaps", nargs="+", type=float, default=None,
                    help="plot only these gaps (ratios of d, as in the study's [gaps] ratios)")
    ap.add_argument("--linear", action="store_true", help="linear IM axis (default: log)")
    a = ap.parse_args()
    prefix = a.prefix or (a.results[:-3] if a.results.endswith(".h5") else a.results)
    if os.path.dirname(prefix):
        os.makedirs(os.path.dirname(prefix), exist_ok=True)
    with open_results(a.results) as f:
        fr = Fragility(f)
        sel = fr.chosen(a.gaps)
        title = text(f.attrs.get("title", os.path.basename(a.results)))
        written = plot_fragility(fr, sel, a, prefix, title)
        written += plot_fit(fr, sel, a, prefix, title)
        if "hazard" in f:
            written += plot_rate(f, fr, sel, a, prefix, title)
    print(*written)


if __name__ == "__main__":
    main()
