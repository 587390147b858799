#!/usr/bin/env bash
# `pounding simulate` (issue 13, part 4): --duration shorter than the record analyses its first part only (a
# 44 s record at --duration 12: 12 s of time series, the peaks of those 12 s, and a line saying so); longer, free
# vibration after the record; the default masses come from the heights (m = mbar rho r^2 h) and say so, and
# --m1/--m2 override them. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# a 44 s two-column record (time s, acceleration g) whose shaking grows after 12 s: the full run's peak is later
awk 'BEGIN { dt = 0.01; for (i = 0; i <= 4400; i++) { t = i * dt; a = (t < 12 ? 0.05 : 0.3) * sin(2 * 3.14159265 * t / 1.2);
             printf "%.2f %.8f\n", t, a } }' > "$tmp/rec44.txt"
sim() { "$bin" simulate --record "$tmp/rec44.txt" --elastic --gap 10 "$@"; }
sim --series "$tmp/full.csv" > "$tmp/full.out"
sim --duration 12 --series "$tmp/short.csv" > "$tmp/short.out"
sim --duration 50 --series "$tmp/long.csv" > "$tmp/long.out"
rows() { echo $(( $(wc -l < "$1") - 1 )); }
[ "$(rows "$tmp/full.csv")" -eq 4401 ] || fail "full run: $(rows "$tmp/full.csv") samples, want 4401 (44 s at 0.01 s)"
[ "$(rows "$tmp/short.csv")" -eq 1201 ] || fail "--duration 12: $(rows "$tmp/short.csv") samples, want 1201 (12 s)"
[ "$(rows "$tmp/long.csv")" -eq 5001 ] || fail "--duration 50: $(rows "$tmp/long.csv") samples, want 5001 (50 s)"
tail -1 "$tmp/short.csv" | grep -q "^12.000000," || fail "--duration 12: the series ends at $(tail -1 "$tmp/short.csv" | cut -d, -f1) s"
grep -q "^analysis_duration_s: 44$" "$tmp/full.out" || fail "full run: no analysis_duration_s: 44"
grep -q "^analysis_duration_s: 12$" "$tmp/short.out" || fail "--duration 12: no analysis_duration_s: 12"
grep -q "^analysis_note: --duration shortened the analysis to the first 12 s of the record's 44 s$" "$tmp/short.out" ||
  fail "--duration 12 does not say it shortened the analysis"
grep -q "^analysis_note: --duration runs 50 s: the record's 44 s, then free vibration$" "$tmp/long.out" ||
  fail "--duration 50 does not say it continues in free vibration"
! grep -q "^analysis_note" "$tmp/full.out" || fail "the full run prints an analysis_note"
# the short run's peak is the peak of the full run's first 12 s, and smaller than the full run's
peak() { sed -n "s/^peak_u1_m: //p" "$1"; }
awk -F, -v p12="$(peak "$tmp/short.out")" -v pall="$(peak "$tmp/full.out")" '
  NR > 1 && $1 <= 12.0000001 { u = $3 < 0 ? -$3 : $3; if (u > m) m = u }
  END {
    if (!(p12 > 0) || (m - p12) / p12 > 1e-5 || (p12 - m) / p12 > 1e-5) { printf "FAIL: peak_u1 at --duration 12 is %s, the full run reaches %g in its first 12 s\n", p12, m; exit 1 }
    if (!(pall > 2 * p12)) { printf "FAIL: the full run peak %s is not larger than the first 12 s peak %s\n", pall, p12; exit 1 }
    printf "ok:   peak_u1 over 12 s %s m (full series first 12 s: %.9g m; full run %s m)\n", p12, m, pall }' "$tmp/full.csv"
# masses: from the heights by default, stated; --m1 overrides
grep -q "^m1_kg: 7.29e+06 (from h = 30 m: m = mbar rho r^2 h, r = h / aspect, mbar 0.6, rho 1800 kg/m^3, aspect 2)$" "$tmp/full.out" ||
  fail "default m1: $(grep m1_kg "$tmp/full.out")"
grep -q "^m2_kg: 2.46038e+07 (from h = 45 m" "$tmp/full.out" || fail "default m2: $(grep m2_kg "$tmp/full.out")"
sim --duration 2 --m1 1e7 --h2 60 > "$tmp/m.out"
grep -q "^m1_kg: 1e+07 (--m1)$" "$tmp/m.out" && grep -q "^m2_kg: 5.832e+07 (from h = 60 m" "$tmp/m.out" ||
  fail "--m1 / --h2: $(grep _kg "$tmp/m.out")"
"$bin" simulate --help | grep "default from --h1: m = mbar rho r^2 h" > /dev/null || fail "--help does not state the mass model"
rc=0; sim --h1 0 > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 2 ] && grep -q "ERROR: --h1 = 0 is out of range, --h1, give a value in \[2, 1000\].*the default mass .* comes from it" "$tmp/err" ||
  fail "--h1 0: exit $rc, $(cat "$tmp/err")"
echo "ok:   series lengths 44 / 12 / 50 s, notes, default masses from the heights"
echo "1 passed, 0 failed"
