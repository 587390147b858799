#!/usr/bin/env bash
# Issue 23 item 7 on the real records of ../shared/records/real: `records select --directory` reads the 85 files
# a study's [records] directory reads (it read 47 .AT2 files); one recording is never chosen twice (the El Centro
# 1940 N-S motion is both ImperialValley_1940_ElCentroArray9_180 (NGA-West2) and ..._ElCentro_NS_Peknold1559pts);
# by default one component per station and at most 2 records of one earthquake; the table shows event, station and
# component and says what was passed over and why; a study using its library whole warns when it holds one recording
# twice. Checked against MANIFEST.tsv, not against the engine's own
# grouping. Without ../shared it is skipped (exit 77), under CI=true it fails. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
ec1=ImperialValley_1940_ElCentroArray9_180
ec2=ImperialValley_1940_ElCentro_NS_Peknold1559pts

# the selection of the issue (ASCE 7-16, SDS 1.0 g, SD1 0.6 g, T = 1 s, 11 records) from the whole directory
"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --directory "$real" -o "$tmp/asce.csv" > "$tmp/asce.out"
grep -q "candidates: 85," "$tmp/asce.out" || fail "not the 85 records of the directory: $(sed -n 4p "$tmp/asce.out")"
grep -q "condition holds: yes" "$tmp/asce.out" || fail "condition: $(cat "$tmp/asce.out")"
# (awk reads the file itself: `grep | head -1` under pipefail failed silently when head closed the pipe first)
chosen=$(awk '!/^#/ { print; exit }' "$tmp/asce.csv" | cut -d, -f4- | tr , '\n')
[ "$(echo "$chosen" | wc -l)" = 11 ] || fail "11 records expected: $chosen"
# event and station of each chosen record from MANIFEST.tsv: no station twice, no event more than twice,
# not both El Centro 1940 files
for id in $chosen; do
  awk -F'\t' -v id="$id" '$1 ~ "^" id "\\." { print $2 "|" $3 "|" $4 }' "$real/MANIFEST.tsv"
done > "$tmp/chosen.tsv"
[ "$(wc -l < "$tmp/chosen.tsv")" = 11 ] || fail "chosen records missing from MANIFEST.tsv: $chosen"
dup=$(cut -d'|' -f1,3 "$tmp/chosen.tsv" | sort | uniq -d)
[ -z "$dup" ] || fail "a station chosen twice: $dup"
many=$(cut -d'|' -f1,2 "$tmp/chosen.tsv" | sort | uniq -c | awk '$1 > 2')
[ -z "$many" ] || fail "more than 2 records of one event: $many"
! { grep -qx "$ec1" <<<"$chosen" && grep -qx "$ec2" <<<"$chosen"; } || fail "both El Centro 1940 files chosen"
# the table: event (year), station and component of each row, from the MANIFEST
while IFS='|' read -r event year station comp; do
  grep -F "$event ($year)" "$tmp/asce.out" | grep -F "$station" > /dev/null ||
    fail "no row with event '$event ($year)' and station '$station': $(cat "$tmp/asce.out")"
done < "$tmp/chosen.tsv"
grep -q "^rules: at most 2 per event, components = one" "$tmp/asce.out" || fail "no rules line: $(cat "$tmp/asce.out")"

# the two El Centro 1940 files among four candidates, four wanted, no event limit: refused as one recording
few=("$real/$ec1.AT2" "$real/$ec2.AT2" "$real/Kobe_1995_NishiAkashi_000.txt" "$real/Landers_1992_Lucerne_260.AT2"
     "$real/Friuli_1976_Tolmezzo_000.AT2")
"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --count 4 --max-per-event 0 --min-scale 0.01 --max-scale 100 \
  "${few[@]}" > "$tmp/ec.out" || fail "five candidates: $(cat "$tmp/ec.out")"
[ "$(grep -c '^ *[0-9]\+ ImperialValley_1940_' "$tmp/ec.out")" = 1 ] || fail "both El Centro 1940 files: $(cat "$tmp/ec.out")"
rc=0
"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --count 5 --max-per-event 0 --min-scale 0.01 --max-scale 100 \
  "${few[@]}" > "$tmp/ec5.out" 2>&1 || rc=$?
[ "$rc" = 2 ] || fail "five of five with one recording twice: exit $rc: $(cat "$tmp/ec5.out")"
grep -q "only 4 of the 5 eligible records are distinct recordings" "$tmp/ec5.out" || fail "$(cat "$tmp/ec5.out")"

# Rinaldi's two components and one other record, three wanted: one component per station by default (an error
# naming the rule), both with --components both
rin=("$real/Northridge_1994_RinaldiReceivingSta_228.AT2" "$real/Northridge_1994_RinaldiReceivingSta_318.AT2"
     "$real/Kobe_1995_NishiAkashi_000.txt")
rc=0
"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --count 3 --min-scale 0.01 --max-scale 100 "${rin[@]}" \
  > "$tmp/rin1.out" 2>&1 || rc=$?
[ "$rc" = 2 ] || fail "Rinaldi twice with components one: exit $rc: $(cat "$tmp/rin1.out")"
grep -q "1 second components" "$tmp/rin1.out" || fail "Rinaldi, one: $(cat "$tmp/rin1.out")"
grep -q "components both" "$tmp/rin1.out" || fail "Rinaldi, one: no way out named: $(cat "$tmp/rin1.out")"
"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --count 3 --min-scale 0.01 --max-scale 100 --components both \
  "${rin[@]}" > "$tmp/rin2.out" || fail "Rinaldi, both: $(cat "$tmp/rin2.out")"
[ "$(grep -c '^ *[0-9]\+ Northridge_1994_Rinaldi' "$tmp/rin2.out")" = 2 ] || fail "components both: $(cat "$tmp/rin2.out")"
grep "Northridge_1994_RinaldiReceivingSta_228" "$tmp/rin2.out" | grep "Northridge-01 (1994) *Rinaldi Receiving Sta *228" > /dev/null ||
  fail "event, station, component columns: $(cat "$tmp/rin2.out")"
# a study that uses its library whole says when the library holds one recording twice (run log WARNING)
{ cat "$src/tests/data/study-select-pair.toml"
  printf '[records]\nfiles = ["%s", "%s", "%s"]\n' "$real/$ec1.AT2" "$real/$ec2.AT2" "$real/Kobe_1995_NishiAkashi_000.txt"
} > "$tmp/dup.toml"
"$bin" run "$tmp/dup.toml" --out "$tmp/dup.h5" > "$tmp/dup.log" 2>&1 || fail "run: $(cat "$tmp/dup.log")"
grep -q "WARNING: records $ec1 and $ec2 are one recording" "$tmp/dup.log" || fail "no duplicate warning: $(cat "$tmp/dup.log")"
[ "$(grep -c "are one recording" "$tmp/dup.log")" = 1 ] || fail "one warning expected: $(cat "$tmp/dup.log")"
echo "records_select_recordings: ok ($(grep -c '^  refused' "$tmp/asce.out") passed over in the 85-record selection)"
