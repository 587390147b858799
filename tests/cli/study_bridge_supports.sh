#!/usr/bin/env bash
# A bridge on several supports through the study runner ([records] supports = N; issue 26 §2; docs/bridge-joint.md):
#  1. two spans on their own supports under `pounding motions` realisations (Deodatis, 100 m, 500 m/s, soft soil):
#     bit-identical at 1 and 2 MPI ranks, batch width 1 and skip_untouched = false;
#  2. each analysis is `pounding simulate --bridge` with the realisation's two files as --support-record: the joint's
#     uncoupled closing and the coupled impact count and peak force to the bit;
#  3. the uncoupled closing agrees with tools/bridge_joint.py's independent one (exact FOH response + ground
#     displacement, SciPy) to the central-difference error;
#  4. uniform input (both spans on support 1) of identical spans never closes the joint; spatial variation does; both
#     inputs in one figure (plot_study --with, figures --with, pounding report A B --html);
#  5. bad input: one ERROR naming the key, exit 2, nothing written.
# Generates its motions (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, bad_run
py=/usr/bin/python3
"$py" -c 'import numpy, scipy, h5py' 2>/dev/null || { echo "skip: needs $py with numpy, scipy, h5py"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

"$bin" motions --supports 2 --spacing 100 --velocity 500 --coherency sobczyk --loss high --spectrum nzs1170.5 \
  --soil D --z 0.5 --r 1.4 --realisations 4 --seed 1 --label "D-high" --quiet --out "$tmp/m" > /dev/null
study=$tmp/svgm.toml
cat > "$study" <<'EOF'
title = "two spans on two supports"
seed = 26
scene = "impacts"

[records]
directory = "m"
supports = 2
polarity = "both"

[gaps]
ratios = [1.0, 4.0, 16.0]

[bridge]
[[bridge.frame]]
label = "span 1"
mass = 1895413.0
period = 1.0204
[[bridge.frame]]
label = "span 2"
mass = 1895413.0
period = 1.0204
support = 2
[[bridge.joint]]
gap = 0.02

[contact]
law = "hertzdamp"
stiffness = 2.0e9
e = 0.6
EOF

# 1. ranks, batch width, skip_untouched
study_invariance

# 2. = pounding simulate --bridge with the two support files (rows 2r: as recorded)
sed -n '/^\[bridge\]/,/^\[contact\]/p' "$study" | sed -e '/^\[bridge\]/d' -e '/^\[contact\]/d' -e 's/^\[\(\[*\)bridge\./[\1/' > "$tmp/bridge.toml"
for r in 001 002; do
  for law in none hertzdamp; do
    "$bin" simulate --bridge "$tmp/bridge.toml" --support-record "$tmp/m/r${r}_s01.AT2" --support-record "$tmp/m/r${r}_s02.AT2" \
      --contact $law --kh 2e9 --e 0.6 --dt 0.0025 --json > "$tmp/sim-$r-$law.json"
  done
done
"$py" - "$tmp/full.h5" "$tmp" "$src/tools" <<'PY'
import json, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
tmp, tools = sys.argv[2], sys.argv[3]
R, M = f["uncoupled/peak_closing"].shape
assert R == 8 and M == 1, (R, M)  # 4 realisations x 2 signs
ids = [s.decode() if isinstance(s, bytes) else s for s in f["records/id"][()]] if "records/id" in f else None
G = len(f["impacts/gap_ratios"])
D = f["uncoupled/peak_closing"][()][:, 0]
cnt = f["impacts/element_impact_count"][()].reshape(R, G, 1)[:, :, 0]
force = f["impacts/element_peak_force"][()].reshape(R, G, 1)[:, :, 0]
for k, r in enumerate(("001", "002")):
    none = json.load(open(f"{tmp}/sim-{r}-none.json"))
    hd = json.load(open(f"{tmp}/sim-{r}-hertzdamp.json"))
    assert D[2 * k] == none["levels"][0]["peak_closing"], (r, D[2 * k], none["levels"][0]["peak_closing"])
    assert cnt[2 * k, 0] == hd["levels"][0]["impacts"] and force[2 * k, 0] == hd["levels"][0]["peak_force"], r
    assert none["supports"] == 2 if "supports" in none else True
    assert cnt[2 * k, 0] > 0, "this realisation must close a 20 mm joint"
# 3. tools/bridge_joint.py's uncoupled closing (exact between samples; ours central difference at h = dt / 4)
sys.path.insert(0, tools)
from bridge_joint import peak_closing
from reference_spatial import read_set
dt, sets, _ = read_set(f"{tmp}/m")
a1 = np.array([sets[r][1] for r in sorted(sets)])
a2 = np.array([sets[r][2] for r in sorted(sets)])
ref = peak_closing(a1, a2, dt, 1.0204, 1.0204, 0.05)
ours = D[0::2]
err = np.abs(ours - ref) / ref
assert err.max() < 1e-3, (ours, ref, err)
# the reversed sign: the closing of -a is the peak of x2 - x1
ref_rev = peak_closing(-a1, -a2, dt, 1.0204, 1.0204, 0.05)
assert (np.abs(D[1::2] - ref_rev) / ref_rev).max() < 1e-3, (D[1::2], ref_rev)
print("per realisation: closing (m)", np.round(ours, 4), "reference", np.round(ref, 4), "max rel. diff %.1e" % err.max())
PY

# 4. uniform input: both spans on support 1 (the realisations' first files): identical spans never close
sed '/^support = 2$/d' "$study" > "$tmp/uniform.toml"
(cd "$tmp" && "$bin" run uniform.toml --out uniform.h5 --quiet > /dev/null 2>&1) || fail "the uniform-input study does not run"
"$py" - "$tmp/uniform.h5" "$tmp/full.h5" <<'PY'
import sys, h5py, numpy as np
u, s = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
assert (u["uncoupled/peak_closing"][()] == 0).all(), u["uncoupled/peak_closing"][()]
assert (u["impacts/impact_count"][()] == 0).all()
assert (s["uncoupled/peak_closing"][()] > 0.05).all(), s["uncoupled/peak_closing"][()]
PY
# 4b. both inputs in one figure (tools/pounding_plots.py plot_bridge_inputs): plot_study --with, `figures --with` (the
# HTML report's figure plan) and `pounding report A B --html` (study A's figures get B: the "inputs" figure); the
# curves: uniform never pounds; the spatial input's share of D > gap and its coupled shares with record-clustered
# Wilson bars (wilson_clustered) at the study's gaps, counted here from the files
if ! "$py" -c 'import matplotlib' 2>/dev/null; then
  [ "${CI:-}" = true ] && fail "needs matplotlib for the inputs figure (CI=true)"
  echo "skip: the inputs figure (no matplotlib for $py)"
else
MPLBACKEND=Agg "$py" "$src/tools/plot_study.py" "$tmp/full.h5" --with "$tmp/uniform.h5" --prefix "$tmp/fig" > "$tmp/fig.out" 2>&1 ||
  fail "plot_study --with: $(cat "$tmp/fig.out")"
[ -s "$tmp/fig-inputs.png" ] && [ -s "$tmp/fig-joints.png" ] || fail "plot_study --with wrote no inputs figure: $(cat "$tmp/fig.out")"
mkdir -p "$tmp/figs"
MPLBACKEND=Agg "$py" "$src/tools/pounding_plots.py" figures "$tmp/full.h5" --with "$tmp/uniform.h5" --dir "$tmp/figs" > /dev/null 2>&1
grep -q "^ok	inputs	inputs.svg	Uniform versus multi-support" "$tmp/figs/figures.tsv" || fail "figures --with: no inputs figure: $(cat "$tmp/figs/figures.tsv")"
grep -q 'input-1' "$tmp/figs/inputs.svg" && grep -q 'input-2' "$tmp/figs/inputs.svg" || fail "the inputs figure lacks an input's curve"
MPLBACKEND=Agg "$py" - "$tmp/full.h5" "$tmp/uniform.h5" "$src/tools" <<'PY'
import sys, h5py, numpy as np
sys.path.insert(0, sys.argv[3])
from pounding_plots import bridge_input, bridge_input_curves, wilson_clustered
s, u = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
assert bridge_input(s) == "2 supports, spatially varying input" and bridge_input(u) == "uniform input"
D = s["uncoupled/peak_closing"][()].ravel()
x = np.array(sorted(set(D)) + [0.0, 1.0])
p, n, bars = bridge_input_curves(s, x)
assert n == D.size and np.allclose(p, [100.0 * (D > v).mean() for v in x], atol=1e-12)
pu, nu, bu = bridge_input_curves(u, x)
assert (pu == 0).all() and all(b[1] == 0 for b in bu) and len(bu) == 3
R, M = s["uncoupled/peak_closing"].shape
G = len(s["impacts/gap_ratios"])
cnt = s["impacts/impact_count"][()].reshape(R, M, G)
cl = np.repeat(np.asarray(s["records/id"][()]).reshape(R, 1), M, axis=1)
for g, (gap, share, lo, hi) in enumerate(bars):
    assert gap == s["impacts/gap_ratios"][g] * s["models/code_gap"][0]
    hit = (cnt[:, :, g] > 0).ravel()
    a, b, _ = wilson_clustered(hit, cl.ravel())
    assert share == 100 * hit.mean() and (lo, hi) == (100 * a, 100 * b), (g, share, lo, hi)
print("inputs figure: uniform 0 %, spatial", [round(b[1], 1) for b in bars], "% coupled at the study's gaps")
PY
if (cd "$tmp" && "$bin" report full.h5 uniform.h5 --html both.html > /dev/null 2> both.err); then
  grep -q 'input-2' "$tmp/both.html" || fail "the HTML comparison of the two inputs has no inputs figure: $(grep -o 'figures: [^<]*' "$tmp/both.html" | head -3)"
else
  fail "pounding report --html of the two inputs: $(cat "$tmp/both.err")"
fi
fi

# 5. bad input
sed '/^supports = 2$/d' "$study" > "$tmp/b1.toml"
bad_run "stands on 2 supports.*\[records\].supports" b1.toml
sed 's/^directory = "m"/suite = "builtin"/' "$study" > "$tmp/b2.toml"
bad_run "names no directory.*b2.toml:[0-9]* \[records\].supports" b2.toml
printf 'seed = 1\n[records]\ndirectory = "m"\nsupports = 2\n' > "$tmp/b3.toml"
bad_run "has no \[bridge\].*\[records\].supports" b3.toml
mkdir -p "$tmp/gap" && cp "$tmp"/m/r00[12]_s0[12].AT2 "$tmp/gap/" && rm "$tmp/gap/r002_s02.AT2"
sed 's/^directory = "m"/directory = "gap"/' "$study" > "$tmp/b4.toml"
bad_run "realisation r002 .* has 1 of the 2 support files.*\[records\].supports" b4.toml
sed 's/^supports = 2/supports = 1/' "$study" > "$tmp/b5.toml"
bad_run "supports = 1 is out of range.*\[records\].supports" b5.toml
echo "multi-support bridge studies: invariance, simulate agreement, SciPy reference, uniform input, bad input"
