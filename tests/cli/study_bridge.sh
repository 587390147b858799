#!/usr/bin/env bash
# Bridges through the study runner ([bridge], issue 26 §1; docs/bridges.md):
#  1. tests/data/bridge/study-four-frame.toml gives bit-identical results at 1 and 2 MPI ranks, at batch width 1 and
#     its default, and with skip_untouched = false (every model rerun with contact);
#  2. the probability scene's criterion is exact for the chain: an analysis pounds at ratio x exactly when ANY joint's
#     uncoupled closing exceeds its gap x d + offset (D = max_j (closing_j - offset_j), d = the smallest joint gap);
#     results format 3 names frames and joints (/system), carries units on every dataset, /models the frames' T, m, k;
#  3. the study's lanes are `pounding simulate --bridge` runs: the per-joint closing (law none) and the coupled
#     per-joint impact counts and peak forces of one record equal simulate's for the same bridge file and record;
#     3b: the same with stick frames (a 3-level Q-Hyst frame, a 2-level modal one), every level's peak;
#  4. sampled frames (period_cov): periods drawn per model, reproducible, k = m (2 pi / T)^2;
#  5. the report names the frames and joints; the figure is the per-joint probability of pounding versus the gap,
#     its coupled markers with record-clustered Wilson intervals (a record's polarities one cluster);
#  6. bad input: one ERROR naming file:line and the key, exit 2, nothing written.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$src/tests/data/bridge/study-four-frame.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, bad_run
py=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }

# 1. ranks, batch width, skip_untouched
study_invariance

# 2. touch <=> any joint's closing > its gap; format 3; units; /models
"$py" - "$tmp/full.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
assert f.attrs["format_version"] == 3
R, M = f["uncoupled/peak_closing"].shape
x = f["impacts/gap_ratios"][()]
G = len(x)
assert M == 1, M
# /settings: the bridge (d, offsets, description), not the buildings' model the sampler only numbers samples with
assert "structures" not in f["settings"] and f["settings/bridge"].attrs["reference_gap"] == 0.0127
dec = lambda a: [s.decode() if isinstance(s, bytes) else s for s in a]
assert dec(f["system/element_label"][()]) == ["joint 1", "joint 2", "joint 3"], dec(f["system/element_label"][()])
d = f["models/code_gap"][()]
assert np.all(d == 0.0127), d
offsets = np.array([0.0, 0.0127, 0.0])
el = f["uncoupled/peak_closing_elements"][()]
D = f["uncoupled/peak_closing"][()]
assert np.array_equal(D, (el - offsets).max(axis=2))
ok = (f["uncoupled/status"][()].reshape(R, M) == 0)[:, :, None] & (f["impacts/status"][()].reshape(R, M, G) == 0)
assert ok.all(), "failed analyses"
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
touch = D[:, :, None] > x[None, None, :] * d[None, :, None]
assert np.array_equal(touch, cnt > 0), (touch.sum(), (cnt > 0).sum())
assert 0 < touch.sum() < touch.size, touch.sum()
# per joint: joint j alone decides some analyses (its own offset counts)
only = [(el[:, :, j, None] - offsets[j] > x[None, None, :] * d[None, :, None]) for j in range(3)]
assert any((only[j] & ~np.logical_or.reduce([only[k] for k in range(3) if k != j])).any() for j in range(3))
ec = f["impacts/element_impact_count"][()].reshape(R, M, G, 3)
assert np.array_equal(np.where(ec < 0, 0, ec).sum(axis=3), cnt)
# every frame's peaks, and /models: frames 1..4 (T, m, k)
u = f["uncoupled"]
for b in (1, 2, 3, 4):
    fl = u[f"peak_u_floors{b}"][()]
    assert fl.shape == (R, M, 1) and np.array_equal(fl[:, :, 0], u[f"peak_u{b}"][()]), b
T = [f["models/T1"][0], f["models/T2"][0], f["models/T3"][0], f["models/T4"][0]]
assert np.allclose(T, [0.47, 1.12, 1.12, 0.47], rtol=1e-12), T
assert f["models/m3"][0] == 3.21145e6 and np.isclose(f["models/k4"][0], 1.30635e6 * (2 * np.pi / 0.47) ** 2, rtol=1e-14)
# units on every dataset of the result groups
missing = []
def visit(name, obj):
    if isinstance(obj, h5py.Dataset) and name.split("/")[0] in ("uncoupled", "impacts", "models", "records") and "units" not in obj.attrs:
        missing.append(name)
f.visititems(visit)
assert not missing, missing
print(f"{touch.sum()} of {touch.size} analyses touch at some joint")
PY

# 3. a lane is pounding simulate --bridge: the same bridge as a bridge file, one record as a study's only record
two_tone() {
  awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
         a = 0.35 * sin(2 * 3.14159265 * 1.1 * t) + 0.2 * sin(2 * 3.14159265 * 2.3 * t + 0.4);
         printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
}
two_tone
sed -n '/^\[bridge\]/,/^\[contact\]/p' "$study" | sed -e '/^\[bridge\]/d' -e '/^\[contact\]/d' -e 's/^\[\(\[*\)bridge\./[\1/' > "$tmp/bridge.toml"
sed -e 's/^suite = "builtin"/files = ["rec.txt"]/' -e '/^limit = /d' -e 's/^polarity = "both"/polarity = "recorded"/' \
    -e 's/^ratios = .*/ratios = [1.0]/' "$study" > "$tmp/one.toml"
(cd "$tmp" && "$bin" run one.toml --out one.h5 --quiet > /dev/null 2> one.err) || fail "the one-record study does not run: $(cat "$tmp/one.err")"
# the study's step: the record's 0.01 s in 4 substeps (the impacts scene's max_dt 0.0025 s)
"$bin" simulate --record "$tmp/rec.txt" --bridge "$tmp/bridge.toml" --contact none --kh 2e9 --e 0.6 --dt 0.0025 --json > "$tmp/none.json"
"$bin" simulate --record "$tmp/rec.txt" --bridge "$tmp/bridge.toml" --contact hertzdamp --kh 2e9 --e 0.6 --dt 0.0025 --json > "$tmp/hd.json"
"$py" - "$tmp/one.h5" "$tmp/none.json" "$tmp/hd.json" <<'PY'
import json, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
none, hd = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
# JSON floats round-trip: the same bits
assert list(f["uncoupled/peak_closing_elements"][0, 0]) == [l["peak_closing"] for l in none["levels"]], (
    f["uncoupled/peak_closing_elements"][0, 0], [l["peak_closing"] for l in none["levels"]])
assert list(f["impacts/element_impact_count"][()].ravel()) == [l["impacts"] for l in hd["levels"]]
assert list(f["impacts/element_peak_force"][()].ravel()) == [l["peak_force"] for l in hd["levels"]]
for b in (1, 2, 3, 4):
    assert f[f"uncoupled/peak_u{b}"][0, 0] == none[f"peak_u{b}"], b
    assert f[f"impacts/peak_u{b}"][()].ravel()[0] == hd[f"peak_u{b}"], b
assert min(l["impacts"] for l in hd["levels"]) > 0, "every joint must be hit by this record"
print("study lane = simulate --bridge: closings", [round(l["peak_closing"], 4) for l in none["levels"]],
      "impacts", [l["impacts"] for l in hd["levels"]])
PY

# 3b. stick frames (issue 26 §1): F2 a 3-level Q-Hyst stick (Rayleigh), F3 a 2-level modal stick; a lane is still
# simulate --bridge of the same file: every level's uncoupled peak (peak_u_floors2/3), per-joint closings, coupled impact
# counts and peak forces, every level's coupled peak u, drift and absolute acceleration, bit for bit; the report's
# per-deck amplification table gives simulate's ratios at each frame's deck; the frames' levels are the bodies' floors of /system.
stick() { sed -e 's/^label = "F2"$/label = "F2"\nstoreys = 3/' -e 's/^label = "F3"$/label = "F3"\nstoreys = 2\ndamping = "modal"/' "$1"; }
stick "$tmp/bridge.toml" > "$tmp/stick_bridge.toml"
stick "$tmp/one.toml" > "$tmp/stick.toml"
grep -q "storeys = 3" "$tmp/stick.toml" && grep -q "storeys = 3" "$tmp/stick_bridge.toml" || fail "no stick frame written"
(cd "$tmp" && "$bin" run stick.toml --out stick.h5 > stick.md 2> stick.err) || fail "the stick study does not run: $(cat "$tmp/stick.err")"
grep -q "A stick frame's is its largest level's" "$tmp/stick.md" || fail "the report does not say what a stick frame's peak is"
"$bin" simulate --record "$tmp/rec.txt" --bridge "$tmp/stick_bridge.toml" --contact none --kh 2e9 --e 0.6 --dt 0.0025 --json > "$tmp/snone.json"
"$bin" simulate --record "$tmp/rec.txt" --bridge "$tmp/stick_bridge.toml" --contact hertzdamp --kh 2e9 --e 0.6 --dt 0.0025 --json > "$tmp/shd.json"
"$py" - "$tmp/stick.h5" "$tmp/snone.json" "$tmp/shd.json" <<'PY'
import json, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
none, hd = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
assert list(f["uncoupled/peak_closing_elements"][0, 0]) == [l["peak_closing"] for l in none["levels"]]
assert list(f["impacts/element_impact_count"][()].ravel()) == [l["impacts"] for l in hd["levels"]]
assert list(f["impacts/element_peak_force"][()].ravel()) == [l["peak_force"] for l in hd["levels"]]
for b, n in ((1, 1), (2, 3), (3, 2), (4, 1)):
    fl = f[f"uncoupled/peak_u_floors{b}"][0, 0]
    assert len(fl) == n and list(fl) == none[f"peak_u{b}"], (b, fl, none[f"peak_u{b}"])
    assert f[f"impacts/peak_u{b}"][()].ravel()[0] == max(hd[f"peak_u{b}"]), b
    # every level's peaks with contact (issue 25 §3 observers): u, drift (a level's storey), absolute acceleration
    for field, key in (("peak_u_floors", f"peak_u{b}"), ("peak_drift", f"peak_drift{b}"),
                       ("peak_acc_floors", f"peak_abs_acc{b}_g")):
        mine = f[f"impacts/{field}{b}"][0, 0, 0]
        assert len(mine) == n and list(mine) == hd[key], (field, b, mine, hd[key])
assert min(l["impacts"] for l in hd["levels"]) > 0, "every joint must be hit by this record"
# the report's per-deck amplification (one analysis: the median is its own ratio) = simulate's, per frame's deck
md = open(sys.argv[1][:-3] + ".md").read().split("## Per-deck amplification")
assert len(md) == 2, "no per-deck amplification section in the report"
rows = {l.split("|")[1].strip(): l.split("|")[2].strip() for l in md[1].split("\n## ")[0].splitlines() if l.startswith("| F")}
for b in (1, 2, 3, 4):
    want = " / ".join(f"{hd[k][-1] / none[k][-1]:.3g}" for k in (f"peak_u{b}", f"peak_drift{b}", f"peak_abs_acc{b}_g"))
    assert rows.get(f"F{b}") == want, (b, rows.get(f"F{b}"), want)
print("stick frames: study lane = simulate --bridge; F2 levels", [round(x, 4) for x in none["peak_u2"]],
      "impacts", [l["impacts"] for l in hd["levels"]])
PY

# 4. sampled frames: periods and masses per model, reproducible, k = m (2 pi / T)^2
sed -e 's/^\[bridge\]$/[bridge]\nsamples = 5\nperiod_cov = 0.2\nmass_cov = 0.1/' -e 's/^ratios = .*/ratios = [1.0]/' \
    -e 's/^limit = 3/limit = 1/' "$study" > "$tmp/sampled.toml"
"$bin" run "$tmp/sampled.toml" --out "$tmp/s1.h5" --quiet > /dev/null 2>&1
"$bin" run "$tmp/sampled.toml" --out "$tmp/s2.h5" --quiet > /dev/null 2>&1
cmp "$tmp/s1.h5" "$tmp/s2.h5" --ignore=output
"$py" - "$tmp/s1.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
m = f["models"]
T = np.array([m[f"T{b}"][()] for b in (1, 2, 3, 4)])
assert T.shape == (4, 5) and len(set(T.ravel())) == 20, T
assert np.allclose(np.array([m[f"k{b}"][()] for b in (1, 2, 3, 4)]),
                   np.array([m[f"m{b}"][()] for b in (1, 2, 3, 4)]) * (2 * np.pi / T) ** 2, rtol=1e-13)
assert abs(np.log(T[1] / 1.12)).max() < 1.0 and len(set(m["m2"][()])) == 5
PY

# 4b. Table 3 of a sampled bridge study: the intervals are clustered by record (a record's sampled bridges and both
# signs one cluster), as the joints figure's: equal to tools/pounding_plots.py wilson_clustered (numpy, written apart)
# on the file's closings, and not the plain Wilson interval on the analyses (which the report gave before)
sed -e 's/^\[bridge\]$/[bridge]\nsamples = 6\nperiod_cov = 0.3\nmass_cov = 0.1/' -e 's/^ratios = .*/ratios = [0.5, 1.0, 2.0, 4.0]/' \
    -e 's/^scene = "impacts"/scene = "probability"/' "$study" > "$tmp/clustered.toml"
"$bin" run "$tmp/clustered.toml" --out "$tmp/cl.h5" > "$tmp/cl.md" 2> "$tmp/cl.err" || fail "the clustered study does not run: $(cat "$tmp/cl.err")"
grep -q "interval is clustered by record" "$tmp/cl.md" || fail "Table 3 does not say its intervals are clustered by record"
MPLBACKEND=Agg "$py" - "$tmp/cl.h5" "$tmp/cl.md" "$src/tools" <<'PY'
import re, sys, h5py, numpy as np
sys.path.insert(0, sys.argv[3])
from pounding_plots import wilson, wilson_clustered
f = h5py.File(sys.argv[1], "r")
D = f["uncoupled/peak_closing"][()]
R, M = D.shape
ok = f["uncoupled/status"][()].reshape(R, M) == 0
d = f["models/code_gap"][()]
cl = np.repeat(np.asarray(f["records/id"][()]).reshape(R, 1), M, axis=1)
md = open(sys.argv[2]).read().split("## Total probability of pounding (Table 3)")[1].split("\n## ")[0]
rows = {float(m.group(1)): (float(m.group(2)), float(m.group(3)))
        for m in re.finditer(r"^\| ([0-9.]+) \| \d+ / \d+ \| [0-9.]+% \| \[([0-9.]+)%, ([0-9.]+)%\] \|", md, re.M)}
assert sorted(rows) == [0.5, 1.0, 2.0, 4.0], rows
differs = 0
for x, (lo, hi) in rows.items():
    y = (D > x * d[None, :])[ok]
    a, b, n_eff = wilson_clustered(y, cl[ok])
    assert abs(100 * a - lo) <= 0.006 and abs(100 * b - hi) <= 0.006, (x, lo, hi, 100 * a, 100 * b, n_eff)
    pa, pb = wilson(y.sum(), y.size)
    differs += abs(100 * pa - lo) > 0.006 or abs(100 * pb - hi) > 0.006
assert differs > 0, "the clustered intervals equal the plain Wilson intervals at every gap: the check cannot tell"
print("Table 3 intervals clustered by record = wilson_clustered at", sorted(rows), f"({differs} differ from plain Wilson)")
PY

# 5. the report names the frames and joints
"$bin" run "$study" --out "$tmp/rep.h5" > "$tmp/rep.md" 2> /dev/null
for want in "joint 1 (F1|F2)" "joint 3 (F3|F4)" "d = 0.0127 m"; do
  grep -qF "$want" "$tmp/rep.md" || fail "the report does not say '$want'"
done
! grep -q "h1 + h2\|building 1 moves" "$tmp/rep.md" || fail "the report speaks of buildings: $(grep -m2 'h1 + h2\|building 1 moves' "$tmp/rep.md")"

# 5b. the figure (tools/pounding_plots.py, the HTML report's figure_plan and plot_study.py): a bridge gets the
# per-joint probability of pounding versus the joint gap in metres, not the pair's gap-ratio curve and T1 x T2 map;
# each joint's curve is the share of analyses whose uncoupled closing there exceeds the gap, each coupled marker the
# share with at least one impact at that joint (both recomputed here from the file)
if "$py" -c 'import matplotlib' 2> /dev/null; then
  "$py" - "$src/tools" "$tmp/r0.h5" <<'PY' || fail "the bridge figure"
import sys
sys.path.insert(0, sys.argv[1])
import h5py, numpy as np
import pounding_plots as pp
f = h5py.File(sys.argv[2], "r")
plan = [name for name, caption, draw in pp.figure_plan(f, sys.argv[2], None)]
assert plan == ["joints"], plan
fig = pp.plot_bridge_joints(f)
el = f["uncoupled/peak_closing_elements"][()]
R, M, J = el.shape
ok = f["uncoupled/status"][()].reshape(R, M) == 0
lines = {}
for line in fig.axes[0].get_lines():
    lines.setdefault(line.get_gid(), []).append(line)
for j in range(J):
    (curve,) = lines[f"joint-{j + 1}"]
    x, p = curve.get_xdata(), curve.get_ydata()
    for i in range(0, len(x), 7):
        want = 100.0 * np.mean(el[:, :, j][ok] > x[i])
        assert abs(p[i] - want) < 1e-9, (j, x[i], p[i], want)
    assert p[0] > 0 and p[-1] == 0, (j, p[0], p[-1])  # from the closings' start to past the largest
ratios, d = f["impacts/gap_ratios"][()], f["models/code_gap"][0]
offsets = f["settings/bridge"].attrs["joint_gap_offsets"]
cnt, st = f["impacts/element_impact_count"][()], f["impacts/status"][()] == 0
for j in range(J):
    pts = sorted((float(l.get_xdata()[0]), float(l.get_ydata()[0])) for l in lines[f"coupled-{j + 1}"]
                 if l.get_marker() not in ("None", "", None, "_"))
    want = sorted((r * d + offsets[j], 100.0 * np.mean(cnt[:, :, g, j][st[:, :, g]] > 0)) for g, r in enumerate(ratios))
    assert np.allclose(pts, want, rtol=1e-12, atol=1e-12), (j, pts, want)
# the coupled markers' 95 % intervals are clustered by record (a record's two polarities are one cluster): Wilson at
# the observed share with n_eff = n / DEFF, Kish's design effect from the cluster totals, n_eff in [C, n] (C at 0 or
# 100 %) -- written again here; a homogeneous case (every record's two signs agree) against scipy's Wilson on the C
# records, and never narrower than the plain Wilson on the n analyses
from scipy import stats
def clustered(y, lab):
    y = np.asarray(y, float); n = y.size; p = y.mean()
    ids = sorted(set(lab)); C = len(ids)
    yc = np.array([sum(v for v, l in zip(y, lab) if l == c) for c in ids]); mc = np.array([list(lab).count(c) for c in ids])
    if 0 < p < 1:
        v = C / (C - 1) * ((yc - p * mc) ** 2).sum() / n ** 2
        ne = min(max(p * (1 - p) / v, C), n)
    else:
        ne = C
    zz = 1.959963984540054 ** 2
    c = (p + zz / (2 * ne)) / (1 + zz / ne); h = np.sqrt(zz) * np.sqrt(p * (1 - p) / ne + zz / (4 * ne * ne)) / (1 + zz / ne)
    return max(min(c - h, p), 0.0), min(max(c + h, p), 1.0)
lo, hi, ne = pp.wilson_clustered([1, 1, 0, 0, 1, 1, 0, 0, 0, 0], ["a", "a", "b", "b", "c", "c", "d", "d", "e", "e"])
ci = stats.binomtest(2, 5).proportion_ci(0.95, method="wilson")
assert ne == 5 and abs(lo - ci.low) < 1e-12 and abs(hi - ci.high) < 1e-12, (lo, hi, ne, ci)
rid = f["records/id"][()]
bars = 0
for cont in fig.axes[0].containers:
    gid = cont.lines[0].get_gid() if cont.lines and cont.lines[0] is not None else None
    if not gid or not gid.startswith("coupled-"):
        continue
    j = int(gid.split("-")[1]) - 1
    x0 = float(cont.lines[0].get_xdata()[0])
    g = int(np.argmin([abs(r * d + offsets[j] - x0) for r in ratios]))
    okg = st[:, :, g]
    hit = (cnt[:, :, g, j] > 0)[okg]
    lab = np.repeat(rid.reshape(R, 1), M, axis=1)[okg]
    lo, hi = clustered(hit, list(lab))
    (seg,) = cont.lines[2][0].get_segments()
    assert abs(seg[0][1] - 100 * lo) < 1e-9 and abs(seg[1][1] - 100 * hi) < 1e-9, (j, g, seg, lo, hi)
    plain = stats.binomtest(int(hit.sum()), hit.size).proportion_ci(0.95, method="wilson")
    assert lo <= plain.low + 1e-12 and hi >= plain.high - 1e-12, (j, g, lo, hi, plain)
    bars += 1
assert bars == J * len(ratios), bars
print("bridge figure: joints", J, "gaps", len(ratios), "record-clustered intervals", bars)
PY
else
  case "${CI:-}" in "" | 0 | false | no) echo "skipped the figure check: no matplotlib" ;; *) fail "no matplotlib (CI)" ;; esac
fi

# 6. bad input: one ERROR naming file:line and the key, exit 2, nothing written
printf '[structures]\nzeta = 0.05\n' | cat "$study" - > "$tmp/b1.toml"
bad_run "takes its frames from \[bridge\].*b1.toml:[0-9]* structures" b1.toml
sed 's/, slack = 0.0127 }/ }/' "$study" > "$tmp/b2.toml"
bad_run "restrainer in a study has no slack.*b2.toml:[0-9]* \[bridge.joint1.restrainer\].slack" b2.toml
sed '0,/^gap = 0.0127/s//gap = 0.0/' "$study" > "$tmp/b3.toml"
bad_run "gap is 0 in a study.*\[bridge.joint1\].gap" b3.toml
sed 's/^period = 1.12/period = 1.12\nspan = 40.0/' "$study" > "$tmp/b4.toml"
bad_run "unknown.*span.*\[bridge.frame2\]" b4.toml
sed 's/^mass = 3.21145e6/mass = -3.2e6/' "$study" > "$tmp/b5.toml"
bad_run "mass = -3200000 is out of range.*b5.toml:[0-9]* \[bridge.frame2\].mass" b5.toml
sed 's/^\[bridge\]$/[bridge]\nsamples = 4/' "$study" > "$tmp/b6.toml"
bad_run "nothing is sampled.*\[bridge\].samples" b6.toml
sed 's/^law = "hertzdamp"/law = "hertzdamp"\ngap_offsets = [0.01]/' "$study" > "$tmp/b7.toml"
bad_run "gap_offsets is given, and the study is a bridge.*\[contact\].gap_offsets" b7.toml
sed 's/^stiffness = 2.0e9/n = 1.5/' "$study" > "$tmp/b8.toml"
bad_run "no contact_stiffness and \[contact\] stiffness is not given.*\[bridge.joint1\].contact_stiffness" b8.toml
sed '0,/^\[\[bridge.joint\]\]/s//[[bridge.joint]]\ngap = 0.0127\n[[bridge.joint]]/' "$study" > "$tmp/b9.toml"
bad_run "4 frames need 3 joints" b9.toml

echo "bridge studies: invariance, first passage per joint, simulate agreement, sampled frames, report, bad input"
