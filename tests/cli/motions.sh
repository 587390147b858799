#!/usr/bin/env bash
# `pounding motions` (issue 26 §2): spatially varying, spectrum-compatible support motions, checked from the
# written files by tools/reference_spatial.py (numpy/scipy, none of our code):
#  - 100 realisations x 2 supports, 100 m, 500 m/s, Sobczyk high loss (beta 0.002), no matching: the summed
#    cross-correlation peaks at the wave-passage delay 0.2 s = 20 steps (+-1 step) and the coherency estimated
#    (Welch, strong phase, second support shifted by the delay, +-0.5 Hz) matches the model at 1-5 Hz within 4
#    standard errors; the same files against the low-loss model (beta 0.0005) FAIL (the check can fail);
#  - 10 realisations x 3 supports, NZS 1170.5 class C, matched: the mean 5 % PSA of the 30 records within 10 % of
#    the target at 20 periods 0.1-3 s (an independent exact-discretisation oscillator), lag 1-3 = 0.4 s;
#  - same seed -> the same bytes; --first 3 --realisations 1 -> realisation 3's files byte for byte;
#  - the AT2 files read back by `pounding records show`; MANIFEST.tsv columns;
#  - bad input: one " ERROR:" line naming the option, exit 2, no folder written; SIGINT: exit 130, nothing written.
# Needs /usr/bin/python3 with numpy and scipy for the reference checks: skipped (exit 77) without them, a failure
# under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# ---- bad input first (no python needed) ----
bad() {  # <option named in the error> <args...>
  local opt=$1; shift
  set +e
  "$bin" motions "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"
  local rc=$?
  set -e
  [ "$rc" = 2 ] || fail "motions $* exited $rc, want 2: $(cat "$tmp/bad.err")"
  [ "$(grep -c '^ ERROR: ' "$tmp/bad.err")" = 1 ] || fail "motions $*: not one ERROR line: $(cat "$tmp/bad.err")"
  grep -q -- "$opt" "$tmp/bad.err" || fail "motions $*: the error does not name $opt: $(cat "$tmp/bad.err")"
  [ ! -s "$tmp/bad.out" ] || fail "motions $*: wrote to stdout"
  [ ! -e "$tmp/never" ] || fail "motions $*: wrote the folder"
  ls "$tmp" | grep -q 'never.tmp' && fail "motions $*: left a temporary folder"
  echo "refused: $(cat "$tmp/bad.err")"
}
o=(--out "$tmp/never")
bad --supports --loss high --soil D "${o[@]}" --supports 1
bad --supports --loss high --soil D "${o[@]}" --supports 40
bad --spacing --loss high --soil D "${o[@]}" --spacing 0
bad --velocity --loss high --soil D "${o[@]}" --velocity 0
bad --loss --coherency harichandran-vanmarcke --soil D "${o[@]}" --loss high
bad --loss --soil D "${o[@]}"
bad --loss --soil D "${o[@]}" --loss extreme
bad --beta --soil D "${o[@]}" --loss high --beta 0.001
bad --coherency --loss high --soil D "${o[@]}" --coherency smooth
bad --soil --loss high "${o[@]}"
bad --soil --loss high --soil F "${o[@]}"
bad --soil --loss high --soil D,D,C "${o[@]}"
bad --z --loss high --soil D "${o[@]}" --z 0.9
bad --f-max --loss high --soil D "${o[@]}" --f-max 60
bad --dt --loss high --soil D "${o[@]}" --dt 0.2
bad --positions --loss high --soil D "${o[@]}" --positions 0,100,50
bad --match-range --loss high --soil D "${o[@]}" --match-range 4,0.05
bad --realisations --loss high --soil D "${o[@]}" --realisations 0
bad --spectrum --loss high --soil D "${o[@]}" --spectrum ec8
mkdir "$tmp/full"; touch "$tmp/full/x"
bad --out --loss high --soil D --out "$tmp/full"
touch "$tmp/afile"
bad --out --loss high --soil D --out "$tmp/afile"

# ---- reproducibility, files ----
"$bin" motions --supports 3 --loss medium --soil C --realisations 4 --duration 12 --strong 5 --seed 7 --quiet \
  --out "$tmp/s1" > /dev/null
"$bin" motions --supports 3 --loss medium --soil C --realisations 4 --duration 12 --strong 5 --seed 7 --quiet \
  --out "$tmp/s2" > /dev/null
"$bin" motions --supports 3 --loss medium --soil C --realisations 1 --first 3 --duration 12 --strong 5 --seed 7 \
  --quiet --out "$tmp/s3" > /dev/null
"$bin" motions --supports 3 --loss medium --soil C --realisations 1 --first 3 --duration 12 --strong 5 --seed 8 \
  --quiet --out "$tmp/s4" > /dev/null
[ "$(ls "$tmp/s1" | grep -c '\.AT2$')" = 12 ] || fail "want 12 AT2 files: $(ls "$tmp/s1")"
for f in "$tmp"/s1/*.AT2; do cmp -s "$f" "$tmp/s2/$(basename "$f")" || fail "same seed, different $(basename "$f")"; done
for j in 01 02 03; do
  cmp -s "$tmp/s1/r003_s$j.AT2" "$tmp/s3/r003_s$j.AT2" || fail "--first 3 differs from realisation 3 (support $j)"
  cmp -s "$tmp/s1/r003_s$j.AT2" "$tmp/s4/r003_s$j.AT2" && fail "seed 8 gave seed 7's realisation 3"
done
head -1 "$tmp/s1/MANIFEST.tsv" | grep -q "^file	event	station	component	realisation	support	position_m" ||
  fail "MANIFEST.tsv header: $(head -1 "$tmp/s1/MANIFEST.tsv")"
"$bin" records show "$tmp/s1/r002_s03.AT2" > "$tmp/show.txt" || fail "records show cannot read the AT2 file"
grep -qi 'npts\|points\|samples' "$tmp/show.txt" || fail "records show: $(cat "$tmp/show.txt")"
grep -q 'Sobczyk' "$tmp/s1/README.md" || fail "README.md does not name the coherency model"

# ---- SIGINT: exit 130, nothing written ----
set +e
"$bin" motions --supports 8 --loss high --soil D --realisations 5000 --duration 60 --quiet --out "$tmp/stopped" 2> "$tmp/stop.err" &
pid=$!
sleep 1.5
kill -INT "$pid"
wait "$pid"
rc=$?
set -e
[ "$rc" = 130 ] || fail "SIGINT: exit $rc, want 130: $(cat "$tmp/stop.err")"
[ ! -e "$tmp/stopped" ] || fail "SIGINT: the folder was written"
ls "$tmp" | grep -q 'stopped.tmp' && fail "SIGINT: a temporary folder was left"

# ---- against the independent reference ----
"$py" -c 'import numpy, scipy' 2>/dev/null ||
  skip_or_fail "needs $py with numpy and scipy (Debian: python3-numpy python3-scipy; tools/setup.sh installs them)"
"$py" "$src/tools/reference_spatial.py" selftest
"$bin" motions --supports 2 --spacing 100 --velocity 500 --coherency sobczyk --loss high --soil D --iterations 0 \
  --realisations 100 --seed 3 --quiet --out "$tmp/coh" > /dev/null
"$py" "$src/tools/reference_spatial.py" check "$tmp/coh" --model sobczyk --beta 0.002 ||
  fail "estimated coherency or lag differs from the model (above)"
if "$py" "$src/tools/reference_spatial.py" check "$tmp/coh" --model sobczyk --beta 0.0005 > "$tmp/wrong.txt"; then
  cat "$tmp/wrong.txt"; fail "the high-loss motions passed as low-loss ones: the check cannot tell them apart"
fi
"$bin" motions --supports 3 --loss medium --spectrum nzs1170.5 --soil C --realisations 10 --seed 4 --quiet \
  --out "$tmp/spec" > /dev/null
"$py" "$src/tools/reference_spatial.py" check "$tmp/spec" --pair 1,3 --spectrum nzs1170.5 --soil C --band 0.1,3 \
  --spectrum-tol 0.10 || fail "mean spectrum or lag 1-3 (above)"
echo "motions: ok"
