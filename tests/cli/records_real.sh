#!/usr/bin/env bash
# `pounding records` on the real records of ../shared/records/real: the embedded suite resolves exactly four
# entries to real files (and --write writes all 25), El Centro's PGA, the suite's spectra. Without ../shared
# it is skipped (exit 77), under CI=true it fails. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$bin" records suite --records-dir "$real" --write "$tmp/suite" >"$tmp/suite2.out"
grep -q "25 records: 4 real, 21 synthetic" "$tmp/suite2.out" || fail "suite with real records: $(tail -1 "$tmp/suite2.out")"
[ "$(ls "$tmp/suite" | wc -l)" = 25 ] || fail "suite --write"
"$bin" records show "$real/ImperialValley_1940_ElCentro_NS_Peknold1559pts.AT2" | grep "0.3188" > /dev/null || fail "El Centro PGA"
"$bin" records spectrum --suite default --records-dir "$real" --periods 0.5,1 -o "$tmp/suite.csv" | grep "25 spectra, 21 synthetic" > /dev/null \
  || fail "suite spectrum"
echo "records_real: ok"
