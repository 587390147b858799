#!/usr/bin/env bash
# Classical modal damping in studies and simulate ([structures] / [structures.buildingK] damping = "modal",
# modal_zeta = [...]; simulate --modal-zeta; issue 25 §2, docs/architecture.md §2.2.3):
#  1. studies/quick-storeys.toml with damping = "modal" is bit-identical at 1 and 2 ranks, batch width 1 and
#     skip_untouched = false (tests/lib/study_invariance.sh), and differs from its Rayleigh run (the key is read);
#  2. a one-record, one-model study of a 3- against a 5-storey building with modal_zeta = [0.02, 0.05, 0.03] gives, bit
#     for bit, pounding simulate --modal-zeta 0.02,0.05,0.03 (coupled: impact count, peak force, first impact, peak
#     u, every floor's peak u, drift and absolute acceleration; uncoupled: every floor's peak u, drift and absolute
#     acceleration, the peak closing) -- the study and simulate fill the System separately and share physics::set_shear_building and the stepper; simulate's JSON reports each
#     mode's ratio (0.02, 0.05, 0.03, then 0.03);
#     2b. the same with building 1 base-isolated (linear bearing): the superstructure's fixed-base modal C acting on
#     the floors' velocities relative to the base (physics::isolated_damping_matrix; refused before);
#     2c. /settings/structures.buildingK holds damping = "modal" and modal_zeta where a building has them ([structures]
#     or its own table; damping alone without modal_zeta), and neither with Rayleigh damping (the default);
#  3. bad input: modal_zeta without damping = "modal", an unknown damping name, modal on an
#     SDOF building, a ratio outside [0, 0.5], --modal-zeta for an SDOF pair or for one-storey buildings: one ERROR naming the key, exit 2, no
#     results file.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$PWD/unused.toml  # set below, once $tmp exists
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study, shear_pair_simulate
fail() { echo "FAIL: $*"; exit 1; }

# 1. invariance of the quick storeys study with modal damping
sed 's/^storey_height = 3.2/storey_height = 3.2\ndamping = "modal"\nmodal_zeta = [0.05, 0.03]/' \
  "$src/studies/quick-storeys.toml" > "$tmp/quick-modal.toml"
study=$tmp/quick-modal.toml
study_invariance
"$bin" run "$src/studies/quick-storeys.toml" --out "$tmp/rayleigh.h5" --quiet > /dev/null 2>&1
if cmp "$tmp/r0.h5" "$tmp/rayleigh.h5" --ignore=study_text,output > /dev/null 2>&1; then
  fail "the modal study gave the Rayleigh study's results"
fi
echo "ok   invariance (ranks, batch width, skip_untouched), and modal != Rayleigh"

# 2. study == simulate, bit for bit
sine_record "$tmp/rec.txt" 0.25 0.9 0.10 3.1
modal=('title="modal damping"' 'structures.damping="modal"' 'structures.modal_zeta=[0.02, 0.05, 0.03]')
shear_pair_study "$tmp/one.toml" "${modal[@]}"
"$bin" run "$tmp/one.toml" --out "$tmp/one.h5" --quiet > /dev/null 2>&1 || fail "the modal study did not run"
sim() { shear_pair_simulate --modal-zeta 0.02,0.05,0.03 "$@"; }
# same_as_simulate NAME [simulate options]: the study $tmp/NAME.h5 against simulate with those options
same_as_simulate() {
  simulate_both "$@"
  PYTHONPATH="$src/tests/lib" /usr/bin/python3 - "$tmp" "$1" <<'PY'
import sys
from study_simulate import load, pair_checks, assert_equal
f, s, u, g = load(*sys.argv[1:3])
name = sys.argv[2]
assert abs(0.5 * f["models/code_gap"][()][0] - 0.064) < 1e-15
# with the coupled run's floors at the gap (issue 25 §3: per-floor observers of the coupled run)
checks = pair_checks(f, s, u, g, coupled_floors=True)
assert s["status"] == "ok" and u["status"] == "ok" and f["impacts/status"][()].ravel()[g] == 0
assert s["impact_count"] > 0, "no impacts at the gap"
assert_equal(checks)
zetas = [b["modal_damping"] for b in s["buildings"]]
assert zetas == [[0.02, 0.05, 0.03], [0.02, 0.05, 0.03, 0.03, 0.03]], zetas
print(f"ok   {name}: study == simulate bit for bit ({len(checks)} numbers; {s['impact_count']} impacts), modal ratios "
      f"{zetas}")
PY
}
same_as_simulate one
# 2b. building 1 base-isolated on a linear bearing, its superstructure modally damped
shear_pair_study "$tmp/iso.toml" "${modal[@]}" \
  'structures.building1.isolation={bearing = "linear", base_mass = 3.0e5, k_eff = 1.2e7, zeta_eff = 0.1}'
"$bin" run "$tmp/iso.toml" --out "$tmp/iso.h5" --quiet > /dev/null 2>&1 || fail "the isolated modal study did not run"
same_as_simulate iso --isolation1 linear --base-mass1 3e5 --bearing-keff1 1.2e7 --bearing-zeta1 0.1

# 2c. /settings/structures.buildingK holds damping = "modal" and modal_zeta where the building has them, and nothing
# with Rayleigh damping (the default: every earlier study's file and bits); per building as in [structures]
shear_pair_study "$tmp/b2.toml" 'title="modal damping per building"' 'structures.building1.damping="modal"' \
  'structures.building2.damping="modal"' 'structures.building2.modal_zeta=[0.04]'
"$bin" run "$tmp/b2.toml" --out "$tmp/b2.h5" --quiet > /dev/null 2>&1 || fail "the per-building modal study did not run"
/usr/bin/python3 - "$tmp" <<'PY'
import sys, h5py
tmp = sys.argv[1]
def damping(name, b):
    a = h5py.File(f"{tmp}/{name}.h5", "r")[f"settings/structures.building{b}"].attrs
    d, z = a.get("damping"), a.get("modal_zeta")
    return (d.decode() if isinstance(d, bytes) else d, None if z is None else [float(x) for x in z])
modal = lambda *z: ("modal", list(z))
want = {("one", 1): modal(0.02, 0.05, 0.03), ("one", 2): modal(0.02, 0.05, 0.03), ("iso", 1): modal(0.02, 0.05, 0.03),
        ("r0", 1): modal(0.05, 0.03), ("r0", 2): modal(0.05, 0.03),
        ("b2", 1): ("modal", None), ("b2", 2): modal(0.04),
        ("rayleigh", 1): (None, None), ("rayleigh", 2): (None, None)}
got = {k: damping(*k) for k in want}
bad = {k: (got[k], w) for k, w in want.items() if got[k] != w}
assert not bad, bad
print(f"ok   settings: damping/modal_zeta of each building as given ({len(want)} buildings), none with Rayleigh")
PY

# 3. bad input
fails=0
body=$(cat "$src/studies/quick-storeys.toml")
b1() { echo "$body" | sed "s/^\[gaps\]/[structures.building1]\n$1\n\n[gaps]/"; }
expect_error zeta_without_modal 'modal_zeta is given without damping = "modal".*\[structures.building1\].modal_zeta' \
  "$(b1 'modal_zeta = [0.02]')"
expect_error damping_name '\[structures.building1\].damping, write damping = "rayleigh"' "$(b1 'damping = "viscous"')"
expect_error modal_sdof 'damping is given for an SDOF building.*\[structures.building1\].damping' \
  "$(b1 'model = "sdof"\ndamping = "modal"')"
expect_error modal_zeta_range '\[structures.building1\].modal_zeta' "$(b1 'damping = "modal"\nmodal_zeta = [0.02, 0.7]')"
rc=0
"$bin" simulate --record "$tmp/rec.txt" --modal-zeta 0.02 > "$tmp/sdof.out" 2>&1 || rc=$?
if [ $rc -ne 2 ] || ! grep -q 'ERROR: --modal-zeta damps multi-storey buildings.*--modal-zeta' "$tmp/sdof.out"; then
  echo "FAIL simulate_sdof (rc $rc):"; cat "$tmp/sdof.out"; fails=$((fails+1))
else echo "ok   simulate_sdof: $(grep ERROR "$tmp/sdof.out")"; fi
# storey options but one storey each: nothing to damp modally (it used to run on --zeta and say nothing)
rc=0
"$bin" simulate --record "$tmp/rec.txt" --storeys1 1 --storeys2 1 --storey-mass1 1e5 --storey-stiffness1 1e8 \
  --modal-zeta 0.02 > "$tmp/one.out" 2>&1 || rc=$?
if [ $rc -ne 2 ] || ! grep -q 'ERROR: --modal-zeta damps multi-storey buildings and every building of this run has one storey' "$tmp/one.out" \
   || [ "$(wc -l < "$tmp/one.out")" -ne 1 ]; then
  echo "FAIL simulate_one_storey (rc $rc):"; cat "$tmp/one.out"; fails=$((fails+1))
else echo "ok   simulate_one_storey: $(grep ERROR "$tmp/one.out")"; fi
[ $fails -eq 0 ] || exit 1
