#!/usr/bin/env bash
# kill -9 of a whole `mpirun -np 2` job mid-run, then --resume: the results equal an uninterrupted run's.
# Also: no results file exists after the kill; --resume against a different study is refused.
# Runs on the synthetic twin of study-small.toml (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# 100 samples per pair: the synthetic records (dt 0.01 s) are cheaper than the real ones, and the kills below
# must land mid-run (measured 1 s for 40 samples on 1 rank, too close to the polling below)
sed -e 's/^samples_per_pair = 8/samples_per_pair = 100/' -e 's/^batch = 3 .*/batch = 4/' \
    "$src/tests/data/study-small-synthetic.toml" > "$tmp/study.toml"
"$bin" run "$tmp/study.toml" --out "$tmp/ref.h5" --quiet > /dev/null 2>&1

setsid mpirun -np 2 "$bin" run "$tmp/study.toml" --out "$tmp/cut.h5" --quiet > /dev/null 2>&1 &
job=$!
# wait until some units are checkpointed, then kill -9 every process of the job
for _ in $(seq 1 400); do
  [ -f "$tmp/cut.h5.ckpt" ] && [ "$(stat -c %s "$tmp/cut.h5.ckpt")" -gt 200000 ] && break
  sleep 0.05
done
# mpirun puts each rank in its own process group: kill the whole session (setsid), and wait until every
# process of it is gone (a surviving rank would still hold the checkpoint's lock, and would still write)
pkill -9 -s "$job" 2>/dev/null || true
for _ in $(seq 1 200); do pgrep -s "$job" > /dev/null || break; sleep 0.05; done
wait "$job" 2>/dev/null || true
[ -f "$tmp/cut.h5" ] && { echo "FAIL: a results file exists after kill -9"; exit 1; }
[ -f "$tmp/cut.h5.ckpt" ] || { echo "FAIL: no checkpoint after kill -9"; exit 1; }
echo "checkpoint after kill -9: $(stat -c %s "$tmp/cut.h5.ckpt") bytes"

# resuming with another study is refused with the reason, and leaves the checkpoint alone
sed 's/^seed = 11/seed = 12/' "$tmp/study.toml" > "$tmp/other.toml"
if "$bin" run "$tmp/other.toml" --out "$tmp/cut.h5" --resume --quiet > "$tmp/other.out" 2>&1; then
  echo "FAIL: resume with a different study was accepted"; exit 1
fi
grep -q "different study" "$tmp/other.out" || { echo "FAIL: no reason given"; cat "$tmp/other.out"; exit 1; }

mpirun -np 2 "$bin" run "$tmp/study.toml" --out "$tmp/cut.h5" --resume --quiet > /dev/null 2> "$tmp/resume.err"
grep resuming "$tmp/resume.err"
[ -f "$tmp/cut.h5.ckpt" ] && { echo "FAIL: checkpoint left after completion"; exit 1; }
/usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$tmp/cut.h5"

# Ctrl-C (SIGINT) of a single-rank run: exit 130, the checkpoint stays valid, --resume completes it
"$bin" run "$tmp/study.toml" --out "$tmp/int.h5" --quiet > /dev/null 2> "$tmp/int.err" &
pid=$!
for _ in $(seq 1 400); do
  [ -f "$tmp/int.h5.ckpt" ] && [ "$(stat -c %s "$tmp/int.h5.ckpt")" -gt 100000 ] && break
  sleep 0.05
done
kill -INT "$pid"
rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || { echo "FAIL: SIGINT exit code $rc (want 130)"; cat "$tmp/int.err"; exit 1; }
grep -q "interrupted" "$tmp/int.err"
[ -f "$tmp/int.h5" ] && { echo "FAIL: results file after SIGINT"; exit 1; }
"$bin" run "$tmp/study.toml" --out "$tmp/int.h5" --resume --quiet > /dev/null 2>&1
/usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$tmp/int.h5"
echo "1 passed, 0 failed"
