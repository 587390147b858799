#!/usr/bin/env bash
# Issue 44 item 7: every input path is checked for its file type before it is opened, and an existing output (the
# checkpoint <out>.ckpt too) must be a regular file. A FIFO, a folder, a device (/dev/zero) is refused with exit 2
# and one " ERROR:" line naming the path and what it is; nothing blocks. Before: a FIFO at <out>.ckpt blocked
# `pounding run` forever (deaf to SIGTERM and SIGINT), a FIFO as the study file blocked until its writer closed and
# then said "the study has no seed", FIFOs as spectrum CSVs (spectrum --file, motions --spectrum-file,
# [records.motions] spectrum_file) blocked, and --record /dev/zero, a FIFO or a folder said "record file not found".
# Every FIFO here has a writer (this shell holds it open read-write), so a reader would wait for data forever; each
# command runs under `timeout -k 5 10` (-k: a blocked run ignored SIGTERM), so a regression fails instead of
# hanging. The FIFO is still a FIFO afterwards.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }

"$bin" records synth --M 6.5 --R 20 --seed 1 --duration 8 -o "$tmp/rec1.AT2" > /dev/null
mkfifo "$tmp/fifo"
exec 3<> "$tmp/fifo"  # a writer that never writes: a read of the FIFO would block
mkdir "$tmp/folder"
study() {  # study <file> <output>
  cat > "$1" <<TOML
title = "input file types"
seed = 44
scene = "probability"
output = "$2"
[records]
files = ["$tmp/rec1.AT2"]
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
TOML
}

# expect_refusal <label> <path named> <regex for what it is> <command...>
expect_refusal() {
  local label=$1 path=$2 re=$3; shift 3
  local rc=0
  (cd "$tmp" && timeout -k 5 10 "$@") > "$tmp/stdout" 2> "$tmp/err" || rc=$?
  if [ "$rc" -eq 2 ] && [ "$(grep -c ' ERROR:' "$tmp/err")" -eq 1 ] && grep -qF -- "$path" "$tmp/err" \
     && grep -qE -- "$re" "$tmp/err" && [ -p "$tmp/fifo" ]; then
    ok "$label: $(cut -c1-220 "$tmp/err")"
  else
    fail "$label: exit $rc$([ "$rc" -eq 124 ] && echo ' (blocked: killed by timeout)')"; cat "$tmp/err"
  fi
}
fifo_is="the path is a FIFO \(named pipe\), not a regular file"

# --- run: the checkpoint, the study file, a record, a spectrum file --------------------------------------------------
study "$tmp/s.toml" s.h5
mkfifo "$tmp/s.h5.ckpt"  # the run itself would open it read-write: its own reads would wait for itself
expect_refusal "run, <out>.ckpt a FIFO" "s.h5.ckpt" "exists and is a FIFO" "$bin" run s.toml --quiet
[ -p "$tmp/s.h5.ckpt" ] && [ ! -e "$tmp/s.h5" ] || fail "the checkpoint FIFO was replaced or results written"
rm "$tmp/s.h5.ckpt"
expect_refusal "run, the study file a FIFO" "$tmp/fifo" "the study file: $fifo_is" "$bin" run "$tmp/fifo" --out r.h5 --quiet
expect_refusal "run, the study file a folder" "$tmp/folder" "the study file: the path is a folder" \
  "$bin" run "$tmp/folder" --out r.h5 --quiet
expect_refusal "run, the study file /dev/zero" "/dev/zero" "the study file: the path is a character device" \
  "$bin" run /dev/zero --out r.h5 --quiet
study "$tmp/recfifo.toml" r.h5
sed -i "s|files = \[\"$tmp/rec1.AT2\"\]|files = [\"$tmp/fifo\"]|" "$tmp/recfifo.toml"
expect_refusal "run, a record file a FIFO" "$tmp/fifo" "the record file: $fifo_is" "$bin" run recfifo.toml --quiet
cat > "$tmp/motions.toml" <<TOML
title = "generated motions, spectrum file a FIFO"
seed = 44
scene = "impacts"
[records.motions]
positions = [0.0, 80.0]
coherency = "none"
spectrum = "csv"
spectrum_file = "fifo"
duration = 10.0
realisations = 1
[gaps]
ratios = [1.0]
[bridge]
[[bridge.frame]]
label = "span 1"
mass = 1895413.0
period = 1.0204
[[bridge.frame]]
label = "span 2"
mass = 1895413.0
period = 0.8
support = 2
[[bridge.joint]]
gap = 0.01
[contact]
law = "hertzdamp"
stiffness = 2.0e9
e = 0.6
TOML
expect_refusal "run, [records.motions] spectrum_file a FIFO" "fifo" "the spectrum file: $fifo_is" \
  "$bin" run motions.toml --out m.h5 --quiet

# --- the spectrum files of spectrum and motions ----------------------------------------------------------------------
expect_refusal "spectrum --file a FIFO" "$tmp/fifo" "the spectrum file: $fifo_is" \
  "$bin" spectrum --code csv --file "$tmp/fifo" --periods 0.5,1
expect_refusal "motions --spectrum-file a FIFO" "$tmp/fifo" "the spectrum file: $fifo_is" \
  "$bin" motions --positions 0,80 --coherency none --spectrum csv --spectrum-file "$tmp/fifo" --realisations 1 \
  --quiet --out m
[ ! -e "$tmp/m" ] || fail "motions left its folder"

# --- record files: simulate, records show ----------------------------------------------------------------------------
expect_refusal "simulate --record /dev/zero" "/dev/zero" "the record file: the path is a character device" \
  "$bin" simulate --record /dev/zero
expect_refusal "simulate --record a FIFO" "$tmp/fifo" "the record file: $fifo_is" "$bin" simulate --record "$tmp/fifo"
expect_refusal "records show a folder" "$tmp/folder" "the record file: the path is a folder" \
  "$bin" records show "$tmp/folder"
expect_refusal "records show a missing file" "$tmp/none.AT2" "the record file: not found" \
  "$bin" records show "$tmp/none.AT2"

# --- HDF5 inputs: report, results ------------------------------------------------------------------------------------
expect_refusal "report a FIFO" "$tmp/fifo" "the HDF5 file: $fifo_is" "$bin" report "$tmp/fifo"
expect_refusal "report --html of a FIFO" "$tmp/fifo" "the HDF5 file: $fifo_is" \
  "$bin" report "$tmp/fifo" --html out.html --no-figures
expect_refusal "results of a folder" "$tmp/folder" "the HDF5 file: the path is a folder" "$bin" results "$tmp/folder"
expect_refusal "results of /dev/zero" "/dev/zero" "the HDF5 file: the path is a character device" "$bin" results /dev/zero

# --- other readers: replay, sample, records spectrum -----------------------------------------------------------------
expect_refusal "replay --input a FIFO" "$tmp/fifo" "the kinematics file: $fifo_is" \
  "$bin" replay --law hertz --kh 1e9 --input "$tmp/fifo"
expect_refusal "sample, the study file a FIFO" "$tmp/fifo" "the study file: $fifo_is" \
  "$bin" sample "$tmp/fifo" --n 2 --out x.csv
expect_refusal "records spectrum of a FIFO" "$tmp/fifo" "the record file: $fifo_is" \
  "$bin" records spectrum "$tmp/fifo" -o sp.csv

# --- what keeps working ---------------------------------------------------------------------------------------------
rc=0; (cd "$tmp" && timeout 120 "$bin" run s.toml --quiet) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && [ -s "$tmp/s.h5" ] && ok "run of a regular study file" || { fail "run s.toml: exit $rc"; cat "$tmp/err"; }
rc=0; (cd "$tmp" && timeout 60 "$bin" report s.h5) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && ok "report of a regular results file" || { fail "report s.h5: exit $rc"; cat "$tmp/err"; }
ln -s rec1.AT2 "$tmp/reclink.AT2"
rc=0; (cd "$tmp" && timeout 60 "$bin" records show reclink.AT2) > /dev/null 2> "$tmp/err" || rc=$?
[ "$rc" -eq 0 ] && ok "records show through a link to a regular file" || { fail "records show reclink.AT2: exit $rc"; cat "$tmp/err"; }

exec 3>&-
[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
