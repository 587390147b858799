#!/usr/bin/env bash
# Issue 24.3: the phase after the units -- a fragility study's fit, bootstrap and jackknife -- shows progress and
# honours a stop. With [report] bootstrap = 100000 the fit phase takes many seconds after a short run phase:
#  - it prints "progress: fit: ..." lines (not a silence of minutes);
#  - SIGTERM (and SIGINT) in the fit phase ends the run within 5 s (measured 0.05 s; the loops stop within one replicate; the rest
#    is the process's own exit on a shared 2-core machine; 15 s for mpirun's teardown, measured 1.2 s) with exit 130, "interrupted during the analysis",
#    no results file and no temporary, and the checkpoint holding every unit;
#  - --resume then loads every unit ("resuming: N of N units already done") and goes straight to the fit;
#  - under mpirun -np 2, SIGUSR1 to mpirun (forwarded to every rank) gives 130; SIGTERM to mpirun stops the ranks the
#    same way but Open MPI's mpirun then exits 1 (its own abort path); skipped without mpirun, a failure under CI=true.
#  - the results' wall_time_s covers the fit: after a --resume that computes no unit it is still the fit's seconds.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d); trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
study() {  # study <file> <bootstrap>
  cat > "$1" <<TOML
title = "fit stop"
seed = 11
scene = "probability"
[records]
suite = "builtin"
synthetic_only = true
limit = 8
[structures]
samples_per_pair = 40
zeta = 0.05
alpha = 0.05
[structures.building1]
period = {lognormal = {median = 0.9, cov = 0.15}}
height = 28.0
mass = 3.1e6
yield_coefficient = {lognormal = {median = 0.15, cov = 0.2}}
[structures.building2]
period = {lognormal = {median = 1.3, cov = 0.15}}
height = 42.0
mass = 4.7e6
yield_coefficient = {lognormal = {median = 0.10, cov = 0.2}}
[gaps]
ratios = [0.25, 0.5, 1.0, 2.0]
[report]
bootstrap = $2
[intensity]
measure = "Sa"
period = "pair"
levels = [0.05, 0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.2]
[hazard]
curve = "$src/studies/example-hazard.csv"
TOML
}
study "$tmp/long.toml" 100000


# waits until the fit phase reports progress in $1 (at most 60 s); sets t_fit
wait_fit() {  # wait_fit <stderr file> <pid>
  for _ in $(seq 1 600); do grep -q "^progress: fit: " "$1" && return 0; kill -0 "$2" 2> /dev/null || return 1; sleep 0.1; done
  return 1
}
stop_in_fit() {  # stop_in_fit <label> <signal> <seconds> <out> <args...>: runs pounding, signals it in the fit phase
  local label=$1 sig=$2 limit=$3 out=$4; shift 4
  local want=130; [ "$sig" = TERM ] && want=143  # SIGTERM (a batch system's time limit) has its own code
  rm -f "$tmp/$out" "$tmp/$out.ckpt"
  # emptied here, not only by the child's redirection: the child opens it after the fork, and until then wait_fit
  # would read the previous run's "progress: fit:" and signal a process that has not yet installed its handlers
  # (a background job of a script starts with SIGINT ignored: the run then finished with exit 0, 2 of 4 under load)
  : > "$tmp/err"
  "$@" > "$tmp/stdout" 2> "$tmp/err" &
  local pid=$!
  if ! wait_fit "$tmp/err" "$pid"; then fail "$label: no 'progress: fit:' line within 60 s"; cat "$tmp/err"; kill -9 "$pid" 2> /dev/null; return 0; fi
  sleep "${POUNDING_STOP_DELAY:-0}"
  local t0; t0=$(date +%s.%N)
  kill "-$sig" "$pid"; rc=0; wait "$pid" || rc=$?
  local took; took=$(echo "$(date +%s.%N) - $t0" | bc)
  if [ "$rc" -eq "$want" ] && [ "$(echo "$took < $limit" | bc)" -eq 1 ] && [ ! -e "$tmp/$out" ] && [ -s "$tmp/$out.ckpt" ] \
     && { [ "$sig" != TERM ] || grep -q "stopped by SIGTERM .*: exit 143; .* --resume" "$tmp/err"; } \
     && grep -qE "interrupted during the analysis \(fit: .*\): all [0-9]+ units are checkpointed in $tmp/$out.ckpt; --resume redoes only the analysis" "$tmp/err"; then
    ok "$label: exit $want ${took} s after SIG$sig in the fit phase, checkpoint kept, no results file"
  else
    fail "$label: exit $rc ${took} s after SIG$sig (want $want within $limit s, no $out, $out.ckpt kept)"; cat "$tmp/err"
  fi
  ls "$tmp"/*.tmp[0-9]* > /dev/null 2>&1 && fail "$label: a temporary was left"
  return 0
}

stop_in_fit "one process" TERM 5 a.h5 "$bin" run "$tmp/long.toml" --out "$tmp/a.h5"
sed -n "/^progress: fit: /p" "$tmp/err" | sed -n 1,2p  # no `| head` under pipefail: SIGPIPE would stop the script silently
# --resume: every unit is loaded, the fit starts again at once (and is stopped again, with SIGINT this time)
stop_in_fit "--resume, SIGINT" INT 5 b.h5 bash -c "cp '$tmp/a.h5.ckpt' '$tmp/b.h5.ckpt' && exec '$bin' run '$tmp/long.toml' --out '$tmp/b.h5' --resume"
grep -qE "resuming: ([0-9]+) of \1 units already done" "$tmp/err" && ok "--resume loaded every unit and went to the fit" \
  || { fail "--resume did not load every unit"; cat "$tmp/err"; }

if command -v mpirun > /dev/null; then
  # mpirun forwards SIGUSR1 to every rank: 130 from the whole job
  # (Open MPI 4.1.4's mpirun can die of a SIGUSR1 that comes in its first second or so, before it forwards: exit 138
  # in 1 of 4 runs under load; docs/cluster.md. So the signal goes 1.5 s into the fit, which lasts about 9 s.)
  POUNDING_STOP_DELAY=1.5 stop_in_fit "mpirun -np 2, SIGUSR1 to mpirun" USR1 15 c.h5 mpirun --oversubscribe -np 2 "$bin" run "$tmp/long.toml" --out "$tmp/c.h5"
  # SIGTERM to mpirun itself: the ranks stop the same way (checkpoint kept, no results), but Open MPI's mpirun exits
  # 1 when it is signalled, whatever its ranks return (README, "Failure behaviour")
  rm -f "$tmp/e.h5" "$tmp/e.h5.ckpt"
  : > "$tmp/err"  # see stop_in_fit
  timeout 120 mpirun --oversubscribe -np 2 "$bin" run "$tmp/long.toml" --out "$tmp/e.h5" > /dev/null 2> "$tmp/err" &
  pid=$!
  if wait_fit "$tmp/err" "$pid"; then
    kill -TERM "$pid"; rc=0; wait "$pid" || rc=$?
    # the ranks' last line ("interrupted during the analysis") can be lost in mpirun's own teardown (seen once in a
    # fresh clone's CI run), so only what stays on disk is checked here: no results, the checkpoint kept
    if { [ "$rc" -eq 1 ] || [ "$rc" -eq 143 ]; } && [ ! -e "$tmp/e.h5" ] && [ -s "$tmp/e.h5.ckpt" ]; then
      ok "SIGTERM to mpirun in the fit: the ranks stopped, checkpoint kept (mpirun's own exit code $rc)"
    else fail "SIGTERM to mpirun: exit $rc"; cat "$tmp/err"; fi
  else fail "mpirun: no fit progress"; cat "$tmp/err"; fi
  # SIGTERM to every rank but not to mpirun, as Slurm's srun / a time limit delivers it to each task: every rank
  # exits 143 (issue 27.6), and so does mpirun, which passes its ranks' code on
  rm -f "$tmp/f.h5" "$tmp/f.h5.ckpt"
  : > "$tmp/err"  # see stop_in_fit
  timeout 120 mpirun --oversubscribe -np 2 "$bin" run "$tmp/long.toml" --out "$tmp/f.h5" > /dev/null 2> "$tmp/err" &
  pid=$!
  if wait_fit "$tmp/err" "$pid"; then
    mp=$(pgrep -P "$pid" -x mpirun || true)
    ranks=$( [ -n "$mp" ] && pgrep -P "$mp" -d ' ' || true)
    if [ -n "$ranks" ]; then
      kill -TERM $ranks; rc=0; wait "$pid" || rc=$?
      if [ "$rc" -eq 143 ] && [ ! -e "$tmp/f.h5" ] && [ -s "$tmp/f.h5.ckpt" ] && grep -q "stopped by SIGTERM" "$tmp/err"; then
        ok "SIGTERM to each rank (a batch system's time limit): mpirun exits 143, checkpoint kept, no results"
      else fail "SIGTERM to each rank: exit $rc (want 143)"; cat "$tmp/err"; fi
    else fail "SIGTERM to each rank: no rank processes found under mpirun"; kill -9 "$pid" 2> /dev/null; fi
  else fail "mpirun (ranks): no fit progress"; cat "$tmp/err"; fi
elif [ "${CI:-}" = true ]; then
  fail "mpirun is missing (CI=true)"
else
  echo "note: no mpirun: the MPI case is not run"
fi

# wall time: a resume that computes no unit still reports the seconds of its fit (it read 9e-05 s before)
study "$tmp/short.toml" 200
# every unit computed and checkpointed, then a (test-only) fault before the results: exit 2, checkpoint complete
POUNDING_INJECT_FAULT=write "$bin" run "$tmp/short.toml" --out "$tmp/d.h5" --quiet > /dev/null 2>&1 || true
t0=$(date +%s.%N)
"$bin" run "$tmp/short.toml" --out "$tmp/d.h5" --resume --quiet > /dev/null 2> "$tmp/err" || { fail "resume: $(cat "$tmp/err")"; }
took=$(echo "$(date +%s.%N) - $t0" | bc)
wall=$(/usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1])['/'].attrs['wall_time_s'])" "$tmp/d.h5" 2>/dev/null || echo none)
if [ "$wall" = none ]; then echo "note: no h5py; wall_time_s read from the log only"; wall=$(sed -n 's/^results: .*(wall time \([0-9.]*\) s.*/\1/p' "$tmp/err"); fi
if [ -n "$wall" ] && [ "$(echo "$wall > 0.25 * $took && $wall <= $took" | bc)" -eq 1 ]; then
  ok "wall_time_s after a resume that ran no unit: $wall s of the process's $took s ($(grep '^results:' "$tmp/err"))"
else
  fail "wall_time_s $wall s does not cover the fit (process $took s)"; cat "$tmp/err"
fi

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
