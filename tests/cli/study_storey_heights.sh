#!/usr/bin/env bash
# [structures.buildingK] storey_height as an array (issue 45 item 6): a shear building's storeys of different heights
# in a study, as simulate --storey-heightK takes them.
#  1. A 3-storey building of 3.2, 4.5 and 3.2 m (height 10.9 m) beside 5 storeys of 3.2 m: the floor levels are the
#     cumulative heights (3.2, 7.7, 10.9 m: /system/dof_height == simulate's floor_levels), the contact elements are
#     simulate's (level 1 floor to floor within level_tolerance, the rest floor to column), and every peak -- coupled
#     and uncoupled, per floor and per element -- equals simulate --storey-height1 3.2,4.5,3.2 bit for bit;
#     /settings holds the array, the run's model line and the report's code-levels table list the heights, and the
#     report's contact levels stand at 3.2, 6.4, 7.7, 9.6 and 10.9 m.
#  2. Bad input, one ERROR each, exit 2, no results: an array of the wrong length, an array without storeys, a height
#     that is not the sum, an SDOF building's array, a height out of range.
# Synthetic records only. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, expect_error
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study
fail() { echo "FAIL: $*"; exit 1; }

sine_record "$tmp/rec.txt" 0.25 0.9 0.10 3.1
uneven=('structures.building1.storey_height=[3.2, 4.5, 3.2]' 'structures.building1.height=10.9')
shear_pair_study "$tmp/h.toml" 'title="storeys of different heights"' "${uneven[@]}"
"$bin" run "$tmp/h.toml" --out "$tmp/h.h5" > "$tmp/h.out" 2>&1 || { cat "$tmp/h.out"; fail "the study did not run"; }
grep -q 'building1: shear building, 3 storeys of 3.2, 4.5, 3.2 m,' "$tmp/h.out" ||
  fail "the run's model line does not list the heights: $(grep -a building1: "$tmp/h.out")"
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/h.h5")
sim() {
  "$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storey-mass1 3e5 --storey-stiffness1 9.80665e7 \
    --storey-height1 3.2,4.5,3.2 --storeys2 5 --storey-mass2 3e5 --storey-stiffness2 9.80665e7 --gap "$gap" \
    --elastic --zeta 0.05 --dt 0.001 --json "$@"
}
simulate_both h
PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" <<'PY'
import sys
import numpy as np
from study_simulate import load, pair_checks, assert_equal
tmp = sys.argv[1]
f, s, u, g = load(tmp, "h")
checks = pair_checks(f, s, u, g, coupled_floors=True)
sysg = f["system"]
b, z = sysg["dof_building"][()], sysg["dof_height"][()]
for k in range(2):
    assert list(z[b == k]) == s["buildings"][k]["floor_levels"], (k, z[b == k], s["buildings"][k]["floor_levels"])
assert list(z[b == 0]) == [3.2, 3.2 + 4.5, 3.2 + 4.5 + 3.2], z[b == 0]
labels = [x.decode() for x in sysg["element_label"][()]]
assert labels == [lv["label"] for lv in s["levels"]], (labels, [lv["label"] for lv in s["levels"]])
assert labels[0] == "level 1" and all("column" in x for x in labels[1:]), labels
assert np.allclose(sysg["element_level_height"][()], [3.2, 6.4, 7.7, 9.6, 10.9], rtol=0, atol=1e-12), sysg["element_level_height"][()]
for e, lv in enumerate(s["levels"]):
    checks += [(f"{lv['label']} impacts", f["impacts/element_impact_count"][0, 0, g, e], lv["impacts"]),
               (f"{lv['label']} peak force", f["impacts/element_peak_force"][0, 0, g, e], lv["peak_force"]),
               (f"{lv['label']} uncoupled closing", f["uncoupled/peak_closing_elements"][0, 0, e], u["levels"][e]["peak_closing"])]
assert s["status"] == "ok" and u["status"] == "ok" and s["impact_count"] > 0
assert_equal(checks)
h = [float(x) for x in f["settings/structures.building1"].attrs["storey_height"]]
assert h == [3.2, 4.5, 3.2], h
print(f"ok   storey_height = [3.2, 4.5, 3.2]: floors at {list(z[b == 0])} m, elements {labels}; study == simulate "
      f"--storey-height1 bit for bit ({len(checks)} numbers, {s['impact_count']} impacts); /settings holds the array")
PY
"$bin" report "$tmp/h.h5" > "$tmp/h.md"
grep -q '^| 1 | 3.2 + 4.5 + 3.2 m (uniform) |' "$tmp/h.md" || fail "the report's code-levels table: $(grep '^| 1 |' "$tmp/h.md")"
for z in 3.200 6.400 7.700 9.600 10.900; do
  grep -q "^### Contact .*building 1 at z1 = $z m" "$tmp/h.md" || fail "the report has no contact level at $z m"
done
echo "ok   the report lists the heights and the contact levels at 3.2, 6.4, 7.7, 9.6, 10.9 m"

# 2. bad input
fails=0
bad() {  # bad <name> <pattern> <key=value ...>: the study with those keys must be refused
  local name=$1 pattern=$2; shift 2
  shear_pair_study "$tmp/$name.src" "title=\"$name\"" "$@"
  expect_error "$name" "$pattern" "$(cat "$tmp/$name.src")"
}
bad length 'storey_height holds 2 values and the building has storeys = 3.*\[structures.building1\].storey_height' \
  'structures.building1.storey_height=[3.2, 4.5]' 'structures.building1.height=7.7'
bad no_storeys 'storey_height holds 3 values (one per storey) and storeys is not given.*add storeys = 3' \
  "${uneven[@]}" 'structures.building1.storeys='
bad sum 'height = 12 m disagrees with the sum of storey_height = \[3.2, 4.5, 3.2\] m, 10.9 m.*give height = 10.9' \
  'structures.building1.storey_height=[3.2, 4.5, 3.2]' 'structures.building1.height=12.0'
bad sdof 'storey_height holds 3 values (one per storey) for an SDOF building' "${uneven[@]}" \
  'structures.building1.model="sdof"' 'structures.building1.storey_stiffness=' 'structures.building1.storeys='
bad range 'storey_height holds 40, out of range' 'structures.building1.storey_height=[3.2, 40.0, 3.2]' \
  'structures.building1.height=46.4'
[ "$fails" -eq 0 ] || fail "$fails bad-input case(s)"
echo "study_storey_heights: ok"
