#!/usr/bin/env bash
# `pounding modes` (issue 25 §2, §5; docs/architecture.md §2.8 "impact-stiffness frames", "Rayleigh"):
#  - the impact-stiffness paper's 1/30-scale frames as uniform shear buildings, m = 6.53 kg per floor, storey
#    stiffness N x the measured lateral stiffness of Table 1 (../shared/research/seeds-models.md §2.1, V13, V14):
#    5 storeys, 137.5e3 N/m -> 6.57 / 19.19 / 30.25 Hz (the note's derived values, +-0.005 Hz), and within 5 / 5 / 10 %
#    of the paper's numerical 6.42 / 19.275 / 31.544 Hz; 15 storeys, 124.5e3 N/m -> 2.23 / 6.66 / 11.02 Hz, within
#    7 % of 2.0976 / 6.285 / 10.455 Hz;
#  - T1.2 of ../shared/research/systems-and-bridges.md: n = 5, m 1e5 kg, k 1e8 N/m, zeta 0.05 on modes 1 and 3 ->
#    each mode's ratio 0.05, 0.0401266873, 0.05, 0.0597130883, 0.0662729700 (1e-9);
#  - --modal-zeta gives each mode its ratio (the last repeating);
#  - --period with both profiles gives T1 (1e-10); one storey gets zeta itself; --modes K prints K rows; the
#    table, --csv and --json agree;
#  - bad input: one " ERROR:" line naming the option, exit 2, nothing on stdout.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# <name> <column> <want,...> <rel tol> <modes args...>: the CSV column (by header name) against values ('-' skips)
check() {
  local name=$1 col=$2 want=$3 tol=$4; shift 4
  "$bin" modes "$@" --csv > "$tmp/$name.csv" 2> "$tmp/$name.err" || fail "$name: $(cat "$tmp/$name.err")"
  awk -F, -v col="$col" -v want="$want" -v tol="$tol" -v name="$name" '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == col) c = i; if (!c) { print name ": no column " col; exit 1 }; next }
    { k++; split(want, w, ","); if (!(k in w) || w[k] == "-") next
      d = ($c - w[k]) / w[k]; if (d < 0) d = -d
      printf "%s mode %d %s %s want %s (rel %.1e, tol %g)\n", name, k, col, $c, w[k], d, tol
      if (!(d <= tol)) bad = 1 }
    END { exit bad }' "$tmp/$name.csv" || fail "$name: $col differs"
}

# V13, V14: the derived values to their printed digits (0.005 Hz of ~6-30 Hz: the tolerance is per value below)
check v13_derived frequency_hz 6.57,19.19,30.25 0.0008 --storeys 5 --mass 6.53 --stiffness 137.5e3
check v13_mode12 frequency_hz 6.42,19.275 0.05 --storeys 5 --mass 6.53 --stiffness 137.5e3
check v13_mode3 frequency_hz -,-,31.544 0.10 --storeys 5 --mass 6.53 --stiffness 137.5e3
check v14_derived frequency_hz 2.23,6.66,11.02 0.0025 --storeys 15 --mass 6.53 --stiffness 124.5e3
check v14_paper frequency_hz 2.0976,6.285,10.455 0.07 --storeys 15 --mass 6.53 --stiffness 124.5e3
# the same frame given per storey and by --period
check v13_lists frequency_hz 6.57348 1e-5 --masses 6.53,6.53,6.53,6.53,6.53 --stiffnesses 137.5e3,137.5e3,137.5e3,137.5e3,137.5e3

# T1.2: Rayleigh on modes 1 and 3
check t12 zeta 0.05,0.0401266873,0.05,0.0597130883,0.0662729700 1e-9 --storeys 5 --mass 1e5 --stiffness 1e8 \
  --zeta 0.05 --rayleigh-modes 1,3
check t11 period_s 0.698071149,0.239148513,0.151705359,0.118092678,0.103539979 1e-8 --storeys 5 --mass 1e5 --stiffness 1e8
check t11_gamma gamma 1.25170170,-0.362148406,0.158578455,-0.0631725011,0.0150407532 1e-8 --storeys 5 --mass 1e5 --stiffness 1e8

# classical modal damping: each mode its ratio, the last repeating
check modal zeta 0.05,0.03,0.03,0.03 1e-15 --storeys 4 --mass 1e5 --stiffness 1e8 --modal-zeta 0.05,0.03

# --period: T1 for both profiles, uniform and per-storey heights; one storey: zeta itself
check period_uniform period_s 0.8 1e-10 --storeys 12 --mass 3e5 --period 0.8
check period_shear period_s 1.3 1e-10 --masses 4e5,3e5,3e5,2e5 --period 1.3 --profile shear --storey-height 4,3,3,3
check sdof zeta 0.07 1e-12 --storeys 1 --mass 2e5 --stiffness 8e7 --zeta 0.07
check sdof_period period_s 0.314159265358979 1e-12 --storeys 1 --mass 2e5 --stiffness 8e7
# the shear profile: k_i in proportion to sum_{j>=i} m_j z_j, here uniform: (n(n+1) - i(i-1)) / (n(n+1)) of k_1
"$bin" modes --storeys 4 --mass 1e5 --period 0.5 --profile shear --json > "$tmp/shear.json"
/usr/bin/python3 - "$tmp/shear.json" <<'PY' || fail "shear profile: $(head -c 300 "$tmp/shear.json")"
import json, sys
k = json.load(open(sys.argv[1]))["stiffnesses"]
want = [(20 - i * (i - 1)) / 20 for i in range(1, 5)]
assert all(abs(a / k[0] - b) < 1e-14 for a, b in zip(k, want)), (k, want)
PY

# --modes, and the three outputs agree
"$bin" modes --storeys 20 --mass 1e5 --stiffness 1e8 --modes 3 --csv > "$tmp/three.csv"
[ "$(wc -l < "$tmp/three.csv")" -eq 4 ] || fail "--modes 3: $(wc -l < "$tmp/three.csv") lines"
"$bin" modes --storeys 20 --mass 1e5 --stiffness 1e8 --modes 3 > "$tmp/three.txt"
grep -q "^   3 " "$tmp/three.txt" && ! grep -q "^   4 " "$tmp/three.txt" || fail "--modes 3 table: $(cat "$tmp/three.txt")"
"$bin" modes --storeys 20 --mass 1e5 --stiffness 1e8 --modes 3 --json > "$tmp/three.json"
/usr/bin/python3 - "$tmp/three.json" "$tmp/three.csv" <<'PY' || fail "json and csv differ"
import csv, json, sys
j = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(j["modes"]) == len(rows) == 3
for m, r in zip(j["modes"], rows):
    for jk, ck in (("period", "period_s"), ("omega", "omega_rad_s"), ("gamma", "gamma"), ("zeta", "zeta"),
                   ("effective_mass_ratio", "effective_mass_ratio")):
        assert abs(m[jk] - float(r[ck])) <= 1e-11 * abs(m[jk]), (jk, m[jk], r[ck])
    assert all(abs(a - float(r[f"phi_{i + 1}"])) <= 1e-11 * max(1, abs(a)) for i, a in enumerate(m["shape"]))
assert abs(sum(m["effective_mass"] for m in j["modes"]) - float(rows[-1]["cumulative_ratio"]) * j["total_mass"]) < 1e-6
PY

# the help points to the documentation (docs/buildings.md), not to sources
"$bin" modes --help > "$tmp/help.txt"
grep -q "docs/buildings.md" "$tmp/help.txt" || fail "--help does not point to docs/buildings.md"
! grep -q "src/" "$tmp/help.txt" || fail "--help names a source file"

# bad input: <option named in the message> <args...>
refuse() {
  local opt=$1; shift
  set +e
  "$bin" modes "$@" > "$tmp/out.txt" 2> "$tmp/err.txt"
  local rc=$?
  set -e
  [ "$rc" -eq 2 ] || fail "modes $*: exit $rc, want 2 ($(cat "$tmp/err.txt"))"
  [ ! -s "$tmp/out.txt" ] || fail "modes $*: wrote to stdout: $(head -3 "$tmp/out.txt")"
  [ "$(wc -l < "$tmp/err.txt")" -eq 1 ] && grep -q "^ ERROR: .*$opt" "$tmp/err.txt" ||
    fail "modes $*: want one ERROR line naming $opt, got: $(cat "$tmp/err.txt")"
  echo "refused: modes $* -> $(cat "$tmp/err.txt")"
}
refuse --storeys --storeys 0 --mass 1e5 --stiffness 1e8
refuse --storeys --storeys 2.5 --mass 1e5 --stiffness 1e8
refuse --storeys --storeys 201 --mass 1e5 --stiffness 1e8
refuse --storeys --mass 1e5 --stiffness 1e8
refuse --mass --storeys 3 --mass -1 --stiffness 1e8
refuse --mass --storeys 3 --mass nan --stiffness 1e8
refuse --mass --storeys 3 --mass 1e12 --stiffness 1e8
refuse --mass --storeys 3 --mass 1,2,3 --stiffness 1e8
refuse --mass/--masses --storeys 3 --stiffness 1e8
refuse --mass/--masses --storeys 3 --mass 1e5 --masses 1e5,1e5,1e5 --stiffness 1e8
refuse --masses --masses 1e5,,1e5 --stiffness 1e8
refuse --masses --storeys 2 --masses 1e5,1e5,1e5 --stiffness 1e8
refuse --stiffnesses --masses 1e5,1e5,1e5 --stiffnesses 1e8,1e8
refuse --stiffness --storeys 3 --mass 1e5 --stiffness inf
refuse --stiffness --storeys 3 --mass 1e5 --stiffness 1e15
refuse --stiffness/--stiffnesses/--period --storeys 3 --mass 1e5
refuse --stiffness/--stiffnesses/--period --storeys 3 --mass 1e5 --stiffness 1e8 --period 0.5
refuse --period --storeys 3 --mass 1e5 --period 0
refuse --period --storeys 3 --mass 1e5 --period 100
refuse --period --storeys 200 --mass 1e9 --period 0.02
refuse --profile --storeys 3 --mass 1e5 --period 0.5 --profile triangle
refuse --profile --storeys 3 --mass 1e5 --stiffness 1e8 --profile shear
refuse --storey-height --storeys 3 --mass 1e5 --stiffness 1e8 --storey-height 3
refuse --storey-height --storeys 3 --mass 1e5 --period 0.5 --storey-height 0
refuse --storey-height --storeys 3 --mass 1e5 --period 0.5 --storey-height 3,3
refuse --zeta --storeys 3 --mass 1e5 --stiffness 1e8 --zeta 0.9
refuse --zeta --storeys 3 --mass 1e5 --stiffness 1e8 --zeta -0.01
refuse --rayleigh-modes --storeys 3 --mass 1e5 --stiffness 1e8 --rayleigh-modes 1,1
refuse --rayleigh-modes --storeys 3 --mass 1e5 --stiffness 1e8 --rayleigh-modes 1,4
refuse --rayleigh-modes --storeys 3 --mass 1e5 --stiffness 1e8 --rayleigh-modes 1,2,3
refuse --rayleigh-modes --storeys 1 --mass 1e5 --stiffness 1e8 --rayleigh-modes 1,2
refuse --modal-zeta --storeys 3 --mass 1e5 --stiffness 1e8 --modal-zeta 0.05 --zeta 0.05
refuse --modal-zeta --storeys 3 --mass 1e5 --stiffness 1e8 --modal-zeta 0.05 --rayleigh-modes 1,3
refuse --modal-zeta --storeys 2 --mass 1e5 --stiffness 1e8 --modal-zeta 0.05,0.04,0.03
refuse --modal-zeta --storeys 2 --mass 1e5 --stiffness 1e8 --modal-zeta 0.05,0.6
refuse --modes --storeys 3 --mass 1e5 --stiffness 1e8 --modes 4
# masses 13 decades apart: beyond a study's floor_mass range (the ranges keep a stick within 12 decades)
refuse --masses --masses 0.001,1e10 --stiffnesses 1e8,1e8
refuse --csv/--json --storeys 3 --mass 1e5 --stiffness 1e8 --csv --json
refuse --bogus --storeys 3 --mass 1e5 --stiffness 1e8 --bogus 1
echo "modes: all checks passed"
