#!/usr/bin/env bash
# Newmark and RK4 on shear buildings in studies and simulate ([analysis] stepper, --stepper; issue 25 step 5,
# physics/system_lane_stepper.hpp):
#  1. for each of newmark and rk4, a one-record, one-model study of a 3- against a 5-storey building (elastic storeys,
#     Rayleigh damping, Hertzdamp at the three common levels; yielding storeys: test_system_steppers) gives, bit for bit, pounding simulate
#     --stepper X (coupled: impact count, peak force, first impact, peak u; uncoupled: every floor's peak u, drift and
#     absolute acceleration, the peak closing); the two steppers' results differ from each other and from central
#     difference's (the key is read), by less than 2 % in the uncoupled peak displacements and 5 % in the coupled ones
#     (62 impacts: measured 2.7 % for Newmark at h = 1 ms);
#  2. the same with building 1 base-isolated on a lead-rubber bearing and rk4;
#  3. bad input: nigam-jennings with shear buildings, newmark with a friction-pendulum bearing (study and simulate),
#     simulate --stepper nigam-jennings with storeys: one ERROR naming the key, exit 2, no results file.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$PWD/unused.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, expect_error
fail() { echo "FAIL: $*"; exit 1; }
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study, shear_pair_simulate

sine_record "$tmp/rec.txt" 0.30 0.9 0.12 3.1 1000
write_study() {  # write_study NAME STEPPER [KEY=VALUE ...]
  local name=$1 st=$2; shift 2
  shear_pair_study "$tmp/$name.toml" 'title="steppers on shear buildings"' "analysis.stepper=\"$st\"" "$@"
}
sim() {  # sim STEPPER [options]
  local st=$1; shift
  shear_pair_simulate --stepper "$st" "$@"
}
# same_as_simulate NAME STEPPER [simulate options]: the study $tmp/NAME.h5 against simulate with those options
same_as_simulate() {
  simulate_both "$@"
  PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" "$1" <<'PY'
import sys
from study_simulate import load, pair_checks, assert_equal
f, s, u, g = load(*sys.argv[1:3])
name = sys.argv[2]
assert abs(0.5 * f["models/code_gap"][()][0] - 0.064) < 1e-15
checks = pair_checks(f, s, u, g)
assert s["status"] in ("ok", "coarse") and u["status"] == "ok", (s["status"], u["status"])
assert s["impact_count"] > 0, "no impacts at the gap"
assert_equal(checks)
print(f"ok   {name}: study == simulate bit for bit ({len(checks)} numbers; {s['impact_count']} impacts, "
      f"peak u {max(s['peak_u1']):.6g} / {max(s['peak_u2']):.6g} m, stepper {s['stepper']})")
PY
}
for st in central-difference newmark rk4; do
  write_study "$st" "$st"
  "$bin" run "$tmp/$st.toml" --out "$tmp/$st.h5" --quiet > "$tmp/$st.out" 2>&1 || { cat "$tmp/$st.out"; fail "the $st study did not run"; }
  [ "$st" = central-difference ] || same_as_simulate "$st" "$st"
done
/usr/bin/python3 - "$tmp" <<'PY'
import sys, h5py
tmp = sys.argv[1]
r = {st: h5py.File(f"{tmp}/{st}.h5", "r") for st in ("central-difference", "newmark", "rk4")}
for k in ("uncoupled/peak_u_floors2", "impacts/peak_u2"):
    x = {st: r[st][k][()].ravel() for st in r}
    for a in ("newmark", "rk4"):
        assert (x[a] != x["central-difference"]).any(), f"{a} gave central difference's {k}"
        rel = max(abs(p - q) / q for p, q in zip(x[a], x["central-difference"]) if q > 0)
        assert rel < (0.02 if k.startswith("uncoupled") else 0.05), (a, k, rel)
        print(f"ok   {k}: {a} differs from central difference by {rel:.3g} (relative)")
    assert (x["newmark"] != x["rk4"]).any(), k
PY

# 2. building 1 isolated on a lead-rubber bearing, rk4
write_study iso rk4 \
  'structures.building1.isolation={bearing = "lead-rubber", base_mass = 3.0e5, k1 = 6.0e7, k2 = 6.0e6, qd = 1.5e5}'
"$bin" run "$tmp/iso.toml" --out "$tmp/iso.h5" --quiet > "$tmp/iso.out" 2>&1 || { cat "$tmp/iso.out"; fail "the isolated rk4 study did not run"; }
same_as_simulate iso rk4 --isolation1 lead-rubber --base-mass1 3e5 --bearing-k1-1 6e7 --bearing-k2-1 6e6 --bearing-qd1 1.5e5

# 3. bad input
fails=0
expect_error nj_shear 'nigam-jennings integrates SDOF bodies only (the pair), and the study has a shear building.*nj_shear.toml:[0-9]* \[analysis\].stepper' \
  "$(sed 's/^stepper = .*/stepper = "nigam-jennings"/' "$tmp/rk4.toml")"
expect_error newmark_fps 'the newmark stepper runs systems of bilinear springs.*building 1 has a friction-pendulum bearing.*\[analysis\].stepper' \
  "$(sed 's/^stepper = .*/stepper = "newmark"/; s/^isolation = .*/isolation = {bearing = "friction-pendulum", base_mass = 3.0e5, radius = 2.0, mu_slow = 0.04, mu_fast = 0.08, rate = 20.0}/' "$tmp/iso.toml")"
rc=0
"$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storeys2 5 --storey-mass1 3e5 --storey-stiffness1 1e8 \
  --stepper nigam-jennings > "$tmp/nj.out" 2>&1 || rc=$?
if [ $rc -ne 2 ] || [ "$(grep -c ERROR "$tmp/nj.out")" -ne 1 ] || ! grep -q 'ERROR: nigam-jennings integrates SDOF bodies only (building1 has 3 floors).*use central-difference, newmark or rk4' "$tmp/nj.out"; then
  echo "FAIL simulate_nj (rc $rc):"; cat "$tmp/nj.out"; fails=$((fails+1))
else echo "ok   simulate_nj: $(grep ERROR "$tmp/nj.out")"; fi
rc=0
sim newmark --isolation1 friction-pendulum --base-mass1 3e5 --bearing-radius1 2 --bearing-mu-slow1 0.04 \
  --bearing-mu-fast1 0.08 --bearing-rate1 20 > "$tmp/fps.out" 2>&1 || rc=$?
if [ $rc -ne 2 ] || [ "$(grep -c ERROR "$tmp/fps.out")" -ne 1 ] || ! grep -q 'ERROR: the newmark stepper runs systems of bilinear springs.*friction-pendulum.*central-difference' "$tmp/fps.out"; then
  echo "FAIL simulate_fps (rc $rc):"; cat "$tmp/fps.out"; fails=$((fails+1))
else echo "ok   simulate_fps: $(grep ERROR "$tmp/fps.out")"; fi
[ $fails -eq 0 ] || exit 1
