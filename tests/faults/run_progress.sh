#!/usr/bin/env bash
# Issue 10.3: progress is never destroyed or silently lost.
#  - a run without --resume refuses to truncate a checkpoint that holds progress (file untouched); --force
#    discards it; --resume with --force is refused
#  - a second run on the same output refuses while the first holds the lock, naming its process; the lock
#    goes with the process (kill -9) and --resume then works
#  - a checkpoint write that fails (file-size limit: EFBIG) stops the run at once with exit 2, the OS error
#    and the path; the checkpoint stays resumable and no temporary is left
#  - a results write that fails exits 2 with the OS error, leaves no results file and no temporary, keeps
#    the checkpoint; --resume then writes the results
#  - a checkpoint written by another build is not resumed
#  - output path problems are found before any work
#  - SIGTERM: exit 130, checkpoint kept, no temporary; stale temporaries of a killed run are removed
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
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
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
run() { rc=0; "$bin" run "$@" > "$tmp/out" 2> "$tmp/err" || rc=$?; }
no_temporaries() { ! ls "$tmp"/*.tmp[0-9]* > /dev/null 2>&1 || { fail "$1: temporary left: $(ls "$tmp"/*.tmp[0-9]*)"; }; }
cmp_results() { /usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$1" > /dev/null || fail "$2: results differ"; }
"$bin" run "$tmp/s.toml" --out "$tmp/ref.h5" --quiet > /dev/null 2>&1
units=$(( 4 * 121 ))

# --- refuse to discard progress -------------------------------------------------------------------
# one thread: the third unit fails after exactly two were stored (on several threads the count depends on which
# units finish before the failing one; this test failed once on 2 CPUs with "holds 4 of 484")
POUNDING_INJECT_FAULT=compute@0 run "$tmp/s.toml" --out "$tmp/a.h5" --quiet --threads 1
[ "$rc" -eq 2 ] && [ -s "$tmp/a.h5.ckpt" ] || fail "could not make a partial checkpoint (rc $rc)"
cp "$tmp/a.h5.ckpt" "$tmp/a.copy"
run "$tmp/s.toml" --out "$tmp/a.h5" --quiet
[ "$rc" -eq 2 ] || fail "a fresh run over a checkpoint with progress: exit $rc (want 2)"
grep -q "checkpoint $tmp/a.h5.ckpt holds 2 of $units units of this study, .*rerun with --resume to continue or --force to discard it" "$tmp/err" \
  || { fail "no refusal message"; cat "$tmp/err"; }
cmp -s "$tmp/a.h5.ckpt" "$tmp/a.copy" && ok "fresh run refused: $(cut -c1-120 "$tmp/err")" || fail "the checkpoint was changed"
run "$tmp/s.toml" --out "$tmp/a.h5" --quiet --resume --force
[ "$rc" -eq 2 ] && grep -q "contradict" "$tmp/err" && ok "--resume --force refused" || fail "--resume --force: rc $rc"
run "$tmp/s.toml" --out "$tmp/a.h5" --quiet --force
[ "$rc" -eq 0 ] && [ ! -e "$tmp/a.h5.ckpt" ] && ok "--force discards the checkpoint and runs" || fail "--force: rc $rc"
cmp_results "$tmp/a.h5" "--force"

# --- one run per output: the lock -----------------------------------------------------------------
: > "$tmp/b.h5.ckpt"
flock -x "$tmp/b.h5.ckpt" sleep 60 &
holder=$!
for _ in $(seq 1 100); do grep -q " $holder " /proc/locks && break; sleep 0.05; done
run "$tmp/s.toml" --out "$tmp/b.h5" --quiet --force
[ "$rc" -eq 2 ] && grep -q "$tmp/b.h5.ckpt is in use by process $holder" "$tmp/err" \
  && ok "locked output refused: $(cut -c1-100 "$tmp/err")" || { fail "locked output: rc $rc"; cat "$tmp/err"; }
kill "$holder"; wait "$holder" 2>/dev/null || true
# a real second pounding run while the first is paused holding the lock; kill -9 releases it
sed 's/^samples_per_pair = 8/samples_per_pair = 64/' "$tmp/s.toml" > "$tmp/big.toml"
"$bin" run "$tmp/big.toml" --out "$tmp/c.h5" --quiet > /dev/null 2>&1 &
first=$!
for _ in $(seq 1 400); do [ -s "$tmp/c.h5.ckpt" ] && break; sleep 0.02; done
kill -STOP "$first"
run "$tmp/big.toml" --out "$tmp/c.h5" --quiet --resume
[ "$rc" -eq 2 ] && grep -q "is in use by process $first" "$tmp/err" && ok "second run refused while the first runs" \
  || { fail "second run on the same output: rc $rc"; cat "$tmp/err"; }
kill -9 "$first"; wait "$first" 2>/dev/null || true
run "$tmp/big.toml" --out "$tmp/c.h5" --quiet --resume
[ "$rc" -eq 0 ] && ok "after kill -9 the lock is gone and --resume completes" || { fail "resume after kill -9: rc $rc"; cat "$tmp/err"; }

# --- checkpoint write fails (EFBIG under ulimit -f) --------------------------------------------------
rm -f "$tmp"/d.h5*
rc=0; ( trap '' XFSZ; ulimit -f 64; exec "$bin" run "$tmp/s.toml" --out "$tmp/d.h5" --quiet ) > "$tmp/out" 2> "$tmp/err" || rc=$?
[ "$rc" -eq 2 ] || { fail "checkpoint write failure: exit $rc (want 2)"; cat "$tmp/err"; }
grep -q "cannot write $tmp/d.h5.ckpt: File too large (EFBIG)" "$tmp/err" && ok "checkpoint write failure: $(grep ERROR "$tmp/err" | cut -c1-140)" \
  || { fail "no OS error and path"; cat "$tmp/err"; }
grep -q "^results:" "$tmp/err" && fail "the run went on after the checkpoint write failed"
[ ! -e "$tmp/d.h5" ] || fail "a results file exists after the checkpoint failure"
no_temporaries "checkpoint failure"
run "$tmp/s.toml" --out "$tmp/d.h5" --quiet --resume
[ "$rc" -eq 0 ] && grep -q "resuming: [1-9][0-9]* of $units units" "$tmp/err" && ok "resumable after the failure: $(grep resuming "$tmp/err")" \
  || { fail "resume after checkpoint failure: rc $rc"; cat "$tmp/err"; }
cmp_results "$tmp/d.h5" "resume after checkpoint failure"

# --- results write fails ---------------------------------------------------------------------------
rm -f "$tmp"/e.h5*
POUNDING_INJECT_FAULT=write run "$tmp/s.toml" --out "$tmp/e.h5" --quiet   # a complete checkpoint, kept
size=$(( $(stat -c %s "$tmp/e.h5.ckpt") / 1024 + 1 ))
rc=0; ( trap '' XFSZ; ulimit -f "$size"; exec "$bin" run "$tmp/s.toml" --out "$tmp/e.h5" --quiet --resume ) > "$tmp/out" 2> "$tmp/err" || rc=$?
[ "$rc" -eq 2 ] || { fail "results write failure: exit $rc (want 2; 139 was the old segfault)"; cat "$tmp/err"; }
grep -q "cannot write $tmp/e.h5.*File too large (EFBIG)" "$tmp/err" && ok "results write failure: $(grep ERROR "$tmp/err" | cut -c1-140)" \
  || { fail "no OS error and path"; cat "$tmp/err"; }
[ ! -e "$tmp/e.h5" ] || fail "a results file exists after the failed write"
no_temporaries "results failure"
[ -s "$tmp/e.h5.ckpt" ] || fail "the checkpoint was lost"
run "$tmp/s.toml" --out "$tmp/e.h5" --quiet --resume
[ "$rc" -eq 0 ] && ok "--resume writes the results after the failed write" || fail "resume after results failure: rc $rc"
cmp_results "$tmp/e.h5" "resume after results failure"

# --- another build's checkpoint ----------------------------------------------------------------------
cp "$bin" "$tmp/other-build"; printf 'x' >> "$tmp/other-build"
POUNDING_INJECT_FAULT=compute@0 "$tmp/other-build" run "$tmp/s.toml" --out "$tmp/f.h5" --quiet > /dev/null 2>&1 || true
run "$tmp/s.toml" --out "$tmp/f.h5" --quiet --resume
[ "$rc" -eq 2 ] && grep -q "written by a different build of pounding" "$tmp/err" && ok "another build's checkpoint refused" \
  || { fail "resume with another build: rc $rc"; cat "$tmp/err"; }

# --- output path problems, before any work --------------------------------------------------------
mkdir -p "$tmp/dir"
check_path() {  # check_path <label> <regex> <args...>
  local label=$1 re=$2; shift 2
  run "$tmp/s.toml" --quiet "$@"
  if [ "$rc" -eq 2 ] && grep -qE "$re" "$tmp/err" && ! grep -q "pounding run:" "$tmp/err"; then ok "$label: $(cut -c1-110 "$tmp/err")"
  else fail "$label: rc $rc"; cat "$tmp/err"; fi
}
check_path "--out DIR" "is an existing folder" --out "$tmp/dir"
check_path "--out DIR/" "names a folder" --out "$tmp/dir/"
check_path "--out ''" "out: the value is empty" --out ""
check_path "missing parent" "does not exist" --out "$tmp/nope/r.h5"
check_path "special file" "exists and is a character device; pounding replaces only regular files" --out /dev/null
if [ "$(id -u)" -eq 0 ] && id nobody > /dev/null 2>&1; then
  chmod 755 "$tmp"; mkdir -p "$tmp/ro"; chmod 555 "$tmp/ro"
  rc=0; runuser -u nobody -- "$bin" run "$tmp/s.toml" --quiet --out "$tmp/ro/r.h5" > "$tmp/out" 2> "$tmp/err" || rc=$?
else
  mkdir -p "$tmp/ro"; chmod 555 "$tmp/ro"
  run "$tmp/s.toml" --quiet --out "$tmp/ro/r.h5"
fi
[ "$rc" -eq 2 ] && grep -q "cannot create files in '$tmp/ro'" "$tmp/err" && ! grep -q "pounding run:" "$tmp/err" \
  && ok "no write permission: $(cut -c1-110 "$tmp/err")" || { fail "no write permission: rc $rc"; cat "$tmp/err"; }
[ -z "$(find "$tmp/dir" "$tmp/ro" -mindepth 1)" ] || fail "files were left in the refused folders"

# --- SIGTERM, and stale temporaries of a killed run ----------------------------------------------------
touch "$tmp/g.h5.tmp4194303"
"$bin" run "$tmp/big.toml" --out "$tmp/g.h5" --quiet > /dev/null 2> "$tmp/err" &
pid=$!
# wait for a finished unit in the checkpoint (the header alone holds nothing, and is not kept)
for _ in $(seq 1 400); do [ -f "$tmp/g.h5.ckpt" ] && [ "$(stat -c %s "$tmp/g.h5.ckpt")" -gt 2000 ] && break; sleep 0.02; done
kill -TERM "$pid"; rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 143 ] && [ -s "$tmp/g.h5.ckpt" ] && grep -q "stopped by SIGTERM" "$tmp/err" && ok "SIGTERM: exit 143, checkpoint kept" || { fail "SIGTERM: rc $rc"; cat "$tmp/err"; }
no_temporaries "SIGTERM (the stale temporary of a killed run must be gone too)"

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
