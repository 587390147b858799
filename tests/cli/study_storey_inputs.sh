#!/usr/bin/env bash
# The inputs an engineer has, in a study of shear buildings:
#  1. [structures.buildingK] floor_mass and storey_stiffness as arrays, one per floor / storey from the bottom (storeys
#     given): a one-record, one-model study equals, bit for bit, simulate --storey-mass1 a,b,c --storey-stiffness1 ...
#     (coupled and uncoupled numbers); /settings holds the arrays; the run's model line lists them;
#  2. the model's mass is the floors': models/m1 = the sum of floor_mass (the mass key is not what the floors carry)
#     and the report's building line prints it;
#  2a. storey_yield (a number or one per storey): study == simulate --storey-yield1;
#  2b. a lead-rubber bearing's rubber dashpot (isolation zeta_eff): study == simulate --bearing-zeta1, c_b as formula;
#  3. bad input, one ERROR each, exit 2, no results: an array of the wrong length, an array without storeys, a value
#     out of range, a height that disagrees with storeys x storey_height.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, expect_error
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study, shear_pair_simulate
fail() { echo "FAIL: $*"; exit 1; }

# 1. study == simulate with per-storey lists, bit for bit
sine_record "$tmp/rec.txt" 0.25 0.9 0.10 3.1
shear_pair_study "$tmp/one.toml" 'title="per-storey inputs"' 'structures.building1.floor_mass=[3.5e5, 3.0e5, 2.0e5]' \
  'structures.building1.storey_stiffness=[1.2e8, 9.80665e7, 7.0e7]'
"$bin" run "$tmp/one.toml" --out "$tmp/one.h5" > "$tmp/one.out" 2>&1 || { cat "$tmp/one.out"; fail "the study did not run"; }
grep -q 'building1: .*floors of 350000, 300000, 200000 kg, storeys of 1.2e+08, 9.80665e+07, 7e+07 N/m' "$tmp/one.out" \
  || fail "the run's model line does not list building 1's floors: $(grep building1 "$tmp/one.out")"
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/one.h5")
pair_gap=$gap
sim() {
  "$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storey-mass1 3.5e5,3.0e5,2.0e5 \
    --storey-stiffness1 1.2e8,9.80665e7,7.0e7 --storeys2 5 --storey-mass2 3e5 --storey-stiffness2 9.80665e7 \
    --gap "$pair_gap" --elastic --zeta 0.05 --dt 0.001 --json "$@"
}
simulate_both one
PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" <<'PY'
import sys
import h5py
import numpy as np
from study_simulate import load, pair_checks, assert_equal
tmp = sys.argv[1]
f, s, u, g = load(tmp, "one")
checks = pair_checks(f, s, u, g)
assert s["status"] == "ok" and u["status"] == "ok"
assert s["impact_count"] > 0, "no impacts at the gap"
assert_equal(checks)
assert s["buildings"][0]["floor_mass"] == [3.5e5, 3.0e5, 2.0e5], s["buildings"][0]
m1 = f["models/m1"][()].ravel()[0]
assert m1 == 8.5e5, f"models/m1 = {m1}, want the floors' 8.5e5 kg (the mass key says 9e5)"
found = {}
def visit(name, obj):
    for k, v in obj.attrs.items():
        if k in ("floor_mass", "storey_stiffness"):
            found[name + "/" + k] = [float(x) for x in np.atleast_1d(v)]
f["settings"].visititems(visit)
assert found["structures.building1/floor_mass"] == [3.5e5, 3.0e5, 2.0e5], found
assert found["structures.building1/storey_stiffness"] == [1.2e8, 9.80665e7, 7.0e7], found
print(f"ok   study == simulate with per-storey lists bit for bit ({len(checks)} numbers; {s['impact_count']} "
      f"impacts); models/m1 = {m1:g} kg, the floors'; settings {found}")
PY
grep -q "building 1: .*mass 850 t.*mass the floors' (floor_mass; mass 900000 kg not used)" <("$bin" report "$tmp/one.h5" 2>&1) \
  || fail "the report's building line does not print the floors' mass: $("$bin" report "$tmp/one.h5" 2>&1 | grep 'building 1:')"
echo "ok   the report prints the floors' 850 t"

# 2a. storey_yield: per-storey strengths (building 1 bilinear, building 2 elastic in the study; simulate gives building
#     2 a strength it never reaches, 1e16 N), study == simulate --storey-yield1 bit for bit, and yielding happens
shear_pair_study "$tmp/fy.toml" 'title="per-storey strengths"' 'structures.building1.hysteresis="bilinear"' \
  'structures.building1.storey_yield=[2.4e5, 2.0e5, 1.2e5]'
"$bin" run "$tmp/fy.toml" --out "$tmp/fy.h5" > "$tmp/fy.out" 2>&1 || { cat "$tmp/fy.out"; fail "the storey_yield study did not run"; }
grep -q 'building1: .*storeys yielding at 240000, 200000, 120000 N' "$tmp/fy.out" \
  || fail "the run's model line does not list building 1's strengths: $(grep building1 "$tmp/fy.out")"
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/fy.h5")
sim() {
  "$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storey-mass1 3e5 --storey-stiffness1 9.80665e7 \
    --storey-yield1 2.4e5,2.0e5,1.2e5 --storeys2 5 --storey-mass2 3e5 --storey-stiffness2 9.80665e7 \
    --storey-yield2 1e16 --gap "$gap" --zeta 0.05 --dt 0.001 --json "$@"
}
simulate_both fy
PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" <<'PY'
import sys
from study_simulate import load, pair_checks, assert_equal
tmp = sys.argv[1]
f, s, u, g = load(tmp, "fy")
checks = pair_checks(f, s, u, g)
assert s["status"] == "ok" and u["status"] == "ok" and s["impact_count"] > 0
assert_equal(checks)
assert s["buildings"][0]["storey_yield"] == [2.4e5, 2.0e5, 1.2e5], s["buildings"][0]["storey_yield"]
assert u["energy_hysteretic_J"] > 0, "building 1 does not yield: the test would not test the strengths"
fy1 = f["models/fy1"][()].ravel()[0]
assert fy1 == 2.4e5, fy1
print(f"ok   storey_yield = [2.4e5, 2e5, 1.2e5] N: study == simulate --storey-yield1 bit for bit ({len(checks)} "
      f"numbers; hysteretic energy {u['energy_hysteretic_J']:.4g} J); models/fy1 = the base storey's {fy1:g} N")
PY

# 2b. a lead-rubber bearing's rubber dashpot (isolation zeta_eff, simulate --bearing-zeta1): c_b = 2 zeta sqrt(k2
#     M_total); the study equals simulate bit for bit, and differs from the bearing without it
lrb='bearing = "lead-rubber", base_mass = 3.0e5, k1 = 1.2e8, k2 = 1.2e7, qd = 6.0e5'
shear_pair_study "$tmp/lrb.toml" 'title="lead-rubber dashpot"' "structures.building1.isolation={$lrb, zeta_eff = 0.05}"
"$bin" run "$tmp/lrb.toml" --out "$tmp/lrb.h5" > "$tmp/lrb.out" 2>&1 || { cat "$tmp/lrb.out"; fail "the LRB study did not run"; }
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/lrb.h5")
lrb_opts=(--isolation1 lead-rubber --base-mass1 3e5 --bearing-k1-1 1.2e8 --bearing-k2-1 1.2e7 --bearing-qd1 6e5)
sim() { pair_gap=$gap shear_pair_simulate "${lrb_opts[@]}" "$@"; }
simulate_both lrb --bearing-zeta1 0.05
sim --contact none > "$tmp/lrb-nodashpot.json"
PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" <<'PY'
import json, math, sys
from study_simulate import load, pair_checks, assert_equal
tmp = sys.argv[1]
f, s, u, g = load(tmp, "lrb")
checks = pair_checks(f, s, u, g)
assert s["status"] == "ok" and u["status"] == "ok" and s["impact_count"] > 0
assert_equal(checks)
c = s["buildings"][0]["isolation"]["bearing_c"]
want = 2 * 0.05 * math.sqrt(1.2e7 * (3e5 + 9e5))
assert abs(c - want) <= 1e-12 * want, (c, want)
none = json.load(open(f"{tmp}/lrb-nodashpot.json"))
assert none["buildings"][0]["isolation"]["bearing_c"] == 0 and none["peak_bearing_u1"] > u["peak_bearing_u1"], \
    (none["peak_bearing_u1"], u["peak_bearing_u1"])
text = f["settings/structures.building1"].attrs["isolation"]
assert "zeta_eff 0.05 (on k2)" in str(text), text
print(f"ok   lead-rubber zeta_eff 0.05: c_b = {c:.6g} N s/m = 2 zeta sqrt(k2 M_total); study == simulate bit for bit "
      f"({len(checks)} numbers); bearing peak {u['peak_bearing_u1']:.4g} m, {none['peak_bearing_u1']:.4g} m without")
PY

# 3. bad input
fails=0
body=$(cat "$src/studies/quick-storeys.toml")
b1() { echo "$body" | sed "s/^\[gaps\]/[structures.building1]\n$1\n\n[gaps]/"; }
expect_error mass_count 'floor_mass holds 2 values and the building has storeys = 3.*\[structures.building1\].floor_mass' \
  "$(b1 'storeys = 3\nheight = 9.6\nfloor_mass = [2e5, 2e5]')"
expect_error no_storeys 'floor_mass holds 3 values (one per storey) and storeys is not given' \
  "$(b1 'floor_mass = [2e5, 2e5, 1e5]')"
expect_error stiffness_range 'storey_stiffness holds -1, out of range' \
  "$(b1 'storeys = 2\nheight = 6.4\nstorey_stiffness = [1e8, -1]')"
expect_error yield_with_cy 'storey_yield is given with another strength' \
  "$(b1 'storeys = 3\nheight = 9.6\nyield_coefficient = 0.1\nstorey_yield = 1e6')"
expect_error yield_count 'storey_yield holds 2 values and the building has storeys = 3' \
  "$(b1 'storeys = 3\nheight = 9.6\nstorey_yield = [1e6, 1e6]')"
expect_error bw_zeta 'linear keys\|zeta_eff' "$(b1 'isolation = {bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, zeta_eff = 0.05}')"
expect_error height_storeys 'height = 30 m disagrees with storeys x storey_height = 10 x 3.2 m = 32 m.*give height = 32, storey_height = 3 (height / storeys) or storeys = 9' \
  "$(b1 'storeys = 10\nheight = 30.0')"
[ $fails -eq 0 ] || exit 1
