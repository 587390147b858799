#!/usr/bin/env bash
# Issue 27 item 4: the master only schedules. Under mpirun every worker rank appends the units it computed to its own
# checkpoint slice <out>.ckpt.rank<r> and sends rank 0 only the unit's id; rank 0 assembles the results by unit id
# from the slices. Checked here:
#  - results bit-identical at 1 and 5 ranks (oversubscribed; 2 and 3: cli.study_ranks);
#  - kill -9 of a 3-rank job leaves slices holding units; a torn record at a slice's end is dropped (said) on resume,
#    and --resume at 2 ranks gives the uninterrupted results; a 2-rank cut resumed at 5 ranks too;
#  - a fresh run refuses a slice holding progress (one ERROR naming it, exit 2), --force discards it;
#  - no slice is left after a completed run; the master receives 8 bytes per unit (POUNDING_MASTER_SERVICE line).
# Runs on the synthetic twin of study-small.toml (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmp() { /usr/bin/python3 "$src/tests/cli/compare_results.py" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
sed -e 's/^samples_per_pair = 8/samples_per_pair = 100/' -e 's/^batch = 3 .*/batch = 4/' \
    "$src/tests/data/study-small-synthetic.toml" > "$tmp/study.toml"
"$bin" run "$tmp/study.toml" --out "$tmp/ref.h5" --quiet > /dev/null 2>&1

for np in 5; do  # 1, 2 and 3 ranks: cli.study_ranks
  timeout 300 mpirun -np $np "$bin" run "$tmp/study.toml" --out "$tmp/n$np.h5" --quiet > /dev/null 2> "$tmp/n$np.err" ||
    { cat "$tmp/n$np.err"; fail "mpirun -np $np"; }
  cmp "$tmp/ref.h5" "$tmp/n$np.h5"
  ls "$tmp" | grep -q 'n'$np'\.h5\.ckpt' && fail "np $np: checkpoint or slices left: $(ls "$tmp")"
  echo "ok: $np ranks equal 1 rank, no checkpoint or slice left"
done

# kill -9 of a whole job once its slices hold units (every process of the session, as cli.study_resume does)
cut() {  # cut <ranks> <out>
  setsid mpirun -np "$1" "$bin" run "$tmp/study.toml" --out "$2" --quiet > /dev/null 2>&1 &
  local job=$!
  for _ in $(seq 1 600); do
    [ -f "$2.ckpt.rank1" ] && [ "$(stat -c %s "$2.ckpt.rank1")" -gt 150000 ] && break
    sleep 0.05
  done
  pkill -9 -s "$job" 2>/dev/null || true
  for _ in $(seq 1 200); do pgrep -s "$job" > /dev/null || break; sleep 0.05; done
  wait "$job" 2>/dev/null || true
  [ -f "$2" ] && fail "a results file exists after kill -9"
  [ -f "$2.ckpt" ] && [ -f "$2.ckpt.rank1" ] || fail "no checkpoint and slice after kill -9: $(ls "$tmp")"
}
cut 3 "$tmp/c3.h5"
echo "ok: kill -9 at 3 ranks: main $(stat -c %s "$tmp/c3.h5.ckpt") bytes, slices $(stat -c %s "$tmp"/c3.h5.ckpt.rank* | tr '\n' ' ')"
# a fresh run refuses the slices' progress with one error naming a slice; the checkpoint is left alone
rc=0; "$bin" run "$tmp/study.toml" --out "$tmp/c3.h5" --quiet > /dev/null 2> "$tmp/fresh.err" || rc=$?
[ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/fresh.err")" -eq 1 ] && grep -q -- "--resume" "$tmp/fresh.err" ||
  { cat "$tmp/fresh.err"; fail "a fresh run over slices with progress: exit $rc"; }
[ -f "$tmp/c3.h5.ckpt.rank1" ] || fail "the refused run removed a slice"
# only slices hold progress (the main file reset to its header): the refusal names the slice
mkdir "$tmp/keep"; cp -p "$tmp"/c3.h5.ckpt* "$tmp/keep/"
/usr/bin/python3 - "$tmp/c3.h5.ckpt" <<'PY'
import struct, sys
p = sys.argv[1]
b = open(p, "rb").read()
blen = struct.unpack_from("<Q", b, 32)[0]
open(p, "wb").write(b[:40 + blen])  # the header alone: rank 0's units gone, the slices' kept
PY
rc=0; "$bin" run "$tmp/study.toml" --out "$tmp/c3.h5" --quiet > /dev/null 2> "$tmp/fresh2.err" || rc=$?
[ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/fresh2.err")" -eq 1 ] && grep -q "c3.h5.ckpt.rank[12] holds [0-9,]* of [0-9,]* units" "$tmp/fresh2.err" ||
  { cat "$tmp/fresh2.err"; fail "a fresh run over a slice with progress (main file empty): exit $rc"; }
echo "ok: fresh run refused: $(grep ERROR "$tmp/fresh2.err")"
cp -p "$tmp"/keep/c3.h5.ckpt* "$tmp/"
# a torn record at the end of slice 2 (a rank killed while writing): dropped and said on resume at 2 ranks
printf 'torn record bytes' >> "$tmp/c3.h5.ckpt.rank2"
timeout 300 mpirun -np 2 "$bin" run "$tmp/study.toml" --out "$tmp/c3.h5" --resume --quiet > /dev/null 2> "$tmp/r3.err" ||
  { cat "$tmp/r3.err"; fail "resume of the 3-rank cut at 2 ranks"; }
grep -q "resuming: [0-9]* of [0-9]* units already done" "$tmp/r3.err" || { cat "$tmp/r3.err"; fail "no resuming line"; }
grep -q "checkpoint .*c3.h5.ckpt.rank2: .*dropped" "$tmp/r3.err" || { cat "$tmp/r3.err"; fail "the torn slice tail was not said"; }
cmp "$tmp/ref.h5" "$tmp/c3.h5"
ls "$tmp" | grep -q 'c3\.h5\.ckpt' && fail "checkpoint or slices left after the resumed run: $(ls "$tmp")"
echo "ok: 3-rank cut resumed at 2 ranks equals 1 rank ($(grep resuming "$tmp/r3.err")); torn slice tail dropped"

cut 2 "$tmp/c2.h5"
timeout 300 mpirun -np 5 "$bin" run "$tmp/study.toml" --out "$tmp/c2.h5" --resume --quiet > /dev/null 2> "$tmp/r2.err" ||
  { cat "$tmp/r2.err"; fail "resume of the 2-rank cut at 5 ranks"; }
cmp "$tmp/ref.h5" "$tmp/c2.h5"
echo "ok: 2-rank cut resumed at 5 ranks equals 1 rank ($(grep resuming "$tmp/r2.err"))"
# and on one rank without mpirun (the slices are read by the single process)
cut 3 "$tmp/c1.h5"
"$bin" run "$tmp/study.toml" --out "$tmp/c1.h5" --resume --quiet > /dev/null 2> "$tmp/r1.err" || { cat "$tmp/r1.err"; fail "resume at 1 rank"; }
cmp "$tmp/ref.h5" "$tmp/c1.h5"
ls "$tmp" | grep -q 'c1\.h5\.ckpt' && fail "slices left after a one-rank resume: $(ls "$tmp")"
echo "ok: 3-rank cut resumed by one process equals 1 rank"

# the master receives the unit id alone
sed "s|\.\./records/|$src/records/|" "$src/studies/quick.toml" > "$tmp/q.toml"
POUNDING_MASTER_SERVICE=1 timeout 120 mpirun -np 2 "$bin" run "$tmp/q.toml" --out "$tmp/m.h5" --quiet > /dev/null 2> "$tmp/m.err"
grep -qE "; 8 bytes per unit to the master \([0-9]+ of 3025 units stored on rank 0\); the master's time per worker unit [0-9.]+ us" "$tmp/m.err" ||
  { cat "$tmp/m.err"; fail "master service line"; }
ls "$tmp" | grep -q 'm\.h5' && fail "files left by the master-service run: $(ls "$tmp")"
echo "ok: $(grep -oE "8 bytes per unit to the master.*per worker unit [0-9.]+ us" "$tmp/m.err")"
echo "all passed"
