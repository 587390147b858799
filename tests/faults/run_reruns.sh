#!/usr/bin/env bash
# Issue 24.8: reruns and damaged checkpoints are never silent.
#  - a 0-byte checkpoint with --resume says it is empty (not "no checkpoint to resume from");
#  - a checkpoint with 4 flipped bytes resumes from the records before the damage and SAYS what was dropped (the
#    record, why, the bytes and about how many units), and the results equal an uninterrupted run's;
#  - a rerun with a different study does not replace a finished results file without --force (exit 2, the file
#    untouched); a rerun of the same study replaces it; --force replaces it; a file that is not a results file is
#    not replaced either.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
cat > "$tmp/s.toml" <<'TOML'
title = "rerun test"
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
sed 's/^seed = 7/seed = 8/; s/^title = "rerun test"/title = "another study"/' "$tmp/s.toml" > "$tmp/other.toml"
run() { rc=0; timeout 120 "$bin" run "$@" --quiet > "$tmp/out" 2> "$tmp/err" || rc=$?; }
run "$tmp/s.toml" --out "$tmp/ref.h5"
units=$(( 4 * 121 ))

# --- a 0-byte checkpoint ---------------------------------------------------------------------------------
: > "$tmp/z.h5.ckpt"
run "$tmp/s.toml" --out "$tmp/z.h5" --resume
[ "$rc" -eq 2 ] && grep -q "checkpoint $tmp/z.h5.ckpt is empty (0 bytes): it holds no finished unit" "$tmp/err" \
  && ok "0-byte checkpoint: $(cut -c1-160 "$tmp/err")" || { fail "0-byte checkpoint: exit $rc"; cat "$tmp/err"; }

# --- 4 flipped bytes in the middle of a complete checkpoint -------------------------------------------------
POUNDING_INJECT_FAULT=write run "$tmp/s.toml" --out "$tmp/f.h5"   # every unit checkpointed, then a failed write
size=$(stat -c %s "$tmp/f.h5.ckpt")
printf '\xde\xad\xbe\xef' | dd of="$tmp/f.h5.ckpt" bs=1 seek=$((size / 2)) conv=notrunc status=none
run "$tmp/s.toml" --out "$tmp/f.h5" --resume
if [ "$rc" -eq 0 ] && grep -qE "checkpoint $tmp/f.h5.ckpt: record [0-9]+ \(unit [0-9]+\) fails its checksum \(damaged bytes\): the [0-9,]+ bytes after unit record [0-9,]+ are dropped \(about [0-9,]+ units\) and those units are computed again" "$tmp/err"; then
  ok "flipped bytes: $(grep -E 'resuming|fails its checksum' "$tmp/err" | tr '\n' ' ' | cut -c1-260)"
else
  fail "flipped bytes: exit $rc, or nothing said about the dropped units"; cat "$tmp/err"
fi
/usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/ref.h5" "$tmp/f.h5" > /dev/null && ok "results after the damaged resume equal an uninterrupted run's" \
  || fail "results after the damaged resume differ"

# --- a finished results file and another study ---------------------------------------------------------------
cp "$tmp/ref.h5" "$tmp/keep.h5"
run "$tmp/other.toml" --out "$tmp/ref.h5"
if [ "$rc" -eq 2 ] && grep -q "$tmp/ref.h5 holds the results of another study (\"rerun test\", $tmp/s.toml, written .*--force" "$tmp/err" \
   && cmp -s "$tmp/ref.h5" "$tmp/keep.h5" && [ ! -e "$tmp/ref.h5.ckpt" ]; then
  ok "another study over finished results refused: $(cut -c1-200 "$tmp/err")"
else
  fail "another study over finished results: exit $rc"; cat "$tmp/err"
fi
run "$tmp/s.toml" --out "$tmp/ref.h5"
[ "$rc" -eq 0 ] && ok "the same study reruns over its own results" || { fail "same-study rerun: exit $rc"; cat "$tmp/err"; }
run "$tmp/other.toml" --out "$tmp/ref.h5" --force
[ "$rc" -eq 0 ] && ok "--force replaces another study's results" || { fail "--force: exit $rc"; cat "$tmp/err"; }
echo "not results" > "$tmp/notes.h5"
run "$tmp/s.toml" --out "$tmp/notes.h5"
[ "$rc" -eq 2 ] && grep -q "exists and is not a pounding results file" "$tmp/err" && grep -q "not results" "$tmp/notes.h5" \
  && ok "a file that is not a results file is not replaced" || { fail "non-results file: exit $rc"; cat "$tmp/err"; }

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
