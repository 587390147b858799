#!/usr/bin/env bash
# Rows of buildings in studies ([structures] buildings = n, issue 25 step 8, docs/rows.md):
#  1. studies/quick-row.toml gives bit-identical results at 1 and 2 MPI ranks, at batch width 1 and its default, and
#     with skip_untouched = false (every model rerun with contact: a row's first passage);
#  2. the probability scene stays exact: an analysis pounds at gap g exactly when ANY joint's uncoupled closing
#     exceeds g (D = the largest over the elements); the per-element rows give the totals; buildings 3..n have
#     their [R, M] and [R, M, G] peaks (uncoupled/peak_u3, impacts/peak_u3) equal to the per-floor rows' maxima;
#     the row's d is 0.005 x the largest joint's (h_j + h_j+1); tools/row_amplification.py's statistics from the file
#     are recomputed here;
#  3. buildings = 2 written out is today's pair study bit for bit (SDOF and shear);
#  4. a row of shear buildings runs (format 3 for three buildings);
#  5. bad input for every new key and combination: one ERROR naming file:line and the key, exit 2, nothing written.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$src/studies/quick-row.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance

# 1. ranks, batch width, skip_untouched
study_invariance

# 2. touch <=> any joint's closing > gap; the rows of buildings 3..n; d; the amplification tool
/usr/bin/python3 "$src/tools/row_amplification.py" "$tmp/full.h5" --json > "$tmp/amp.json"
/usr/bin/python3 - "$tmp/full.h5" "$tmp/amp.json" <<'PY'
import json, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
R, M = f["uncoupled/peak_closing"].shape
G = len(f["impacts/gap_ratios"])
assert f.attrs["format_version"] == 3
D = f["uncoupled/peak_closing"][()]
d = f["models/code_gap"][()]
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
ok = (f["uncoupled/status"][()].reshape(R, M) == 0)[:, :, None] & (f["impacts/status"][()].reshape(R, M, G) == 0)
assert ok.all(), "failed analyses"
x = f["impacts/gap_ratios"][()]
touch = D[:, :, None] > x[None, None, :] * d[None, :, None]
assert np.array_equal(touch, cnt > 0), (touch.sum(), (cnt > 0).sum())
assert 0 < touch.sum() < touch.size, touch.sum()
# ANY joint: per element (joint 1|2 and 2|3 of the one level) the closing, D their largest, both joints decide
el = f["uncoupled/peak_closing_elements"][()]
labels = [s.decode() if isinstance(s, bytes) else s for s in f["system/element_label"][()]]
assert labels == ["1|2 level 1", "2|3 level 1"], labels
assert np.array_equal(el.max(axis=2), D)
only = [(el[:, :, j, None] > x[None, None, :] * d[None, :, None]) for j in range(2)]
assert (only[0] & ~only[1]).any() and (only[1] & ~only[0]).any(), "each joint alone must decide some analysis"
ec = f["impacts/element_impact_count"][()].reshape(R, M, G, -1)
assert np.array_equal(np.where(ec < 0, 0, ec).sum(axis=3), cnt)
# each joint's coupled impacts happen where that joint touched uncoupled (first passage, per joint) or the other did
assert ((ec[:, :, :, 1] > 0) <= (only[1] | only[0])).all()
# buildings 3..n: [R, M] and [R, M, G] peaks; the per-floor maxima
u = f["uncoupled"]
for b in (1, 2, 3):
    fl = u[f"peak_u_floors{b}"][()]
    assert fl.shape == (R, M, 1) and np.array_equal(fl[:, :, 0], u[f"peak_u{b}"][()]), b
pu3 = f["impacts/peak_u3"][()].reshape(R, M, G)
assert np.array_equal(pu3[~touch], np.broadcast_to(u["peak_u3"][()][:, :, None], touch.shape)[~touch])
assert (pu3[touch] != np.broadcast_to(u["peak_u3"][()][:, :, None], touch.shape)[touch]).any()
# the row's d: 0.005 x the largest joint's height sum; building 3's period drawn per sample (one slot), in /models
h1, h2, h3 = f["models/h1"][()], f["models/h2"][()], f["models/h3"][()]
assert np.array_equal(d, np.maximum(0.005 * (h1 + h2), 0.005 * (h2 + h3)))
assert (d > 0.005 * (h1 + h2) * (1 + 1e-12)).any()
T3 = f["models/T3"][()]
assert len(set(T3)) == M and f["models/T3"].attrs["units"] in ("s", b"s")
assert np.allclose(f["models/k3"][()], 4 * np.pi ** 2 * f["models/m3"][()] / T3 ** 2, rtol=1e-12)
assert "T4" not in f["models"]
# the amplification statistics, recomputed from the datasets
amp = json.load(open(sys.argv[2]))
assert [p["position"] for p in amp["positions"]] == ["end-left", "interior", "end-right"]
for g in range(G):
    for p in amp["positions"]:
        vals = []
        for b in p["buildings"]:
            c = f[f"impacts/peak_u{b}"][()].reshape(R, M, G)[:, :, g]
            vals.append((c / u[f"peak_u{b}"][()]).ravel())
        a = np.concatenate(vals)
        s = p["gaps"][g]
        assert abs(s["median"] - np.median(a)) <= 1e-12 * np.median(a), (s, np.median(a))
        assert abs(s["p_amplified"] - np.mean(a > 1.0)) < 1e-12
print(f"{touch.sum()} of {touch.size} analyses touch at some joint; per-joint and per-building rows consistent")
print(json.dumps(amp["positions"][0]["gaps"][0]))
PY

# 3. buildings = 2 written out: the pair study bit for bit (SDOF, and shear)
base=$src/tests/data/study-small-synthetic.toml
"$bin" run "$base" --out "$tmp/pair.h5" --quiet > /dev/null 2>&1
sed 's/^samples_per_pair = 8/samples_per_pair = 8\nbuildings = 2/' "$base" > "$tmp/two.toml"
grep -q '^buildings = 2' "$tmp/two.toml"
"$bin" run "$tmp/two.toml" --out "$tmp/two.h5" --quiet > /dev/null 2>&1
cmp "$tmp/pair.h5" "$tmp/two.h5" --ignore=study_text,output
storeys=$src/studies/quick-storeys.toml
sed 's/^\[contact\]/[analysis]\nsubsteps = 2\n\n[contact]/' "$storeys" > "$tmp/s.toml"
sed 's/^model = "shear"/model = "shear"\nbuildings = 2/' "$tmp/s.toml" > "$tmp/s2.toml"
"$bin" run "$tmp/s.toml" --out "$tmp/s.h5" --quiet > /dev/null 2>&1
"$bin" run "$tmp/s2.toml" --out "$tmp/s2.h5" --quiet > /dev/null 2>&1
cmp "$tmp/s.h5" "$tmp/s2.h5" --ignore=study_text,output

# 4. a row of three shear buildings (storeys from the sampled heights; building 3 fixed at 12 storeys)
# (coarse = "keep": one of the 448 analyses is above the Hertz resolution limit at the record step, which this
# check of the row's bookkeeping does not need)
sed -e 's/^buildings = 3/buildings = 3\nmodel = "shear"/' -e 's/^period = {lognormal.*/period = 1.2\nstoreys = 12/' \
  -e 's/^\[contact\]/[analysis]\ncoarse = "keep"\n\n[contact]/' "$study" > "$tmp/shear.toml"
"$bin" run "$tmp/shear.toml" --out "$tmp/shear.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 - "$tmp/shear.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
u = f["uncoupled"]
assert u["peak_u_floors3"].shape[2] == 12, u["peak_u_floors3"].shape
assert np.array_equal(np.nanmax(u["peak_u_floors3"][()], axis=2), u["peak_u3"][()])
assert np.array_equal(np.nanmax(u["peak_closing_elements"][()], axis=2), u["peak_closing"][()])
assert (f["impacts/impact_count"][()] > 0).any()
print("shear row:", u["peak_closing_elements"].shape[2], "elements")
PY

# 5. bad input
fails=0
body=$(cat "$study")
expect_error buildings_one ':22 \[structures\].buildings' "$(echo "$body" | sed 's/^buildings = 3/buildings = 1/')"
expect_error buildings_many ':22 \[structures\].buildings' "$(echo "$body" | sed 's/^buildings = 3/buildings = 17/')"
expect_error buildings_text ':22 \[structures\].buildings' "$(echo "$body" | sed 's/^buildings = 3/buildings = "three"/')"
expect_error table_beyond '\[structures.building4\] is given but the row has buildings = 3.*set \[structures\] buildings = 4' \
  "$(echo "$body" | sed 's/^\[gaps\]/[structures.building4]\nperiod = 1.0\n\n[gaps]/')"
expect_error table_in_pair '\[structures.building3\] is given but the row has buildings = 2' \
  "$(echo "$body" | sed 's/^buildings = 3/buildings = 2/')"
expect_error grid_third 'building3 of the row has a grid of 2 periods.*give \[structures.building3\] period' \
  "$(echo "$body" | sed 's/^period = {lognormal.*/periods = [1.0, 1.5]/')"
expect_error no_period_third 'building3 of the row has a grid of 2 periods.*\[structures.building3\]' \
  "$(echo "$body" | sed 's/^period = {lognormal.*/zeta = 0.05/')"
expect_error key_third ':28 .*colour' \
  "$(echo "$body" | sed 's/^period = {lognormal.*/period = 1.0\ncolour = "red"/')"
expect_error range_third '\[structures.building3\].period' \
  "$(echo "$body" | sed 's/^period = {lognormal.*/period = 50.0/')"
# (a row mixing SDOF and shear buildings, refused here before, runs: cli.study_rows_mixed)
# different storey heights in a row run: building3's floors (3.0 m storeys) meet building2's columns (3.2 m) --
# refused before floors against columns (docs/floor-contact.md)
echo "$body" | sed -e 's/^buildings = 3/buildings = 3\nmodel = "shear"/' -e 's/^period = {lognormal.*/period = 1.0\nstorey_height = 3.0/' \
  > "$tmp/storey_heights.toml"
if "$bin" run "$tmp/storey_heights.toml" --out "$tmp/storey_heights.h5" --quiet > "$tmp/storey_heights.out" 2>&1 &&
   /usr/bin/python3 - "$tmp/storey_heights.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
assert any(l.startswith("2|3 ") and "column" in l for l in labels), labels
assert not any(l.startswith("1|2 ") and "column" in l for l in labels), labels
print("ok   storey_heights: a row of 3.2 / 3.2 / 3.0 m storeys runs;", ", ".join(labels[:6]), "...")
PY
then :; else echo "FAIL storey_heights:"; cat "$tmp/storey_heights.out"; fails=$((fails+1)); fi
expect_error equal_heights 'equal_heights = true is for a pair.*\[structures\].equal_heights' \
  "$(echo "$body" | sed 's/^buildings = 3/buildings = 3\nequal_heights = true/')"
expect_error stepper 'a row of 3 buildings.*\[analysis\].stepper, write stepper = "central-difference"' \
  "$(echo "$body" | sed 's/^\[contact\]/[analysis]\nstepper = "nigam-jennings"\n\n[contact]/')"
expect_error stereomechanical 'a row of 3 buildings has a contact at every joint.*\[contact\].law' \
  "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "stereomechanical"/')"
# ([intensity] with a row, refused here before, runs: cli.fragility_rows)
[ $fails -eq 0 ]
echo "1 passed, 0 failed"
