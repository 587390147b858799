#!/usr/bin/env bash
# e(v0) in the kernel (issue 26 §3): central difference latches v0 at each contact onset and sets the lane's Hertzdamp
# damping from e(v0) (kernel::VelocityRestitution; physics/velocity_restitution.hpp).
#  - one free impact through the kernel (collide --stepper central-difference, calibrated): e_effective = e(v0) of
#    the preset at v0 = 2 and of a table at 0.7 m/s, to 1e-6, with the onset counted outside/inside the valid range;
#  - simulate with a constant curve e(v) = 0.65 runs the same pair as --e 0.65 (the damping constant enters the force
#    as xibar x (1 / v0) instead of (xibar x ddot) / v0: the same to rounding): the same impacts, peaks within 1e-6;
#  - a curve whose e falls with v dissipates more than --e at its low-velocity value, less than at its high one;
#  - restitution_outside_valid counts every impact when the valid range lies above all impacts, none when it covers
#    them; the JSON carries the same;
#  - refused with one error naming the option: multi-storey, other laws and steppers, --e with a curve.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py=/usr/bin/python3
val() { awk -v k="$1:" '$1 == k { print $2 }' "$2"; }

# the kernel's latch on one free impact
"$bin" collide --law hertzdamp --damping-law calibrated --stepper central-difference --restitution-preset lindsay2011 \
  --v0 2 > "$tmp/c1.txt" || fail "collide CD: $(cat "$tmp/c1.txt")"
grep -q "^restitution_applied: kernel" "$tmp/c1.txt" || fail "not through the kernel: $(cat "$tmp/c1.txt")"
$py -c "
e = float('$(val e_effective "$tmp/c1.txt")'); want = -0.0012 * 8 + 0.0011 * 4 - 0.0838 * 2 + 0.9979
print('kernel e(2):', e, 'want', want); assert abs(e - want) < 1e-6" || fail "kernel e(2)"
[ "$(val restitution_outside_valid "$tmp/c1.txt")" = 0 ] || fail "v0 = 2 counted outside"
"$bin" collide --law hertzdamp --damping-law calibrated --stepper central-difference --restitution-table 1:0.9,3:0.5 \
  --v0 0.7 > "$tmp/c2.txt"
$py -c "
e = float('$(val e_effective "$tmp/c2.txt")'); print('kernel table e(0.7):', e); assert abs(e - 0.9) < 1e-6" \
  || fail "kernel table: $(cat "$tmp/c2.txt")"
[ "$(val restitution_outside_valid "$tmp/c2.txt")" = 1 ] || fail "v0 = 0.7 not counted outside [1, 3]"

# simulate: a constant curve = --e
"$bin" simulate --gap 0.03 --json > "$tmp/e.json"
"$bin" simulate --gap 0.03 --restitution-polynomial 0.65 --json > "$tmp/p.json"
"$bin" simulate --gap 0.03 --restitution-table 0:0.95,0.2:0.95,0.6:0.4,10:0.4 --json > "$tmp/t.json"
"$bin" simulate --gap 0.03 --e 0.95 --json > "$tmp/e95.json"
"$bin" simulate --gap 0.03 --e 0.4 --json > "$tmp/e40.json"
"$bin" simulate --gap 0.03 --restitution-polynomial 0.65 --restitution-valid 50,60 --json > "$tmp/out.json"
"$bin" simulate --gap 0.03 --restitution-polynomial 0.65 --restitution-valid 50,60 > "$tmp/out.txt"
$py - "$tmp" <<'PY' || fail "simulate"
import json, sys
d = sys.argv[1]
j = {k: json.load(open(f"{d}/{k}.json")) for k in ("e", "p", "t", "e95", "e40", "out")}
e, p = j["e"], j["p"]
assert e["impact_count"] == p["impact_count"] > 0, (e["impact_count"], p["impact_count"])
for k in ("peak_u1", "peak_u2"):
    for a, b in zip(e[k], p[k]):
        assert abs(a / b - 1) < 1e-6, (k, a, b)
assert abs(e["peak_force"] / p["peak_force"] - 1) < 1e-6, (e["peak_force"], p["peak_force"])
assert p["restitution_outside_valid"] == 0 and "restitution" in p and "restitution" not in e
ce = lambda x: x["energy_contact_dissipated_J"]
print("contact energy: e 0.95", ce(j["e95"]), "table", ce(j["t"]), "e 0.4", ce(j["e40"]))
assert ce(j["e95"]) < ce(j["t"]) < ce(j["e40"])
assert j["out"]["restitution_outside_valid"] == j["out"]["impact_count"] > 0, j["out"]["restitution_outside_valid"]
PY
grep -q "^restitution_outside_valid: [1-9][0-9]* of [1-9]" "$tmp/out.txt" || fail "text count: $(tail -3 "$tmp/out.txt")"

bad() {
  local opt=$1; shift
  set +e; "$bin" "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"; local rc=$?; set -e
  [ "$rc" -eq 2 ] || fail "$* -> exit $rc (want 2): $(cat "$tmp/bad.err")"
  [ ! -s "$tmp/bad.out" ] || fail "$* wrote to stdout"
  [ "$(grep -c ' ERROR:' "$tmp/bad.err")" -eq 1 ] || fail "$*: not one ERROR line: $(cat "$tmp/bad.err")"
  grep -q -- "$opt" "$tmp/bad.err" || fail "$*: the error does not name $opt: $(cat "$tmp/bad.err")"
  echo "ok: $(cat "$tmp/bad.err")"
}
bad --restitution-preset simulate --restitution-preset lindsay2011 --storeys1 3
bad --restitution-polynomial simulate --restitution-polynomial 0.7 --contact kelvin
bad --restitution-polynomial simulate --restitution-polynomial 0.7 --stepper rk4
bad --e simulate --restitution-polynomial 0.7 --e 0.5
echo "simulate_restitution: all checks passed"
