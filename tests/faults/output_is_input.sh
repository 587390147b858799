#!/usr/bin/env bash
# Issue 44 items 1-3: no command writes an output over one of its own inputs, nor over another of its outputs.
# Each refusal: exit 2 before any work, one " ERROR:" line naming the output path, the input unchanged (checksum
# before and after), no output or checkpoint left. Files are compared by device and inode (stat), so the same file
# spelled ./x, reached through a symbolic link or a hard link is caught too (a hard link the atomic rename would
# only split, but it names the same file and is refused alike).
#  1. report R.h5 --html R.h5 (and A.h5 R.h5 --html R.h5, ./R.h5, a link to R.h5, a hard link);
#  2. run S.toml --out q.html with [report] html = true: its report would replace its results (before: exit 0, only
#     the HTML left, the checkpoint deleted); --out the study file, --out a record file of the study (--force);
#  3. replay --input k.csv --out k.csv (and through a link);
#  and the same helper in sample --out (the study), simulate --series (the record), records spectrum -o,
#  records select -o and records suite --write (a record). What must keep working: report --html to a new file, replay to another file, a run
#  with html = true (results and report beside them).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
sum() { sha256sum "$1" | cut -d' ' -f1; }

"$bin" records synth --M 6.5 --R 20 --seed 1 --duration 8 -o "$tmp/rec1.AT2" > /dev/null
"$bin" records synth --M 6.8 --R 15 --seed 2 --duration 8 -o "$tmp/rec2.AT2" > /dev/null
cat > "$tmp/s.toml" <<TOML
title = "output is input"
seed = 44
scene = "probability"
output = "s.h5"
[records]
files = ["rec1.AT2", "rec2.AT2"]
[structures]
samples_per_pair = 4
[structures.building1]
period = 0.9
height = 28.0
mass = 3.1e6
yield_coefficient = 0.15
[structures.building2]
period = 1.3
height = 42.0
mass = 4.7e6
yield_coefficient = 0.10
[report]
bootstrap = 0
html = true
TOML

# expect_refusal <label> <input that must not change> <output path> <command...>; each case starts from the inputs
# as they were made (restore), so that it fails on its own when the check is missing
expect_refusal() {
  local label=$1 input=$2 out=$3; shift 3
  cp "$tmp"/orig/* "$tmp"/  # in place: hard links stay links
  local before; before=$(sum "$input")
  local rc=0
  (cd "$tmp" && timeout -k 5 60 "$@") > "$tmp/stdout" 2> "$tmp/err" || rc=$?
  if [ "$rc" -eq 2 ] && [ "$(sum "$input")" = "$before" ] && [ "$(grep -c ' ERROR:' "$tmp/err")" -eq 1 ] \
     && grep -qF -- " ERROR: the output path '$out' is the same file as" "$tmp/err"; then
    ok "$label: $(cut -c1-220 "$tmp/err")"
  else
    fail "$label: exit $rc, input $( [ "$(sum "$input")" = "$before" ] && echo unchanged || echo CHANGED)"
    cat "$tmp/err"
  fi
}

# --- what keeps working, and gives the files for the refusals --------------------------------------------------
rc=0; (cd "$tmp" && timeout 120 "$bin" run s.toml --out r.h5 --quiet) > "$tmp/stdout" 2> "$tmp/err" || rc=$?
if [ "$rc" -eq 0 ] && [ -s "$tmp/r.h5" ] && grep -q "<html" "$tmp/r.html" && [ ! -e "$tmp/r.h5.ckpt" ]; then
  ok "run with html = true: r.h5 and r.html"
else
  fail "run with html = true: exit $rc"; cat "$tmp/err"; exit 1
fi
cp "$tmp/r.h5" "$tmp/a.h5"
rc=0; (cd "$tmp" && "$bin" report r.h5 --html new.html --no-figures) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && grep -q "<html" "$tmp/new.html" && ok "report --html to a new file" || { fail "report --html new.html: exit $rc"; cat "$tmp/err"; }
rc=0; (cd "$tmp" && "$bin" report a.h5 r.h5 --html both.html --no-figures) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && grep -q "<html" "$tmp/both.html" && ok "report A B --html to a new file" || { fail "report A B --html both.html: exit $rc"; cat "$tmp/err"; }
printf 'time,penetration\n0,-0.001\n0.001,0.002\n0.002,0.004\n0.003,0.002\n0.004,-0.001\n0.005,-0.002\n' > "$tmp/k.csv"
replay=(replay --law hertz --kh 1e9)
rc=0; (cd "$tmp" && "$bin" "${replay[@]}" --input k.csv --out k2.csv) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && grep -q "force_N" "$tmp/k2.csv" && ok "replay to another file" || { fail "replay --out k2.csv: exit $rc"; cat "$tmp/err"; }

mkdir "$tmp/orig"
cp "$tmp"/{r.h5,a.h5,s.toml,rec1.AT2,rec2.AT2,k.csv} "$tmp/orig/"

# --- 1. report --html over a results file it reads ---------------------------------------------------------------
expect_refusal "report R --html R" "$tmp/r.h5" r.h5 "$bin" report r.h5 --html r.h5 --no-figures
expect_refusal "report A R --html R" "$tmp/r.h5" r.h5 "$bin" report a.h5 r.h5 --html r.h5 --no-figures
expect_refusal "report R --html ./R" "$tmp/r.h5" ./r.h5 "$bin" report r.h5 --html ./r.h5 --no-figures
ln -s r.h5 "$tmp/link.html"
expect_refusal "report R --html (a link to R)" "$tmp/r.h5" link.html "$bin" report r.h5 --html link.html --no-figures
[ -L "$tmp/link.html" ] || fail "the link was replaced"
ln "$tmp/r.h5" "$tmp/hard.html"
expect_refusal "report R --html (a hard link to R)" "$tmp/r.h5" hard.html "$bin" report r.h5 --html hard.html --no-figures

# --- 2. run: the HTML report over the results, outputs over the study or a record --------------------------------
cp "$tmp"/orig/* "$tmp"/
rc=0; (cd "$tmp" && timeout -k 5 60 "$bin" run s.toml --out q.html --quiet) > "$tmp/stdout" 2> "$tmp/err" || rc=$?
if [ "$rc" -eq 2 ] && [ ! -e "$tmp/q.html" ] && [ ! -e "$tmp/q.html.ckpt" ] && [ "$(grep -c ' ERROR:' "$tmp/err")" -eq 1 ] \
   && grep -qF " ERROR: the output path 'q.html' is the same file as the results file 'q.html'" "$tmp/err"; then
  ok "run --out q.html with html = true: $(cut -c1-220 "$tmp/err")"
else
  fail "run --out q.html with html = true: exit $rc"; cat "$tmp/err" "$tmp/stdout"; ls "$tmp"
fi
expect_refusal "run --out the study file" "$tmp/s.toml" s.toml "$bin" run s.toml --out s.toml --force --quiet
expect_refusal "run --out a record of the study" "$tmp/rec2.AT2" rec2.AT2 "$bin" run s.toml --out rec2.AT2 --force --quiet
[ ! -e "$tmp/rec2.AT2.ckpt" ] && [ ! -e "$tmp/s.toml.ckpt" ] || fail "a checkpoint was left beside an input"

# --- 3. replay --out over its --input --------------------------------------------------------------------------------
expect_refusal "replay --input k.csv --out k.csv" "$tmp/k.csv" k.csv "$bin" "${replay[@]}" --input k.csv --out k.csv
ln -s k.csv "$tmp/klink.csv"
expect_refusal "replay --out (a link to the input)" "$tmp/k.csv" klink.csv "$bin" "${replay[@]}" --input k.csv --out klink.csv

# --- the other commands that read and write files ------------------------------------------------------------------
ln -s s.toml "$tmp/study.csv"
expect_refusal "sample --out (a link to the study)" "$tmp/s.toml" study.csv "$bin" sample s.toml --n 2 --out study.csv
ln -s rec1.AT2 "$tmp/rec1.csv"
expect_refusal "simulate --series (a link to the record)" "$tmp/rec1.AT2" rec1.csv \
  "$bin" simulate --record rec1.AT2 --series rec1.csv
expect_refusal "records spectrum -o a record" "$tmp/rec1.AT2" rec1.AT2 "$bin" records spectrum rec1.AT2 -o rec1.AT2
expect_refusal "records select -o a record" "$tmp/rec2.AT2" rec2.AT2 \
  "$bin" records select --asce7 1.0,0.6,8 --period 0.8 --count 1 --max-scale 50 rec1.AT2 rec2.AT2 -o rec2.AT2
cat > "$tmp/suite.toml" <<TOML
[suite]
name = "one real record"
seed = 1
dt = 0.01
[[record]]
id = "rec1"
event = "synthetic"
year = 2026
station = "none"
M = 6.5
pga_g = 0.3
R_km = 20.0
vs30 = 300.0
F = 0
file = "rec1.AT2"
TOML
expect_refusal "records suite --write over a record it read" "$tmp/rec1.AT2" ./rec1.AT2 \
  "$bin" records suite suite.toml --write .

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
