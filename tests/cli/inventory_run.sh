#!/usr/bin/env bash
# `pounding inventory run` (issue 48; docs/inventory.md): a street of three buildings (CSV, street order), each adjacent
# pair a pair study from a template; the answers per pair (CSV, Markdown ranking) equal each pair's own report; a
# second run reruns nothing, a changed template reruns every pair; 2 MPI ranks give the same results bit for bit; bad
# templates are refused before any work.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cd "$tmp"
cat > street.csv <<'CSV'
id,block,order,frontage,depth,gap_next,storeys,storey_height,system,year_built,site_class
A,main,1,10,15,0.04,3,3.2,rc-omf,1965,C
B,main,2,12,15,0.12,5,3.0,rc-smf,2001,C
C,main,3,10,15,,2,3.5,urm-wall,1920,C
CSV
cat > street.toml <<'TOML'
title = "three buildings"
seed = 5
output = "out/street.h5"
[inventory]
file = "street.csv"
ss = 1.0
s1 = 0.4
samples = 2
records = 3
[records]
suite = "builtin"
synthetic_only = true
select = 3
TOML
mkdir out
"$bin" inventory run street.toml --quiet > run1.out 2> run1.err || fail "run: $(tail -3 run1.err)"
grep -q "3 buildings, 2 adjacent pairs; 2 to run, 0 current" run1.err || fail "run: $(grep inventory run1.err)"
grep -q "Pairs ranked by P(pounding)" out/street.html || fail "no ranking in street.html"
for f in out/street.pairs.csv out/street.md out/street.pairs/A--B.toml out/street.pairs/A--B.h5 out/street.pairs/B--C.md; do
  [ -s "$f" ] || fail "missing $f"
done
# the CSV's answer at the existing gap is the pair's own report's
"$bin" report out/street.pairs/A--B.h5 --csv > ab.csv
want=$(awk -F, '$1 == "existing" { print $8 }' ab.csv)
got=$(awk -F, '$1 == "A" && $2 == "B" { print $8 }' out/street.pairs.csv)
awk -v a="$want" -v b="$got" 'BEGIN { exit !(a != "" && (a - b)^2 < 1e-10) }' || fail "A-B: pairs.csv $got, report $want"
grep -q '^existing = 0.04' out/street.pairs/A--B.toml || fail "A-B: the measured gap is not the existing gap"
grep -q 'select = 3' out/street.pairs/A--B.toml || fail "A-B: the template's [records] did not reach the pair"
echo "run: 2 pairs; A-B P(existing) $got as its report"
# again: nothing to run
"$bin" inventory run street.toml --quiet > run2.out 2> run2.err || fail "rerun: $(tail -3 run2.err)"
grep -q "2 to run" run2.err && fail "rerun ran the pairs again"
grep -q "0 to run, 2 current" run2.err || fail "rerun: $(grep inventory run2.err)"
cmp -s run1.out run2.out || fail "rerun: another ranking"
# 2 ranks, a changed seed: every pair again, results as one rank's
cp -r out out1
sed -i 's/^seed = 5/seed = 6/' street.toml
"$bin" inventory run street.toml --quiet > /dev/null 2> run3.err || fail "seed 6: $(tail -3 run3.err)"
grep -q "2 to run, 0 current" run3.err || fail "a changed template did not rerun the pairs"
cp out/street.pairs/B--C.h5 one_rank.h5
timeout 300 mpirun -np 2 "$bin" inventory run street.toml --quiet --force > /dev/null 2> run4.err || fail "2 ranks: $(tail -3 run4.err)"
/usr/bin/python3 "$src/tests/cli/compare_results.py" one_rank.h5 out/street.pairs/B--C.h5 > cmp.out || fail "2 ranks: $(tail -3 cmp.out)"
echo "2 ranks: B-C bit-identical to 1 rank"
# a fragility template: Sa stripes and a hazard curve (a path relative to the template, rebased for the pairs'
# studies): P in 50 years at each measured gap, as the pair's own fragility report gives it
mkdir hz
cp "$src/studies/example-hazard.csv" .
cat > hz.toml <<'TOML'
seed = 7
scene = "probability"
output = "hz/street.h5"
[inventory]
file = "street.csv"
samples = 2
[records]
suite = "builtin"
synthetic_only = true
limit = 3
[intensity]
measure = "Sa"
period = "pair"
levels = [0.2, 0.6, 1.2]
max_scale = 10
[hazard]
curve = "example-hazard.csv"
years = 50
target = 2.0
source = "example curve (tools/example_hazard.py)"
TOML
"$bin" inventory run hz.toml --quiet > hz.out 2> hz.err || fail "fragility template: $(tail -3 hz.err)"
"$bin" report hz/street.pairs/A--B.h5 --csv > hzab.csv
want=$(awk -F, '$1 == "fragility" && $3 == 0.04 { print $14 }' hzab.csv)
got=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "p_hazard_years") c = i; next } $1 == "A" { print $c }' hz/street.pairs.csv)
awk -v a="$want" -v b="$got" 'BEGIN { exit !(a != "" && (a - b)^2 < 1e-10 * (a^2 + 1e-30)) }' || fail "A-B in 50 years: pairs.csv $got, report $want"
echo "fragility template: A-B P in 50 years $got as its report"

# bad templates
refuse() {
  local name=$1 want=$2
  set +e; "$bin" inventory run "$name.toml" --quiet > "$name.out" 2> "$name.err"; local rc=$?; set -e
  [ $rc = 2 ] || fail "$name: exit $rc"
  grep -qF -- "$want" "$name.err" || fail "$name: want '$want' in $(cat "$name.err")"
  echo "$name refused: $(cut -c1-140 "$name.err")"
}
sed 's/^samples = 2/sample = 2/' street.toml > typo.toml
refuse typo "unknown key 'sample'"
{ cat street.toml; printf '[structures]\nmodel = "shear"\n'; } > structures.toml
refuse structures "[structures] is made per pair"
sed 's/street.csv/nowhere.csv/' street.toml > missing.toml
refuse missing "nowhere.csv"
set +e; "$bin" run street.toml --quiet > as_study.out 2> as_study.err; rc=$?; set -e
[ $rc = 2 ] && grep -q "pounding inventory run" as_study.err || fail "pounding run of a template: exit $rc $(cat as_study.err)"
echo "pounding run of a template refused: $(cut -c1-120 as_study.err)"
echo "inventory run: all checks passed"
