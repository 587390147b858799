#!/usr/bin/env bash
# `pounding inventory` (issue 48; docs/inventory.md):
#  - design: the worked ELF example and an 8-storey steel frame against tools/elf_reference.py (an independent script,
#    SciPy's eigensolver) to 1e-6 in every storey's Vx and stiffness;
#  - check: the shipped street (14 buildings, 13 pairs: 5 shared walls, 1 pair with floors aligned at a gap...), the
#    pairs CSV; synth: the same seed gives the same file, another seed another, and check reads it;
#  - bad input: one " ERROR:" line naming the file:row or feature and the field, exit 2, no output left.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py=/usr/bin/python3; [ -x "$py" ] || py=python3

# design against the reference: storey lines "storey i ... Vx <v> N  k <k> N/m"
compare() {  # <name> <pounding design args> -- <reference args>
  local name=$1; shift
  local mine=() ref=()
  while [ "$1" != -- ]; do mine+=("$1"); shift; done; shift; ref=("$@")
  "$bin" inventory design "${mine[@]}" > "$tmp/$name.out" 2> "$tmp/$name.err" || fail "$name: $(cat "$tmp/$name.err")"
  "$py" "$src/tools/elf_reference.py" "${ref[@]}" > "$tmp/$name.ref"
  "$py" - "$tmp/$name.out" "$tmp/$name.ref" "$name" <<'PY'
import re, sys
out = open(sys.argv[1]).read(); ref = dict(l.split() for l in open(sys.argv[2]))
rows = re.findall(r"storey\s+(\d+) .*?Vx\s+(\S+) N\s+k\s+(\S+) N/m\s+Vy\s+(\S+) N", out)
assert rows, out
bad = 0
for i, vx, k, vy in rows:
    for key, mine in (("Vx", vx), ("K", k), ("Vy", vy)):
        want = float(ref[f"{key}{i}"]); rel = abs(float(mine) - want) / want
        if rel > 5e-4: print(f"{sys.argv[3]} storey {i} {key} {mine} want {want}"); bad = 1
print(f"{sys.argv[3]}: {len(rows)} storeys agree with tools/elf_reference.py (4 printed digits)")
sys.exit(bad)
PY
}
compare rc_smf --system rc-smf --storeys 5 --storey-height 3.2 --plan-area 450 --unit-weight 9.80665 --sds 1 --sd1 0.6 --s1 0.6 \
  -- --storeys 5 --storey-height 3.2 --floor-mass 4.5e5 --sds 1 --sd1 0.6 --s1 0.6 --tl 8 --r 8 --omega0 3 --ct 0.0466 --x 0.9
# 8 storeys of 3.8 m, 600 m^2 at 6 kPa: floor mass 600 x 6000 / 9.80665; SD1 0.25 g: Cu 1.45
compare steel_smf --system steel-smf --storeys 8 --storey-height 3.8 --plan-area 600 --sds 0.5 --sd1 0.25 --s1 0.3 \
  -- --storeys 8 --storey-height 3.8 --floor-mass 367097.8 --sds 0.5 --sd1 0.25 --s1 0.3 --tl 8 --r 8 --omega0 3 --ct 0.0724 --x 0.8
grep -q "Cu = 1.45" "$tmp/steel_smf.out" || fail "steel_smf: Cu is not 1.45: $(head -1 "$tmp/steel_smf.out")"

# the shipped street
"$bin" inventory check "$src/studies/street.geojson" --pairs-csv "$tmp/pairs.csv" > "$tmp/street.out" || fail "check street"
grep -q "14 buildings, 13 adjacent pairs" "$tmp/street.out" || fail "street: $(head -1 "$tmp/street.out")"
[ "$(grep -c ',shared wall,' "$tmp/pairs.csv")" = 5 ] || fail "street: not 5 shared walls: $(cat "$tmp/pairs.csv")"
# 105-107: 5 cm apart (to the millimetre), facing 22 m, floors 3.0 m against 3.2 m
awk -F, '$1 == "105-main" && $2 == "107-main" && $3 == "gap" && $4 == 0.05 && $5 == 22 && $6 == "no" && $7 == 1.2 { ok = 1 }
         END { exit !ok }' "$tmp/pairs.csv" || fail "street: 105-107 row: $(cat "$tmp/pairs.csv")"
grep -q '^111-main,113-main,shared wall,0.0000,18.000,yes,0.000$' "$tmp/pairs.csv" || fail "street: the twins"
echo "street: 14 buildings, 13 pairs, 5 shared walls"

# a pair as a study: written, run (2 samples per record), the designed period and the measured gap in the results
(cd "$tmp" && "$bin" inventory pair "$src/studies/street.geojson" --a 107-main --b 111-main --out pair.toml --samples 2 \
   > pair.out) || fail "pair: $(cat "$tmp/pair.out")"
grep -q '^existing = 0.1$' "$tmp/pair.toml" || fail "pair: the measured gap 0.1 m is not the existing gap: $(grep existing "$tmp/pair.toml")"
grep -q '^mcer = true' "$tmp/pair.toml" || fail "pair: not at MCE shaking"
(cd "$tmp" && "$bin" run pair.toml --quiet > run.out 2>&1) || fail "pair study: $(tail -3 "$tmp/run.out")"
"$bin" report "$tmp/107-main--111-main.h5" > "$tmp/pair.md"
grep -q "lognormal(median 1.20762 s" "$tmp/pair.md" || fail "pair: 107-main's period (Cu Ta = 1.2076 s) is not in the report"
grep -q "At the existing gap" "$tmp/pair.md" || fail "pair: no answer at the existing gap"
echo "pair: 107-main beside 111-main written as a study and run"

# synth: deterministic in the seed
"$bin" inventory synth --buildings 300 --seed 7 --out "$tmp/a.geojson" > /dev/null
"$bin" inventory synth --buildings 300 --seed 7 --out "$tmp/b.geojson" > /dev/null
"$bin" inventory synth --buildings 300 --seed 8 --out "$tmp/c.geojson" > /dev/null
cmp -s "$tmp/a.geojson" "$tmp/b.geojson" || fail "synth: the same seed gave two files"
cmp -s "$tmp/a.geojson" "$tmp/c.geojson" && fail "synth: two seeds gave one file"
"$bin" inventory check "$tmp/a.geojson" > "$tmp/a.out" || fail "check synth: $(tail -1 "$tmp/a.out")"
grep -q "300 buildings" "$tmp/a.out" || fail "synth check: $(head -1 "$tmp/a.out")"
echo "synth: deterministic; $(head -1 "$tmp/a.out" | cut -d';' -f1)"

# bad input: <name> <expected text in the error> <command...>
refuse() {
  local name=$1 want=$2; shift 2
  set +e; "$@" > "$tmp/$name.out" 2> "$tmp/$name.err"; local rc=$?; set -e
  [ $rc = 2 ] || fail "$name: exit $rc, want 2"
  [ "$(grep -c ' ERROR:' "$tmp/$name.err")" = 1 ] || fail "$name: not one ERROR line: $(cat "$tmp/$name.err")"
  grep -qF -- "$want" "$tmp/$name.err" || fail "$name: want '$want' in: $(cat "$tmp/$name.err")"
  echo "$name refused: $(cut -c1-150 "$tmp/$name.err")"
}
head='id,block,order,frontage,depth,gap_next,storeys,storey_height,system,design_level,site_class'
printf '%s\nA,b,1,10,10,0,3,3,rc-smf,high,D\nB,b,2,10,10,,3,3,rc-smff,high,D\n' "$head" > "$tmp/system.csv"
refuse unknown_system "system.csv:3" "$bin" inventory check "$tmp/system.csv"
printf '%s\nA,b,1,10,10,0,0,3,rc-smf,high,D\n' "$head" > "$tmp/storeys.csv"
refuse storeys_zero "storeys" "$bin" inventory check "$tmp/storeys.csv"
printf '%s\nA,b,1,10,10,,3,3,rc-smf,high,\n' "$head" > "$tmp/site.csv"
refuse no_site "site class is missing" "$bin" inventory check "$tmp/site.csv"
sed 's/"107-main"/"105-main"/' "$src/studies/street.geojson" > "$tmp/dup.geojson"
refuse duplicate_id "used twice" "$bin" inventory check "$tmp/dup.geojson"
refuse out_is_input "--pairs-csv" "$bin" inventory check "$tmp/site.csv" --pairs-csv "$tmp/site.csv"
refuse bad_level "design level" "$bin" inventory design --system rc-smf --storeys 3 --storey-height 3 --plan-area 100 \
  --sds 1 --sd1 0.5 --s1 0.5 --design-level medium
refuse site_e "site-specific" "$bin" inventory design --system rc-smf --storeys 3 --storey-height 3 --plan-area 100 \
  --ss 1.5 --s1 0.6 --site E
[ -e "$tmp/none.csv" ] && fail "an output was left"
echo "inventory: all checks passed"
