#!/usr/bin/env bash
# `pounding simulate --initial-uK / --initial-vK`: pull-back and free-vibration tests against closed forms.
#  1. an SDOF pair without contact, released from u1 = 0.05 m, v2 = 0.2 m/s (a record of zeros, --duration 12 s):
#     the series against u(t) = exp(-zeta w t) (u0 cos wd t + (v0 + zeta w u0) / wd sin wd t) within 2e-5 m; the
#     damped period from successive peaks within 2e-3 s of T / sqrt(1 - zeta^2), the damping ratio from the
#     logarithmic decrement within 2e-4 of 0.05;
#  2. a 2-storey building (Rayleigh 5 % on modes 1 and 2: classical, each mode 5 %) released from u = [0.02, 0.05]
#     m with v = [0, 0.1] m/s: its floors at t = 2.3 s (final_u1) against the modal solution (numpy eigh, each mode a
#     damped SDOF) within 1e-5 m;
#  3. bad lists: a count that is not 1 or the floors', a displacement above --u-limit: one ERROR naming the option.
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, sim, bad
awk 'BEGIN { for (i = 0; i <= 200; i++) printf "%.2f 0\n", i * 0.01 }' > "$tmp/rec.txt"  # 2 s of zeros

# 1. the SDOF pair
sim --contact none --m1 1e6 --T1 1.0 --initial-u1 0.05 --m2 2e6 --T2 0.7 --initial-v2 0.2 --zeta 0.05 --elastic \
    --gap 1 --dt 0.001 --duration 12 --series "$tmp/sdof.csv" > "$tmp/sdof.txt"
"$py" - "$tmp/sdof.csv" <<'PY' || fail "the SDOF pair's free vibration"
import csv, math, sys
import numpy as np
rows = list(csv.DictReader(open(sys.argv[1])))
t = np.array([float(r["t_s"]) for r in rows])
def closed(T, zeta, u0, v0):
    w = 2 * math.pi / T
    wd = w * math.sqrt(1 - zeta * zeta)
    return np.exp(-zeta * w * t) * (u0 * np.cos(wd * t) + (v0 + zeta * w * u0) / wd * np.sin(wd * t)), 2 * math.pi / wd
for key, T, u0, v0 in (("u1_m", 1.0, 0.05, 0.0), ("u2_m", 0.7, 0.0, 0.2)):
    u = np.array([float(r[key]) for r in rows])
    want, Td = closed(T, 0.05, u0, v0)
    err = np.max(np.abs(u - want))
    assert err < 2e-5, (key, err)
    peaks = [i for i in range(1, len(u) - 1) if u[i] > u[i - 1] and u[i] >= u[i + 1] and u[i] > 0]
    tp = []  # each peak's time and height from a parabola through the three samples
    for i in peaks:
        a, b, c = u[i - 1], u[i], u[i + 1]
        x = 0.5 * (a - c) / (a - 2 * b + c)
        tp.append((t[i] + x * (t[1] - t[0]), b - 0.25 * (a - c) * x))
    periods = [tp[j + 1][0] - tp[j][0] for j in range(len(tp) - 1)]
    deltas = [math.log(tp[j][1] / tp[j + 1][1]) for j in range(len(tp) - 1)]
    zeta = [d / math.sqrt(4 * math.pi ** 2 + d * d) for d in deltas]
    assert max(abs(p - Td) for p in periods) < 2e-3, (key, periods, Td)
    assert max(abs(z - 0.05) for z in zeta) < 2e-4, (key, zeta)
    print(f"ok:   {key}: max |u - closed form| {err:.2e} m; damped period {np.mean(periods):.5f} s (closed form "
          f"{Td:.5f}); zeta from the log decrement {np.mean(zeta):.5f} (0.05), {len(periods)} cycles")
PY

# 2. two storeys against the modal solution
sim --contact none --storeys1 2 --storey-mass1 2e5,1.5e5 --storey-stiffness1 2e8,1.5e8 --initial-u1 0.02,0.05 \
    --initial-v1 0,0.1 --storeys2 1 --storey-mass2 1e5 --storey-stiffness2 1e8 --zeta 0.05 --elastic --gap 1 \
    --dt 0.0005 --duration 2.3 --json > "$tmp/two.json"
"$py" - "$tmp/two.json" <<'PY' || fail "the 2-storey building's free vibration"
import json, math, sys
import numpy as np
from scipy.linalg import eigh
j = json.load(open(sys.argv[1]))
m = np.array([2e5, 1.5e5]); k = [2e8, 1.5e8]
M = np.diag(m); K = np.array([[k[0] + k[1], -k[1]], [-k[1], k[1]]])
w2, phi = eigh(K, M)
u0, v0, t, zeta = np.array([0.02, 0.05]), np.array([0.0, 0.1]), 2.3, 0.05
u = np.zeros(2)
for n in range(2):
    w = math.sqrt(w2[n]); wd = w * math.sqrt(1 - zeta * zeta); p = phi[:, n]
    Mj = p @ M @ p
    q0, dq0 = p @ M @ u0 / Mj, p @ M @ v0 / Mj
    u += p * math.exp(-zeta * w * t) * (q0 * math.cos(wd * t) + (dq0 + zeta * w * q0) / wd * math.sin(wd * t))
got = np.array(j["final_u1"])
err = np.max(np.abs(got - u))
assert err < 1e-5, (got, u, err)
assert [round(z, 12) for z in j["buildings"][0]["modal_damping"]] == [0.05, 0.05], j["buildings"][0]["modal_damping"]
print(f"ok:   2 storeys at t = 2.3 s: floors {got.round(7).tolist()} m, modal solution {u.round(7).tolist()} m "
      f"(max difference {err:.1e} m)")
PY

# 3. bad input
bad "--initial-u1 has 3 values and building 1 has 2 floors" --storeys1 2 --initial-u1 0.1,0.1,0.1 --storeys2 1
bad "--initial-v2 has 2 values and building 2 is an SDOF" --initial-v2 0.1,0.2
bad "--initial-u1 = 20 is out of range" --initial-u1 20
bad "--initial-v2 describes building 2 and this run is a --bridge" --bridge "$src/studies/bridge-joint.toml" --initial-v2 0.1
echo "ok:   bad initial states: one ERROR naming the option"
