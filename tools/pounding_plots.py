#!/usr/bin/python3
"""The engine's figures, in one module (issue 29): tools/plot_study.py, tools/plot_fragility.py and
tools/plot_spectra.py are thin command lines over it, and the HTML report (`pounding report R.h5 --html`) runs

    /usr/bin/python3 tools/pounding_plots.py figures RESULTS.h5 --dir DIR [--report-csv CSV]

which writes every figure the results file holds as SVG into DIR and DIR/figures.tsv (one line per figure:
"ok<TAB>name<TAB>file<TAB>caption" or "left-out<TAB>name<TAB><TAB>why"):
  separation   (pair study) probability of at least one impact versus separation in metres, bootstrap band, code
               rules and the advice -- drawn from the engine's own report CSV, so figure and report agree
  probability  (grid study) probability versus gap ratio, Wilson intervals, cubic fit (and the paper's Table 3)
  periods      (grid study with a period grid) the T1 x T2 heat map at one gap ratio
  fragility, fit, rate   (study with [intensity]; rate with [hazard]) fragility curves with the stripes and the
               interval of theta, observed versus fitted, annual rate and probability versus separation beside the
               hazard curve
  selection    (study with [records] select) the chosen records' scaled spectra against the target
A figure that fails is listed as left out with its error; the others are still drawn. SVG text stays text
(svg.fonttype none) and every id is prefixed with the figure's name, so several figures can live in one page.
Debian's python3-numpy, python3-h5py and python3-matplotlib."""
import argparse
import csv
import io
import math
import os
import re
import shutil
import subprocess
import sys
import textwrap
import types

try:
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.lines
    import matplotlib.patches
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    import numpy as np
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
except ImportError as e:  # a clear line instead of a traceback (the HTML report shows it as the reason)
    raise SystemExit(f"pounding_plots.py: {sys.executable} lacks {e.name} (Debian: apt-get install python3-numpy "
                     "python3-h5py python3-matplotlib; tools/setup.sh installs them)")

PROG = "plot_fragility.py"  # the fragility messages name the command line they come from
DPI = 200
Z95 = 1.959963984540054


# ---- shared helpers ------------------------------------------------------------------------------------------

def wilson(k, n, z=Z95):
    """95 % Wilson score interval of k in n. Exactly, lo <= k/n <= hi, lo = 0 at k = 0 and hi = 1 at k = n; in
    floating point centre - half can land a few ulp above 0 (k = 0) or centre + half below 1 (k = n), which gave a
    negative error bar that matplotlib rejects -- so the bounds are clipped to [0, k/n] and [k/n, 1]."""
    k = np.asarray(k, float)
    n = np.asarray(n, float)
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return np.minimum(np.maximum(centre - half, 0.0), p), np.maximum(np.minimum(centre + half, 1.0), p)


def wilson_clustered(y, cluster, z=Z95):
    """95 % Wilson interval of a share whose 0/1 outcomes `y` come in clusters (`cluster`: one label per outcome, e.g.
    the record id: a record's two polarities and its models are not independent draws). The effective sample size is
    n / DEFF with Kish's design effect (Kish 1965, Survey Sampling §5.4; the effective-n Wilson interval of Korn &
    Graubard 1998) estimated from the cluster totals: DEFF = v_clu / v_srs, v_clu = C/(C-1) sum_c (y_c - p m_c)^2 /
    n^2 (the ratio estimator's variance with C clusters of m_c outcomes and y_c successes), v_srs = p (1 - p) / n;
    n_eff is clipped to [C, n] (DEFF between 1 and the mean cluster size), and is C when p is 0 or 1 (no variance to
    estimate a DEFF from: the conservative end). Returns lo, hi (Wilson at k = p n_eff of n_eff) and n_eff."""
    y = np.asarray(y, float)
    lab = np.asarray(cluster)
    n = y.size
    if n == 0:
        return 0.0, 1.0, 0.0
    keys, inv = np.unique(lab, return_inverse=True)
    C = keys.size
    p = y.mean()
    if 0.0 < p < 1.0 and C > 1:
        yc = np.bincount(inv, weights=y, minlength=C)
        mc = np.bincount(inv, minlength=C).astype(float)
        v_clu = C / (C - 1) * np.sum((yc - p * mc) ** 2) / (n * n)
        n_eff = float(np.clip(p * (1 - p) / v_clu if v_clu > 0 else n, C, n))
    else:
        n_eff = float(C)
    lo, hi = wilson(p * n_eff, n_eff, z)
    return float(lo), float(hi), n_eff


def phi(u):
    return 0.5 * (1.0 + np.vectorize(math.erf)(np.asarray(u, float) / math.sqrt(2.0)))


def save(fig, base, formats):
    """base.png at 200 dpi plus base.<ext> for each other format; returns the names written."""
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


attr_str = text


def wrap_title(title, fig, share=1.0, fontsize=10):
    """The title broken into lines that fit `share` of the figure's width (a long one was clipped on both sides)."""
    chars = max(20, int(share * fig.get_figwidth() * 72 / (0.55 * fontsize)))
    return "\n".join(textwrap.fill(line, chars) for line in title.split("\n"))


# ---- fragility studies (tools/plot_fragility.py) ----------------------------------------------------------

def lognormal_cdf(x, theta, beta):
    """P(pound | IM = x) = Phi(ln(x / theta) / beta); beta = 0 is the step at theta."""
    x = np.asarray(x, float)
    if beta <= 0:
        return (x >= theta).astype(float)
    return phi(np.log(x / theta) / beta)


def open_results(path):
    """The fragility study's file, or exit non-zero naming it and what to run."""
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
        self.metres = text(g.attrs.get("gap_units", "")) == "m"  # [gaps] metres: the gaps are metres
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
        if self.metres:
            return f"{self.gaps[i]:g} m"
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


def plot_fragility(fr, sel, a, title):
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
    fig.suptitle(f"{title}\nfragility per gap: P = Phi(ln(x / theta) / beta)" + ("" if fr.pair or fr.metres else
                 " (gaps as ratios of each model's code gap d)"), fontsize=9)
    fig.tight_layout(rect=(0, 0.07 if ncol == 3 and nrow > 1 else (0.12 if ncol == 3 else 0.36 / (1 + nrow)), 1, 1))
    return fig


def plot_fit(fr, sel, a, title):
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
    return fig


def interval_bars(ax, x, y, lo, hi, color, label):
    """Points with their interval drawn as it is: a bootstrap percentile interval need not contain the point
    estimate (a rate near its cap), which errorbar refuses ("'yerr' must not contain negative values"). y None: the
    interval alone."""
    x, lo, hi = np.asarray(x, float), np.asarray(lo, float), np.asarray(hi, float)
    ok = np.isfinite(lo) & np.isfinite(hi)
    ax.vlines(x[ok], lo[ok], hi[ok], color=color, lw=1.2, label=label if y is None else None)
    w = 0.006 * (np.nanmax(x) - np.nanmin(x) if len(x) > 1 else 1.0)
    ax.hlines(np.concatenate([lo[ok], hi[ok]]), np.concatenate([x[ok], x[ok]]) - w, np.concatenate([x[ok], x[ok]]) + w,
              color=color, lw=1.2)
    if y is not None:
        ax.plot(x, y, "o", color=color, label=label)


def plot_rate(f, fr, sel, a, title):
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
        xlabel = "separation between the buildings (m)" + ("" if fr.metres else f"; d = {d:.3f} m")
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
    interval_bars(ax_r, xs[s], rate[s], rlo[s], rhi[s], "C3", f"the study's gaps, {conf} bootstrap interval over records")
    interval_bars(ax_p, xs[s], 100 * prob[s], 100 * plo[s], 100 * phi_[s], "C3", f"the study's gaps, {conf} bootstrap interval")
    if "rate_jack_hi" in h:  # files written before the jackknife have none
        jl, jh = h["rate_jack_lo"][()][s], h["rate_jack_hi"][()][s]
        pjl, pjh = h["probability_jack_lo"][()][s], h["probability_jack_hi"][()][s]
        ok = np.isfinite(jl) & np.isfinite(jh)
        dx = 0.012 * (cx.max() if len(cx) else xs.max())  # beside the bootstrap bars
        interval_bars(ax_r, xs[s][ok] + dx, None, jl[ok], jh[ok], "C1", f"{conf} jackknife interval over records")
        interval_bars(ax_p, xs[s][ok] + dx, None, 100 * pjl[ok], 100 * pjh[ok], "C1", f"{conf} jackknife interval")
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
    ge = existing_gap(f)  # [gaps] existing: the as-built gap, where the axis is metres
    if ge is not None and unit == "m":
        for ax in (ax_r, ax_p):
            ax.axvline(ge, color="k", lw=2.0, ls="-.", gid="existing", label=f"existing {ge:g} m" if ax is ax_r else None)
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
    return fig


def main_fragility(argv=None, doc=""):
    ap = argparse.ArgumentParser(prog="plot_fragility.py", description=doc.split("\n", 1)[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=doc)
    ap.add_argument("results", help="results file of a study with [intensity] (pounding run)")
    ap.add_argument("-o", "--prefix", default=None, help="output prefix (default: the results file without .h5)")
    ap.add_argument("--format", nargs="+", default=[], choices=["png", "svg", "pdf"],
                    help="extra formats besides the 200 dpi PNG (always written)")
    ap.add_argument("--gaps", nargs="+", type=float, default=None,
                    help="plot only these gaps (ratios of d, as in the study's [gaps] ratios)")
    ap.add_argument("--linear", action="store_true", help="linear IM axis (default: log)")
    a = ap.parse_args(argv)
    prefix = a.prefix or (a.results[:-3] if a.results.endswith(".h5") else a.results)
    if os.path.dirname(prefix):
        os.makedirs(os.path.dirname(prefix), exist_ok=True)
    with open_results(a.results) as f:
        fr = Fragility(f)
        sel = fr.chosen(a.gaps)
        title = text(f.attrs.get("title", os.path.basename(a.results)))
        written = save(plot_fragility(fr, sel, a, title), prefix + "-fragility", a.format)
        written += save(plot_fit(fr, sel, a, title), prefix + "-fit", a.format)
        if "hazard" in f:
            written += save(plot_rate(f, fr, sel, a, title), prefix + "-rate", a.format)
    print(*written)



# ---- pair and grid studies (tools/plot_study.py) --------------------------------------------------------

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


def plot_pair(f, rows, source):
    """Probability of at least one impact versus separation in metres, from the rows of the engine's report CSV."""
    conf = float(f["settings/report"].attrs.get("confidence", 0.95)) if "settings/report" in f else 0.95
    band = [r for r in rows if r["table"] == "curve_band"]
    if not band:
        raise SystemExit(f"plot_study.py: the report of {source} has no curve_band rows; nothing to plot")
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
    # the codes' design displacements (rows code_design: ASCE 7-16, EC8 or Standard 2800 from the design spectrum)
    # dashed, and for shear buildings each rule's governing contact level (rows code_level, the largest over the
    # levels) dotted; gid "code_design" / "code_level" (tests/cli/plot_layout.py finds them)
    design = {}
    for r in rows:
        if r["table"] == "code_design":
            design.setdefault(round(float(r["gap_m"]), 6), [float(r["probability"]), []])[1].append(r["name"])
    for i, (gm, (prob, names)) in enumerate(sorted(design.items())):
        ax.axvline(gm, color=f"C{(2 + len(rules) + i) % 10}", lw=1.4, ls="--", alpha=0.9, gid="code_design",
                   label=textwrap.fill(" / ".join(names), 44) + f":\n  {gm:.3f} m, P = {100 * prob:.1f} %")
    governing = {}
    for r in rows:
        if r["table"] == "code_level":
            rule, _, level = r["name"].partition(" at ")
            if float(r["gap_m"]) > governing.get(rule, (-1.0, ""))[0]:
                governing[rule] = (float(r["gap_m"]), level)
    for i, (rule, (gm, level)) in enumerate(sorted(governing.items(), key=lambda kv: kv[1][0])):
        ax.axvline(gm, color=f"C{(2 + len(rules) + len(design) + i) % 10}", lw=1.4, ls=":", gid="code_level",
                   label=textwrap.fill(f"{rule}, governing contact {level}", 44) + f":\n  {gm:.3f} m")
    # [gaps] existing: the as-built gap (row "existing"), a black vertical line labelled with its metres
    existing = [r for r in rows if r["table"] == "existing"]
    for r in existing:
        ge = float(r["gap_m"])
        ax.axvline(ge, color="k", lw=2.0, ls="-.", gid="existing",
                   label=f"existing {ge:g} m: P = {100 * float(r['probability']):.1f} %")
    rules = {**rules, **{g: None for g in design}, **{g: None for g, _ in governing.values()},
             **{float(r["gap_m"]): None for r in existing}}  # x-axis extent

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
    # upper edge falls below 0.5 % (the curve runs on to the study's curve_max, far past the data). Advice or a code
    # rule beyond curve_max (an isolated building: advice 0.53-0.69 m on a curve to 0.40 m, issue 45 item 2) widens
    # the axis past the curve's end: the curve stops there, the advice and the rules stay in view with their labels.
    tail = g[hi >= 0.5]
    x_end = max([tail.max() if tail.size else g.max()] + ends + list(rules))
    ax.set_xlim(0, 1.15 * x_end if x_end > g.max() else min(g.max(), 1.15 * x_end))
    ax.set_ylim(0, 100)
    ax.set_xlabel("separation between the buildings (m)")
    ax.set_ylabel("probability of at least one impact (%)")
    ax.set_title(wrap_title(attr_str(f.attrs["title"]), fig, 0.62), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    return fig




def metres_axis(f):
    """[gaps] metres: the gap axis is metres (/gaps attribute unit = "m"), every model's gap the same."""
    return "gaps" in f and attr_str(f["gaps"].attrs.get("unit", "")) == "m"


def existing_gap(f):
    """[gaps] existing (m), or None."""
    g = f["settings/gaps"].attrs if "settings/gaps" in f else {}
    return float(g["existing"]) if "existing" in g else None


def grid_demands(f):
    """A grid study's peak closings, ok mask and gap units: (pc [records, models], ok, d [models]); d is each model's
    code gap, or 1 (m) on a metres axis ([gaps] metres), so that pc / d is the demand on the study's axis."""
    pc = f["uncoupled/peak_closing"][()]
    R, M = pc.shape
    ok = f["uncoupled/status"][()].reshape(R, M) == 0  # [records, models]; format 1 stored it flat
    d = f["models/code_gap"][()]
    return pc, ok, np.ones_like(d) if metres_axis(f) else d


def paper_compared(f):
    rep = f["settings/report"].attrs if "settings/report" in f else {}
    return "compare_with" not in rep or attr_str(rep["compare_with"]) == "stochastic-pounding"


def plot_probability(f, fit_min=0.1, fit_max=1.0, source=""):
    """A grid study's probability of at least one impact versus the gap ratio."""
    pc, ok, d = grid_demands(f)
    z = (pc / d[None, :])[ok]
    n = z.size
    if n == 0:
        raise SystemExit(f"plot_study.py: {source} has no valid analysis (all {pc.size} excluded); nothing to plot")
    metres = metres_axis(f)
    if metres:  # the axis, curve and fit range in metres (the study's own settings)
        top = float(f["settings/gaps"].attrs["curve_max"])
        rep = f["settings/report"].attrs
        fit_min, fit_max = float(rep["fit_min"]), float(rep["fit_max"])
    x = np.linspace(0.005, 1.5, 300) if not metres else np.linspace(top / 300, top, 300)
    zs = np.sort(z)
    p = 100.0 * (n - np.searchsorted(zs, x, side="right")) / n
    sel = (x >= fit_min - 1e-12) & (x <= fit_max + 1e-12)
    c = np.polyfit(x[sel], p[sel], 3)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(x, p, lw=2, label=f"this study, continuous (n = {n})")
    ax.plot(x[sel], np.polyval(c, x[sel]), "--", label="cubic fit: {:.1f}x³ {:+.1f}x² {:+.1f}x {:+.1f}".format(*c))
    paper_x = np.array([0.1, 0.2, 0.3, 0.5, 0.7, 1.0]) if not metres else f["gaps/axis"][()]
    if paper_compared(f) and not metres:
        ax.plot(paper_x, [71.09, 45.56, 25.26, 6.12, 1.14, 0.0], "ks", label="paper, Table 3")
        xx = np.linspace(0.1, 1.0, 100)
        ax.plot(xx, -213.7 * xx**3 + 510.3 * xx**2 - 403.4 * xx + 106.8, "k:", label="paper, eq. 10")
    for r in paper_x:
        k = int(np.sum(z > r))
        lo, hi = wilson(k, n)
        ax.errorbar([r], [100 * k / n], yerr=[[100 * (k / n - lo)], [100 * (hi - k / n)]], fmt="o", color="C3",
                    capsize=3)
    ge = existing_gap(f)
    if ge is not None and (metres or np.all(d == d[0])):  # on a ratio axis only where every model has one d
        xe = ge if metres else ge / d[0]
        k = int(np.sum(pc[ok] > ge))
        ax.axvline(xe, color="k", lw=2.0, ls="-.", gid="existing", label=f"existing {ge:g} m: P = {100 * k / n:.1f} %")
    ax.set_xlabel("gap g (m)" if metres else "gap ratio g / d  (d = 0.005 (h1 + h2))")
    ax.set_ylabel("probability of at least one impact (%)")
    ax.set_title(wrap_title(attr_str(f.attrs["title"]), fig), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def period_grids(f):
    """Each building its own grid (files before periods1/periods2: one grid for both)."""
    g = f["models"]
    p1 = g["periods1"][()] if "periods1" in g else g["periods"][()]
    p2 = g["periods2"][()] if "periods2" in g else g["periods"][()]
    return p1, p2


def plot_periods(f, ratio=0.3):
    """The T1 x T2 heat map of the probability of at least one impact at gap ratio `ratio`."""
    pc, ok, d = grid_demands(f)
    p1, p2 = period_grids(f)
    i1, i2 = f["models"]["i1"][()], f["models"]["i2"][()]
    if metres_axis(f):  # the axis' third gap (or its last) in metres, not a ratio
        axis = f["gaps/axis"][()]
        ratio = float(axis[min(2, len(axis) - 1)])
    hit = (pc > ratio * d[None, :]) & ok
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
    ax.set_title(f"gap {ratio:g} m" if metres_axis(f) else f"gap ratio {ratio}")
    fig.tight_layout()
    return fig


def impact_gaps(f):
    """The impacts scene's gap axis and the metres one unit of it is: ([gaps] ratios) /impacts/gap_ratios and model 0's
    code gap d (a bridge's reference gap); ([gaps] metres) /impacts/gap_axis and 1; (empty, d) without the scene."""
    d = f["models/code_gap"][()] if "models/code_gap" in f else np.array([])
    dref = float(d[0]) if d.size else float(f["settings/bridge"].attrs.get("reference_gap", 0.0)) \
        if "settings/bridge" in f else 1.0
    if "impacts/gap_axis" in f:
        return f["impacts/gap_axis"][()], 1.0
    return (f["impacts/gap_ratios"][()] if "impacts/gap_ratios" in f else np.array([])), dref


def is_bridge(f):
    return "settings/bridge" in f and "uncoupled/peak_closing_elements" in f and "system/element_label" in f


def joint_names(f):
    """ "joint 1 (F1|F2)": each joint's label with the frames either side (from /system)."""
    sysg = f["system"]
    labels = [text(x) for x in sysg["element_label"][()]]
    blab = [text(x) for x in sysg["building_label"][()]]
    dof_b = sysg["dof_building"][()]
    names = []
    for e, lab in enumerate(labels):
        sides = []
        for k in ("element_left_dof", "element_right_dof"):
            dof = int(sysg[k][e])
            sides.append(blab[dof_b[dof]] if 0 <= dof < len(dof_b) else "wall")
        names.append(f"{lab} ({sides[0]}|{sides[1]})")
    return names


def plot_bridge_joints(f, source=""):
    """A bridge study: the probability that each joint pounds versus its gap in metres -- the share of analyses
    whose uncoupled closing at that joint exceeds the gap (first passage: exact for a joint alone, as the study's
    own criterion is for the bridge) -- with the coupled runs' observed share at the study's gaps (the impacts
    scene, 95 % Wilson intervals clustered by record: wilson_clustered, a record's polarities and models one
    cluster), any joint at the study's joint gaps (reference gap + each joint's offset), and the
    report's targets."""
    el = f["uncoupled/peak_closing_elements"][()]  # [records, models, joints]
    R, M, J = el.shape
    ok = f["uncoupled/status"][()].reshape(R, M) == 0
    names = joint_names(f)
    offsets = np.asarray(f["settings/bridge"].attrs.get("joint_gap_offsets", np.zeros(J)), float).reshape(-1)
    if offsets.size != J:
        offsets = np.zeros(J)
    closing = el[ok]  # [analyses, joints]
    n = closing.shape[0]
    if n == 0:
        raise SystemExit(f"{source}: no valid analysis (all {R * M} excluded); nothing to plot")
    top = float(np.nanmax(closing)) if np.isfinite(closing).any() else 0.0
    ratios, dref = impact_gaps(f)
    top = max(top, float(np.max(ratios) * dref + offsets.max()) if ratios.size else 0.0)
    x = np.linspace(0.0, 1.05 * max(top, 1e-6), 400)
    fig, ax = plt.subplots(figsize=(8, 4.6))
    for j in range(J):
        c = np.sort(closing[:, j][np.isfinite(closing[:, j])])
        p = 100.0 * (n - np.searchsorted(c, x, side="right")) / n
        ax.plot(x, p, color=f"C{j}", lw=2, label=f"{names[j]}: uncoupled closing > gap", gid=f"joint-{j + 1}")
    D = np.max(closing - offsets[None, :], axis=1)
    Ds = np.sort(D)
    ax.plot(x, 100.0 * (n - np.searchsorted(Ds, x, side="right")) / n, color="k", lw=1.2, ls="--",
            label="any joint, joints at reference gap + offset", gid="any-joint")
    if "impacts/element_impact_count" in f and ratios.size:
        cnt = f["impacts/element_impact_count"][()]  # [records, models, gaps, joints]
        st = f["impacts/status"][()].reshape(R, M, len(ratios)) == 0
        # a record's analyses (both polarities, every model) are one cluster: record-clustered Wilson intervals
        rid = np.asarray(f["records/id"][()]) if "records/id" in f else np.arange(R)
        cl = np.repeat(rid.reshape(R, 1), M, axis=1)
        for j in range(J):
            for g, r in enumerate(ratios):
                okg = st[:, :, g]
                m = int(okg.sum())
                if m == 0:
                    continue
                hit = cnt[:, :, g, j][okg] > 0
                k = int(hit.sum())
                lo, hi, _ = wilson_clustered(hit, cl[okg])
                gap = r * dref + offsets[j]
                ax.errorbar([gap], [100.0 * k / m], yerr=[[100 * (k / m - lo)], [100 * (hi - k / m)]],
                            fmt="osD^v<>p"[j % 8], mfc="none", color=f"C{j}", ms=5, capsize=2, gid=f"coupled-{j + 1}",
                            label=f"{names[j]}: coupled runs, at least one impact" if g == 0 else None)
    rep = f["settings/report"].attrs if "settings/report" in f else {}
    for t in np.atleast_1d(rep.get("targets", [])):
        ax.axhline(float(t), color="0.5", lw=0.8, ls=":", label=f"target {float(t):g} %")
    ax.set_xlim(0.0, x[-1])
    ax.set_ylim(-2, 102)
    ax.set_xlabel("joint gap (m)")
    ax.set_ylabel("probability of pounding at the joint (%)")
    inp = bridge_input(f)
    ax.set_title(wrap_title(f"{text(f.attrs.get('title', ''))} ({inp}; n = {n} analyses)", fig, 0.62), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    return fig


def bridge_supports_used(f):
    """The supports a bridge study's frames and abutments stand on (their `support`, default 1), from the study text
    the file keeps; [records] supports groups the files but a study may still put every frame on support 1."""
    try:
        import tomllib
        b = tomllib.loads(text(f.attrs.get("study_text", ""))).get("bridge", {})
    except Exception:  # no text or no tomllib: the records' grouping
        sup = f["settings/records"].attrs.get("supports", 1) if "settings/records" in f else 1
        return set(range(1, int(sup) + 1))
    ab = b.get("abutment", {})
    return {int(x.get("support", 1)) for x in b.get("frame", []) + [ab.get(k, {}) for k in ab]} or {1}


def bridge_input(f):
    """ "uniform input" or "N supports, spatially varying input": a bridge file's input (bridge_supports_used)."""
    n = len(bridge_supports_used(f))
    return f"{n} supports, spatially varying input" if n > 1 else "uniform input"


def bridge_input_curves(f, x):
    """A bridge file's probability of pounding (any joint) versus the reference gap in metres x: the share of ok
    analyses whose uncoupled D (/uncoupled/peak_closing, the largest over the joints of closing - joint offset) exceeds
    x (first passage), and at the study's gaps the coupled runs' share with at least one impact with its 95 % Wilson
    interval clustered by record (wilson_clustered). Returns (p [%] at x, n, [(gap m, share %, lo %, hi %), ...])."""
    D = f["uncoupled/peak_closing"][()]
    R, M = D.shape
    ok = f["uncoupled/status"][()].reshape(R, M) == 0
    Ds = np.sort(D[ok])
    n = Ds.size
    p = 100.0 * (n - np.searchsorted(Ds, x, side="right")) / max(n, 1)
    bars = []
    if "impacts/impact_count" in f and ("impacts/gap_ratios" in f or "impacts/gap_axis" in f):
        ratios, dref = impact_gaps(f)
        cnt = f["impacts/impact_count"][()].reshape(R, M, len(ratios))
        st = f["impacts/status"][()].reshape(R, M, len(ratios)) == 0
        rid = np.asarray(f["records/id"][()]) if "records/id" in f else np.arange(R)
        cl = np.repeat(rid.reshape(R, 1), M, axis=1)
        for g, r in enumerate(ratios):
            okg = st[:, :, g] & ok
            if not okg.any():
                continue
            hit = cnt[:, :, g][okg] > 0
            lo, hi, _ = wilson_clustered(hit, cl[okg])
            bars.append((float(r * dref), 100.0 * hit.mean(), 100.0 * lo, 100.0 * hi))
    return p, n, bars


def plot_bridge_inputs(files, sources=()):
    """Uniform versus multi-support input (issue 26 §2: how much does spatial variation matter?): for each bridge
    results file (the same bridge and records, one per input), the probability that the bridge pounds at any joint
    versus the reference joint gap -- uncoupled first passage as a line, the coupled runs' share with an impact at the
    study's gaps with record-clustered Wilson 95 % bars -- in one figure."""
    top = 1e-6
    for f in files:
        D = f["uncoupled/peak_closing"][()]
        if np.isfinite(D).any():
            top = max(top, float(np.nanmax(D)))
        ratios, dref = impact_gaps(f)
        if ratios.size:
            top = max(top, float(np.max(ratios) * dref))
    x = np.linspace(0.0, 1.05 * top, 400)
    fig, ax = plt.subplots(figsize=(8, 4.6))
    for i, f in enumerate(files):
        p, n, bars = bridge_input_curves(f, x)
        name = bridge_input(f)
        ax.plot(x, p, color=f"C{i}", lw=2, label=f"{name}: uncoupled D > gap (n = {n})", gid=f"input-{i + 1}")
        for k, (g, share, lo, hi) in enumerate(bars):
            ax.errorbar([g], [share], yerr=[[share - lo], [hi - share]], fmt="os"[i % 2], mfc="none", color=f"C{i}",
                        ms=5, capsize=2, gid=f"input-{i + 1}-coupled",
                        label=f"{name}: coupled runs, at least one impact" if k == 0 else None)
    rep = files[0]["settings/report"].attrs if "settings/report" in files[0] else {}
    for t in np.atleast_1d(rep.get("targets", [])):
        ax.axhline(float(t), color="0.5", lw=0.8, ls=":", label=f"target {float(t):g} %")
    ax.set_xlim(0.0, x[-1])
    ax.set_ylim(-2, 102)
    ax.set_xlabel("reference joint gap (m; every joint at it plus its offset)")
    ax.set_ylabel("probability of pounding at any joint (%)")
    ax.set_title(wrap_title(f"{text(files[0].attrs.get('title', ''))}: uniform versus multi-support input", fig, 0.62),
                 fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    return fig


def is_pair(f):
    st = f["settings/structures"].attrs if "settings/structures" in f else {}
    return int(st.get("heights_specified", 0)) == 1


def main_study(argv=None, doc=""):
    ap = argparse.ArgumentParser(prog="plot_study.py", description=doc.split("\n", 1)[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=doc)
    ap.add_argument("results")
    ap.add_argument("--prefix", default=None)
    ap.add_argument("--ratio", type=float, default=0.3)
    ap.add_argument("--fit-min", type=float, default=0.1)
    ap.add_argument("--fit-max", type=float, default=1.0)
    ap.add_argument("--format", nargs="+", default=[], choices=["svg", "pdf"],
                    help="extra formats besides the 200 dpi PNG")
    ap.add_argument("--pounding", default=None, help="the pounding binary (pair studies run its report --csv)")
    ap.add_argument("--with", dest="others", action="append", default=[], metavar="RESULTS",
                    help="a bridge study: the same bridge under the other input (uniform or multi-support); adds "
                         "PREFIX-inputs.png, both inputs in one figure (repeatable)")
    a = ap.parse_args(argv)
    prefix = a.prefix or a.results.rsplit(".", 1)[0]
    f = h5py.File(a.results, "r")
    if is_pair(f):
        rows = report_rows(find_pounding(a.pounding), a.results)
        print(*save(plot_pair(f, rows, a.results), prefix + "-separation", a.format))
        return
    if is_bridge(f):
        written = save(plot_bridge_joints(f, a.results), prefix + "-joints", a.format)
        others = [h5py.File(o, "r") for o in a.others]
        if others:
            bad = [o for o, g in zip(a.others, others) if "settings/bridge" not in g]
            if bad:
                sys.exit(f"--with {bad[0]}: not a bridge study's results")
            written += save(plot_bridge_inputs([f] + others), prefix + "-inputs", a.format)
        print(*written)
        return
    written = save(plot_probability(f, a.fit_min, a.fit_max, a.results), prefix + "-probability", a.format)
    written += save(plot_periods(f, a.ratio), prefix + "-periods", a.format)
    print(*written)


# ---- spectra (tools/plot_spectra.py) -----------------------------------------------------------------

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


def plain_log_ticks(axis):
    """Numbers at 1, 2 and 5 of every decade (0.1, 0.2, 0.5, 1, 2, 5 g), none at the minor ticks: on the few
    decades a spectrum spans, decade labels alone left Sa above 1 g without a number."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def plot_selection(a, meta, names, data):
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
    ax.set_title(a.title or wrap_title(f"{meta.get('rule', 'selection')}", fig, 0.6, 9) +
                 f"\nsuite factor {float(meta.get('suite_factor', 1)):.3f}, "
                 f"condition holds: {meta.get('condition_holds', '?')}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              ncol=2 if S.shape[1] > 16 else 1)
    fig.tight_layout()
    return fig


def main_spectra(argv=None, doc=""):
    ap = argparse.ArgumentParser(prog="plot_spectra.py", description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="a `records spectrum` or `records select` CSV, or a results file with /selection")
    ap.add_argument("-o", "--output", default="spectra.png")
    ap.add_argument("--normalize", action="store_true", help="divide each spectrum by its value at T = 0 (PGA)")
    ap.add_argument("--logx", action="store_true", help="logarithmic period axis")
    ap.add_argument("--loglog", action="store_true", help="logarithmic period and Sa axes (selection CSVs)")
    ap.add_argument("--title", default="")
    a = ap.parse_args(argv)
    selection = read_results_selection(a.csv) if is_hdf5(a.csv) else read_selection(a.csv)
    if selection is not None:
        fig = plot_selection(a, *selection)
        fig.savefig(a.output, dpi=150)
        plt.close(fig)
        data = selection[2]
        print(f"wrote {a.output}: selection of {data.shape[1] - 3} records, min mean/target "
              f"{np.min(data[:, 2] / data[:, 1]):.4f}")
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
    ax.set_title(a.title or wrap_title(f"5 %-damped elastic spectra ({a.csv})", fig, 0.6), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6 if named else 8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              ncol=2 if named and len(names) > 15 else 1)
    fig.tight_layout()
    fig.savefig(a.output, dpi=150)
    print(f"wrote {a.output}: {S.shape[1]} spectra ({nsyn} synthetic), peak mean {mean.max():.3f} at T = {T[mean.argmax()]:.3g} s")




# ---- the HTML report's figures -------------------------------------------------------------------------------

def svg_text(fig, name):
    """The figure as an inline <svg> element: text kept as text, no XML prolog, every id prefixed with `name`."""
    buf = io.StringIO()
    buf.name = f"figure-{name}.svg"  # what a savefig hook sees (tests/cli/plot_layout.py names the figure by it)
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": name}):
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    s = buf.getvalue()
    s = s[s.index("<svg"):]
    ids = set(re.findall(r'\bid="([^"]+)"', s))
    s = re.sub(r'\bid="([^"]+)"', lambda m: f'id="{name}-{m.group(1)}"', s)
    s = re.sub(r'(href="#|url\(#)([^")]+)', lambda m: m.group(1) + (f"{name}-{m.group(2)}" if m.group(2) in ids
                                                                     else m.group(2)), s)
    return s.replace("<svg ", f'<svg role="img" aria-label="{name}" ', 1)


def read_report_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def figure_plan(f, path, report_csv, others=()):
    """(name, caption, function returning the figure) for every figure the file holds; `others`: open results files
    given beside it (figures --with: a bridge study's other input)."""
    title = text(f.attrs.get("title", os.path.basename(path)))
    plan = []
    if "fragility" in f:
        fr = Fragility(f)
        sel = fr.chosen(None)
        a = types.SimpleNamespace(linear=False, format=[])
        plan.append(("fragility", "Fragility per gap: the fitted lognormal within the stripes (faint beyond them, "
                     "over grey), the curves at the ends of theta's bootstrap interval, and the observed fraction at "
                     "each stripe with its Wilson interval.", lambda: plot_fragility(fr, sel, a, title)))
        plan.append(("fit", "Observed versus fitted probability at every gap and stripe.",
                     lambda: plot_fit(fr, sel, a, title)))
        if "hazard" in f:
            plan.append(("rate", "Annual rate and probability in the design life of pounding versus separation, the "
                         "risk-targeted separation with its intervals, and the site hazard curve.",
                         lambda: plot_rate(f, fr, sel, a, title)))
    elif is_pair(f):
        def pair():
            if not report_csv:
                raise RuntimeError("no report CSV given (--report-csv)")
            return plot_pair(f, read_report_csv(report_csv), path)
        plan.append(("separation", "Probability of at least one impact versus separation in metres, with the "
                     "bootstrap band over records and models, the code rules (legend) and the advised separation "
                     "at each target.", pair))
    elif is_bridge(f):
        plan.append(("joints", "Probability of pounding at each joint versus its gap in metres: the share of "
                     "analyses whose uncoupled closing at the joint exceeds the gap, the coupled runs' share with at "
                     "least one impact at the study's gaps (Wilson 95 % intervals clustered by record), any joint at "
                     "the study's joint gaps, and the report's targets.", lambda: plot_bridge_joints(f, path)))
        if others and all("settings/bridge" in g for g in others):  # (two SDOF frames on one support: format 2)
            plan.append(("inputs", "Uniform versus multi-support input: the probability that the bridge pounds at "
                         "any joint versus the reference joint gap, per input -- the uncoupled first passage as a "
                         "line, the coupled runs' share with an impact at the study's gaps with Wilson 95 % intervals "
                         "clustered by record.", lambda: plot_bridge_inputs([f] + list(others))))
    elif "uncoupled" in f:
        plan.append(("probability", "Probability of at least one impact versus the gap ratio x = g / d, with Wilson "
                     "intervals and the cubic fit.", lambda: plot_probability(f, source=path)))
        p1, p2 = period_grids(f)
        if len(p1) * len(p2) > 1:
            plan.append(("periods", "Probability of at least one impact at gap ratio 0.3 by period pair (T1 x T2).",
                         lambda: plot_periods(f, 0.3)))
    if "selection" in f:
        def selection():
            a = types.SimpleNamespace(loglog=True, logx=False, title="")
            return plot_selection(a, *read_results_selection(path))
        plan.append(("selection", "The selected records' spectra, scaled, against the design spectrum (target), "
                     "with their mean and the code's rule.", selection))
    return plan


def main_figures(argv=None):
    ap = argparse.ArgumentParser(prog="pounding_plots.py figures",
                                 description="every figure of a results file as SVG, for the HTML report")
    ap.add_argument("results")
    ap.add_argument("--dir", required=True, help="folder for the SVGs and figures.tsv (must exist)")
    ap.add_argument("--report-csv", default=None, help="`pounding report RESULTS --csv` (the pair figure's rows)")
    ap.add_argument("--with", dest="others", action="append", default=[], metavar="RESULTS",
                    help="a results file given beside it (a bridge study's other input: the 'inputs' figure)")
    a = ap.parse_args(argv)
    lines = []
    others = [h5py.File(o, "r") for o in a.others]
    with h5py.File(a.results, "r") as f:
        for name, caption, draw in figure_plan(f, a.results, a.report_csv, others):
            try:
                svg = svg_text(draw(), name)
            except (Exception, SystemExit) as e:  # one figure's failure leaves the others
                plt.close("all")
                why = " ".join(str(e).split()) or type(e).__name__
                lines.append(f"left-out\t{name}\t\t{type(e).__name__}: {why}")
                continue
            with open(os.path.join(a.dir, name + ".svg"), "w") as out:
                out.write(svg)
            lines.append(f"ok\t{name}\t{name}.svg\t{caption}")
    with open(os.path.join(a.dir, "figures.tsv"), "w") as out:
        out.write("".join(line + "\n" for line in lines))
    print(f"{len(lines)} figures: " + ", ".join(line.split("\t")[1] + (" (left out)" if not line.startswith("ok") else "")
                                               for line in lines))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "figures":
        main_figures(sys.argv[2:])
    else:
        raise SystemExit("usage: pounding_plots.py figures RESULTS.h5 --dir DIR [--report-csv CSV] "
                         "(tools/plot_study.py, plot_fragility.py, plot_spectra.py are the other command lines)")
