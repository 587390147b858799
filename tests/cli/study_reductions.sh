#!/usr/bin/env bash
# Issue 27 item 5: [outputs] per_model = false keeps only the reductions (study/reductions.hpp).
#  1. studies/quick.toml (8 samples per pair here) both ways: the report's exact tables (Table 2, Table 3, the period
#     map, the cubic fit of the curve) are identical digit for digit; the separation advice read from the histograms
#     is within one bin (a factor 10^(1/200)) above the per-model run's exact order statistic; no /uncoupled, no
#     per-model /models in the reductions file; the report says what comes from histograms.
#  2. bit-identical reductions for 1 process, mpirun -np 2, --threads 1/2, batch = 1, and SIGINT + --resume.
#     The checkpoint is one snapshot per rank (format 5, issue 27.5): a 3-rank job killed (-9) and resumed at 2 ranks,
#     stopped again, its absorbed slices put back (a stop between rank 0's snapshot and their removal), resumed at 1
#     rank: the same file. Its size does not grow with the models (256 and 1024 samples per pair: the difference is
#     the done bits alone); a damaged snapshot, a slice sharing part of its units with the main file
#     (tests/cli/snapshot.py) and a per_model = true resume of a snapshot are refused; a failed unit keeps the units.
#  3. the memory check admits with per_model = false the study it refuses with per_model = true.
#  4. the impacts scene and [report] html with per_model = false: one clear error each, exit 2, nothing written.
# Synthetic records only (no ../shared). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/kill_job.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
cmp() { /usr/bin/python3 "$src/tests/cli/compare_results.py" "$@"; }
suite="$src/records/stochastic-pounding-suite.toml"
# quick.toml, smaller: 121 period pairs x 8 samples x 25 synthetic records = 24,200 analyses
sed -e 's/^samples_per_pair = 32/samples_per_pair = 8/' -e "s#^suite = .*#suite = \"$suite\"#" \
    "$src/studies/quick.toml" > "$tmp/full.toml"
sed 's/^\[structures\]/[outputs]\nper_model = false\n\n[structures]/' "$tmp/full.toml" > "$tmp/red.toml"
grep -q '^per_model = false' "$tmp/red.toml" || { echo "FAIL: could not write the study"; exit 1; }

"$bin" run "$tmp/full.toml" --out "$tmp/full.h5" --quiet --threads 2 > /dev/null 2>&1
"$bin" run "$tmp/red.toml" --out "$tmp/red.h5" --quiet --threads 2 > /dev/null 2>&1
"$bin" report "$tmp/full.h5" > "$tmp/full.md"
"$bin" report "$tmp/red.h5" > "$tmp/red.md"

# 1. the exact sections, line for line (the advice and code-rule sections are checked below)
section() {  # section <file> <heading start>: the lines of that "## " section
  awk -v h="## $2" 'index($0, h) == 1 { on = 1; print; next } /^## / { on = 0 } on' "$1"
}
for h in "Probability of at least one impact per record (Table 2)" "Total probability of pounding (Table 3)" \
         "Probability by period pair" "Cubic fit"; do
  section "$tmp/full.md" "$h" > "$tmp/a.txt"; section "$tmp/red.md" "$h" > "$tmp/b.txt"
  [ -s "$tmp/a.txt" ] || fail "no section '$h' in the per-model report"
  if diff -q "$tmp/a.txt" "$tmp/b.txt" > /dev/null; then
    echo "ok   '$h' identical ($(grep -c '^|' "$tmp/a.txt") table lines)"
  else
    fail "'$h' differs:"; diff "$tmp/a.txt" "$tmp/b.txt" | head -20
  fi
done
grep -q "From histograms" "$tmp/red.md" || fail "the reductions report does not say what comes from histograms"
grep -q "## Code separation rules" "$tmp/red.md" && grep -q "Not given: the study kept only its reductions" "$tmp/red.md" \
  || fail "the reductions report does not say why the code rules are left out"
/usr/bin/python3 - "$tmp/full.md" "$tmp/red.md" <<'PY' || fails=$((fails + 1))
import re, sys
def advice(path):
    text = open(path).read()
    sec = text[text.index("## Separation advice in gap ratios"):]
    rows = [l for l in sec.splitlines() if re.match(r"\| [0-9.]+% \|", l)]
    out = []
    for l in rows:
        c = l.split("|")
        lo, hi = (float(v) for v in c[3].strip(" []").split(","))
        out.append((float(c[2]), lo, hi))
    return out
a, b = advice(sys.argv[1]), advice(sys.argv[2])
step = 10 ** (1 / 200)
# x: within one bin above the exact order statistic; the interval ends: the same record draws, the models within a
# record drawn by counts of the histogram: within one bin and 5 % (the within-record draws' Monte Carlo error)
bad = [(x, y) for x, y in zip(a, b) if not (x[0] - 5e-4 <= y[0] <= x[0] * step + 5e-4)]
bad += [(x, y) for x, y in zip(a, b) for i in (1, 2) if not (x[i] * 0.95 - 5e-4 <= y[i] <= x[i] * step * 1.05 + 5e-4)]
print(("FAIL" if bad or len(a) != len(b) or not a else "ok  ") + f"   advice (x, lo, hi) per model {a}, from histograms {b} (one bin: x {step:.4f})")
sys.exit(1 if bad or len(a) != len(b) or not a else 0)
PY
/usr/bin/python3 - "$tmp/red.h5" <<'PY' || fails=$((fails + 1))
import sys, h5py
f = h5py.File(sys.argv[1], "r")
bad = [n for n in ("uncoupled", "models/T1", "models/code_gap", "gaps/metres") if n in f]
need = [n for n in ("reductions/gap_hits", "reductions/histogram", "reductions/pair_hits", "models/periods1") if n not in f]
units = [d for d in f["reductions"] if "units" not in f["reductions"][d].attrs or "description" not in f["reductions"][d].attrs]
ok = not bad and not need and not units
print(("ok  " if ok else "FAIL") + f"   reductions file: per-model datasets present {bad}, missing {need}, unlabelled {units}")
sys.exit(0 if ok else 1)
PY

# Python: pounding.Results gives the same table2/table3 from the reductions file (skipped without the module)
pydir="$(dirname "$bin")/python"
if PYTHONPATH="$pydir" /usr/bin/python3 -c "import pounding, pandas" 2>/dev/null; then
  PYTHONPATH="$pydir" /usr/bin/python3 - "$tmp/full.h5" "$tmp/red.h5" <<'PY' || fails=$((fails + 1))
import sys, pounding
a, b = pounding.Results(sys.argv[1]), pounding.Results(sys.argv[2])
ok = a.table3.equals(b.table3) and a.table2.equals(b.table2)
print(("ok  " if ok else "FAIL") + f"   Python table2/table3 from the reductions file equal the per-model file's ({len(b.table2)} records)")
sys.exit(0 if ok else 1)
PY
else
  echo "skip Python check: the pounding module is not built next to $bin"
fi

# 2. invariance: ranks, threads, batch width, stop + resume
"$bin" run "$tmp/red.toml" --out "$tmp/t1.h5" --quiet --threads 1 > /dev/null 2>&1
timeout 300 mpirun -np 2 "$bin" run "$tmp/red.toml" --out "$tmp/r2.h5" --quiet > /dev/null 2>&1
sed 's/^\[contact\]/[analysis]\nbatch = 3\n\n[contact]/' "$tmp/red.toml" > "$tmp/narrow.toml"
"$bin" run "$tmp/narrow.toml" --out "$tmp/narrow.h5" --quiet > /dev/null 2>&1
cmp "$tmp/red.h5" "$tmp/t1.h5" || fail "threads 1 vs 2 differ"
cmp "$tmp/red.h5" "$tmp/r2.h5" || fail "1 process vs mpirun -np 2 differ"
# every rank folds its own units (issue 27.4) and rank 0 sums the counts: 3 ranks, and a 3-rank job killed (-9) once
# its slices hold units, resumed at 2 ranks (rank 0 folds the slices' units at resume, the workers their new ones)
timeout 300 mpirun -np 3 --oversubscribe "$bin" run "$tmp/red.toml" --out "$tmp/r3.h5" --quiet > /dev/null 2>&1
cmp "$tmp/red.h5" "$tmp/r3.h5" || fail "1 process vs mpirun -np 3 differ"
# (128 samples per pair here, 387,200 analyses: long enough for the stops to land while units remain)
sed 's/^samples_per_pair = 8/samples_per_pair = 128/' "$tmp/red.toml" > "$tmp/mid.toml"
"$bin" run "$tmp/mid.toml" --out "$tmp/mid.h5" --quiet > /dev/null 2>&1
export POUNDING_TEST_CHECKPOINT_S=0.05  # snapshots every 50 ms (5 s by default): a kill finds units in them
kill_when_grown "$tmp/k.h5.ckpt.rank2" 20000 mpirun -np 3 --oversubscribe "$bin" run "$tmp/mid.toml" --out "$tmp/k.h5" --quiet
if [ -f "$tmp/k.h5" ]; then echo "note: the 3-rank run finished before the kill; resume not exercised"
else
  for f in "$tmp"/k.h5.ckpt*; do [ "$(head -c 8 "$f")" = PNDCKPT5 ] || fail "$f is not a snapshot (format 5)"; done
  mkdir "$tmp/cut" && cp "$tmp"/k.h5.ckpt.rank* "$tmp/cut/"
  # resumed at 2 ranks with --threads 1 and killed (-9) once rank 0 has absorbed the slices ("resuming" is said after
  # its snapshot is saved and the slices removed), then the cut's slices put back: all their units are in rank 0's
  # snapshot, so they must be skipped, not counted twice
  setsid mpirun -np 2 "$bin" run "$tmp/mid.toml" --out "$tmp/k.h5" --resume --threads 1 > /dev/null 2> "$tmp/k.err" &
  job=$!
  for _ in $(seq 1 400); do grep -q resuming "$tmp/k.err" && break; sleep 0.05; done
  pkill -9 -s "$job" 2>/dev/null || true
  for _ in $(seq 1 200); do pgrep -s "$job" > /dev/null || break; sleep 0.05; done
  wait "$job" 2>/dev/null || true
  if [ -f "$tmp/k.h5" ]; then echo "note: the 2-rank resume finished before its kill; stale slices not exercised"
  else
    cp "$tmp"/cut/k.h5.ckpt.rank2 "$tmp/"  # rank 2 was not part of the 2-rank run: its cut slice is back as it was
    timeout 300 "$bin" run "$tmp/mid.toml" --out "$tmp/k.h5" --resume --quiet > /dev/null 2> "$tmp/k2.err" \
      || fail "resume at 1 rank with a stale slice: $(cat "$tmp/k2.err")"
    echo "ok   3-rank cut: $(grep resuming "$tmp/k.err") at 2 ranks, stopped; with the stale slice back at 1 rank: $(grep resuming "$tmp/k2.err")"
  fi
  [ -f "$tmp/k.h5" ] || timeout 300 mpirun -np 2 "$bin" run "$tmp/mid.toml" --out "$tmp/k.h5" --resume --quiet > /dev/null 2>&1
  cmp "$tmp/mid.h5" "$tmp/k.h5" || fail "3-rank cut resumed (2 ranks, then 1) differs"
  ls "$tmp"/k.h5.ckpt* > /dev/null 2>&1 && fail "checkpoint files left after the results: $(ls "$tmp"/k.h5.ckpt*)"
fi
cmp "$tmp/red.h5" "$tmp/narrow.h5" --ignore=study_text,batch,output || fail "batch 3 vs the default differ"
# a unit that fails on rank 1 (its third): every rank saves what it folded before the job stops (exit 2), so the
# resume starts from more than nothing (no periodic snapshot: 1000 s apart here) and gives the same file
rc=0; POUNDING_TEST_CHECKPOINT_S=1000 POUNDING_INJECT_FAULT=compute@1 timeout 300 mpirun -np 2 "$bin" run "$tmp/red.toml" --out "$tmp/f.h5" --quiet \
  > /dev/null 2> "$tmp/f.err" || rc=$?
"$bin" run "$tmp/red.toml" --out "$tmp/f.h5" --resume --quiet > /dev/null 2> "$tmp/f2.err" || fail "resume after a failed unit: $(cat "$tmp/f2.err")"
done_at=$(sed -n 's/^resuming: \([0-9]*\) of.*/\1/p' "$tmp/f2.err")
{ [ "$rc" -eq 2 ] && [ "${done_at:-0}" -gt 0 ]; } && echo "ok   failed unit (exit 2): $(cat "$tmp/f2.err" | head -1)" \
  || fail "failed unit: exit $rc, resumed with '${done_at}' units: $(cat "$tmp/f.err")"
cmp "$tmp/red.h5" "$tmp/f.h5" || fail "a failed unit + --resume differs"
"$bin" run "$tmp/red.toml" --out "$tmp/int.h5" --threads 1 > /dev/null 2> "$tmp/int.err" &
pid=$!
for _ in $(seq 1 400); do
  [ -f "$tmp/int.h5.ckpt" ] && [ "$(stat -c %s "$tmp/int.h5.ckpt")" -gt 20000 ] && break
  sleep 0.05
done
kill -INT "$pid"
rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || fail "SIGINT exit code $rc (want 130): $(cat "$tmp/int.err")"
[ -f "$tmp/int.h5" ] && fail "results file after SIGINT"
# the same checkpoint resumed by the per-model study, and damaged: one error each, exit 2, the checkpoint kept
cp "$tmp/int.h5.ckpt" "$tmp/int.keep"
rc=0; "$bin" run "$tmp/full.toml" --out "$tmp/int.h5" --resume --quiet > /dev/null 2> "$tmp/mix.err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/mix.err")" -eq 1 ] && grep -q "reductions only" "$tmp/mix.err" \
  && command cmp -s "$tmp/int.h5.ckpt" "$tmp/int.keep"; } && echo "ok   per_model = true --resume of a snapshot refused: $(cat "$tmp/mix.err")" \
  || fail "per_model = true --resume of a snapshot: exit $rc: $(cat "$tmp/mix.err")"
printf '\x55' | dd of="$tmp/int.h5.ckpt" bs=1 seek=300 conv=notrunc status=none
rc=0; "$bin" run "$tmp/red.toml" --out "$tmp/int.h5" --resume --quiet > /dev/null 2> "$tmp/bad.err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/bad.err")" -eq 1 ] && grep -q "int.h5.ckpt is damaged" "$tmp/bad.err"; } \
  && echo "ok   damaged snapshot refused: $(cat "$tmp/bad.err")" || fail "damaged snapshot: exit $rc: $(cat "$tmp/bad.err")"
cp "$tmp/int.keep" "$tmp/int.h5.ckpt"
# a slice sharing one unit with the main file and holding one more (two runs' files mixed): refused, never summed
/usr/bin/python3 "$src/tests/cli/snapshot.py" overlap "$tmp/int.h5.ckpt" "$tmp/int.h5.ckpt.rank1" > /dev/null
rc=0; "$bin" run "$tmp/red.toml" --out "$tmp/int.h5" --resume --quiet > /dev/null 2> "$tmp/ovl.err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/ovl.err")" -eq 1 ] && grep -q "int.h5.ckpt.rank1 shares 1 of its 2 units" "$tmp/ovl.err"; } \
  && echo "ok   partly overlapping snapshot refused: $(cat "$tmp/ovl.err")" || fail "partly overlapping snapshot: exit $rc: $(cat "$tmp/ovl.err")"
rm "$tmp/int.h5.ckpt.rank1"
"$bin" run "$tmp/red.toml" --out "$tmp/int.h5" --resume --quiet --threads 2 > /dev/null 2>&1
cmp "$tmp/red.h5" "$tmp/int.h5" || fail "SIGINT + --resume differs"

# the checkpoint's size does not grow with the models: 256 and 1024 samples per pair (3,025 and 12,100 units of 256
# models), each stopped by SIGTERM (exit 143, docs/cluster.md) after a snapshot with units; the sizes differ by the done bits (one per unit) alone,
# where unit records would hold 25 bytes per analysis
size_at() {  # size_at <samples>: the stopped run's checkpoint bytes
  sed "s/^samples_per_pair = 8/samples_per_pair = $1/" "$tmp/red.toml" > "$tmp/s$1.toml"
  "$bin" run "$tmp/s$1.toml" --out "$tmp/s$1.h5" --threads 1 > /dev/null 2> "$tmp/s$1.err" &
  local pid=$!
  for _ in $(seq 1 400); do
    [ -f "$tmp/s$1.h5.ckpt" ] && [ "$(stat -c %s "$tmp/s$1.h5.ckpt")" -gt 20000 ] && break
    sleep 0.05
  done
  kill -TERM "$pid"; local rc=0; wait "$pid" || rc=$?
  [ "$rc" -eq 143 ] || echo "SIGTERM gave exit $rc (want 143): $(cat "$tmp/s$1.err")" >&2
  stat -c %s "$tmp/s$1.h5.ckpt"
}
a=$(size_at 256 2> "$tmp/size.err"); b=$(size_at 1024 2>> "$tmp/size.err")
[ -s "$tmp/size.err" ] && fail "$(cat "$tmp/size.err")"
want=$(( (12100 + 7) / 8 - (3025 + 7) / 8 ))
{ [ $((b - a)) -eq "$want" ] && [ "$b" -lt 1000000 ]; } \
  && echo "ok   checkpoint bytes at 256 and 1024 samples per pair: $a and $b (difference $((b - a)) = the done bits; unit records: 25 bytes per analysis)" \
  || fail "checkpoint bytes at 256 and 1024 samples per pair: $a and $b (want a difference of $want, below 1 MB)"
unset POUNDING_TEST_CHECKPOINT_S

# 3. the memory check (POUNDING_TEST_MEMORY_AVAILABLE stands in for MemAvailable: 2 GiB)
mem() {  # mem <per_model>: one record, one period pair, 2e7 samples
  printf 'seed = 3\nscene = "probability"\n[records]\nsuite = "builtin"\nsynthetic_only = true\nlimit = 1\n[outputs]\nper_model = %s\n[structures]\nperiods = [1.0]\nsamples_per_pair = 20000000\n' "$1" > "$tmp/mem.toml"
}
export POUNDING_TEST_MEMORY_AVAILABLE=2147483648
mem true
rc=0; "$bin" run "$tmp/mem.toml" --out "$tmp/mem.h5" --quiet > /dev/null 2> "$tmp/mem.err" || rc=$?
{ [ "$rc" -eq 2 ] && grep -q "per_model = false" "$tmp/mem.err"; } \
  && echo "ok   per_model = true refused on 2 GiB: $(cat "$tmp/mem.err")" || fail "per_model = true: exit $rc: $(cat "$tmp/mem.err")"
mem false
: > "$tmp/mem.err"  # emptied before the fork: the loop below must not read the refusal above (faults/run_fit_stop.sh)
"$bin" run "$tmp/mem.toml" --out "$tmp/mem.h5" --threads 1 > /dev/null 2> "$tmp/mem.err" &
pid=$!
for _ in $(seq 1 400); do [ -f "$tmp/mem.h5.ckpt" ] && break; grep -q ERROR "$tmp/mem.err" && break; sleep 0.05; done
kill -INT "$pid" 2>/dev/null || true
rc=0; wait "$pid" || rc=$?
{ [ "$rc" -eq 130 ] && ! grep -q ERROR "$tmp/mem.err"; } && echo "ok   per_model = false admitted on 2 GiB (stopped with SIGINT)" \
  || fail "per_model = false: exit $rc: $(cat "$tmp/mem.err")"
unset POUNDING_TEST_MEMORY_AVAILABLE

# 4. what the reductions cannot hold is refused before any work
sed 's/^scene = "probability"/scene = "impacts"/' "$tmp/red.toml" > "$tmp/imp.toml"
rc=0; "$bin" run "$tmp/imp.toml" --out "$tmp/imp.h5" --quiet > /dev/null 2> "$tmp/imp.err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/imp.err")" -eq 1 ] && grep -q "imp.toml:.*per_model" "$tmp/imp.err" && [ ! -e "$tmp/imp.h5" ]; } \
  && echo "ok   impacts scene refused: $(cat "$tmp/imp.err")" || fail "impacts scene: exit $rc: $(cat "$tmp/imp.err")"

sed 's/^\[report\]/[report]\nhtml = true/' "$tmp/red.toml" > "$tmp/html.toml"
rc=0; "$bin" run "$tmp/html.toml" --out "$tmp/html.h5" --quiet > /dev/null 2> "$tmp/html.err" || rc=$?
{ [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/html.err")" -eq 1 ] && grep -q "HTML report" "$tmp/html.err" && [ ! -e "$tmp/html.h5" ]; } \
  && echo "ok   [report] html refused: $(cat "$tmp/html.err")" || fail "[report] html: exit $rc: $(cat "$tmp/html.err")"

[ "$fails" -eq 0 ] && echo "1 passed, 0 failed" || { echo "$fails failed"; exit 1; }
