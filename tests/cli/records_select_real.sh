#!/usr/bin/env bash
# `pounding records select` on the real PEER records of ../shared/records/real (every .AT2 and .txt there, 85 files,
# the set a study's [records] directory reads):
# 11 records for an ASCE 7-16 design spectrum (SDS 1.0 g, SD1 0.6 g) at T = 1 s and 7 for an EC8 type 1
# ground C spectrum (agR 0.3 g) for the pair T = 0.9, 1.3 s. The printed condition must hold, 11 and 7 records
# must be listed with their factors, and the EC8 PGA ratio must be >= 1. Without ../shared it is skipped (exit
# 77), under CI=true it fails. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$bin" records select --asce7 1.0,0.6,8 --period 1.0 --directory "$real" -o "$tmp/asce.csv" > "$tmp/asce.out"
grep -q "candidates: 85," "$tmp/asce.out" || fail "ASCE 7-16: not the 85 records: $(sed -n 4p "$tmp/asce.out")"
grep -q "condition holds: yes" "$tmp/asce.out" || fail "ASCE 7-16: $(cat "$tmp/asce.out")"
[ "$(grep -c '\.\(AT2\|txt\)$' "$tmp/asce.out")" = 11 ] || fail "ASCE 7-16: 11 records expected: $(cat "$tmp/asce.out")"
"$bin" records select --ec8 1,C,0.3 --rule EC8 --period 0.9,1.3 --count 7 --directory "$real" > "$tmp/ec8.out"
grep -q "condition holds: yes" "$tmp/ec8.out" || fail "EC8: $(cat "$tmp/ec8.out")"
[ "$(grep -c '\.\(AT2\|txt\)$' "$tmp/ec8.out")" = 7 ] || fail "EC8: 7 records expected: $(cat "$tmp/ec8.out")"
ratio=$(sed -n 's/.*mean PGA \/ ag S = \([0-9.]*\)).*/\1/p' "$tmp/ec8.out")
awk -v r="$ratio" 'BEGIN { exit !(r >= 1 - 1e-6) }' || fail "EC8 PGA ratio $ratio < 1"
echo "records_select_real: ok ($(grep 'suite factor' "$tmp/asce.out"); EC8 $(grep 'suite factor' "$tmp/ec8.out"))"
