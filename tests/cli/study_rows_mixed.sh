#!/usr/bin/env bash
# Rows mixing SDOF and shear buildings (issue 25 §2 "a row of buildings", docs/rows.md; refused before: "one model
# throughout"):
#  1. a one-record, one-model row (SDOF, 3-storey shear, SDOF) with [contact] levels = "top" equals, bit for bit,
#     pounding simulate --buildings 3 --storeys1 1 --storeys2 3 --storeys3 1 with the SDOFs' floors where the study's
#     rule puts them (building 1, 6.5 m high: the middle building's floor 2 at 6.4 m; building 3, 9.0 m: its roof at
#     9.6 m) -- coupled: impact count, peak force, first impact, peak u of each building; uncoupled: every floor's
#     peak u, drift and absolute acceleration, the peak closing; per element: the study's /system labels;
#  1b. the same row with [structures] rayleigh_modes = [1, 3] (refused before: "rayleigh_modes is given for an SDOF
#     building") equals simulate --rayleigh-modes2 1,3 bit for bit: the shear building takes modes 1 and 3, the SDOFs
#     keep their zeta (the rule's one storey: their uncoupled peaks are 1.'s, building 2's all differ);
#  1c. the same row with [structures] damping = "modal", modal_zeta = [0.03, 0.06] (refused before: "damping is given
#     for an SDOF building") equals simulate --modal-zeta 0.03,0.06 bit for bit; the SDOFs keep their zeta;
#  2. quick-row with building 2 a shear building is bit-identical at 1 and 2 ranks, batch width 1 and
#     skip_untouched = false, and every analysis's per-element rows give its totals (the SDOF joints' one element,
#     whose level varies with the sample, lands in the joint's row): sum of element impacts = impact_count, largest
#     element closing = peak_closing;
#  3. bad input still refused: an SDOF with isolation in a row, an SDOF's own rayleigh_modes or damping, [structures]
#     rayleigh_modes or damping = "modal" where every building is an SDOF.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$PWD/unused.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, expect_error
fail() { echo "FAIL: $*"; exit 1; }

# 1. study == simulate
awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
       a = 0.30 * sin(2 * 3.14159265 * 0.8 * t) + 0.12 * sin(2 * 3.14159265 * 2.7 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
cat > "$tmp/one.toml" <<EOF
title = "mixed row"
seed = 7
scene = "impacts"
output = "out.h5"

[records]
files = ["rec.txt"]
polarity = "recorded"

[structures]
buildings = 3
storey_height = 3.2
zeta = 0.05
hysteresis = "elastic"
samples_per_pair = 1

[structures.building1]
period = 0.45
height = 6.5
mass = 4.0e5

[structures.building2]
model = "shear"
period = 0.9
height = 9.6
storeys = 3
mass = 9.0e5
storey_stiffness = 9.80665e7

[structures.building3]
period = 0.7
height = 9.0
mass = 6.0e5

[gaps]
ratios = [0.1, 0.2, 0.5, 1.0]

[analysis]
max_dt = 0.001

[contact]
law = "hertzdamp"
e = 0.5
levels = "top"
EOF
"$bin" run "$tmp/one.toml" --out "$tmp/one.h5" --quiet > "$tmp/one.out" 2>&1 || { cat "$tmp/one.out"; fail "the mixed row did not run"; }
# d = 0.005 max(6.5 + 9.6, 9.6 + 9.0) = 0.093 m; x = 0.5
# the study's gap at x = 0.5, to the bit (0.5 d, d = 0.005 max(h_j + h_j+1))
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/one.h5")
sim() {
  "$bin" simulate --record "$tmp/rec.txt" --buildings 3 --contact-levels top --elastic --zeta 0.05 --dt 0.001 \
    --gap "$gap" --storeys1 1 --storey-height1 6.4 --m1 4.0e5 --T1 0.45 \
    --storeys2 3 --storey-mass2 3e5 --storey-stiffness2 9.80665e7 \
    --storeys3 1 --storey-height3 9.6 --m3 6.0e5 --T3 0.7 --json "$@"
}
# same_as_simulate NAME [simulate options]: the study $tmp/NAME.h5 against simulate with those options
same_as_simulate() {
  simulate_both "$@"
  PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" "$1" <<'PY'
import sys
from study_simulate import load, pair_checks, assert_equal
f, s, u, g = load(*sys.argv[1:3])
name = sys.argv[2]
assert abs(0.5 * f["models/code_gap"][()][0] - 0.0465) < 1e-15, f["models/code_gap"][()]  # d = 0.093 m
checks = pair_checks(f, s, u, g, buildings=3)
assert s["status"] == "ok" and u["status"] == "ok" and f["impacts/status"][()].ravel()[g] == 0
assert s["impact_count"] > 0, "no impacts at the gap"
assert_equal(checks)
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
theirs = [lv["label"] for lv in s["levels"]]
assert labels == theirs, (labels, theirs)
print(f"ok   {name}: (SDOF, 3-storey, SDOF) study == simulate bit for bit ({len(checks)} numbers; "
      f"{s['impact_count']} impacts; elements {labels})")
PY
}
same_as_simulate one
# shared_damping NAME KEYS MODEL_LINE [simulate options]: one.toml with KEYS (TOML lines, \n-separated) added to
# [structures]; building 2's model line matches MODEL_LINE, the study equals simulate with the options bit for bit,
# the SDOFs' uncoupled peaks are one.h5's and every floor of the shear building differs
shared_damping() {
  local name=$1 keys=$2 line=$3
  shift 3
  sed "s/^\[structures\]\$/[structures]\n$keys/" "$tmp/one.toml" > "$tmp/$name.toml"
  grep -qxF "${keys%%\\n*}" "$tmp/$name.toml" || fail "$name.toml: no ${keys%%\\n*} line"
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" > "$tmp/$name.out" 2>&1 \
    || { cat "$tmp/$name.out"; fail "the row with [structures] ${keys%%\\n*} did not run"; }
  grep -q "building2: .*$line" "$tmp/$name.out" || fail "building 2's model line: $(grep building2 "$tmp/$name.out")"
  same_as_simulate "$name" "$@"
  /usr/bin/python3 - "$tmp" "$name" <<'PY'
import sys, h5py
import numpy as np
tmp, name = sys.argv[1:3]
a, b = h5py.File(f"{tmp}/one.h5", "r"), h5py.File(f"{tmp}/{name}.h5", "r")
for k in ("peak_u_floors1", "peak_u_floors3", "peak_acc_floors1", "peak_acc_floors3"):
    assert np.array_equal(a[f"uncoupled/{k}"][()], b[f"uncoupled/{k}"][()]), f"an SDOF's {k} changed ({name})"
assert (a["uncoupled/peak_u_floors2"][()] != b["uncoupled/peak_u_floors2"][()]).all(), f"{name} changed nothing"
print(f"ok   {name}: the SDOFs' uncoupled peaks unchanged, the shear building's all changed")
PY
}
# 1b. [structures] rayleigh_modes = [1, 3] in the same row: the shear building takes modes 1 and 3, the SDOFs keep
# their zeta (the rule's one storey) -- simulate --rayleigh-modes2 1,3
shared_damping modes 'rayleigh_modes = [1, 3]' 'Rayleigh damping on modes 1 and 3' --rayleigh-modes2 1,3
# 1c. [structures] damping = "modal" with modal_zeta in the same row (refused before: "damping is given for an SDOF
# building"): the shear building takes classical modal damping, the SDOFs keep their zeta -- simulate --modal-zeta
shared_damping modal 'damping = "modal"\nmodal_zeta = [0.03, 0.06]' 'classical modal damping' --modal-zeta 0.03,0.06

# 2. invariance of a mixed quick row, and the per-element rows give the totals
sed 's/^\[structures.building3\]/[structures.building2]\nmodel = "shear"\n\n[structures.building3]/' \
  "$src/studies/quick-row.toml" | sed 's/^samples_per_pair = 8/samples_per_pair = 3/' > "$tmp/mixed.toml"
study=$tmp/mixed.toml
study_invariance
/usr/bin/python3 - "$tmp/r0.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
count = f["impacts/impact_count"][()]            # [R, M, G]
elem = f["impacts/element_impact_count"][()]     # [R, M, G, E]
closing = f["uncoupled/peak_closing"][()]        # [R, M]
ec = f["uncoupled/peak_closing_elements"][()]    # [R, M, E]
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
ok = f["uncoupled/status"][()] == 0 if "uncoupled/status" in f else np.ones(closing.shape, bool)
assert (elem >= 0).all(), "an element row was not filled (-1)"
assert (elem.sum(axis=-1) == count).all(), "per-element impacts do not sum to the totals"
assert np.array_equal(np.nanmax(ec, axis=-1)[ok], closing[ok]), "the largest element closing is not the peak closing"
assert not np.isnan(ec[ok]).any(), "an element closing was not filled"
joints = sorted({l.split(" ")[0] for l in labels})
assert joints == ["1|2", "2|3"], labels
print(f"ok   mixed quick row: invariant; per-element rows give the totals ({count.size} analyses x gaps, elements {labels})")
PY

# 3. bad input
fails=0
body=$(cat "$src/studies/quick-row.toml")
expect_error all_sdof 'rayleigh_modes is given and every building is an SDOF.*\[structures\].rayleigh_modes' \
  "$(echo "$body" | sed 's/^\[structures\]$/[structures]\nrayleigh_modes = [1, 3]/')"
expect_error sdof_own_modes 'rayleigh_modes is given for an SDOF building.*\[structures.building3\].rayleigh_modes' \
  "$(echo "$body" | sed 's/^\[structures.building3\]/[structures.building2]\nmodel = "shear"\n\n[structures.building3]\nrayleigh_modes = [1, 3]/')"
expect_error all_sdof_modal 'damping = "modal" is given and every building is an SDOF.*\[structures\].damping' \
  "$(echo "$body" | sed 's/^\[structures\]$/[structures]\ndamping = "modal"/')"
expect_error sdof_own_damping 'damping is given for an SDOF building.*\[structures.building3\].damping' \
  "$(echo "$body" | sed 's/^\[structures.building3\]/[structures.building2]\nmodel = "shear"\n\n[structures.building3]\ndamping = "modal"/')"
expect_error sdof_isolated 'isolation is given for an SDOF building' \
  "$(echo "$body" | sed 's/^\[structures.building3\]/[structures.building2]\nmodel = "shear"\n\n[structures.building3]\nisolation = {bearing = "linear", k_eff = 1e7}/')"
[ $fails -eq 0 ] || exit 1
