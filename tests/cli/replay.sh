#!/usr/bin/env bash
# `pounding replay` (issue 26 §3; physics/replay.hpp): a contact law evaluated on imposed kinematics.
#  - Hertz on a half-sine penetration A sin(pi t / T): the force at every sample is kh d^1.5 (closed form, 1e-12) and
#    the loop encloses no energy; the work in approach is kh A^2.5 / 2.5 (trapezoid, 1e-3);
#  - Hertzdamp (Lankarani-Nikravesh): F = kh d^1.5 (1 + 3 (1 - e^2) / 4 ddot / v0), v0 interpolated at the crossing
#    (computed here independently), the dissipated energy against SciPy's quad of kh xibar / v0 d^1.5 ddot^2;
#  - without a velocity column the rate is differentiated (the output says so) and the energy stays within 0.5 %;
#  - u1, u2 and --gap give the same forces as the penetration;
#  - the linear law on the free impact's own motion d = (v0 / w) sin(w t) reproduces `pounding collide`'s peak force;
#  - a measured force 1.1 x the law's: eq. 10's peak error 100 x 0.1 / 1.1 % and the time-averaged |dF|;
#  - a restitution table: each impact's e is e(v0) at its own latched v0;
#  - bad files: one " ERROR:" line naming FILE:LINE (or the option), exit 2, nothing on stdout, no --out file.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py=/usr/bin/python3

# kinematics: <file> <columns> -- half sine A = 10 mm, T = 20 ms, samples every 0.1 ms from -2.05 ms (the crossings
# fall between samples); two impacts with the second at half the amplitude when "two"
$py - "$tmp" <<'PY'
import math, sys
d = sys.argv[1]
A, T, h = 0.01, 0.02, 1e-4
ts = [-0.00205 + i * h for i in range(int(0.0265 / h))]
def pen(t): return A * math.sin(math.pi * t / T)
def vel(t): return A * math.pi / T * math.cos(math.pi * t / T)
with open(f"{d}/half.csv", "w") as f:
    f.write("# a half-sine penetration\ntime,penetration,velocity\n")
    for t in ts: f.write(f"{t!r},{pen(t)!r},{vel(t)!r}\n")
with open(f"{d}/half_nov.csv", "w") as f:
    f.write("time,penetration\n")
    for t in ts: f.write(f"{t!r},{pen(t)!r}\n")
with open(f"{d}/half_u.csv", "w") as f:
    f.write("time,u1,u2,v1,v2\n")
    for t in ts:
        u2 = 0.003 * math.sin(7 * t); v2 = 0.021 * math.cos(7 * t)
        f.write(f"{t!r},{pen(t) + 0.05 + u2!r},{u2!r},{vel(t) + v2!r},{v2!r}\n")
# two impacts: the second at a third of the speed
with open(f"{d}/two.csv", "w") as f:
    f.write("time,penetration,velocity\n")
    for t in [-0.00205 + i * h for i in range(int(0.0665 / h))]:
        if t < 0.03: p, v = pen(t), vel(t)
        else: p, v = pen(t - 0.04) / 3, vel(t - 0.04) / 3
        f.write(f"{t!r},{p!r},{v!r}\n")
PY

# Hertz: closed form at every sample, no energy enclosed
"$bin" replay --law hertz --kh 2e9 --input "$tmp/half.csv" --out "$tmp/hertz.csv" --json > "$tmp/hertz.json"
$py - "$tmp/hertz.csv" "$tmp/hertz.json" <<'PY' || fail "hertz half-sine"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1]))); j = json.load(open(sys.argv[2]))
kh, A = 2e9, 0.01
for r in rows:
    d = float(r["penetration_m"]); F = float(r["force_N"])
    want = kh * d ** 1.5 if d > 0 else 0.0
    assert abs(F - want) <= 1e-12 * kh * A ** 1.5, (r, want)
assert j["impacts"] == 1 and j["velocity"] == "given", j
im = j["impact_list"][0]
wa = kh * A ** 2.5 / 2.5
assert abs(im["work_approach"] / wa - 1) < 1e-3, (im, wa)
assert abs(im["energy_dissipated"]) < 1e-9 * wa, im
assert abs(j["peak_force"] / (kh * A ** 1.5) - 1) < 1e-4, j
print("hertz ok: work in", im["work_approach"], "closed form", wa)
PY

# Hertzdamp, Lankarani-Nikravesh, e = 0.6: the law by hand, and the energy against SciPy
"$bin" replay --law hertzdamp --damping-law lankarani-nikravesh --e 0.6 --kh 2e9 --input "$tmp/half.csv" \
  --out "$tmp/hd.csv" --json > "$tmp/hd.json"
$py - "$tmp/hd.csv" "$tmp/hd.json" <<'PY' || fail "hertzdamp half-sine"
import csv, json, math, sys
rows = list(csv.DictReader(open(sys.argv[1]))); j = json.load(open(sys.argv[2]))
kh, A, T, e = 2e9, 0.01, 0.02, 0.6
xi = 3 * (1 - e * e) / 4
d = [float(r["penetration_m"]) for r in rows]; v = [float(r["velocity_mps"]) for r in rows]
i = next(k for k in range(1, len(d)) if d[k] > 0 and d[k - 1] <= 0)
sc = -d[i - 1] / (d[i] - d[i - 1]); v0 = v[i - 1] + sc * (v[i] - v[i - 1])
assert abs(j["impact_list"][0]["v0"] - v0) < 1e-15, (j["impact_list"][0]["v0"], v0)
for r, dk, vk in zip(rows, d, v):
    want = max(0.0, kh * dk ** 1.5 * (1 + xi * vk / v0)) if dk > 0 else 0.0
    assert abs(float(r["force_N"]) - want) <= 1e-12 * kh * A ** 1.5, (r, want)
try:
    from scipy.integrate import quad
    w = math.pi / T
    def integrand(t):  # F ddot over the contact, the damping part only (the elastic part encloses nothing)
        dd, vv = A * math.sin(w * t), A * w * math.cos(w * t)
        return kh * xi / v0 * dd ** 1.5 * vv * vv if 1 + xi * vv / v0 > 0 else -kh * dd ** 1.5 * vv
    ref = quad(integrand, 0, T, limit=200, points=[T * 0.9])[0]
    got = j["impact_list"][0]["energy_dissipated"]
    print("hertzdamp energy", got, "scipy", ref, got / ref - 1)
    assert abs(got / ref - 1) < 2e-3
except ImportError:
    print("skip the SciPy energy check: no scipy")
print("hertzdamp ok, clamps", j["tensile_force_clamps"])
PY

# differentiated velocity
"$bin" replay --law hertzdamp --damping-law lankarani-nikravesh --e 0.6 --kh 2e9 --input "$tmp/half_nov.csv" \
  --json > "$tmp/nov.json"
$py - "$tmp/hd.json" "$tmp/nov.json" <<'PY' || fail "differentiated velocity"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert b["velocity"].startswith("differentiated"), b["velocity"]
ea, eb = a["energy_dissipated"], b["energy_dissipated"]
print("energy given", ea, "differentiated", eb)
assert abs(eb / ea - 1) < 5e-3 and abs(b["peak_force"] / a["peak_force"] - 1) < 5e-3
PY

# u1, u2 and the gap
"$bin" replay --law hertzdamp --damping-law lankarani-nikravesh --e 0.6 --kh 2e9 --input "$tmp/half_u.csv" --gap 0.05 \
  --out "$tmp/u.csv" > /dev/null
$py - "$tmp/hd.csv" "$tmp/u.csv" <<'PY' || fail "u1 - u2 - gap"
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
assert len(a) == len(b)
for x, y in zip(a, b):
    assert abs(float(x["force_N"]) - float(y["force_N"])) <= 1e-6 * 2e9 * 0.01 ** 1.5, (x, y)
PY

# the free impact of collide: linear law, d = (v0 / w) sin(w t)
"$bin" collide --law linear --kh 1e9 --m1 1e6 --m2 1e6 --v0 1 --json > "$tmp/collide.json"
$py - "$tmp" <<'PY'
import math, sys
k, meff, v0 = 1e9, 5e5, 1.0
w = math.sqrt(k / meff); T = math.pi / w; h = T / 4000
with open(f"{sys.argv[1]}/free.csv", "w") as f:
    f.write("time,penetration,velocity\n")
    for i in range(-10, 4011):
        t = (i + 0.5) * h
        f.write(f"{t!r},{v0 / w * math.sin(w * t)!r},{v0 * math.cos(w * t)!r}\n")
PY
"$bin" replay --law linear --kh 1e9 --input "$tmp/free.csv" --json > "$tmp/free.json"
$py -c "
import json
c = json.load(open('$tmp/collide.json')); r = json.load(open('$tmp/free.json'))
print('collide peak', c['peak_force_N'], 'replay peak', r['peak_force'])
assert abs(r['peak_force'] / c['peak_force_N'] - 1) < 1e-5
assert abs(r['impact_list'][0]['peak_penetration'] / c['peak_penetration_m'] - 1) < 1e-5" || fail "collide vs replay"

# a measured force 1.1 x the law's
$py - "$tmp/hertz.csv" "$tmp/meas.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w") as f:
    f.write("time,penetration,velocity,force\n")
    for r in rows: f.write(f"{r['time_s']},{r['penetration_m']},{r['velocity_mps']},{1.1 * float(r['force_N'])!r}\n")
PY
"$bin" replay --law hertz --kh 2e9 --input "$tmp/meas.csv" --json > "$tmp/meas.json"
$py - "$tmp/hertz.csv" "$tmp/meas.json" <<'PY' || fail "error metrics"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1]))); j = json.load(open(sys.argv[2]))
t = [float(r["time_s"]) for r in rows]; F = [float(r["force_N"]) for r in rows]
area = sum(0.5 * (t[i + 1] - t[i]) * (F[i] + F[i + 1]) for i in range(len(t) - 1))
mad = 0.1 * area / (t[-1] - t[0])
assert abs(j["peak_error_pct"] - 100 * 0.1 / 1.1) < 1e-9, j["peak_error_pct"]
assert abs(j["impact_list"][0]["peak_error_pct"] - 100 * 0.1 / 1.1) < 1e-9
assert abs(j["mean_abs_difference"] / mad - 1) < 1e-9, (j["mean_abs_difference"], mad)
print("metrics ok", j["peak_error_pct"], j["mean_abs_difference"])
PY

# e(v0) per impact
"$bin" replay --law hertzdamp --damping-law calibrated --kh 2e9 --restitution-table 0.5:0.9,2:0.6 \
  --input "$tmp/two.csv" --json > "$tmp/two.json"
$py - "$tmp/two.json" <<'PY' || fail "e(v0) per impact"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["impacts"] == 2, j["impacts"]
for im in j["impact_list"]:
    v = im["v0"]; want = 0.9 + (min(max(v, 0.5), 2) - 0.5) / 1.5 * (0.6 - 0.9)
    assert abs(im["e"] - want) < 1e-12, (im, want)
a, b = j["impact_list"]
assert abs(b["v0"] / a["v0"] - 1 / 3) < 1e-3 and a["e"] < b["e"], (a, b)
print("e(v0):", a["v0"], a["e"], b["v0"], b["e"])
PY

# the figure
if $py -c "import matplotlib" 2>/dev/null; then
  $py "$src/tests/cli/plot_layout.py" -- "$src/tools/plot_replay.py" "$tmp/hd.csv" "$tmp/hd.png" || fail "replay figure"
fi

# a UTF-8 byte-order mark (Excel's "CSV UTF-8") is skipped, as in the study's CSV files: the same replay
{ printf '\xef\xbb\xbf'; cat "$tmp/half.csv"; } > "$tmp/bom.csv"
"$bin" replay --law hertz --kh 2e9 --input "$tmp/bom.csv" --out "$tmp/bom_out.csv" > /dev/null 2> "$tmp/bom.err" \
  || fail "a kinematics file with a BOM was refused: $(cat "$tmp/bom.err")"
cmp -s "$tmp/bom_out.csv" "$tmp/hertz.csv" || fail "a kinematics file with a BOM gives another replay than without"
echo "ok: a UTF-8 BOM is skipped"

# bad input
bad() {
  local where=$1; shift
  rm -f "$tmp/bad_out.csv"
  set +e; "$bin" replay "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"; local rc=$?; set -e
  [ "$rc" -eq 2 ] || fail "$* -> exit $rc (want 2): $(cat "$tmp/bad.err")"
  [ ! -s "$tmp/bad.out" ] || fail "$* wrote to stdout: $(cat "$tmp/bad.out")"
  [ ! -e "$tmp/bad_out.csv" ] || fail "$* left --out"
  [ "$(grep -c ' ERROR:' "$tmp/bad.err")" -eq 1 ] || fail "$*: not one ERROR line: $(cat "$tmp/bad.err")"
  grep -qF -- "$where" "$tmp/bad.err" || fail "$*: the error does not name $where: $(cat "$tmp/bad.err")"
  echo "ok: $(cat "$tmp/bad.err")"
}
printf 'time,penetration\n0,0\n0.1,0.001\n0.2,abc\n' > "$tmp/b1.csv"
bad "$tmp/b1.csv:4" --law hertz --kh 1e9 --input "$tmp/b1.csv" --out "$tmp/bad_out.csv"
printf 'time,penetration\n0,0\n0.1,0.001\n0.1,0.002\n' > "$tmp/b2.csv"
bad "$tmp/b2.csv:4" --law hertz --kh 1e9 --input "$tmp/b2.csv" --out "$tmp/bad_out.csv"
printf '# c\ntime,pen\n0,0\n' > "$tmp/b3.csv"
bad "$tmp/b3.csv:2" --law hertz --kh 1e9 --input "$tmp/b3.csv"
printf 'time,penetration\n0,0\n0.1\n' > "$tmp/b4.csv"
bad "$tmp/b4.csv:3" --law hertz --kh 1e9 --input "$tmp/b4.csv"
printf 'time,u1\n0,0\n0.1,0\n0.2,0\n' > "$tmp/b5.csv"
bad "$tmp/b5.csv:1" --law hertz --kh 1e9 --input "$tmp/b5.csv"
printf 'time,penetration\n0,0\n0.1,0.001\n' > "$tmp/b6.csv"
bad "$tmp/b6.csv" --law hertz --kh 1e9 --input "$tmp/b6.csv"
printf 'time,penetration\n0,0\n0.1,500\n0.2,0\n' > "$tmp/b7.csv"
bad "$tmp/b7.csv:3" --law hertz --kh 1e9 --input "$tmp/b7.csv"
bad "$tmp/missing.csv" --law hertz --kh 1e9 --input "$tmp/missing.csv"
bad --law --law stereomechanical --kh 1e9 --input "$tmp/half.csv"
bad --m1 --law kelvin --kh 1e9 --input "$tmp/half.csv"
bad --kh --law hertz --kh -1 --input "$tmp/half.csv"
bad --out --law hertz --kh 1e9 --input "$tmp/half.csv" --out "$tmp"
bad --e --law hertzdamp --kh 1e9 --input "$tmp/half.csv" --e 0.8 --restitution-preset lindsay2011
echo "replay: all checks passed"
