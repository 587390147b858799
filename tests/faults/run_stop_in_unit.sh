#!/usr/bin/env bash
# A stop reaches the steppers inside a unit of work, and a long unit is never silent:
#  - a shear-building study whose one unit takes far longer than the stop may wait (substeps = 10000, 16 models: about 30 s): progress lines
#    keep coming while the unit runs (a heartbeat every 10 s when stderr is not a terminal), and SIGTERM ends the
#    run with exit 143 within 2 s, the checkpoint kept (nothing of the abandoned unit in it);
#  - the same under mpirun -np 2 with SIGTERM to every rank (what a batch system's scancel does), within 3 s;
#  - a stop inside a later unit of a short study: --resume then computes the abandoned unit again, and the results
#    are those of an uninterrupted run (bit for bit).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
factor=${POUNDING_TIMEOUT_FACTOR:-1}
tmp=$(mktemp -d); trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
study() {  # study <file> <substeps> <records> <samples per period pair>
  cat > "$1" <<TOML
title = "a long unit"
seed = 11
scene = "probability"
[records]
suite = "builtin"
synthetic_only = true
limit = $3
[structures]
model = "shear"
storey_height = 3.2
periods = [1.5]
samples_per_pair = $4
[analysis]
substeps = $2
[gaps]
ratios = [0.1, 0.5]
TOML
}
# seconds since $1 (date +%s.%N), 2 decimals
since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }'; }
# kill -TERM, then the seconds until the process $1 is gone (waited for; its exit status in $rc)
stop_and_time() {
  local pid=$1 t0
  t0=$(date +%s.%N)
  kill -TERM "${@:2}" 2>/dev/null || true
  rc=0; wait "$pid" || rc=$?
  took=$(since "$t0")
}

# --- one long unit, one rank ---------------------------------------------------------------------------------
study "$tmp/long.toml" 10000 1 16
"$bin" run "$tmp/long.toml" --out "$tmp/long.h5" > /dev/null 2> "$tmp/err" &
pid=$!
sleep 12
beats=$(grep -c '^progress: units 0/' "$tmp/err" || true)
[ "$beats" -ge 1 ] && ok "a long unit reports progress while it runs ($beats line(s) in 12 s: $(grep '^progress: units 0/' "$tmp/err" | tail -1))" \
  || { fail "no progress line in the 12 s of a running unit"; cat "$tmp/err"; }
kill -0 "$pid" 2>/dev/null || fail "the long unit finished within 12 s: the test needs a longer one (raise substeps)"
stop_and_time "$pid" "$pid"
awk -v t="$took" -v f="$factor" 'BEGIN { exit !(t <= 2 * f) }' && [ "$rc" -eq 143 ] && grep -q "stopped by SIGTERM" "$tmp/err" \
  && ok "SIGTERM inside the unit: exit 143 after ${took} s" || { fail "SIGTERM inside the unit: rc $rc after ${took} s"; cat "$tmp/err"; }
[ ! -e "$tmp/long.h5" ] || fail "a results file was written by a stopped run"

# --- the same on 2 ranks, SIGTERM to every rank ------------------------------------------------------------------
if command -v mpirun > /dev/null; then
  timeout $((120 * factor)) mpirun -np 2 "$bin" run "$tmp/long.toml" --out "$tmp/mpi.h5" --quiet > /dev/null 2> "$tmp/err" &
  pid=$!
  sleep 6
  ranks=$(pgrep -f "$bin run $tmp/long.toml --out $tmp/mpi.h5" | grep -v "^$pid\$" || true)
  # shellcheck disable=SC2086
  stop_and_time "$pid" $ranks
  # mpirun's own teardown after its ranks ended adds about a second on the 2-core VM: 3 s here
  awk -v t="$took" -v f="$factor" 'BEGIN { exit !(t <= 3 * f) }' && [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] \
    && grep -q "stopped by SIGTERM" "$tmp/err" && ok "2 ranks, SIGTERM to every rank inside their units: mpirun exit $rc after ${took} s" \
    || { fail "2 ranks, SIGTERM: rc $rc after ${took} s"; cat "$tmp/err"; }
  [ ! -e "$tmp/mpi.h5" ] || fail "a results file was written by a stopped MPI run"
fi

# --- a stop inside a later unit: --resume gives the uninterrupted run's results ---------------------------------
study "$tmp/short.toml" 1000 3 4
"$bin" run "$tmp/short.toml" --out "$tmp/ref.h5" --quiet > /dev/null 2>&1
t0=$(date +%s.%N)
"$bin" run "$tmp/short.toml" --out "$tmp/ref2.h5" --quiet --force > /dev/null 2>&1
unit_s=$(awk -v t="$(since "$t0")" 'BEGIN { printf "%.2f", t / 3 }')
"$bin" run "$tmp/short.toml" --out "$tmp/cut.h5" > /dev/null 2> "$tmp/err" &
pid=$!
sleep "$(awk -v u="$unit_s" 'BEGIN { printf "%.2f", 1.5 * u }')"
stop_and_time "$pid" "$pid"
if [ "$rc" -eq 143 ]; then
  rc=0; "$bin" run "$tmp/short.toml" --out "$tmp/cut.h5" --resume --quiet > /dev/null 2> "$tmp/err" || rc=$?
  [ "$rc" -eq 0 ] && /usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$tmp/cut.h5" > /dev/null \
    && ok "stopped inside a unit (${unit_s} s a unit), resumed: the results of an uninterrupted run" \
    || { fail "resume after a stop inside a unit: rc $rc or results differ"; cat "$tmp/err"; }
else
  fail "the short study's run was not stopped by SIGTERM (rc $rc; a unit ${unit_s} s)"
fi

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
