#!/usr/bin/env bash
# Issue 10.2: an error on any rank, in any phase, ends the whole job promptly (a `timeout` turns a hang into
# a failure), with exit code 2 and ONE " ERROR:" line, for 1, 2 and 3 ranks (3 oversubscribed):
# startup (--resume with no checkpoint, --resume with another study's checkpoint, a record that fails to
# load on one rank), mid-run (a worker's or the master's unit throws) and the results write. Faults are
# injected with the test-only POUNDING_INJECT_FAULT=<phase>@<rank>. After a mid-run failure the checkpoint
# is valid: --resume finishes with results identical to an uninterrupted run.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
limit=$(( 60 * ${POUNDING_TIMEOUT_FACTOR:-1} ))
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/s.toml" <<'TOML'
title = "fault test"
seed = 7
scene = "probability"
[records]
suite = "builtin"
synthetic_only = true
limit = 4
[structures]
samples_per_pair = 8
[analysis]
batch = 8
TOML
sed 's/^seed = 7/seed = 8/' "$tmp/s.toml" > "$tmp/other.toml"
"$bin" run "$tmp/s.toml" --out "$tmp/ref.h5" --quiet > /dev/null 2>&1
fails=0
launch() {  # launch <ranks> <args...>: runs the job under timeout, sets rc and err
  local np=$1; shift
  local t0=$SECONDS
  rc=0
  if [ "$np" -eq 1 ]; then
    timeout "$limit" "$bin" "$@" > "$tmp/out" 2> "$tmp/err" || rc=$?
  else
    timeout "$limit" mpirun --oversubscribe -x POUNDING_INJECT_FAULT -np "$np" "$bin" "$@" > "$tmp/out" 2> "$tmp/err" || rc=$?
  fi
  took=$((SECONDS - t0))
}
expect_error() {  # expect_error <label> <message regex>
  local n
  n=$(grep -c '^ ERROR' "$tmp/err" || true)
  if [ "$rc" -eq 124 ]; then echo "FAIL $1: hung (killed by timeout after ${limit} s)"; fails=$((fails + 1)); return; fi
  if [ "$rc" -ne 2 ]; then echo "FAIL $1: exit code $rc (want 2)"; cat "$tmp/err"; fails=$((fails + 1)); return; fi
  if [ "$n" -ne 1 ]; then echo "FAIL $1: $n ERROR lines (want exactly 1)"; cat "$tmp/err"; fails=$((fails + 1)); return; fi
  if ! grep -qE "$2" "$tmp/err"; then echo "FAIL $1: message does not match /$2/"; cat "$tmp/err"; fails=$((fails + 1)); return; fi
  if ls "$tmp"/cut.h5 "$tmp"/cut.h5.tmp* > /dev/null 2>&1; then
    echo "FAIL $1: a results or temporary file was left"; ls "$tmp"; fails=$((fails + 1)); return; fi
  echo "ok   $1 (${took} s): $(grep '^ ERROR' "$tmp/err" | cut -c1-110)"
}

for np in 1 2 3; do
  rm -f "$tmp"/cut.h5*
  export POUNDING_INJECT_FAULT=none
  launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --resume --quiet
  expect_error "np=$np resume without checkpoint" "no checkpoint to resume from"
  [ -e "$tmp/cut.h5.ckpt" ] && { echo "FAIL np=$np: an empty checkpoint was left"; fails=$((fails + 1)); }

  if [ "$np" -gt 1 ]; then
    export POUNDING_INJECT_FAULT=load@$((np - 1))
    launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --quiet
    expect_error "np=$np input loading fails on rank $((np - 1)) only" "injected fault in phase 'load' on rank $((np - 1))"
  fi

  # mid-run: the last rank's third unit throws (a worker's, or the master's when np = 1)
  export POUNDING_INJECT_FAULT=compute@$((np - 1))
  launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --quiet
  expect_error "np=$np a unit fails mid-run on rank $((np - 1))" "injected fault in phase 'compute'"
  [ -s "$tmp/cut.h5.ckpt" ] || { echo "FAIL np=$np: no checkpoint kept after the mid-run failure"; fails=$((fails + 1)); }

  export POUNDING_INJECT_FAULT=none
  launch "$np" run "$tmp/other.toml" --out "$tmp/cut.h5" --resume --quiet
  expect_error "np=$np resume with another study's checkpoint" "different study"

  if [ "$np" -gt 1 ]; then  # the master's own unit fails while workers compute
    export POUNDING_INJECT_FAULT=compute@0
    launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --resume --quiet
    expect_error "np=$np the master's unit fails mid-run" "injected fault in phase 'compute' on rank 0"
  fi

  export POUNDING_INJECT_FAULT=write
  launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --resume --quiet
  expect_error "np=$np the results write fails" "injected fault in phase 'write'"
  [ -s "$tmp/cut.h5.ckpt" ] || { echo "FAIL np=$np: the checkpoint was lost when the results write failed"; fails=$((fails + 1)); }

  export POUNDING_INJECT_FAULT=none
  launch "$np" run "$tmp/s.toml" --out "$tmp/cut.h5" --resume --quiet
  if [ "$rc" -ne 0 ]; then echo "FAIL np=$np: --resume after the failures: exit $rc"; cat "$tmp/err"; fails=$((fails + 1));
  else
    /usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$tmp/cut.h5" > /dev/null \
      && echo "ok   np=$np --resume after the failures gives the uninterrupted run's results" \
      || { echo "FAIL np=$np: resumed results differ"; fails=$((fails + 1)); }
  fi
done
[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
