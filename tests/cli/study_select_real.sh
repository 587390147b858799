#!/usr/bin/env bash
# [records] select = 11 from the real PEER records of ../shared/records/real (every .AT2 and two-column .txt
# there, 85 records, as studies/real-records.toml loads them) to an ASCE 7-16 target (SDS 1.0 g, SD1 0.6 g,
# TL 8 s) for the pair of median periods 0.9 and 1.3 s: the run log's selection (rows, suite factor, smallest
# ratio, verdict, the records passed over as one recording twice, a second component or over an event's quota)
# equals `pounding records select --directory` on the same directory, the condition holds, and /records holds
# exactly the 11 chosen records. Without ../shared it is skipped (exit 77), under CI=true it fails.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
real=$(cd "$real" && pwd)
{ cat "$src/tests/data/study-select-pair.toml"
  printf '[records]\ndirectory = "%s"\nselect = 11\n[target_spectrum]\ncode = "ASCE 7-16"\nsds = 1.0\nsd1 = 0.6\ntl = 8.0\n' "$real"
} > "$tmp/real.toml"
"$bin" run "$tmp/real.toml" --out "$tmp/real.h5" > "$tmp/run.log" 2>&1 || fail "run: $(cat "$tmp/run.log")"
mapfile -t files < <(ls "$real"/*.AT2 "$real"/*.txt | LC_ALL=C sort)
[ "${#files[@]}" = 85 ] || fail "expected 85 records in $real, found ${#files[@]}"
# the same directory through `records select --directory`: one reader, the same 85 files (issue 23 item 7)
"$bin" records select --asce7 1.0,0.6,8 --period 0.9,1.3 --count 11 --directory "$real" > "$tmp/cli.out" ||
  fail "records select: $(cat "$tmp/cli.out")"
rows() { sed -n '/^target: /,/^condition/p' "$1" | awk '/^ *[0-9]+ /{ print $1, $2, $3, $4, $5; next } { print }' |
         grep -v '^target: '; }
rows "$tmp/run.log" > "$tmp/study.rows"
rows "$tmp/cli.out" > "$tmp/cli.rows"
grep -q "candidates: 85," "$tmp/study.rows" || fail "not 85 candidates: $(cat "$tmp/study.rows")"
grep -q "^rules: at most 2 per event, components = one" "$tmp/study.rows" || fail "rules: $(cat "$tmp/study.rows")"
grep -q "condition holds: yes" "$tmp/study.rows" || fail "condition: $(cat "$tmp/study.rows")"
[ "$(grep -c '^ *[0-9]\+ ' "$tmp/study.rows")" = 11 ] || fail "11 rows expected: $(cat "$tmp/study.rows")"
diff "$tmp/cli.rows" "$tmp/study.rows" || fail "the study's selection differs from records select"
# issue 23 item 7: before the rules this selection held both El Centro 1940 files (one N-S motion, two
# digitisations) and both components of Delta and Palo Alto
grep -q "refused ImperialValley_1940_ElCentro_NS_Peknold1559pts: the same recording as ImperialValley_1940_ElCentroArray9_180" \
  "$tmp/study.rows" || fail "El Centro 1940 chosen twice: $(cat "$tmp/study.rows")"
[ "$(grep -c '^ *[0-9]\+ \(ImperialValley_1979_Delta\|LomaPrieta_1989_PaloAlto\)' "$tmp/study.rows")" = 2 ] ||
  fail "Delta and Palo Alto: one component each expected: $(cat "$tmp/study.rows")"
"$bin" report "$tmp/real.h5" | sed -n '/^## Records selected/,$p' > "$tmp/report.md"
[ "$(grep -c '^| ' "$tmp/report.md")" = 12 ] || fail "report: a header and 11 rows expected: $(cat "$tmp/report.md")"
echo "study_select_real: ok ($(grep -m1 '^suite factor' "$tmp/run.log"); $(grep -m1 '^min mean' "$tmp/run.log"))"
