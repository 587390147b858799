#!/usr/bin/env bash
# `pounding simulate --buildings N` (a row of buildings, issue 25 step 8, docs/rows.md):
#  1. three elastic SDOF buildings pounding with Hertzdamp under a two-tone record, against
#     tools/reference_systems.py row (solve_ivp with event-located onsets, its own uncoupled run; none of our code):
#     peak displacements within 1e-3, impact counts per joint equal, amplifications within 1e-3;
#  2. --buildings 2 prints today's pair output byte for byte; buildings 3..N default to building 1's options (odd K)
#     and building 2's (even K): --buildings 4 without row options is the row 1-2-1-2;
#  3. a row of shear buildings (--storeys3) runs, its levels labelled by joint;
#  4. bad row options: exit 2, one ERROR naming the option, nothing on stdout.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"
two_tone_record 0.9

# 1. against the SciPy row
row=(--buildings 3 --m1 2e6 --k1 8e7 --m2 3e6 --k2 4.5e7 --m3 1.5e6 --k3 1.2e8 --elastic --zeta 0.05 --gap 0.01
     --contact hertzdamp --kh 2e10 --e 0.65 --dt 0.000125 --duration 6)
sim "${row[@]}" --json > "$tmp/row.json"
"$py" - "$tmp/rec.txt" "$tmp/ref.json" <<'PY'
import json, math, sys
t, a = [], []
for line in open(sys.argv[1]):
    x, y = line.split()
    a.append(float(y) * 9.80665)
a = a[:601]  # --duration 6
ms, ks = [2e6, 3e6, 1.5e6], [8e7, 4.5e7, 1.2e8]
bodies = [dict(m=[m], k=[k], a0=2 * 0.05 * math.sqrt(k * m) / m, a1=0.0) for m, k in zip(ms, ks)]
json.dump(dict(dt=0.01, ag=a, duration=0.01 * (len(a) - 1), substeps=[80], bodies=bodies, gap=0.01, kc=2e10, n=1.5,
               e=0.65, v0_min=1e-3), open(sys.argv[2], "w"))
PY
"$py" "$src/tools/reference_systems.py" row "$tmp/ref.json" "$tmp/ref.txt"
"$py" - "$tmp/row.json" "$tmp/ref.txt" <<'PY' || fail "simulate --buildings 3 differs from the SciPy row"
import json, sys
r = json.load(open(sys.argv[1]))
ref = {}
for line in open(sys.argv[2]):
    w = line.split()
    ref[tuple(w[:-1])] = float(w[-1])
bad = 0
assert r["status"] == "ok", r["status"]
labels = [l["label"] for l in r["levels"]]
assert labels == ["1|2 level 1", "2|3 level 1"], labels
for b in range(3):
    got, want = r[f"peak_u{b + 1}"][0], ref[("peak_u", "80", str(b), "1")]
    amp, amp_ref = r[f"amplification_u{b + 1}"][0], ref[("amplification", "80", str(b))]
    ok = abs(got - want) <= 1e-3 * want and abs(amp - amp_ref) <= 1e-3 * amp_ref
    bad += not ok
    print(f"building {b + 1}: peak {got:.6g} m (reference {want:.6g}), amplification {amp:.5f} (reference {amp_ref:.5f})"
          f"{'' if ok else '  FAIL'}")
for e, l in enumerate(r["levels"]):
    want = int(ref[("impacts", str(e))])
    bad += l["impacts"] != want
    print(f"{l['label']}: {l['impacts']} impacts (reference {want})")
assert sum(l["impacts"] for l in r["levels"]) >= 2, "the row must pound"
assert all(l["impacts"] > 0 for l in r["levels"]), "both joints must pound"
sys.exit(1 if bad else 0)
PY

# 2. --buildings 2 is the pair; defaults of buildings 3..N
sim --T1 0.8 --T2 1.3 --dt 0.0025 > "$tmp/pair.txt"
sim --T1 0.8 --T2 1.3 --dt 0.0025 --buildings 2 > "$tmp/two.txt"
cmp -s "$tmp/pair.txt" "$tmp/two.txt" || fail "--buildings 2 changed the pair's output"
sim --T1 0.8 --T2 1.3 --dt 0.0025 --buildings 4 --json > "$tmp/d4.json"
sim --T1 0.8 --T2 1.3 --dt 0.0025 --buildings 4 --T3 0.8 --T4 1.3 --h3 30 --h4 45 --json > "$tmp/g4.json"
cmp -s "$tmp/d4.json" "$tmp/g4.json" || fail "buildings 3 and 4 do not default to buildings 1 and 2"
"$py" - "$tmp/d4.json" <<'PY' || fail "the 1-2-1-2 row"
import json, sys
r = json.load(open(sys.argv[1]))
assert [l["label"] for l in r["levels"]] == ["1|2 level 1", "2|3 level 1", "3|4 level 1"], r["levels"]
assert "peak_u4" in r and "peak_u5" not in r
PY

# 3. a row of shear buildings
sim --buildings 3 --storeys1 3 --storeys2 5 --storeys3 3 --storey-mass3 2e5 --storey-stiffness3 3e8 --json \
  > "$tmp/shear.json"
"$py" - "$tmp/shear.json" <<'PY' || fail "the shear row"
import json, sys
r = json.load(open(sys.argv[1]))
labels = [l["label"] for l in r["levels"]]
assert labels == [f"{j} level {k}" for k in (1, 2, 3) for j in ("1|2", "2|3")], labels
assert len(r["peak_u3"]) == 3 and len(r["peak_u2"]) == 5
PY

# 4. bad input
bad '--buildings = 1 is out of range.*--buildings' --buildings 1
bad '--buildings = 9 is out of range.*--buildings' --buildings 9
bad '--T4 is for building 4 and the row has --buildings 3.*give --buildings 4' --buildings 3 --T4 1.0
bad '--storeys5 is for building 5' --storeys5 3
bad '--m3 describes an SDOF, and building 3 has 4 storeys.*--m3' --buildings 3 --storeys3 4 --m3 1e6
bad '--storeys3 = 0 is out of range' --buildings 3 --storeys3 0
bad '--storey-height3' --buildings 3 --storeys3 2 --storey-height3 500
bad '--T3' --buildings 3 --T3 -1
echo "1 passed, 0 failed"
