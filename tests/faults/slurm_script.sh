#!/bin/bash
# The Slurm batch script of docs/cluster.md, run as written with stand-ins for srun and scontrol (issue 27.6):
# a SIGTERM to the running pounding (what a time limit or scancel sends every task) must end the first attempt
# with 143 and a requeue, and the requeued attempt must resume from the checkpoint and finish.
# usage: slurm_script.sh <pounding binary> <source dir>
set -euo pipefail
bin=$(readlink -f "$1"); src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok: $*"; }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# the script, from the docs, with the study and output of this test
awk '/^```bash$/{on=1; next} /^```$/{on=0} on' "$src/docs/cluster.md" > "$tmp/job.sh"
grep -q '^srun ' "$tmp/job.sh" && grep -q 'scontrol requeue' "$tmp/job.sh" || { echo "FAIL: no batch script in docs/cluster.md"; exit 1; }
sed -i -e "s|^STUDY=.*|STUDY=$tmp/study.toml|" -e "s|^OUT=.*|OUT=$tmp/results/r.h5|" "$tmp/job.sh"
# quick.toml with longer units, so that the stop lands in the units
sed -e 's/^samples_per_pair = .*/samples_per_pair = 160/' -e "s|\.\./records/|$src/records/|" \
  "$src/studies/quick.toml" > "$tmp/study.toml"

mkdir "$tmp/path"
ln -s "$bin" "$tmp/path/pounding"
printf '#!/bin/sh\n[ "$1" = --kill-on-bad-exit=1 ] && shift\nexec "$@"\n' > "$tmp/path/srun"
printf '#!/bin/sh\necho "$@" >> "%s/scontrol.log"\n' "$tmp" > "$tmp/path/scontrol"
chmod +x "$tmp/path/srun" "$tmp/path/scontrol"
export PATH="$tmp/path:$PATH" SLURM_SUBMIT_DIR="$tmp" SLURM_JOB_ID=4242

# attempt 1: SIGTERM after the first finished unit is in the checkpoint
bash "$tmp/job.sh" > "$tmp/log1" 2>&1 &
job=$!
for _ in $(seq 1 1500); do
  [ -f "$tmp/results/r.h5.ckpt" ] && [ "$(stat -c %s "$tmp/results/r.h5.ckpt")" -gt 2000 ] && break; sleep 0.02
done
p=$(pgrep -P "$job" -x pounding || true)
if [ -z "$p" ]; then fail "attempt 1: pounding was not running under the script"; cat "$tmp/log1"; exit 1; fi
kill -TERM "$p"
rc=0; wait "$job" || rc=$?
if [ "$rc" -eq 0 ] && grep -q "stopped (exit 143) with a checkpoint: requeueing" "$tmp/log1" \
   && grep -q "^requeue 4242$" "$tmp/scontrol.log" && [ ! -e "$tmp/results/r.h5" ] && [ -s "$tmp/results/r.h5.ckpt" ]; then
  ok "attempt 1: SIGTERM -> exit 143, checkpoint kept, job requeued"
else
  fail "attempt 1: script exit $rc"; cat "$tmp/log1"; cat "$tmp/scontrol.log" 2> /dev/null || true
fi

# attempt 2 (the requeued job): the script adds --resume and finishes
rc=0; bash "$tmp/job.sh" > "$tmp/log2" 2>&1 || rc=$?
if [ "$rc" -eq 0 ] && grep -q "^done (exit 0): $tmp/results/r.h5" "$tmp/log2" && grep -q "resuming: [1-9][0-9]* of" "$tmp/log2" \
   && [ -s "$tmp/results/r.h5" ] && [ ! -e "$tmp/results/r.h5.ckpt" ] && [ "$(wc -l < "$tmp/scontrol.log")" -eq 1 ]; then
  ok "attempt 2: resumed ($(grep -o 'resuming: [0-9]* of [0-9]* units' "$tmp/log2")) and done, no second requeue"
else
  fail "attempt 2: script exit $rc"; cat "$tmp/log2"
fi

# an uninterrupted run gives the same results, bit for bit
"$bin" run "$tmp/study.toml" --out "$tmp/whole.h5" --quiet > /dev/null 2>&1
if /usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/whole.h5" "$tmp/results/r.h5" > /dev/null; then
  ok "the requeued job's results equal an uninterrupted run's"
else
  fail "the requeued job's results differ from an uninterrupted run's"
fi

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
