#!/usr/bin/env bash
# Issue 24.1: no writer replaces a device node, a FIFO or a folder with a regular file. `pounding sample --out`,
# `records select -o`, `records synth -o` and `records spectrum -o` refuse a path that exists and is not a
# regular file, before any work: exit 2, one " ERROR:" line naming the path, the special file untouched (still a
# FIFO / a character device), no temporary beside it. A symbolic link to a regular file is followed: the file it
# names is replaced, the link stays a link. (`run --out` refused such paths already: tests/faults/run_progress.sh.)
# The character device is made with mknod (root only; skipped, with a note, where mknod is not allowed).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
study=$src/studies/paper-structures.toml
"$bin" records synth --M 6.5 --R 20 --seed 1 -o "$tmp/rec1.AT2" > /dev/null
"$bin" records synth --M 6.8 --R 15 --seed 2 -o "$tmp/rec2.AT2" > /dev/null
"$bin" records synth --M 7.0 --R 30 --seed 3 -o "$tmp/rec3.AT2" > /dev/null

mkfifo "$tmp/fifo.csv"
specials=("$tmp/fifo.csv")
if mknod "$tmp/null.csv" c 1 3 2> /dev/null; then specials+=("$tmp/null.csv")
else echo "note: mknod not allowed here; the character-device case is not run"; fi

kind() { stat -c %F "$1"; }
for f in "${specials[@]}"; do
  before=$(kind "$f")
  for cmd in sample select synth spectrum; do
    rc=0
    case $cmd in
      sample) timeout 60 "$bin" sample "$study" --n 2 --out "$f" > "$tmp/out" 2> "$tmp/err" || rc=$? ;;
      select) timeout 60 "$bin" records select --asce7 1.0,0.6,8 --period 0.8 --count 2 --max-scale 50 \
                "$tmp"/rec*.AT2 -o "$f" > "$tmp/out" 2> "$tmp/err" || rc=$? ;;
      synth) timeout 60 "$bin" records synth --M 6.5 --R 20 --seed 9 -o "$f" > "$tmp/out" 2> "$tmp/err" || rc=$? ;;
      spectrum) timeout 60 "$bin" records spectrum "$tmp/rec1.AT2" -o "$f" > "$tmp/out" 2> "$tmp/err" || rc=$? ;;
    esac
    after=$(kind "$f")
    if [ "$rc" -eq 2 ] && [ "$after" = "$before" ] && grep -q "ERROR: the output path '$f' exists and is a" "$tmp/err" \
       && [ "$(grep -c ERROR "$tmp/err")" -eq 1 ]; then
      ok "$cmd onto $before: $(cut -c1-150 "$tmp/err")"
    else
      fail "$cmd onto $before: exit $rc, now $after"; cat "$tmp/err"
    fi
    ls "$tmp"/*.tmp[0-9]* > /dev/null 2>&1 && fail "$cmd: a temporary was left: $(ls "$tmp"/*.tmp[0-9]*)"
  done
done
# sample refuses before the work (no 'wrote' line), select before the selection table
grep -q "wrote" "$tmp/out" && fail "work was done before the refusal"

# a link to a regular file: that file is replaced, the link kept
echo old > "$tmp/target.csv"; ln -s target.csv "$tmp/link.csv"
"$bin" sample "$study" --n 2 --out "$tmp/link.csv" > /dev/null 2> "$tmp/err" || fail "sample through a link: $(cat "$tmp/err")"
[ -L "$tmp/link.csv" ] && grep -q "^i1,i2,sample" "$tmp/target.csv" && ok "a link to a regular file: the file replaced, the link kept" \
  || fail "the link was replaced or its target not written"

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
