#!/usr/bin/env bash
# `pounding simulate` with base isolation and moat walls (issue 25 §2; docs/architecture.md §2.2.3, §2.2.4):
#  - a linear isolated 3-storey building (k_eff, zeta_eff 0.1, superstructure Rayleigh 5 % on its FIXED-BASE modes
#    1 and 2) beside a fixed one far away: the base (bearing) and floor peaks against tools/reference_systems.py isolation
#    (lsim of Kelly's relative-coordinate assembly; the Rayleigh coefficients from scipy.linalg.eigh here) within
#    1e-3 at h = dt/10;
#  - a lead-rubber isolated 3-storey building with a moat 0.1 m each side beside a fixed 5-storey one 0.05 m away:
#    the moat is hit, moat_impacts1 = the moat elements' impacts, the energy balance closes within 1e-4, --json and
#    the text agree;
#  - friction-pendulum and Bouc-Wen bearings with the moat: their numbers, the moat hit, the energy balance (their
#    response against SciPy is tests/physics/test_isolation_smooth.cpp);
#  - bad isolation options: one ERROR line naming the option, exit 2, nothing on stdout.
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, two_tone_record, sim, bad
two_tone_record 0.5
sim() { "$bin" simulate --record "$tmp/rec.txt" --dt 0.001 "$@"; }  # bad() calls this one too

# 1. linear bearing against lsim
sim --storeys1 3 --storeys2 3 --storey-mass1 3e5 --storey-stiffness1 9.81e7 --isolation1 linear --base-mass1 3e5 \
    --bearing-keff1 1.2e7 --bearing-zeta1 0.1 --gap 5 --elastic --json > "$tmp/lin.json"
"$py" - "$tmp/lin.json" "$tmp/rec.txt" "$src/tools/reference_systems.py" "$tmp" <<'PY'
import json, subprocess, sys
import numpy as np
from scipy import linalg
out = json.load(open(sys.argv[1]))
rec = np.loadtxt(sys.argv[2])
m, k, mb, keff, zb = [3e5] * 3, [9.81e7] * 3, 3e5, 1.2e7, 0.1
n = 3
Ks = np.diag([k[i] + (k[i + 1] if i + 1 < n else 0) for i in range(n)]) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
w = np.sqrt(linalg.eigh(Ks, np.diag(m), eigvals_only=True))
a0, a1 = 2 * 0.05 * w[0] * w[1] / (w[0] + w[1]), 2 * 0.05 / (w[0] + w[1])
cb = 2 * zb * np.sqrt(keff * (mb + sum(m)))
inp = {"m_base": mb, "k_b": keff, "c_b": cb, "m": m, "k": k, "a0": a0, "a1": a1, "dt": 0.01,
       "ag": list(rec[:, 1] * 9.80665), "substeps": 10}
json.dump(inp, open(sys.argv[4] + "/in.json", "w"))
subprocess.run([sys.executable, sys.argv[3], "isolation", sys.argv[4] + "/in.json", sys.argv[4] + "/out.txt"], check=True)
ref = {}
for line in open(sys.argv[4] + "/out.txt"):
    key, i, v = line.split()
    ref[(key, int(i))] = float(v)
got = [out["peak_bearing_u1"]] + out["peak_u1"]
worst = max(abs(g - ref[("peak_u", i)]) / ref[("peak_u", i)] for i, g in enumerate(got))
print(f"linear isolated: bearing peak {got[0]:.6g} m (lsim {ref[('peak_u', 0)]:.6g}), largest relative error {worst:.3g}")
assert worst < 1e-3, worst
b = out["buildings"][0]["isolation"]
assert b["bearing"] == "linear" and abs(b["bearing_c"] - cb) < 1e-9 * cb, b
PY

# 2. lead-rubber with a moat beside a fixed 5-storey building
args=(--storeys1 3 --storeys2 5 --storey-mass1 3e5 --storey-stiffness1 9.81e7 --isolation1 lead-rubber --base-mass1 3e5
      --bearing-k1-1 1.2e8 --bearing-k2-1 1.2e7 --bearing-qd1 6e5 --moat-gap1 0.1 --gap 0.05)
sim "${args[@]}" > "$tmp/lrb.txt"
sim "${args[@]}" --json > "$tmp/lrb.json"
"$py" - "$tmp/lrb.json" "$tmp/lrb.txt" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
text = dict(l.split(": ", 1) for l in open(sys.argv[2]) if ": " in l)
moat = [l for l in out["levels"] if "moat" in l["label"]]
assert len(moat) == 2 and [l["gap"] for l in moat] == [0.1, 0.1], moat
assert out["moat_impacts1"] > 0 and out["moat_impacts1"] == sum(l["impacts"] for l in moat), out["moat_impacts1"]
assert abs(out["energy_balance_error_rel"]) < 1e-4, out["energy_balance_error_rel"]
assert out["buildings"][0]["isolation"]["isolator_fy"] == 6e5 * 1.2e8 / (1.2e8 - 1.2e7)
assert int(text["moat_impacts1"]) == out["moat_impacts1"]
assert abs(float(text["peak_bearing_u1_m"]) - out["peak_bearing_u1"]) < 1e-5 * out["peak_bearing_u1"]
assert out["peak_bearing_u1"] > 0.1 and out["status"] == "ok"
print(f"lead-rubber + moat: bearing peak {out['peak_bearing_u1']:.4g} m, moat impacts {out['moat_impacts1']}, "
      f"energy balance {out['energy_balance_error_rel']:.2g}")
PY

# 3. friction pendulum (R 2 m, mu 0.05 -> 0.10 at 20 s/m, u_y 0.5 mm) and Bouc-Wen (the lead-rubber numbers, eta 2)
#    with the moat: the bearing's numbers (W = g M_total, W/R), the moat hit, the energy balance within 1e-3
for bearing in friction-pendulum bouc-wen; do
  if [ $bearing = friction-pendulum ]; then
    opts=(--bearing-radius1 2 --bearing-mu-slow1 0.05 --bearing-mu-fast1 0.1 --bearing-rate1 20 --bearing-uy1 5e-4)
  else
    opts=(--bearing-k1-1 1.2e8 --bearing-k2-1 1.2e7 --bearing-qd1 6e5 --bearing-eta1 2 --bearing-beta1 0.9
          --bearing-gamma1 0.1)
  fi
  args=(--storeys1 3 --storeys2 5 --storey-mass1 3e5 --storey-stiffness1 9.81e7 --isolation1 $bearing --base-mass1 3e5
        "${opts[@]}" --moat-gap1 0.1 --gap 0.05)
  sim "${args[@]}" > "$tmp/$bearing.txt"
  sim "${args[@]}" --json > "$tmp/$bearing.json"
  "$py" - "$tmp/$bearing.json" "$tmp/$bearing.txt" $bearing <<'PY'
import json, math, sys
out = json.load(open(sys.argv[1]))
text = dict(l.split(": ", 1) for l in open(sys.argv[2]) if ": " in l)
iso = out["buildings"][0]["isolation"]
assert iso["bearing"] == sys.argv[3] and iso["bearing_c"] == 0, iso
if sys.argv[3] == "friction-pendulum":
    W = 9.80665 * 1.2e6
    assert abs(iso["bearing_weight_N"] - W) < 1e-9 * W and abs(iso["bearing_pendulum_k_N_m"] - W / 2) < 1e-9 * W, iso
    assert iso["isolated_periods"][0] > 2 * math.pi * math.sqrt(2 / 9.80665), iso  # a flexible superstructure: longer
    assert float(text["building1_bearing_mu_fast"]) == 0.1
else:
    assert abs(iso["bearing_uy_m"] - 6e5 / 1.08e8) < 1e-15 and iso["bearing_eta"] == 2, iso
assert iso["isolator_fy"] is None and iso["isolator_alpha"] is None, iso  # no yield point: null (nan in the text)
assert out["moat_impacts1"] > 0 and out["status"] == "ok", (out["moat_impacts1"], out["status"])
assert abs(out["energy_balance_error_rel"]) < 1e-3, out["energy_balance_error_rel"]
assert abs(float(text["peak_bearing_u1_m"]) - out["peak_bearing_u1"]) < 1e-5 * out["peak_bearing_u1"]
print(f"{sys.argv[3]} + moat: bearing peak {out['peak_bearing_u1']:.4g} m, residual {out['final_bearing_u1']:.3g} m, "
      f"moat impacts {out['moat_impacts1']}, energy balance {out['energy_balance_error_rel']:.2g}")
PY
done

# 4. bad options
bad "--isolation1" --isolation1 friction
bad "--bearing-radius1" --isolation1 friction-pendulum --bearing-mu-slow1 0.05
bad "--bearing-radius1" --isolation1 friction-pendulum --bearing-radius1 0 --bearing-mu-slow1 0.05
bad "--bearing-mu-slow1" --isolation1 friction-pendulum --bearing-radius1 2
bad "--bearing-mu-slow1" --isolation1 friction-pendulum --bearing-radius1 2 --bearing-mu-slow1 0.9
bad "--bearing-rate1" --isolation1 friction-pendulum --bearing-radius1 2 --bearing-mu-slow1 0.05 --bearing-mu-fast1 0.1
bad "--bearing-uy1" --isolation1 friction-pendulum --bearing-radius1 2 --bearing-mu-slow1 0.05 --bearing-uy1 0.5
bad "--bearing-keff1" --isolation1 friction-pendulum --bearing-radius1 2 --bearing-mu-slow1 0.05 --bearing-keff1 1e7
bad "--bearing-radius1" --isolation1 lead-rubber --bearing-k1-1 1e7 --bearing-k2-1 1e6 --bearing-qd1 1e5 --bearing-radius1 2
bad "--bearing-beta1" --isolation1 lead-rubber --bearing-k1-1 1e7 --bearing-k2-1 1e6 --bearing-qd1 1e5 --bearing-eta1 2
bad "--bearing-gamma1" --isolation1 bouc-wen --bearing-k1-1 1e7 --bearing-k2-1 1e6 --bearing-qd1 1e5 --bearing-gamma1 0.9
bad "--bearing-eta1" --isolation1 bouc-wen --bearing-k1-1 1e7 --bearing-k2-1 1e6 --bearing-qd1 1e5 --bearing-eta1 9
bad "--bearing-k2-1" --isolation1 bouc-wen --bearing-k1-1 1e7 --bearing-k2-1 1e7 --bearing-qd1 1e5
bad "--bearing-keff1" --isolation1 linear
bad "--bearing-zeta1" --isolation1 linear --bearing-keff1 1e7 --bearing-zeta1 0.9
bad "--bearing-k2-1" --isolation1 lead-rubber --bearing-k1-1 1e7 --bearing-k2-1 2e7 --bearing-qd1 1e5
bad "--bearing-qd1" --isolation1 lead-rubber --bearing-k1-1 1e7 --bearing-k2-1 1e6
bad "--base-mass2" --isolation2 linear --bearing-keff2 1e7 --base-mass2 0
bad "--isolation1" --moat-gap1 0.1
bad "--moat-gap1" --isolation1 linear --bearing-keff1 1e7 --moat-e1 0.5
bad "--moat-law1" --isolation1 linear --bearing-keff1 1e7 --moat-gap1 0.1 --moat-law1 stereomechanical
bad "--moat-e1" --isolation1 linear --bearing-keff1 1e7 --moat-gap1 0.1 --moat-e1 0

# 5. simulate takes the ranges of the study keys that mean the same (one list, src/config/study_keys.cpp): a value
#    just outside a key's range in `pounding study-reference` is refused naming the key's range, and a shake-table
#    model (6.53 kg floors, the impact-stiffness paper's scale; base 10 kg, k_eff 500 N/m) runs as a study would run
#    it (simulate refused base masses below 1e3 kg and bearings below 1e3 N/m while a study took them).
"$bin" study-reference > "$tmp/ref.md"
"$py" - "$tmp/ref.md" > "$tmp/limits.txt" <<'PY'
import re, sys
section, rows = None, {}
for line in open(sys.argv[1]):
    if line.startswith("## "):
        section = "isolation" if "isolation = {" in line else "moat" if "moat = {" in line else None
    elif section and line.startswith("| `"):
        cells = [c.strip() for c in line.split("|")[1:-1]]
        m = re.match(r"[\[(]\s*(-?[0-9.e+-]+),\s*(-?[0-9.e+-]+)\s*\]", cells[4])
        if m: rows[(section, cells[0].strip("`"))] = (float(m.group(1)), float(m.group(2)))
options = {("isolation", "base_mass"): "--base-mass1", ("isolation", "k_eff"): "--bearing-keff1",
           ("isolation", "zeta_eff"): "--bearing-zeta1", ("moat", "gap"): "--moat-gap1",
           ("moat", "stiffness"): "--moat-stiffness1", ("isolation", "k1"): "--bearing-k1-1",
           ("isolation", "qd"): "--bearing-qd1", ("isolation", "radius"): "--bearing-radius1",
           ("isolation", "mu_slow"): "--bearing-mu-slow1", ("isolation", "u_y"): "--bearing-uy1"}
for key, option in options.items():
    lo, hi = rows[key]
    print(option, key[1], lo / 2 if lo > 0 else lo - 1, hi * 2)
PY
[ "$(wc -l < "$tmp/limits.txt")" -eq 10 ] || fail "study-reference: not every isolation/moat range was found"
while read -r option key below above; do
  case $option in
    --bearing-keff1|--bearing-zeta1|--base-mass1) base=(--isolation1 linear --bearing-keff1 1e7) ;;
    --moat-gap1|--moat-stiffness1) base=(--isolation1 linear --bearing-keff1 1e7 --moat-gap1 0.1 --moat-law1 linear --moat-stiffness1 1e8) ;;
    --bearing-k1-1|--bearing-qd1) base=(--isolation1 lead-rubber --bearing-k1-1 1e7 --bearing-k2-1 0 --bearing-qd1 1e5) ;;
    *) base=(--isolation1 friction-pendulum --bearing-radius1 2 --bearing-mu-slow1 0.05) ;;
  esac
  args=(); skip=0  # the base options less the one under test
  for x in "${base[@]}"; do
    if [ $skip -eq 1 ]; then skip=0; elif [ "$x" = "$option" ]; then skip=1; else args+=("$x"); fi
  done
  for v in $below $above; do
    bad "$option" "${args[@]}" "$option" "$v"
    grep -q "as $key in a study" "$tmp/bad.err" || fail "$option $v: the error does not quote $key's range"
  done
done < "$tmp/limits.txt"
sim --storeys1 3 --storeys2 3 --storey-mass1 6.53 --storey-stiffness1 1.375e5 --storey-mass2 6.53 \
    --storey-stiffness2 1.375e5 --isolation1 linear --base-mass1 10 --bearing-keff1 500 --bearing-zeta1 0.1 \
    --gap 5 --elastic --json > "$tmp/small.json" || fail "a shake-table isolated building (base 10 kg, 500 N/m) is refused"
"$py" -c 'import json,sys; o=json.load(open(sys.argv[1])); assert o["status"] == "ok", o["status"]' "$tmp/small.json" \
  || fail "the shake-table isolated building did not run"
echo "simulate_isolation: ok"
