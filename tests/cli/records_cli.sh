#!/usr/bin/env bash
# `pounding records ...` end to end: synth -> AT2 -> show/spectrum round trip, the synthetic suite, bad input
# (exit 2, file:line in the message, no partial output). The real-record part is records_real.sh.
set -euo pipefail
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# synth writes an AT2 file that show reads back at the requested PGA
"$bin" records synth --M 6.9 --R 15.2 --vs30 288.62 --F 1 --seed 3 --pga 0.51 -o "$tmp/s.AT2" >"$tmp/synth.out"
[ -f "$tmp/s.AT2" ] || fail "synth wrote nothing"
[ ! -e "$tmp/s.AT2.tmp" ] || fail "temporary file left behind"
head -4 "$tmp/s.AT2" | grep -q "NPTS=" || fail "line 4 of the AT2 has no NPTS"
"$bin" records show "$tmp/s.AT2" >"$tmp/show.out"
pga=$(awk 'NR==2 {print $6}' "$tmp/show.out")
awk -v p="$pga" 'BEGIN { exit !(p > 0.5099 && p < 0.5101) }' || fail "PGA after round trip is $pga, not 0.51"
# same seed -> same file
"$bin" records synth --M 6.9 --R 15.2 --vs30 288.62 --F 1 --seed 3 --pga 0.51 -o "$tmp/s2.AT2" >/dev/null
cmp -s "$tmp/s.AT2" "$tmp/s2.AT2" || fail "same seed gave a different file"

# spectrum CSV: PSA(T=0) = PGA
"$bin" records spectrum "$tmp/s.AT2" --periods 0,0.5,1 -o "$tmp/spec.csv" >/dev/null
grep -q "^period_s,s$" "$tmp/spec.csv" || fail "spectrum header"
awk -F, '$1 == "0" { exit !($2 > 0.5099 && $2 < 0.5101) }' "$tmp/spec.csv" || fail "PSA(0) != PGA"
[ "$(grep -vc '^#\|^period' "$tmp/spec.csv")" = 3 ] || fail "expected 3 period rows"

# the embedded suite: 25 records, all synthetic without a directory (with the real records: records_real.sh)
"$bin" records suite --synthetic-only >"$tmp/suite.out"
grep -q "25 records: 0 real, 25 synthetic" "$tmp/suite.out" || fail "synthetic-only suite"

# bad input: exit 2, file and line named, no output file
printf 'h1\nh2\nh3\nNPTS= 3, DT= .01 SEC\n .1 abc .3\n' >"$tmp/bad.AT2"
set +e
"$bin" records spectrum "$tmp/bad.AT2" -o "$tmp/bad.csv" 2>"$tmp/err" >/dev/null
rc=$?
set -e
[ "$rc" = 2 ] || fail "bad file exit code $rc"
grep -q "bad.AT2:5" "$tmp/err" || fail "error does not name file:line: $(cat "$tmp/err")"
grep -q "'abc' is not a number" "$tmp/err" || fail "error does not say what is wrong"
[ ! -e "$tmp/bad.csv" ] && [ ! -e "$tmp/bad.csv.tmp" ] || fail "partial output after an error"
set +e
"$bin" records synth --M 6.9 --R 15 --vs30 300 --F 3 -o "$tmp/x.AT2" 2>"$tmp/err2" >/dev/null
rc=$?
set -e
[ "$rc" = 2 ] || fail "bad --F exit code $rc"
grep -q "F = 3" "$tmp/err2" || fail "bad --F message: $(cat "$tmp/err2")"
[ ! -e "$tmp/x.AT2" ] || fail "output written despite the error"
echo "records_cli: ok"
