#!/usr/bin/env bash
# The code rules at each contact level of a multi-storey pair: a 5-storey building of 4.0 m storeys (20 m, T 0.6 s)
# beside an 8-storey one of 3.0 m storeys (24 m, T 0.9 s), uniform storey stiffnesses and equal floor masses, ASCE
# 7-16 design spectrum (site C, Ss 1.5, S1 0.6: SDS 1.2, SD1 0.56), R 8, Cd 5.5 and R 6, Cd 5. The floors meet at
# 12 m only (floor 3 of building 1, floor 4 of building 2); every other floor below the lower roof faces the
# neighbour's column. The report's rows per level (CSV rows code_level: gap_m, lo = u1, hi = u2) are checked against
# an independent evaluation here: the contact points enumerated from the floor levels, Gamma1 phi1 from numpy's
# eigh of K phi = w^2 M phi (M = I, K the uniform chain), linear interpolation on a column, and ASCE 7-16 11.4.6 /
# 12.8.6 / 12.9.1 written out: delta_M(z) = (Cd / R) Gamma1 phi1(z) Sa(T1) g T1^2 / 4 pi^2; separate lots the sum,
# same property the SRSS; the 0.005 h rule 0.005 (z1 + z2). Within 1e-6 relative. The periods are the study's (as
# given), and the Markdown names the clause and the inputs. Args: <pounding binary>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py=${POUNDING_PYTHON:-/usr/bin/python3}

"$bin" records suite --synthetic-only --write "$tmp/lib" > /dev/null
cat > "$tmp/a.toml" <<'TOML'
title = "code rules per contact level"
seed = 5
scene = "probability"
[records]
directory = "lib"
select = 7
[structures]
model = "shear"
samples_per_pair = 1
[structures.building1]
period = 0.6
height = 20.0
storeys = 5
storey_height = 4.0
asce7_r = 8
asce7_cd = 5.5
[structures.building2]
period = 0.9
height = 24.0
storeys = 8
storey_height = 3.0
asce7_r = 6
asce7_cd = 5
[target_spectrum]
code = "ASCE 7-16"
ss = 1.5
s1 = 0.6
site_class = "C"
TOML
"$bin" run "$tmp/a.toml" --out "$tmp/a.h5" --quiet > "$tmp/a.md" 2> "$tmp/a.err" || fail "run: $(cat "$tmp/a.err")"
"$bin" report "$tmp/a.h5" --csv > "$tmp/a.csv"
grep -q "^## Code separation rules at each contact level" "$tmp/a.md" || fail "no per-level section"
grep -q "^### Contact level 3/4: building 1 at z1 = 12.000 m" "$tmp/a.md" || fail "no floor-to-floor level at 12 m"
grep -q "| 1 | 5 x 4 m (uniform) | 0.6000 (as given) |" "$tmp/a.md" || fail "building 1's inputs: $(grep '^| 1 |' "$tmp/a.md")"
grep -q "ASCE 7-16 sec. 12.12.3" "$tmp/a.md" || fail "no clause"

"$py" - "$tmp/a.csv" <<'PY'
import sys, csv, math
import numpy as np
g = 9.80665
def sa(T, sds=1.2, sd1=0.56, tl=8.0):  # ASCE 7-16 11.4.6
    t0, ts = 0.2 * sd1 / sds, sd1 / sds
    return sds * (0.4 + 0.6 * T / t0) if T < t0 else sds if T <= ts else sd1 / T if T <= tl else sd1 * tl / T**2
def gphi(n):  # Gamma1 phi1 at floors 1..n of a uniform chain, equal masses
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] = 2.0 if i < n - 1 else 1.0
        if i + 1 < n: K[i, i + 1] = K[i + 1, i] = -1.0
    w, v = np.linalg.eigh(K)  # M = I
    phi = v[:, 0]
    return (phi.sum() / (phi @ phi)) * phi
B = [dict(n=5, h=4.0, T=0.6, R=8, Cd=5.5), dict(n=8, h=3.0, T=0.9, R=6, Cd=5)]
for b in B:
    b["z"] = [b["h"] * (i + 1) for i in range(b["n"])]
    b["gp"] = list(gphi(b["n"]))
    b["f"] = b["Cd"] / b["R"] * sa(b["T"]) * g * b["T"]**2 / (4 * math.pi**2)
def column(b, z):  # (label part, Gamma1 phi1) of building b's column at height z (linear between its floors)
    zs, gs = [0.0] + b["z"], [0.0] + b["gp"]
    j = max(i for i in range(len(zs) - 1) if zs[i] <= z)
    xi = (z - zs[j]) / (zs[j + 1] - zs[j])
    return f"column {j}-{j + 1}", (1 - xi) * gs[j] + xi * gs[j + 1]
tol, want = 0.05, {}
b1, b2 = B
for i, z in enumerate(b1["z"]):  # building 1's floors (left)
    near = [j for j, y in enumerate(b2["z"]) if abs(y - z) <= tol]
    if near:
        j = near[0]; want[f"level {i + 1}/{j + 1}"] = (z, b1["gp"][i], b2["z"][j], b2["gp"][j], True)
    elif z < b2["z"][-1]:
        lab, gg = column(b2, z); want[f"level {i + 1}/{lab}"] = (z, b1["gp"][i], z, gg, False)
for j, z in enumerate(b2["z"]):  # building 2's floors against building 1's column
    if any(abs(y - z) <= tol for y in b1["z"]) or z >= b1["z"][-1]: continue
    lab, gg = column(b1, z); want[f"{lab}/level {j + 1}"] = (z, gg, z, b2["gp"][j], False)
assert len(want) == 10 and "level 3/4" in want, sorted(want)
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["table"] == "code_level"]
got = {r["name"]: r for r in rows}
def close(a, b, what):
    if not abs(a - b) <= 1e-6 * max(abs(b), 1e-12) + 5e-7:  # the CSV's 6 decimals
        raise SystemExit(f"FAIL {what}: report {a!r}, independent {b!r}")
n = 0
for lab, (z1, g1, z2, g2, floors) in want.items():
    d1, d2 = b1["f"] * g1, b2["f"] * g2
    for rule, gap, u1, u2 in [("Standard 2800 0.005 h at the level", 0.005 * (z1 + z2), 0.005 * z1, 0.005 * z2),
                              ("ASCE 7-16 design, separate lots", d1 + d2, d1, d2),
                              ("ASCE 7-16 design, same property", math.hypot(d1, d2), d1, d2)]:
        r = got.get(f"{rule} at {lab}")
        if r is None: raise SystemExit(f"FAIL: no row '{rule} at {lab}' (rows: {sorted(got)})")
        close(float(r["gap_m"]), gap, f"{rule} at {lab} separation")
        close(float(r["lo"]), u1, f"{rule} at {lab} u1")
        close(float(r["hi"]), u2, f"{rule} at {lab} u2")
        n += 1
if len(rows) != n: raise SystemExit(f"FAIL: {len(rows)} code_level rows, {n} expected")
print(f"{n} per-level rows within 1e-6; Gamma1 phi1 roof {b1['gp'][-1]:.6f}, {b2['gp'][-1]:.6f}; "
      f"level 3/4: u1 {b1['f'] * want['level 3/4'][1]:.6f} m, u2 {b2['f'] * want['level 3/4'][3]:.6f} m")
PY
