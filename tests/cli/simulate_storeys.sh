#!/usr/bin/env bash
# `pounding simulate` with multi-storey buildings and --json, `pounding collide --json` (issue 25 §4;
# docs/architecture.md §2.7.3):
#  - --json of the SDOF pair holds the text output's numbers (the same run, full precision);
#  - two one-storey buildings given by storey options are the same pair: every observer bit-identical;
#  - 3 vs 5 storeys of 3.2 m: peak_u1/peak_u2 one per floor, three contact levels, totals consistent with them;
#    amplification per floor = coupled peak / the peak of the same buildings never touching (exactly 1 there);
#  - a linear 3-storey building without contact (Rayleigh 5 % on modes 1 and 2) against an independent SciPy
#    solution (eigh for the Rayleigh coefficients, lsim of the state-space model on the same piecewise-linear
#    ground motion): peak floor displacements within 5e-4 at h = dt/10 (measured 6.1e-5; central difference
#    errs by about (h omega_3)^2 / 24 = 2e-4 in the top mode);
#  - bad storey options: one ERROR line naming the option, exit 2, nothing on stdout;
#  - collide --json: the text's values at full precision, status and its note.
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, two_tone_record, sim, bad
# a 12 s two-column record (time s, acceleration g): two tones, 0.25 g
two_tone_record 1.3
# --dt 0.001 (10 substeps) resolves the contacts of the pair (status ok; at the record step it is "coarse", exit 3)

# 1. the pair: --json against the text output
sim --gap 0.02 --dt 0.001 > "$tmp/pair.txt"
sim --gap 0.02 --dt 0.001 --json --series "$tmp/pair.csv" > "$tmp/pair.json"
[ "$(wc -l < "$tmp/pair.csv")" -eq 12002 ] || fail "--json --series: $(wc -l < "$tmp/pair.csv") lines, want 12002"
! grep -q storeys "$tmp/pair.txt" || fail "the pair's text output changed: it names storeys"
"$py" - "$tmp/pair.txt" "$tmp/pair.json" <<'PY' || fail "pair --json differs from its text output"
import json, sys
text = dict(l.split(": ", 1) for l in open(sys.argv[1]).read().splitlines())
j = json.load(open(sys.argv[2]))
pairs = [("peak_u1_m", j["peak_u1"][0]), ("peak_u2_m", j["peak_u2"][0]), ("impact_count", j["impact_count"]),
         ("peak_contact_force_N", j["peak_force"]), ("peak_closing_m", j["peak_closing"]),
         ("t_first_impact_s", j["t_first_impact"]), ("peak_abs_acc1_g", j["peak_abs_acc1_g"][0]),
         ("energy_input_J", j["energy_input_J"]), ("contact_energy_dissipated_J", j["levels"][0]["contact_energy"]),
         ("h_omega_contact", j["h_omega_contact"]), ("status", j["status"])]
assert j["impact_count"] > 0, "the pair does not pound: the test needs impacts"
for name, v in pairs:
    t = text[name]
    ok = t == v if isinstance(v, str) else abs(float(t) - v) <= 5e-6 * abs(v) + 1e-300
    assert ok, f"{name}: text {t}, json {v}"
assert len(j["levels"]) == 1 and j["levels"][0]["level"] == 1 and j["levels"][0]["impacts"] == j["impact_count"]
assert j["amplification_u1"][0] != 1.0 and len(j["amplification_acc2"]) == 1  # against the pair without pounding
print(f"ok:   pair --json = text ({j['impact_count']} impacts, peak force {j['peak_force']:.6g} N)")
PY

# 2. two one-storey buildings through the storey options: the same pair, the same bits
sim --gap 0.02 --dt 0.001 --json --storeys1 1 --storeys2 1 > "$tmp/one.json"
"$py" - "$tmp/pair.json" "$tmp/one.json" <<'PY' || fail "one-storey buildings differ from the pair"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in a:  # the buildings' heights differ (the SDOF's --h, the storey's 3.2 m), and with them the drift ratios
    if k != "buildings" and not k.startswith("peak_drift_ratio"):
        assert a[k] == b[k], f"{k}: {a[k]} vs {b[k]}"
print("ok:   --storeys1 1 --storeys2 1 gives the pair's observers bit for bit")
PY

# 3. 3 vs 5 storeys of 3.2 m at common floors
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 --json > "$tmp/35.json"
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 > "$tmp/35.txt"
# the same buildings 5 m apart: never touching, the uncoupled run
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 5 --dt 0.001 --json > "$tmp/35free.json"
"$py" - "$tmp/35.json" "$tmp/35.txt" "$tmp/35free.json" <<'PY' || fail "3 vs 5 storeys"
import json, math, sys
j = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
free = json.load(open(sys.argv[3]))
# amplification per floor = coupled peak / the peak of the run without contact (here: 5 m apart, no impact)
assert free["impact_count"] == 0
for b in ("1", "2"):
    for key, peak in (("u", "peak_u"), ("drift", "peak_drift")):
        want = [c / f for c, f in zip(j[peak + b], free[peak + b])]
        got = j["amplification_" + key + b]
        assert all(abs(g - w) <= 1e-14 * w for g, w in zip(got, want)), (key + b, got, want)
        assert all(a == 1.0 for a in free["amplification_" + key + b]), free["amplification_" + key + b]
assert max(j["amplification_acc1"]) > 1.5, j["amplification_acc1"]  # pounding raises floor accelerations
assert "amplification_u2: " in text
assert len(j["peak_u1"]) == 3 and len(j["peak_u2"]) == 5, (j["peak_u1"], j["peak_u2"])
assert [l["level"] for l in j["levels"]] == [1, 2, 3], j["levels"]
assert j["impact_count"] == sum(l["impacts"] for l in j["levels"]) and j["impact_count"] > 0
assert j["peak_force"] == max(l["peak_force"] for l in j["levels"])
b1, b2 = j["buildings"]
assert b1["floor_levels"] == [3.2, 6.4, 9.600000000000001] and len(b2["floor_levels"]) == 5
# uniform stick: omega_1 = 2 sqrt(k/m) sin(pi / (2 (2n + 1)))
for b, n, m, k in ((b1, 3, 2e5, 3e8), (b2, 5, 2.5e5, 2.2e8)):
    w1 = 2 * math.sqrt(k / m) * math.sin(math.pi / (2 * (2 * n + 1)))
    assert abs(b["periods"][0] - 2 * math.pi / w1) < 1e-10 * b["periods"][0], (b["periods"][0], 2 * math.pi / w1)
    assert abs(b["modal_damping"][0] - 0.05) < 1e-12 and abs(b["modal_damping"][1] - 0.05) < 1e-12
assert j["status"] == "ok"
# drift: storey 1 drift = floor 1 displacement's peak; drift ratio = drift / 3.2 m
assert j["peak_drift2"][0] == j["peak_u2"][0] and len(j["peak_drift_ratio2"]) == 5
assert all(abs(r - d / 3.2) <= 1e-12 * r for r, d in zip(j["peak_drift_ratio1"], j["peak_drift1"]))
assert "building2_storeys: 5" in text and "level 3: impacts" in text
print(f"ok:   3 vs 5 storeys: {j['impact_count']} impacts at levels "
      f"{[l['impacts'] for l in j['levels']]}, peak_u2 roof {j['peak_u2'][-1]:.4g} m")
PY

# which floors pound: the lower roof only; a gap offset per level (level 3 at 1.01 m never touches)
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 --json --contact-levels top > "$tmp/top.json"
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 --json --gap-offsets 0,0,1 > "$tmp/off.json"
"$py" - "$tmp/top.json" "$tmp/off.json" <<'PY' || fail "--contact-levels top / --gap-offsets"
import json, sys
top, off = (json.load(open(p)) for p in sys.argv[1:3])
assert [(l["level"], l["label"]) for l in top["levels"]] == [(3, "level 3")], top["levels"]
assert top["impact_count"] == top["levels"][0]["impacts"] > 0
assert [l["gap"] for l in off["levels"]] == [0.01, 0.01, 1.01], [l["gap"] for l in off["levels"]]
assert off["levels"][2]["impacts"] == 0 and off["levels"][2]["t_first_impact"] is None
assert off["levels"][2]["peak_closing"] < 1.01 and off["levels"][0]["impacts"] > 0
print(f"ok:   --contact-levels top: {top['impact_count']} impacts at the lower roof; --gap-offsets 0,0,1: level 3 free")
PY
# storeys of 3.0 and 3.1 m: floors meet within --level-tolerance 0.35 (3.0/3.1, 6.0/6.2, 9.0/9.3 m); within 0.05 none
# do, and each floor below the other's roof strikes the other's column (floor to column, linear shape functions):
# 3.0 on 0-3.1 m (the ground end), 3.1 on 3-6 m, 6.0 on 3.1-6.2, 6.2 on 6-9, 9.0 on 6.2-9.3 (9.3 m is above 9 m)
sim --storeys1 3 --storey-height1 3.0 --storeys2 5 --storey-height2 3.1 --elastic --gap 5 --dt 0.001 --json \
    --level-tolerance 0.35 > "$tmp/tol.json"
sim --storeys1 3 --storey-height1 3.0 --storeys2 5 --storey-height2 3.1 --elastic --gap 0.005 --dt 0.001 --json > "$tmp/tol0.json"
sim --storeys1 3 --storey-height1 3.0 --storeys2 5 --storey-height2 3.1 --elastic --gap 0.005 --dt 0.001 --json \
    --shape-functions cubic > "$tmp/cubic.json"
"$py" - "$tmp/tol.json" "$tmp/tol0.json" "$tmp/cubic.json" <<'PY' || fail "--level-tolerance / floors against columns"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert [l["label"] for l in a["levels"]] == ["level 1", "level 2", "level 3"], a["levels"]
assert a["column_shears"] == [], a["column_shears"]
want = ["level 1/column 0-1", "column 1-2/level 1", "level 2/column 1-2", "column 2-3/level 2", "level 3/column 2-3"]
assert [l["label"] for l in b["levels"]] == want, [l["label"] for l in b["levels"]]
xi = [3.0 / 3.1, 0.1 / 3.0, 2.9 / 3.1, 0.2 / 3.0, 2.8 / 3.1]
cs = b["column_shears"]
assert [c["label"] for c in cs] == want, cs
for c, x, l in zip(cs, xi, b["levels"]):
    assert abs(c["xi"] - x) < 1e-12, (c, x)
    F = l["peak_force"]
    assert abs(c["below"] - F * (1 - x) ** 2 * (1 + 2 * x)) <= 1e-9 * max(F, 1), (c, F)
    assert abs(c["below"] + c["above"] - F) <= 1e-9 * max(F, 1), (c, F)
assert sum(l["impacts"] for l in b["levels"]) > 0, b["levels"]
c = json.load(open(sys.argv[3]))
assert [l["label"] for l in c["levels"]] == want and c["levels"] != b["levels"], "cubic shape functions change nothing"
assert [x["xi"] for x in c["column_shears"]] == [x["xi"] for x in cs]
print("ok:   floors against columns:", ", ".join(f'{l["label"]} {l["impacts"]}' for l in b["levels"]))
PY

# a diverged run (Hertz contact of 3.2e10 N/m^1.5 at the record step 0.01 s, given as --dt): exit 3, status diverged, the totals
# -1 like every per-level count (the kernel's mark of a lane without results), not a sum of marks
set +e
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --kh 3.2e10 --dt 0.01 --json > "$tmp/div.json"
rc=$?
set -e
[ $rc -eq 3 ] || fail "a diverged multi-storey run exits $rc, want 3"
"$py" - "$tmp/div.json" <<'PY' || fail "a diverged run's JSON"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["status"] == "diverged", j["status"]
assert j["impact_count"] == -1 and j["tensile_force_clamps"] == -1, (j["impact_count"], j["tensile_force_clamps"])
assert all(l["impacts"] == -1 for l in j["levels"])
print("ok:   a diverged run: status diverged, exit 3, counts -1")
PY

# 4. a linear 3-storey building without contact against SciPy
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 2 --storey-mass2 1e5 \
    --storey-stiffness2 2e8 --gap 5 --elastic --dt 0.001 --json > "$tmp/lin.json"
"$py" - "$tmp/rec.txt" "$tmp/lin.json" <<'PY' || fail "linear 3-storey building against SciPy"
import json, sys
import numpy as np
from scipy import linalg, signal
t, ag_g = np.loadtxt(sys.argv[1], unpack=True)
def strict(c):
    raise ValueError(f"{c} is not JSON")
j = json.load(open(sys.argv[2]), parse_constant=strict)
assert j["impact_count"] == 0
assert all(l["t_first_impact"] is None for l in j["levels"]) and j["t_first_impact"] is None  # NaN as null
n, m, k, zeta = 3, 2e5, 3e8, 0.05
M = np.diag([m] * n)
K = np.zeros((n, n))
for i in range(n):
    K[i, i] += k
    if i > 0:
        K[i - 1, i - 1] += k; K[i, i - 1] -= k; K[i - 1, i] -= k
w = np.sqrt(linalg.eigh(K, M, eigvals_only=True))
a0, a1 = 2 * zeta * w[0] * w[1] / (w[0] + w[1]), 2 * zeta / (w[0] + w[1])
C = a0 * M + a1 * K
Mi = np.linalg.inv(M)
A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])
B = np.vstack([np.zeros((n, 1)), -np.ones((n, 1))])
tf = np.arange(0, 12 + 1e-9, 0.0005)
agf = np.interp(tf, t, ag_g * 9.80665)
_, _, x = signal.lsim((A, B, np.eye(2 * n), np.zeros((2 * n, 1))), agf, tf)
ref = np.abs(x[:, :n]).max(axis=0)
got = np.array(j["peak_u1"])
rel = np.abs(got - ref) / ref
assert rel.max() < 5e-4, f"peak floor displacements {got} vs SciPy {ref} (relative {rel})"
print(f"ok:   linear 3 storeys: peaks {np.array2string(got, precision=5)} m, SciPy {np.array2string(ref, precision=5)}, "
      f"worst relative difference {rel.max():.2e}")
PY

# 5. bad storey options: one ERROR line naming the option, exit 2, nothing on stdout
bad "--storeys1" --storeys1 0
bad "--storeys2" --storeys2 500
bad "--storey-height1" --storeys1 3 --storey-height1 0
bad "--storey-mass2" --storeys2 3 --storey-mass2 -5
bad "--storey-stiffness1" --storeys1 3 --storey-stiffness1 nan
bad "--k1" --storeys1 3 --k1 1e8
bad "--h2" --storeys2 4 --h2 20
bad "--series" --storeys1 3 --series "$tmp/s.txt"
bad "--contact-levels" --storeys1 3 --contact-levels roof
bad "--level-tolerance" --storeys1 3 --level-tolerance 2
bad "--level-tolerance, give --level-tolerance < 0.5 m" --storeys1 3 --storey-height1 1.0 --level-tolerance 0.6
bad "--level-tolerance" --storeys1 3 --storey-height2 3.5 --level-tolerance -0.01
bad "--shape-functions" --storeys1 3 --storey-height2 3.5 --shape-functions quadratic
bad "--gap-offsets" --storeys1 3 --storeys2 3 --gap-offsets 0,0
bad "--gap-offsets" --storeys1 3 --gap 0.1 --gap-offsets -0.2
[ ! -e "$tmp/s.csv" ] || fail "a refused run wrote its series"
# the structure's own top frequency beyond central difference's limit: --dt at the record step refused with the substeps
# that satisfy it; without --dt simulate takes them (physics::choose_step) and says so
bad "--dt, give --dt <= 4.7619e-05 s" --storeys1 5 --storey-mass1 1e3 --storey-stiffness1 3e11 --dt 0.01
sim --storeys1 5 --storey-mass1 1e3 --storey-stiffness1 3e11 > "$tmp/stiff.txt" || fail "the stiff storeys without --dt: exit $?"
grep -q '^step: 4.7619e-05 s (record step 0.01 s / 210), chosen: stable for the structures (h < 4.78e-05 s: 210 substeps at least)' \
  "$tmp/stiff.txt" || fail "the stiff storeys' step: $(grep '^step' "$tmp/stiff.txt")"
# Rayleigh-damped tall buildings of short storeys: 40 storeys of 1 m at --dt 0.005 pass the undamped h omega_max < 2
# (1.62), but the storey dashpots on the stepper's predicted velocity need h^2 w^2 + 4 h (2 zeta w) < 4 (Gershgorin's
# bounds: omega_max <= 324 rad/s, 2 zeta omega <= 418 1/s, h <= 0.00211 s; physics::structure_step_max): refused
# before any work with the step that does. Before the check knew the damping, this run went through and DIVERGED.
tall=(--storeys1 40 --storey-height1 1 --storeys2 40 --storey-height2 1 --gap 0.5)
bad "--dt, give --dt <= 0.002 s (the record step 0.01 s / 5)" "${tall[@]}" --dt 0.005
# and the step it advises runs without divergence
sim "${tall[@]}" --dt 0.002 --json > "$tmp/tall.json" || fail "40 storeys of 1 m at the advised --dt 0.002: exit $?"
"$py" -c 'import json, sys; j = json.load(open(sys.argv[1])); assert j["status"] == "ok", j["status"]' "$tmp/tall.json" ||
  fail "40 storeys of 1 m at the advised --dt 0.002 did not run ok"
echo "ok:   bad storey options refused with one error each"

# 6. collide --json
"$bin" collide --e 0.5 --law kelvin --kh 1e9 > "$tmp/c.txt"
"$bin" collide --e 0.5 --law kelvin --kh 1e9 --json > "$tmp/c.json"
"$py" - "$tmp/c.txt" "$tmp/c.json" <<'PY' || fail "collide --json"
import json, sys
text = dict(l.split(": ", 1) for l in open(sys.argv[1]).read().splitlines())
j = json.load(open(sys.argv[2]))
assert list(j)[:len(text)] == list(text), (list(j), list(text))
for name in ("e_effective", "peak_force_N", "contact_duration_s", "energy_lost_J", "h_omega_limit"):
    assert abs(float(text[name]) - j[name]) <= 5e-9 * abs(j[name]), (name, text[name], j[name])
assert j["law"] == "kelvin" and text["status"].startswith(j["status"])
assert ("status_note" in j) == (j["status"] == "off-target")
print(f"ok:   collide --json: e_effective {j['e_effective']:.9g}, status {j['status']}")
PY
