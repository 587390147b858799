#!/usr/bin/env bash
# Threads in a study run (issue 28): `pounding run --threads N` and [analysis] threads give bit-identical results
# for 1, 2 and 3 threads (studies/quick.toml: SDOF pairs; studies/quick-storeys.toml: shear buildings, format 3),
# for 2 ranks x 2 threads, and for a run stopped with SIGINT on 2 threads then resumed on 3; a bad thread count is
# one error naming the key or option, before any work. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmp() { /usr/bin/python3 "$src/tests/cli/compare_results.py" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }

# quick.toml (3,025 units of 32 models): --threads 1, 2, 3 and the study key threads = 2
for t in 1 2 3; do
  "$bin" run "$src/studies/quick.toml" --out "$tmp/q$t.h5" --quiet --threads "$t" > /dev/null 2> "$tmp/q$t.err"
  want="1 rank x $t thread"; [ "$t" -gt 1 ] && want="${want}s"
  grep -q "$want)" "$tmp/q$t.err" || { cat "$tmp/q$t.err"; fail "quick.toml --threads $t: no '$want'"; }
done
cmp "$tmp/q1.h5" "$tmp/q2.h5"
cmp "$tmp/q1.h5" "$tmp/q3.h5"
/usr/bin/python3 - "$tmp/q3.h5" <<'PY'
import sys, h5py
t = h5py.File(sys.argv[1], "r")["timing"].attrs["threads"]
assert t == 3, f"/timing threads = {t}, want 3"
PY
# the copies in $tmp take the records suite by its absolute path (a study's relative paths are its directory's)
sed -e "s|^suite = \"\.\./records/|suite = \"$src/records/|" -e 's/^\[report\]/[analysis]\nthreads = 2\n\n[report]/' \
    "$src/studies/quick.toml" > "$tmp/quick-key.toml"
grep -q '^threads = 2' "$tmp/quick-key.toml" || fail "could not add [analysis] threads to quick.toml"
  "$bin" run "$tmp/quick-key.toml" --out "$tmp/qk.h5" --quiet > /dev/null 2> "$tmp/qk.err" ||
  { cat "$tmp/qk.err"; fail "[analysis] threads = 2 was refused"; }
grep -q "1 rank x 2 threads)" "$tmp/qk.err" || fail "[analysis] threads = 2 did not give 2 threads"
cmp "$tmp/q1.h5" "$tmp/qk.h5" --ignore=study_text,study_path

# shear buildings (results format 3: per-floor and per-element rows)
for t in 1 3; do
  "$bin" run "$src/studies/quick-storeys.toml" --out "$tmp/s$t.h5" --quiet --threads "$t" > /dev/null 2>&1
done
cmp "$tmp/s1.h5" "$tmp/s3.h5"

# 2 ranks x 2 threads (rank 0's pool between its messages, a threaded worker rank)
timeout 300 mpirun -np 2 "$bin" run "$src/studies/quick.toml" --out "$tmp/m.h5" --quiet --threads 2 > /dev/null 2> "$tmp/m.err"
grep -q "2 ranks x 2 threads)" "$tmp/m.err" || { cat "$tmp/m.err"; fail "mpirun -np 2 --threads 2"; }
cmp "$tmp/q1.h5" "$tmp/m.h5"
# under mpirun with several ranks the automatic count is 1 per rank
timeout 300 mpirun -np 2 "$bin" run "$src/studies/quick-storeys.toml" --out "$tmp/m0.h5" --quiet > /dev/null 2> "$tmp/m0.err"
grep -q "2 ranks x 1 thread)" "$tmp/m0.err" || { cat "$tmp/m0.err"; fail "mpirun -np 2 without --threads: not 1 thread per rank"; }
cmp "$tmp/s1.h5" "$tmp/m0.h5"

# SIGINT on 2 threads mid-run: exit 130, checkpoint kept; --resume on 3 threads gives the same file
sed -e 's/^samples_per_pair = 32/samples_per_pair = 64/' -e '/^threads = /d' "$tmp/quick-key.toml" > "$tmp/big.toml"
"$bin" run "$tmp/big.toml" --out "$tmp/int.h5" --quiet --threads 2 > /dev/null 2> "$tmp/int.err" &
pid=$!
for _ in $(seq 1 600); do
  [ -f "$tmp/int.h5.ckpt" ] && [ "$(stat -c %s "$tmp/int.h5.ckpt")" -gt 200000 ] && break
  sleep 0.05
done
kill -INT "$pid"
rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || { cat "$tmp/int.err"; fail "SIGINT with 2 threads: exit $rc, want 130"; }
grep -q "interrupted: .* units done and checkpointed" "$tmp/int.err" || { cat "$tmp/int.err"; fail "no interrupted line"; }
[ -f "$tmp/int.h5" ] && fail "a results file after SIGINT"
"$bin" run "$tmp/big.toml" --out "$tmp/int.h5" --resume --quiet --threads 3 > /dev/null 2> "$tmp/res.err"
grep resuming "$tmp/res.err"
"$bin" run "$tmp/big.toml" --out "$tmp/ref.h5" --quiet --threads 1 > /dev/null 2>&1
cmp "$tmp/ref.h5" "$tmp/int.h5"

# bad counts: one error naming the key or the option, exit 2, no output and no checkpoint left
bad() {  # <what> <expected text> <command...>
  local what=$1 want=$2; shift 2
  rc=0; "$@" > "$tmp/bad.out" 2> "$tmp/bad.err" || rc=$?
  [ "$rc" -eq 2 ] || { cat "$tmp/bad.err"; fail "$what: exit $rc, want 2"; }
  [ "$(grep -c 'ERROR' "$tmp/bad.err")" -eq 1 ] || { cat "$tmp/bad.err"; fail "$what: not one ERROR line"; }
  grep -q -- "$want" "$tmp/bad.err" || { cat "$tmp/bad.err"; fail "$what: the error does not name $want"; }
  [ -e "$tmp/bad.h5" ] || [ -e "$tmp/bad.h5.ckpt" ] && fail "$what: output left behind"
  return 0
}
for v in -1 1025 1.5 '"two"'; do
  sed "s/^threads = 2/threads = $v/" "$tmp/quick-key.toml" > "$tmp/bad.toml"
  bad "[analysis] threads = $v" "threads" "$bin" run "$tmp/bad.toml" --out "$tmp/bad.h5" --quiet
done
for v in -1 1025 x; do
  bad "--threads $v" "--threads" "$bin" run "$src/studies/quick.toml" --out "$tmp/bad.h5" --quiet --threads "$v"
done
echo "1 passed, 0 failed"
