#!/usr/bin/python3
"""Runs one plotting tool (tools/plot_*.py) with its arguments and checks the layout of every figure it saves
(issue 23 item 9: figures a client can receive). Figure.savefig is replaced: each figure is drawn with Agg and
checked, not written (which halves the time; cli.plot_study and cli.plot_fragility check the written files):
  - every text (titles, axis labels, tick numbers, annotations, legend entries) lies inside the figure;
  - no two texts overlap;
  - every visible panel (colour bars aside) shows tick numbers on both axes;
  - --stripes LO,HI (fragility): a panel whose IM axis runs past the stripes marks it (a patch with gid
    "beyond-stripes"), and its full-weight curve (lw >= 2) stays within the stripes;
  - --pair-report CSV (pair separation): the x-axis ends near the data (at most 1.3 x the last of: the advised
    separations, the code rules, where the band's upper edge falls below 0.5 %), and each advice label
    "<t> %: <s> m" sits right beside its advised separation's point (s, t);
  - --names a,b,...: each record name appears in some text of the figure.
tools/pounding_plots.py figures (the HTML report's SVGs, drawn into buffers) is checked the same way.
Usage: plot_layout.py [--stripes LO,HI] [--pair-report CSV] [--names N1,N2] -- TOOL.py ARGS...
       plot_layout.py --jobs FILE   (many such checks in one process: one a line, arguments separated by \x1f)
Exits 1 listing every violation; prints one line per checked figure."""
import csv
import itertools
import os
import runpy
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import numpy as np  # noqa: E402

opts = {}
failures, checked = [], []
seen = set()


def parse(argv):
    """[--opt VALUE]... -- TOOL.py ARGS... -> (options, tool, its args)"""
    o = {}
    while argv and argv[0] != "--":
        o[argv[0]] = argv[1]
        argv = argv[2:]
    return o, argv[1], argv[2:]


def texts_of(fig):
    """(label for messages, Text, its axes or None) of every visible, non-empty text the reader sees, once each."""
    out, ids = [], set()
    ax = None

    def add(kind, t):
        if t is not None and id(t) not in ids and t.get_visible() and t.get_text().strip():
            ids.add(id(t))
            out.append((f"{kind} {t.get_text().strip()[:40]!r}", t, ax))

    for ax in fig.axes:
        if not ax.get_visible():
            continue
        for kind, t in (("title", ax.title), ("title", ax._left_title), ("title", ax._right_title),
                        ("x label", ax.xaxis.label), ("y label", ax.yaxis.label)):
            add(kind, t)
        for t in ax.texts:
            add("text", t)
        lo, hi = sorted(ax.get_xlim())
        for t in ax.xaxis.get_ticklabels(which="both"):
            if lo <= t.get_position()[0] <= hi:
                add("x tick", t)
        lo, hi = sorted(ax.get_ylim())
        for t in ax.yaxis.get_ticklabels(which="both"):
            if lo <= t.get_position()[1] <= hi:
                add("y tick", t)
        if ax.get_legend():
            for t in ax.get_legend().get_texts():
                add("legend", t)
    ax = None
    for leg in fig.legends:
        for t in leg.get_texts():
            add("legend", t)
    for t in fig.texts:
        add("figure text", t)
    if getattr(fig, "_suptitle", None) is not None:
        add("suptitle", fig._suptitle)
    return out


def check(fig, name):
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    W, H = fig.bbox.width, fig.bbox.height
    bad = []
    items = [(k, t, t.get_window_extent(r)) for k, t, _ in texts_of(fig)]
    owner = {id(t): a for _, t, a in texts_of(fig)}
    for k, t, b in items:
        if b.x0 < -1 or b.y0 < -1 or b.x1 > W + 1 or b.y1 > H + 1:
            bad.append(f"{k} is outside the figure ({b.x0:.0f}..{b.x1:.0f} x {b.y0:.0f}..{b.y1:.0f} of {W:.0f} x {H:.0f} px)")
    for (k1, _, b1), (k2, _, b2) in itertools.combinations(items, 2):
        if b1.shrunk(0.98, 0.9).overlaps(b2.shrunk(0.98, 0.9)):
            bad.append(f"{k1} overlaps {k2}")
    # a label inside a panel must not be crossed by a line drawn over it (an opaque box above the line hides it)
    for k, t, b in items:
        ax = owner[id(t)]
        if ax is None or not k.startswith("text"):
            continue
        patch = t.get_bbox_patch()
        hidden_below = patch is not None and (patch.get_alpha() or 1) >= 0.9
        for line in ax.lines:
            if not line.get_visible() or (hidden_below and line.get_zorder() < t.get_zorder()):
                continue
            path = line.get_transform().transform_path(line.get_path())
            if len(path.vertices) >= 2 and path.intersects_bbox(b.shrunk(0.9, 0.6), filled=False):
                bad.append(f"{k} is crossed by a line")
                break
    boxes = []
    for i, ax in enumerate(fig.axes):
        box = tuple(np.round(ax.get_position().bounds, 4))
        twin = box in boxes  # a twinx/twiny axes shares its panel with the one drawn first
        boxes.append(box)
        if not ax.get_visible() or twin or hasattr(ax, "_colorbar") or ax.get_label() == "<colorbar>":
            continue
        for axis, kind in ((ax.xaxis, "x tick"), (ax.yaxis, "y tick")):
            n = sum(1 for k, t, _ in items if k.startswith(kind) and owner[id(t)] is ax)
            if n < 2:
                bad.append(f"panel {i} ({ax.get_title()[:30]!r}) shows {n} {kind} numbers")
    if "--stripes" in opts and "-fragility" in name:
        lo, hi = (float(v) for v in opts["--stripes"].split(","))
        for i, ax in enumerate(fig.axes):
            if not ax.get_visible() or ax.get_xscale() != "log":
                continue
            x0, x1 = ax.get_xlim()
            if x0 < lo * 0.999 or x1 > hi * 1.001:
                if not any(p.get_gid() == "beyond-stripes" for p in ax.patches):
                    bad.append(f"panel {i} ({ax.get_title()!r}): the IM axis runs past the stripes {lo:g}-{hi:g} unmarked")
                for line in ax.lines:
                    x = np.asarray(line.get_xdata(), float)
                    if line.get_linewidth() >= 2 and x.size > 2 and (x.min() < lo * 0.999 or x.max() > hi * 1.001):
                        bad.append(f"panel {i} ({ax.get_title()!r}): a full-weight curve runs {x.min():.3g}-{x.max():.3g}, "
                                   f"past the stripes {lo:g}-{hi:g}")
    if "--pair-report" in opts:
        rows = list(csv.DictReader(open(opts["--pair-report"])))
        ax = fig.axes[0]
        band = [r for r in rows if r["table"] == "curve_band"]
        g = np.array([float(r["gap_m"]) for r in band])
        hi = np.array([100 * float(r["hi"]) for r in band])
        # the advice: the interval's upper end, or the lognormal's where the records do not resolve the target
        lognormal = {r["probability"]: float(r["hi"]) for r in rows if r["table"] == "separation_lognormal"}
        seps = [(100 * float(r["probability"]),
                 lognormal[r["probability"]] if r["name"].startswith("not resolved") else float(r["hi"]))
                for r in rows if r["table"] == "separation"]
        rules = [float(r["gap_m"]) for r in rows if r["table"] in ("code_rule", "code_design")]
        governing = {}
        for r in rows:  # each per-level rule's governing (largest) separation over the contact levels
            if r["table"] == "code_level":
                rule = r["name"].partition(" at ")[0]
                governing[rule] = max(governing.get(rule, 0.0), float(r["gap_m"]))
        rules += list(governing.values())
        # every code design row (ASCE 7-16, EC8, Standard 2800) and every governing per-level gap is drawn
        for gid, want in (("code_design", [float(r["gap_m"]) for r in rows if r["table"] == "code_design"]),
                          ("code_level", list(governing.values()))):
            drawn = [line.get_xdata()[0] for line in ax.lines if line.get_gid() == gid]
            for v in want:
                if not any(abs(x - v) <= 1e-6 for x in drawn):
                    bad.append(f"no {gid} line at {v:.4f} m")
        x_end = max([g[hi >= 0.5].max()] + [s for _, s in seps] + rules)
        right = ax.get_xlim()[1]
        if not x_end <= right <= 1.3 * x_end:
            bad.append(f"the x-axis ends at {right:.3f} m; the data end at {x_end:.3f} m")
        for t, s in seps:
            px, py = ax.transData.transform((s, t))
            hits = [b for k, tx, b in items if tx.get_text().startswith(f"{t:g} %:") and f"{s:.3f}" in tx.get_text()]
            if not hits:
                bad.append(f"no advice label for {t:g} % ({s:.3f} m)")
            elif not any(0 <= b.x0 - px <= 20 and abs((b.y0 + b.y1) / 2 - py) <= 6 for b in hits):
                b = hits[0]
                bad.append(f"the {t:g} % advice label is at ({b.x0:.0f}, {(b.y0 + b.y1) / 2:.0f}) px, not beside its "
                           f"point ({px:.0f}, {py:.0f}) px")
    if "--names" in opts:
        shown = " ".join(t.get_text() for _, t, _ in items)
        for n in opts["--names"].split(","):
            if n not in shown:
                bad.append(f"record {n} is not named")
    checked.append(f"{name}: {len(items)} texts")
    failures.extend(f"{name}: {b}" for b in bad)


def savefig(self, fname, *args, **kwargs):
    """Checks the figure instead of writing it (cli.plot_study and cli.plot_fragility check the files)."""
    if id(self) not in seen:
        seen.add(id(self))
        check(self, os.path.basename(str(getattr(fname, "name", fname))))  # a buffer: the name it carries


def run_tool(tool, tool_args):
    """Runs the tool as __main__ with its arguments; False when it exits with an error."""
    sys.argv = [tool] + tool_args
    try:
        runpy.run_path(tool, run_name="__main__")
    except SystemExit as e:
        if e.code not in (None, 0):
            failures.append(f"{os.path.basename(tool)} {' '.join(tool_args)[:120]} exited with {e.code}")
            return False
    return True


matplotlib.figure.Figure.savefig = savefig
if sys.argv[1:2] == ["--jobs"]:
    # many checks in this one process (matplotlib imported once): FILE holds one job a line, its arguments
    # ([--opt VALUE]... -- TOOL.py ARGS...) separated by the unit separator \x1f
    jobs = [line.rstrip("\n").split("\x1f") for line in open(sys.argv[2]) if line.strip()]
else:
    jobs = [sys.argv[1:]]
for job in jobs:
    opts, tool, tool_args = parse(job)
    before = len(checked)
    seen.clear()  # ids of closed figures are reused
    import matplotlib.pyplot as plt  # noqa: E402 -- a tool's figures left open must not reach the next job
    if run_tool(tool, tool_args) and len(checked) == before:
        failures.append(f"{os.path.basename(tool)} {' '.join(tool_args)[:120]} saved no figure")
    plt.close("all")
for c in checked:
    print(f"  checked {c}")
for f in failures:
    print(f"FAIL: {f}")
sys.exit(1 if failures else 0)
