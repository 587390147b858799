#!/usr/bin/env bash
# `pounding simulate` with buildings that are not uniform: --storey-massK, --storey-stiffnessK, --storey-heightK and
# --storey-yieldK take one value (every floor / storey) or one per floor / storey from the bottom:
#  - the floors, storeys, strengths and levels of the run are the lists given (--json buildings[]);
#  - the periods of a non-uniform 3-storey building against an independent SciPy eigh
#    (tools/reference_systems.py modes) within 1e-9;
#  - one value is the uniform building bit for bit (the list "2e5" = the number 2e5);
#  - a list of the wrong length, a value out of the key's range: one ERROR line naming the option (and the count);
#  - --yield-coefficientK: a 3-storey building's base storey yields at Cy M g (the upper ones by the shear profile), an
#    SDOF is --fyK = Cy m g bit for bit; --scale 2 doubles a linear run's every peak exactly (a power of two).
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, two_tone_record, sim, bad
two_tone_record 1.3

# 1. per-storey lists: the run's numbers, and the periods against SciPy's eigh of the same M and K
sim --storeys1 3 --storey-mass1 2e5,2e5,1.5e5 --storey-stiffness1 3e8,2.5e8,2e8 --storey-height1 4.5,3.2,3.2 \
    --storey-yield1 9e5,7e5,5e5 --storeys2 4 --storey-mass2 2.5e5 --storey-stiffness2 2.2e8 --gap 0.05 --dt 0.001 \
    --json > "$tmp/lists.json"
"$py" "$src/tools/reference_systems.py" modes --masses 2e5,2e5,1.5e5 --stiffnesses 3e8,2.5e8,2e8 > "$tmp/ref.json"
"$py" - "$tmp/lists.json" "$tmp/ref.json" <<'PY' || fail "per-storey lists"
import json, sys
j, ref = (json.load(open(p)) for p in sys.argv[1:3])
b1, b2 = j["buildings"][0], j["buildings"][1]
assert b1["floor_mass"] == [2e5, 2e5, 1.5e5], b1["floor_mass"]
assert b1["storey_stiffness"] == [3e8, 2.5e8, 2e8], b1["storey_stiffness"]
assert b1["storey_yield"] == [9e5, 7e5, 5e5], b1["storey_yield"]
assert all(abs(a - b) < 1e-12 for a, b in zip(b1["floor_levels"], [4.5, 7.7, 10.9])), b1["floor_levels"]
assert b2["floor_mass"] == [2.5e5] * 4 and b2["storey_stiffness"] == [2.2e8] * 4, b2
want = [m["period"] for m in ref["modes"]]
for got, w in zip(b1["periods"], want):
    assert abs(got - w) <= 1e-9 * w, (b1["periods"], want)
print(f"ok:   3 non-uniform storeys: periods {[round(t, 6) for t in b1['periods']]} s = SciPy eigh "
      f"{[round(t, 6) for t in want]} s; masses, stiffnesses, yields and levels as given")
PY

# 2. one value is the uniform building: the same bits as before lists
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 --json > "$tmp/one.json"
sim --storeys1 3 --storey-mass1 2e5,2e5,2e5 --storey-stiffness1 3e8,3e8,3e8 --storeys2 5 --storey-mass2 2.5e5 \
    --storey-stiffness2 2.2e8 --gap 0.01 --dt 0.001 --json > "$tmp/three.json"
cmp -s "$tmp/one.json" "$tmp/three.json" || fail "three equal values differ from one value"
echo "ok:   2e5,2e5,2e5 = 2e5 (every observer bit for bit)"

# 3. bad lists: the option, the count it needs
bad "--storey-mass1 has 2 values and building 1 has 3 storeys" --storeys1 3 --storey-mass1 2e5,2e5 --storeys2 2
bad "--storey-stiffness2 has 4 values and building 2 has 3 storeys" --storeys1 2 --storeys2 3 \
    --storey-stiffness2 1e8,1e8,1e8,1e8
bad "--storey-height1 = 0.001 is out of range" --storeys1 2 --storey-height1 3.2,0.001 --storeys2 2
bad "--storey-mass1 = -5 is out of range" --storeys1 2 --storey-mass1 2e5,-5 --storeys2 2
bad "--storey-yield1 = 0 is out of range" --storeys1 2 --storey-yield1 1e6,0 --storeys2 2
bad "--storey-mass3 has 2 values and building 3 has 3 storeys" --buildings 3 --storeys1 2 --storeys2 2 --storeys3 3 \
    --storey-mass3 1e5,1e5
echo "ok:   a list of the wrong length or a value out of range: one ERROR naming the option"

# 4. --yield-coefficientK and --scale
sim --storeys1 3 --storey-mass1 2e5,2e5,1.5e5 --storey-stiffness1 3e8 --yield-coefficient1 0.1 --storeys2 2 \
    --duration 3 --dt 0.001 --json > "$tmp/cy.json"
"$py" - "$tmp/cy.json" <<'PY' || fail "--yield-coefficient1 of a 3-storey building"
import json, sys
y = json.load(open(sys.argv[1]))["buildings"][0]["storey_yield"]
base = 0.1 * 5.5e5 * 9.80665
assert abs(y[0] - base) <= 1e-12 * base and y[0] > y[1] > y[2] > 0, (y, base)
print(f"ok:   --yield-coefficient1 0.1: storey yields {[round(v) for v in y]} N, the base's Cy M g = {base:.6g} N")
PY
sim --m1 1e6 --yield-coefficient1 0.1 --duration 3 --json > "$tmp/cy1.json"
sim --m1 1e6 --fy1 "$("$py" -c 'print(repr(0.1 * 1e6 * 9.80665))')" --duration 3 --json > "$tmp/fy1.json"
cmp -s "$tmp/cy1.json" "$tmp/fy1.json" || fail "--yield-coefficient1 0.1 differs from --fy1 = 0.1 m g"
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 2 --elastic --contact none --gap 1 \
    --duration 4 --dt 0.001 --json > "$tmp/x1.json"
sim --storeys1 3 --storey-mass1 2e5 --storey-stiffness1 3e8 --storeys2 2 --elastic --contact none --gap 1 \
    --duration 4 --dt 0.001 --json --scale 2 > "$tmp/x2.json"
"$py" - "$tmp/x1.json" "$tmp/x2.json" <<'PY' || fail "--scale 2"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("peak_u1", "peak_u2", "peak_drift1"):
    assert [2 * x for x in a[k]] == b[k], (k, a[k], b[k])
print(f"ok:   --scale 2: every peak exactly twice ({a['peak_u1'][-1]:.6g} -> {b['peak_u1'][-1]:.6g} m)")
PY
bad "--yield-coefficient1 with --storey-yield1" --storeys1 2 --storey-yield1 1e6 --yield-coefficient1 0.1 --storeys2 2
bad "--scale = 0 is out of range" --scale 0
bad "--yield-coefficient2 = 9 is out of range" --yield-coefficient2 9
echo "ok:   --yield-coefficient with another strength, --scale and Cy out of range: one ERROR each"
