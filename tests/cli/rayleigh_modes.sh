#!/usr/bin/env bash
# Rayleigh damping on chosen modes (issue 25 §2: "Rayleigh on two modes (default modes 1 and 2 with the given ratio)
# ... report the ratio each mode actually gets"): [structures] / [structures.buildingK] rayleigh_modes = [i, j],
# simulate --rayleigh-modesK i,j, pounding modes --rayleigh-modes.
#  1. simulate --json: the ratio every mode of a uniform 4-storey building gets with --rayleigh-modes1 1,3 against
#     the Rayleigh formula zeta_r = a0/(2 omega_r) + a1 omega_r/2 with a0, a1 solved here from zeta at modes 1 and 3 and
#     omega_r = 2 sqrt(k/m) sin((2r - 1) pi / (2 (2n + 1))) (closed form, uniform stick), to 1e-12; modes 1 and 3 get
#     zeta exactly, mode 2 less, mode 4 more; building 2 (default) zeta at modes 1 and 2; pounding modes agrees;
#  2. a one-record, one-model study (building 1: 3 storeys, rayleigh_modes = [1, 3]; building 2: 4 storeys,
#     rayleigh_modes = [3, 6], fewer storeys than mode 6: the rule gives modes 3 and 4) equals, bit for bit,
#     simulate --rayleigh-modes1 1,3 --rayleigh-modes2 3,4 (coupled and uncoupled numbers), and differs from simulate
#     with the default modes; the run's model line states the modes and the rule; /settings holds rayleigh_modes;
#  3. bad input, one ERROR each, exit 2, no results.
# Modes 1 and 2 (the default) keep every study's bits: the cli study tests (cli.study_storeys, cli.study_rows, ...).
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, expect_error
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study, shear_pair_simulate
fail() { echo "FAIL: $*"; exit 1; }

# 1. the ratio each mode gets
"$bin" simulate --storeys1 4 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 3 --storey-mass2 2e5 \
  --storey-stiffness2 3e8 --zeta 0.05 --rayleigh-modes1 3,1 --dt 0.001 --duration 1 --json > "$tmp/ratios.json"
"$bin" modes --storeys 4 --mass 2e5 --stiffness 3e8 --zeta 0.05 --rayleigh-modes 1,3 --json > "$tmp/modes.json"
/usr/bin/python3 - "$tmp" <<'PY'
import json, math, sys
tmp = sys.argv[1]
s = json.load(open(f"{tmp}/ratios.json"))
modes = json.load(open(f"{tmp}/modes.json"))
def expected(n, m, k, zeta, i, j):
    w = [2 * math.sqrt(k / m) * math.sin((2 * r - 1) * math.pi / (2 * (2 * n + 1))) for r in range(1, n + 1)]
    wi, wj = w[i - 1], w[j - 1]
    a0 = 2 * zeta * wi * wj / (wi + wj)  # equal ratios: Chopra eq. 11.4.9
    a1 = 2 * zeta / (wi + wj)
    return [a0 / (2 * x) + a1 * x / 2 for x in w]
b1, b2 = s["buildings"]
for b, want, modes_used in ((b1, expected(4, 2e5, 3e8, 0.05, 1, 3), [1, 3]), (b2, expected(3, 2e5, 3e8, 0.05, 1, 2), [1, 2])):
    got = b["modal_damping"]
    assert len(got) == len(want), (got, want)
    err = max(abs(a - c) for a, c in zip(got, want))
    assert err < 1e-12, (b["label"], got, want, err)
    assert b["rayleigh_modes"] == modes_used, b
z = b1["modal_damping"]
assert abs(z[0] - 0.05) < 1e-15 and abs(z[2] - 0.05) < 1e-15 and z[1] < 0.05 < z[3], z
zm = [m["zeta"] for m in modes["modes"]]
assert max(abs(a - c) for a, c in zip(zm, z)) < 1e-15, (zm, z)
print(f"ok   ratios: building1 modes 1,3 -> {[round(x, 6) for x in z]}, building2 modes 1,2 -> "
      f"{[round(x, 6) for x in b2['modal_damping']]} (closed form, 1e-12); pounding modes the same")
PY

# 2. study == simulate, bit for bit
sine_record "$tmp/rec.txt" 0.25 0.9 0.10 3.1
shear_pair_study "$tmp/one.toml" 'title="Rayleigh modes"' 'structures.building1.rayleigh_modes=[1, 3]' \
  structures.building2.height=12.8 structures.building2.storeys=4 structures.building2.mass=1.2e6 \
  'structures.building2.rayleigh_modes=[6, 3]'
"$bin" run "$tmp/one.toml" --out "$tmp/one.h5" > "$tmp/one.out" 2>&1 || { cat "$tmp/one.out"; fail "the study did not run"; }
grep -q 'building1: .*Rayleigh damping on modes 1 and 3 (a sample of n < 3 storeys' "$tmp/one.out" \
  || fail "the run's model line does not state building 1's modes: $(grep building1 "$tmp/one.out")"
grep -q 'building2: .*Rayleigh damping on modes 3 and 6' "$tmp/one.out" \
  || fail "the run's model line does not state building 2's modes: $(grep building2 "$tmp/one.out")"
# the study's gap at x = 0.5, to the bit (0.5 d, d = 0.005 max(h_j + h_j+1))
gap=$(/usr/bin/python3 -c "import sys, h5py; print(repr(0.5 * h5py.File(sys.argv[1], 'r')['models/code_gap'][()].ravel()[0]))" "$tmp/one.h5")
pair_storeys2=4 pair_gap=$gap
sim() { shear_pair_simulate "$@"; }
simulate_both one --rayleigh-modes1 1,3 --rayleigh-modes2 3,4
sim --contact none > "$tmp/default.json"
PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" <<'PY'
import json, sys
from study_simulate import load, pair_checks, assert_equal
tmp = sys.argv[1]
f, s, u, g = load(tmp, "one")
d = json.load(open(f"{tmp}/default.json"))
checks = pair_checks(f, s, u, g)
assert s["status"] == "ok" and u["status"] == "ok" and f["impacts/status"][()].ravel()[g] == 0
assert s["impact_count"] > 0, "no impacts at the gap"
assert_equal(checks)
assert [b["rayleigh_modes"] for b in s["buildings"]] == [[1, 3], [3, 4]], s["buildings"]
# the modes matter: simulate with the default modes gives other numbers
same = sum(1 for i, v in enumerate(d["peak_u2"]) if v == u["peak_u2"][i])
assert same == 0, ("default modes give the same building-2 peaks", d["peak_u2"], u["peak_u2"])
print(f"ok   study == simulate --rayleigh-modes1 1,3 --rayleigh-modes2 3,4 bit for bit ({len(checks)} numbers; "
      f"{s['impact_count']} impacts); the default modes differ")
PY
/usr/bin/python3 - "$tmp/one.h5" <<'PY' || fail "/settings does not hold rayleigh_modes"
import sys, h5py
f = h5py.File(sys.argv[1], "r")
found = {}
def visit(name, obj):
    for k, v in obj.attrs.items():
        if k == "rayleigh_modes" or name.endswith("rayleigh_modes"):
            found[name + "/" + k] = v
    if name.endswith("rayleigh_modes") and isinstance(obj, h5py.Dataset):
        found[name] = obj[()]
f["settings"].visititems(visit)
vals = sorted(str(list(v)) for v in found.values())
assert vals == ["[1.0, 3.0]", "[3.0, 6.0]"], found
print("ok   settings:", found)
PY

# 3. bad input
fails=0
body=$(cat "$src/studies/quick-storeys.toml")
b1() { echo "$body" | sed "s/^\[gaps\]/[structures.building1]\n$1\n\n[gaps]/"; }
expect_error same_mode 'rayleigh_modes is not two different mode numbers.*\[structures.building1\].rayleigh_modes' \
  "$(b1 'rayleigh_modes = [2, 2]')"
expect_error one_mode '\[structures.building1\].rayleigh_modes' "$(b1 'rayleigh_modes = [3]')"
expect_error fraction '\[structures.building1\].rayleigh_modes' "$(b1 'rayleigh_modes = [1, 2.5]')"
expect_error mode_zero '\[structures.building1\].rayleigh_modes' "$(b1 'rayleigh_modes = [0, 2]')"
expect_error with_modal 'rayleigh_modes is given with damping = "modal".*\[structures.building1\].rayleigh_modes' \
  "$(b1 'damping = "modal"\nrayleigh_modes = [1, 3]')"
expect_error sdof 'rayleigh_modes is given for an SDOF building.*\[structures.building1\].rayleigh_modes' \
  "$(b1 'model = "sdof"\nrayleigh_modes = [1, 3]')"
refuse() {  # refuse NAME PATTERN simulate-options...
  local name=$1 pattern=$2 rc=0; shift 2
  "$bin" simulate "$@" > "$tmp/$name.out" 2>&1 || rc=$?
  if [ $rc -ne 2 ] || ! grep -q -- "$pattern" "$tmp/$name.out" || [ "$(wc -l < "$tmp/$name.out")" -ne 1 ]; then
    echo "FAIL $name (rc $rc):"; cat "$tmp/$name.out"; fails=$((fails+1))
  else echo "ok   $name: $(cat "$tmp/$name.out")"; fi
}
three=(--storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 3 --duration 1)
refuse sim_one_storey 'ERROR: --rayleigh-modes1 for a one-storey building, --rayleigh-modes1' --rayleigh-modes1 1,2
refuse sim_beyond "ERROR: --rayleigh-modes1 '1,4' is not two different modes of building 1's 3 storeys" \
  "${three[@]}" --rayleigh-modes1 1,4
refuse sim_same "ERROR: --rayleigh-modes2 '2,2' is not two different modes" "${three[@]}" --rayleigh-modes2 2,2
refuse sim_modal 'ERROR: --rayleigh-modes1 with --modal-zeta' "${three[@]}" --rayleigh-modes1 1,3 --modal-zeta 0.05
refuse sim_row_beyond 'ERROR: --rayleigh-modes3 is for building 3 and the row has --buildings 2' "${three[@]}" \
  --rayleigh-modes3 1,2
refuse sim_row_inherit "ERROR: --rayleigh-modes1 '1,3' is not two different modes of building 3's 2 storeys.*--rayleigh-modes3" \
  "${three[@]}" --buildings 3 --storeys3 2 --rayleigh-modes1 1,3
[ $fails -eq 0 ] || exit 1
