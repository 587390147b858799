#!/usr/bin/env bash
# Issue 10.4 and 10.5: an absurd ground-motion record is an error (exit 2, one " ERROR: <what>, <file:line>,
# <fix>" line, no output file), never a run to the end with a report full of nan:
#   - a record in cm/s2 read as g (PGA ~30 g), scale = 1000, a files entry's scale: PGA above 5 g, naming the
#     file and the line of the peak sample, the PGA and the likely cause (units, scale); `records show`
#     still shows the record, with the same message as a WARNING
#   - a value that overflows in m/s2 (1e308 g) and 'nan' (file:line); 1e308 in m/s2 (finite): the PGA bound
#   - DT = 1e308, DT = 1e-300 (outside [1e-4, 0.1] s), DT = NaN ("not a number", not "missing"), a two-column
#     file sampled at 0.5 s
#   - NPTS = 1 (a record shorter than 2 s), NPTS larger and smaller than the data (both numbers, NPTS line)
#   - binary garbage: the message shows a short escaped excerpt, never the raw bytes
# Records are generated here (4 s sines); nothing from ../shared. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }

# at2 <file> <units line> <npts header> <dt header> <amplitude> <spike> [values]: an AT2 file of `values`
# (default 401) samples of amp sin(2 pi t / 0.5) at dt 0.01 with sample 203 set to `spike` (line 45).
at2() {
  local f=$1 units=$2 npts=$3 dt=$4 amp=$5 spike=$6 n=${7:-401}
  {
    printf 'PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Generated, 0\n%s\n' "$units"
    printf 'NPTS= %s, DT= %s SEC\n' "$npts" "$dt"
    awk -v n="$n" -v a="$amp" -v s="$spike" 'BEGIN {
      for (i = 0; i < n; i++) {
        v = (i == 203) ? s : a * sin(2 * 3.141592653589793 * i * 0.01 / 0.5)
        printf "%15.7E", v
        if (i % 5 == 4 || i == n - 1) printf "\n"
      } }'
  } > "$f"
}
study() {  # study <toml> <files line> [extra [records] lines]
  printf 'seed = 1\n[records]\n%s\n%s\n[structures]\nperiods = [1.0]\nsamples_per_pair = 2\n' "$2" "${3:-}" > "$1"
}
# expect <label> <command...>: exit 2, one " ERROR: " line holding every pattern in ${want[@]}, no output
expect() {
  local label=$1 rc=0
  shift
  "$@" > "$tmp/out" 2> "$tmp/err" || rc=$?
  local bad=""
  [ "$rc" = 2 ] || bad+=" exit $rc (want 2);"
  grep -q '^ ERROR: ' "$tmp/err" || bad+=" no ' ERROR: ' line;"
  [ "$(wc -l < "$tmp/err")" = 1 ] || bad+=" $(wc -l < "$tmp/err") lines on stderr (want 1);"
  local p
  for p in "${want[@]}"; do grep -qF -- "$p" "$tmp/err" || bad+=" no '$p';"; done
  ! ls "$tmp"/o.h5* "$tmp"/o.csv* > /dev/null 2>&1 || bad+=" output left: $(ls "$tmp"/o.h5* "$tmp"/o.csv* 2>/dev/null);"
  if [ -n "$bad" ]; then fail "$label:$bad stderr: $(head -c 400 "$tmp/err")"; else ok "$label: $(head -c 160 "$tmp/err")"; fi
  rm -f "$tmp"/o.h5* "$tmp"/o.csv*  # one failure must not fail the next check
}
run_study() { "$bin" run "$1" --out "$tmp/o.h5" --quiet; }
sim() { "$bin" simulate --duration 2 --record "$@" --series "$tmp/o.csv"; }

# --- a good record runs, so that the refusals below are about the records -----------------------------
at2 "$tmp/good.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 401 .0100 0.3 0.5
study "$tmp/good.toml" "files = [\"$tmp/good.AT2\"]"
run_study "$tmp/good.toml" > /dev/null 2> "$tmp/err" && ok "good record: study runs" || fail "good record: $(cat "$tmp/err")"
rm -f "$tmp"/o.h5*

# --- PGA bound: cm/s2 read as g, scale ------------------------------------------------------------------
# 0.3 g written in cm/s2 (294), spike 490 cm/s2 = 0.5 g on line 45; the header does not name its units
at2 "$tmp/cms2.AT2" 'ACCELERATION TIME SERIES' 401 .0100 294.2 490.3
study "$tmp/cms2.toml" "files = [\"$tmp/cms2.AT2\"]" 'units = "g"'
want=("cms2.AT2:45" "PGA 490.3 g" "above the 5 g" "is the file in cm/s2" '[records] units = "cm/s2"' "0.5 g")
expect "study: cm/s2 record read as g" run_study "$tmp/cms2.toml"
study "$tmp/cms2ok.toml" "files = [\"$tmp/cms2.AT2\"]" 'units = "cm/s2"'
run_study "$tmp/cms2ok.toml" > /dev/null 2> "$tmp/err" && ok "units = cm/s2: study runs" || fail "units = cm/s2: $(cat "$tmp/err")"
rm -f "$tmp"/o.h5*
study "$tmp/scale.toml" "files = [\"$tmp/good.AT2\"]" 'scale = 1000'
want=("good.AT2:45" "PGA 500 g" "0.5 g in the file, times scale 1000" "[records] scale" "too large")
expect "study: scale = 1000" run_study "$tmp/scale.toml"
study "$tmp/fscale.toml" "files = [{path = \"$tmp/good.AT2\", scale = 20}]"
want=("good.AT2:45" "PGA 10 g" "files entry's scale (20)")
expect "study: files entry scale = 20" run_study "$tmp/fscale.toml"
want=("cms2.AT2:45" "PGA 490.3 g" "add --units cm/s2")
expect "simulate: cm/s2 record read as g" sim "$tmp/cms2.AT2"
sim "$tmp/cms2.AT2" --units cm/s2 > /dev/null 2> "$tmp/err" && ok "simulate --units cm/s2 runs" || fail "simulate --units cm/s2: $(cat "$tmp/err")"
rm -f "$tmp"/o.csv*
rc=0
"$bin" records show "$tmp/cms2.AT2" > "$tmp/out" 2> "$tmp/err" || rc=$?
if [ "$rc" = 0 ] && grep -q "^ WARNING: PGA 490.3 g.*cms2.AT2:45.*refuse this record" "$tmp/err" && grep -q "^cms2 " "$tmp/out"; then
  ok "records show: displays the record with a warning"
else
  fail "records show: exit $rc, stdout $(cat "$tmp/out"), stderr $(cat "$tmp/err")"
fi

# --- non-finite and overflowing values ------------------------------------------------------------------
at2 "$tmp/big.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 401 .0100 0.3 1e308
want=("big.AT2:45" "value '1.0000000E+308' g overflows to infinity in m/s2")
expect "value 1e308 g" sim "$tmp/big.AT2"
at2 "$tmp/bigms.AT2" 'ACCELERATION TIME SERIES IN M/S/S' 401 .0100 0.3 1e308
want=("bigms.AT2:45" "above the 5 g")
expect "value 1e308 m/s2 (finite): PGA bound" sim "$tmp/bigms.AT2"
at2 "$tmp/nan.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 401 .0100 0.3 0.5
sed -i '30s/^ *[^ ]*/ nan/' "$tmp/nan.AT2"
want=("nan.AT2:30" "non-finite value 'nan'")
expect "value nan" sim "$tmp/nan.AT2"

# --- time step ------------------------------------------------------------------------------------------
for dt in 1e308 1e-300; do
  at2 "$tmp/dt.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 401 "$dt" 0.3 0.5
  want=("dt.AT2:4" "DT = ${dt/e3/e+3} s is outside [0.0001, 0.1] s")
  expect "DT = $dt" sim "$tmp/dt.AT2"
  study "$tmp/dt.toml" "files = [\"$tmp/dt.AT2\"]"
  expect "study: DT = $dt" run_study "$tmp/dt.toml"
done
at2 "$tmp/dtnan.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 401 NaN 0.3 0.5
want=("dtnan.AT2:4" "DT = 'NaN' is not a number")
expect "DT = NaN" sim "$tmp/dtnan.AT2"
grep -q missing "$tmp/err" && fail "DT = NaN is reported as missing: $(cat "$tmp/err")"
awk 'BEGIN { for (i = 0; i < 20; i++) printf "%g %g\n", i * 0.5, 0.1 * sin(i) }' > "$tmp/slow.txt"
want=("slow.txt:20" "the time column's step" "0.5 s is outside [0.0001, 0.1] s")
expect "two-column record at 0.5 s" sim "$tmp/slow.txt"

# --- length and NPTS ------------------------------------------------------------------------------------
at2 "$tmp/one.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 1 .0100 0.3 0.5 1
want=("one.AT2" "the record lasts 0 s (1 samples at dt = 0.01 s), less than the 2 s")
expect "NPTS = 1: simulate" sim "$tmp/one.AT2"
study "$tmp/one.toml" "files = [\"$tmp/one.AT2\"]"
expect "NPTS = 1: study" run_study "$tmp/one.toml"
at2 "$tmp/more.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 300 .0100 0.3 0.5
want=("more.AT2:4" "NPTS = 300 on line 4 but the file holds 401 values (the first extra one on line 65)")
expect "NPTS < values" sim "$tmp/more.AT2"
at2 "$tmp/less.AT2" 'ACCELERATION TIME SERIES IN UNITS OF G' 500 .0100 0.3 0.5
want=("less.AT2:4" "NPTS = 500 but 401 values found")
expect "NPTS > values" sim "$tmp/less.AT2"

# --- binary garbage: a short escaped excerpt ------------------------------------------------------------
{ head -5 "$tmp/good.AT2"; printf '\x01\x02\xff\xfeGARBAGE\x1b[31mRED\x07\x00tail-of-a-long-binary-token-that-goes-on-and-on-and-on\n'; } > "$tmp/bin.AT2"
want=("bin.AT2:6" "'\\x01\\x02\\xFF\\xFEGARBAGE\\x1B[31mRED\\x07\\x00tail-of-a-long-bina...' is not a number")
expect "binary garbage" sim "$tmp/bin.AT2"
if LC_ALL=C grep -q '[^ -~]' "$tmp/err"; then fail "binary garbage: raw bytes echoed: $(od -c "$tmp/err" | head -5)"; fi

if [ "$fails" -gt 0 ]; then
  echo "FAIL: $fails check(s) failed"
  exit 1
fi
echo "input_records: ok"
