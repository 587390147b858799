#!/usr/bin/env bash
# Friction-pendulum and Bouc-Wen bearings in studies ([structures.buildingK] isolation = {bearing =
# "friction-pendulum" | "bouc-wen", ...}, issue 25 §2, §6):
#  1. a one-record, one-model study of each bearing (an isolated 3-storey building beside a fixed 5-storey one, the
#     link-element pair's storeys) gives, bit for bit, pounding simulate's numbers with the equivalent
#     --isolation1/--bearing-* options: the coupled run at the gap 0.5 d = 0.064 m (impact count, peak force, first
#     impact, peak u1 with the base, peak u2) and the uncoupled run (--contact none: every floor's peak u, drift and
#     absolute acceleration of the isolated building, the peak closing) -- the study (study/system_block.cpp) and
#     simulate (cli/commands/simulate.cpp) fill the System separately and share physics::set_isolated_building and
#     the system stepper, so any difference is a wiring error, not round-off;
#  2. the probability scene of the same study writes the impacts scene's uncoupled rows, bit for bit;
#  3. a study with both (building 1 on friction pendulums, building 2 on Bouc-Wen bearings, a sampled period, two
#     records) is bit-identical at 1 and 2 ranks, batch width 1 and skip_untouched = false (tests/lib/study_invariance.sh);
#  4. bad input: a key of another bearing, a missing required key, absurd values, mu_fast without a rate, gamma
#     outside [-beta, beta]: one ERROR naming file:line and the key, exit 2, no results file.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$PWD/unused.toml  # set below, once $tmp exists
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance
fail() { echo "FAIL: $*"; exit 1; }
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study, shear_pair_simulate
sine_record "$tmp/rec.txt" 0.15 0.5 0.10 3.1
sine_record "$tmp/rec2.txt" 0.15 0.8 0.10 3.1
fps='bearing = "friction-pendulum", base_mass = 3.0e5, radius = 2.0, mu_slow = 0.05, mu_fast = 0.1, rate = 20.0, u_y = 5e-4'
bw='bearing = "bouc-wen", base_mass = 3.0e5, k1 = 3.0e7, k2 = 1.2e6, qd = 6.0e5, a = 1.0, beta = 0.6, gamma = 0.4, eta = 2'
fps_opts=(--isolation1 friction-pendulum --base-mass1 3e5 --bearing-radius1 2.0 --bearing-mu-slow1 0.05
          --bearing-mu-fast1 0.1 --bearing-rate1 20 --bearing-uy1 5e-4)
bw_opts=(--isolation1 bouc-wen --base-mass1 3e5 --bearing-k1-1 3e7 --bearing-k2-1 1.2e6 --bearing-qd1 6e5
         --bearing-a1 1.0 --bearing-beta1 0.6 --bearing-gamma1 0.4 --bearing-eta1 2)
# write_study <file> <scene> <isolation of building 1> [KEY=VALUE ...]
write_study() {
  local file=$1 scene=$2 iso=$3; shift 3
  shear_pair_study "$file" 'title="isolators"' "scene=\"$scene\"" "structures.building1.isolation={$iso}" \
    'contact.damping_law="three-spring"' "$@"
}
sim() { shear_pair_simulate "$@"; }

# 1. each bearing: study == simulate, bit for bit; 2. the probability scene's uncoupled rows == the impacts scene's
for b in fps bw; do
  opts="${b}_opts[@]"
  write_study "$tmp/$b.toml" impacts "${!b}"
  "$bin" run "$tmp/$b.toml" --out "$tmp/$b.h5" --quiet > /dev/null 2>&1 || fail "$b: the study did not run"
  write_study "$tmp/${b}_p.toml" probability "${!b}"
  "$bin" run "$tmp/${b}_p.toml" --out "$tmp/${b}_p.h5" --quiet > /dev/null 2>&1 || fail "$b: the probability study"
  sim "${!opts}" --contact hertzdamp --damping-law three-spring --e 0.5 > "$tmp/$b.json"
  sim "${!opts}" --contact none > "$tmp/${b}_free.json"
  /usr/bin/python3 - "$tmp" "$b" <<'PY'
import json, sys, h5py
import numpy as np
tmp, b = sys.argv[1], sys.argv[2]
f, p = h5py.File(f"{tmp}/{b}.h5", "r"), h5py.File(f"{tmp}/{b}_p.h5", "r")
s, u = json.load(open(f"{tmp}/{b}.json")), json.load(open(f"{tmp}/{b}_free.json"))
G = list(f["impacts/gap_ratios"][()])
g = G.index(0.5)
assert abs(0.5 * f["models/code_gap"][()][0] - 0.064) < 1e-15
at = lambda name: f[name][()].ravel()[g]
checks = [  # (what, study, simulate): bit for bit
    ("impact_count", at("impacts/impact_count"), s["impact_count"]),
    ("peak_force", at("impacts/peak_force"), s["peak_force"]),
    ("t_first_impact", at("impacts/t_first_impact"), s["t_first_impact"]),
    ("peak_u1", at("impacts/peak_u1"), max(max(s["peak_u1"]), s["peak_bearing_u1"])),  # the study's includes the base
    ("peak_u2", at("impacts/peak_u2"), max(s["peak_u2"])),
    ("uncoupled peak_closing", f["uncoupled/peak_closing"][()].ravel()[0], u["peak_closing"]),
]
floors = lambda name: list(f[name][()].ravel())
for name, mine, theirs in [("peak_u_floors1", floors("uncoupled/peak_u_floors1"), [u["peak_bearing_u1"]] + u["peak_u1"]),
                           ("peak_drift1", floors("uncoupled/peak_drift1")[1:], u["peak_drift1"]),
                           ("peak_acc_floors1", floors("uncoupled/peak_acc_floors1")[1:], u["peak_abs_acc1_g"])]:
    checks += [(f"uncoupled {name}[{i}]", a, c) for i, (a, c) in enumerate(zip(mine, theirs, strict=True))]
assert s["status"] == "ok" and u["status"] == "ok" and at("impacts/status") == 0
assert s["impact_count"] > 0, "no impact at 0.064 m: the coupled comparison would not test the contact"
for what, mine, theirs in checks:
    assert mine == theirs, f"{b}: {what}: study {mine!r}, simulate {theirs!r}"
# the bearing is the named one: the study's settings text names it
text = f["settings/structures.building1"].attrs["isolation"]
text = text.decode() if isinstance(text, bytes) else str(text)
assert text.startswith("friction-pendulum bearing" if b == "fps" else "bouc-wen bearing"), text
for name in f["uncoupled"]:
    assert np.array_equal(f["uncoupled"][name][()], p["uncoupled"][name][()], equal_nan=True), f"{b}: probability {name}"
print(f"{b}: {len(checks)} numbers equal to simulate's, {s['impact_count']} impacts at 0.064 m, peak force "
      f"{s['peak_force']:.6g} N; the probability scene's uncoupled rows equal")
PY
done

# 3. both bearings, a sampled period, two records: ranks, batch width, skip_untouched
study=$tmp/both.toml
write_study "$study" impacts "$fps" "structures.building2.isolation={${bw/base_mass = 3.0e5, /}}" \
  'records.files=["rec.txt", "rec2.txt"]' structures.samples_per_pair=4 \
  'structures.building2.period={lognormal = {median = 1.22, cov = 0.2}}' structures.building2.storey_stiffness= \
  'gaps.ratios=[0.1, 0.5, 1.0, 3.0, 6.0]'
study_invariance
/usr/bin/python3 - "$tmp/r0.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
assert (f["uncoupled/status"][()] == 0).all() and (f["impacts/status"][()] == 0).all()
T2 = f["models/T2"][()]
assert len(np.unique(T2)) == 4, T2  # four sampled periods of building 2
n = f["impacts/impact_count"][()]
assert (n > 0).any() and (n == 0).any(), n
print(f"both bearings: {int((n > 0).sum())} of {n.size} coupled analyses pound; ranks, batch 1 and skip_untouched agree")
PY

# 4. bad input: one ERROR naming file:line and the key, exit 2, no results
bad() {  # bad <key named> <isolation table of building 1>
  write_study "$tmp/bad.toml" impacts "$2"
  rm -f "$tmp/bad.h5"
  set +e; "$bin" run "$tmp/bad.toml" --out "$tmp/bad.h5" --quiet > "$tmp/bad.out" 2> "$tmp/bad.err"; local rc=$?; set -e
  [ $rc -eq 2 ] || fail "{$2}: exit $rc, want 2"
  [ ! -e "$tmp/bad.h5" ] || fail "{$2}: wrote results"
  [ "$(grep -c ERROR "$tmp/bad.err")" -eq 1 ] || fail "{$2}: not one ERROR line: $(cat "$tmp/bad.err")"
  grep -q "ERROR: .*bad.toml:23 \[structures.building1.isolation\]\.$1," "$tmp/bad.err" ||
    fail "{$2}: the error does not name bad.toml:23 and $1: $(cat "$tmp/bad.err")"
}
bad radius 'bearing = "friction-pendulum", mu_slow = 0.05'
bad mu_slow 'bearing = "friction-pendulum", radius = 2.0'
bad radius 'bearing = "friction-pendulum", radius = 500.0, mu_slow = 0.05'
bad radius 'bearing = "friction-pendulum", radius = 0.0, mu_slow = 0.05'
bad mu_slow 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.9'
bad mu_fast 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.05, mu_fast = -0.1, rate = 20.0'
bad rate 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.05, mu_fast = 0.1'
bad u_y 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.05, u_y = 0.5'
bad k_eff 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.05, k_eff = 1e6'
bad qd 'bearing = "friction-pendulum", radius = 2.0, mu_slow = 0.05, qd = 1e5'
bad radius 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, radius = 2.0'
bad beta 'bearing = "lead-rubber", k1 = 3e7, k2 = 1.2e6, qd = 6e5, beta = 0.5'
bad a 'bearing = "linear", k_eff = 1e6, a = 1.0'
bad qd 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6'
bad k2 'bearing = "bouc-wen", k1 = 3e7, k2 = 3e7, qd = 6e5'
bad gamma 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, beta = 0.3, gamma = 0.5'
bad eta 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, eta = 9'
bad eta 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, eta = 1.5'
bad a 'bearing = "bouc-wen", k1 = 3e7, k2 = 1.2e6, qd = 6e5, a = 0.0'
bad bearing 'bearing = "friction pendulum", radius = 2.0, mu_slow = 0.05'
echo "1 passed, 0 failed"
