# Sourced by the `pounding simulate` shell tests with SciPy references (tests/cli/simulate_storeys.sh,
# simulate_isolation.sh) after they set $bin (the pounding binary) and $src (the source dir). It sources
# needs_real_records.sh (skip_or_fail), then:
#   $py                       the Python with numpy and scipy ($POUNDING_PYTHON or /usr/bin/python3), or skips
#                             (exit 77; a failure under CI=true)
#   $tmp                      a temporary directory removed at exit
#   fail "<what>"             prints FAIL: <what> and exits 1
#   two_tone_record <f1 Hz>   writes $tmp/rec.txt: a 12 s two-column record (time s, acceleration g) at dt 0.01,
#                             0.15 g at f1 plus 0.10 g at 3.1 Hz (phase 0.4)
#   sim <options>             pounding simulate --record $tmp/rec.txt <options>
#   bad <text> <options>      sim <options> must exit 2 with nothing on stdout and exactly one ERROR line on stderr
#                             that matches "ERROR: .*<text>"
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import numpy, scipy' 2>/dev/null ||
  skip_or_fail "needs $py with numpy and scipy (Debian: python3-numpy python3-scipy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
two_tone_record() {
  awk -v f1="$1" 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
                   a = 0.15 * sin(2 * 3.14159265 * f1 * t) + 0.10 * sin(2 * 3.14159265 * 3.1 * t + 0.4);
                   printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
}
sim() { "$bin" simulate --record "$tmp/rec.txt" "$@"; }
bad() {
  local want=$1; shift
  set +e; sim "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"; local rc=$?; set -e
  [ $rc -eq 2 ] || fail "$*: exit $rc, want 2"
  [ ! -s "$tmp/bad.out" ] || fail "$*: wrote to stdout: $(head -3 "$tmp/bad.out")"
  grep -q "ERROR: .*$want" "$tmp/bad.err" || fail "$*: the error does not name $want: $(cat "$tmp/bad.err")"
  [ "$(grep -c ERROR "$tmp/bad.err")" -eq 1 ] || fail "$*: more than one ERROR line"
  [ "$(wc -l < "$tmp/bad.err")" -eq 1 ] || fail "$*: more than one line on stderr: $(cat "$tmp/bad.err")"
}
