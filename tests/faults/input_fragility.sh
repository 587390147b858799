#!/usr/bin/env bash
# Issue 24.2, 24.6, 24.8: a fragility study's inputs are checked before the first unit, and nothing fails after
# the work.
#  - large arrays: a hazard table of 8,200 rows and 9,000 gap ratios are written (HDF5 attributes over 64 KiB used
#    to fail at the very end, "HDF5 error: attr im", and --resume failed the same way forever);
#  - [hazard] k without k0 (and the reverse), and levels no record reaches (PGV in cm/s; Sa levels of 9-10 g with
#    max_scale = 1), with or without [hazard], are errors before any unit (no checkpoint left), naming file:line
#    and the key;
#  - a hazard curve that is a FIFO or /dev/zero is refused at once (before: blocked forever / ate 1 GB in 3.5 s),
#    naming the limit; a file over the 16 MiB limit is refused by its size;
#  - a UTF-8 byte-order mark (Excel's "CSV UTF-8") is read; a first row "nan,0.5" is an error, not a header;
#  - period = "pair" gives the [0.01, 20] s check; sds = nan is "not a finite number".
# Each check runs under `timeout` (a hang is a failure). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
# study <file> <[intensity] lines> <[hazard] lines (or "")> [extra top-level sections]
study() {
  {
    cat <<TOML
title = "fragility input checks"
seed = 5
scene = "probability"
output = "$tmp/out.h5"
[records]
suite = "builtin"
synthetic_only = true
limit = 3
[structures]
samples_per_pair = 4
zeta = 0.05
alpha = 0.05
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
bootstrap = 50
[intensity]
$2
TOML
    [ -n "$3" ] && printf '[hazard]\n%s\n' "$3"
    printf '%s\n' "${4:-}"
  } > "$1"
}
sa='measure = "Sa"
period = 1.0
levels = [0.1, 0.2, 0.4, 0.8]'
expect_error() {  # expect_error <label> <regex> <study>
  local label=$1 re=$2 f=$3
  rm -f "$tmp/out.h5" "$tmp/out.h5.ckpt"
  rc=0; timeout 30 "$bin" run "$f" --quiet > "$tmp/stdout" 2> "$tmp/err" || rc=$?
  if [ "$rc" -eq 2 ] && grep -qE "$re" "$tmp/err" && [ "$(grep -c ' ERROR:' "$tmp/err")" -eq 1 ] \
     && ! grep -q "pounding run:" "$tmp/err" && [ ! -e "$tmp/out.h5" ] && [ ! -e "$tmp/out.h5.ckpt" ]; then
    ok "$label: $(cut -c1-200 "$tmp/err")"
  else
    fail "$label: exit $rc (want 2 before any unit, matching /$re/)"; cat "$tmp/err"
  fi
}
expect_run() {  # expect_run <label> <study>
  rm -f "$tmp/out.h5" "$tmp/out.h5.ckpt"
  rc=0; timeout 120 "$bin" run "$2" --quiet --force > "$tmp/stdout" 2> "$tmp/err" || rc=$?
  if [ "$rc" -eq 0 ] && [ -s "$tmp/out.h5" ] && timeout 60 "$bin" report "$tmp/out.h5" > "$tmp/report" 2>&1; then
    ok "$1"
  else
    fail "$1: exit $rc"; tail -5 "$tmp/err"; tail -3 "$tmp/report" 2>/dev/null || true
  fi
}

# --- large arrays are written (used to fail after the work) ----------------------------------------
/usr/bin/python3 - "$tmp/big-hazard.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("Sa_g,annual_rate\n")
    for i in range(8200):
        x = 0.05 * math.exp(i * math.log(100) / 8199)   # 0.05 .. 5 g
        f.write(f"{x:.10g},{4e-4 * x ** -2.5:.10g}\n")
PY
study "$tmp/big-hazard.toml" "$sa" "curve = \"$tmp/big-hazard.csv\""
expect_run "hazard table of 8,200 rows written and reported" "$tmp/big-hazard.toml"
ratios=$(/usr/bin/python3 -c "print(', '.join(f'{0.01 * (i + 1):.2f}' for i in range(9000)))")
study "$tmp/big-gaps.toml" "$sa" "k0 = 1e-4
k = 2.5" "[gaps]
ratios = [$ratios]"
sed -i 's/^bootstrap = 50/bootstrap = 0/' "$tmp/big-gaps.toml"
expect_run "9,000 gap ratios written and reported" "$tmp/big-gaps.toml"

# --- found before the first unit ----------------------------------------------------------------------
study "$tmp/k.toml" "$sa" "k = 2.5"
expect_error "[hazard] k without k0" "k.toml:[0-9]+ \[hazard\]\.k.*k0" "$tmp/k.toml"
study "$tmp/k0.toml" "$sa" "k0 = 1e-4"
expect_error "[hazard] k0 without k" "gives k0 without k.*k0.toml:[0-9]+ \[hazard\]\.k0" "$tmp/k0.toml"
study "$tmp/pgv.toml" 'measure = "PGV"
levels = [4, 8, 12, 16]' "k0 = 1e-4
k = 2.5"
expect_error "PGV levels in cm/s" "every record is dropped from .* stripes.*pgv.toml:[0-9]+ \[intensity\]\.levels.*m/s" "$tmp/pgv.toml"
study "$tmp/high.toml" 'measure = "Sa"
period = 1.0
max_scale = 1
levels = [9, 9.5, 10]' ""
expect_error "Sa levels of 9-10 g with max_scale = 1, no [hazard]" "every record is dropped .*max_scale" "$tmp/high.toml"

# --- hazard curves that hang or eat memory ------------------------------------------------------------
mkfifo "$tmp/fifo.csv"
study "$tmp/fifo.toml" "$sa" "curve = \"$tmp/fifo.csv\""
expect_error "hazard curve is a FIFO" "hazard curve: the path is a FIFO.*fifo.toml:[0-9]+ \[hazard\]\.curve" "$tmp/fifo.toml"
study "$tmp/zero.toml" "$sa" 'curve = "/dev/zero"'
expect_error "hazard curve /dev/zero" "character device.*16 MiB" "$tmp/zero.toml"
truncate -s 17M "$tmp/huge.csv"
study "$tmp/huge.toml" "$sa" "curve = \"$tmp/huge.csv\""
expect_error "hazard curve of 17 MiB" "more than the limit of 16 MiB" "$tmp/huge.toml"

# --- smaller ones ----------------------------------------------------------------------------------------
printf '\xef\xbb\xbfSa,rate\n0.05,0.02\n0.1,0.008\n0.2,0.002\n0.4,0.0004\n0.8,0.00005\n1.6,0.000004\n' > "$tmp/bom.csv"
study "$tmp/bom.toml" "$sa" "curve = \"$tmp/bom.csv\""
expect_run "hazard CSV with a UTF-8 byte-order mark and a header" "$tmp/bom.toml"
printf '\xef\xbb\xbf0.05,0.02\n0.1,0.008\n0.2,0.002\n0.4,0.0004\n' > "$tmp/bom2.csv"
study "$tmp/bom2.toml" "$sa" "curve = \"$tmp/bom2.csv\""
expect_run "hazard CSV with a byte-order mark and no header" "$tmp/bom2.toml"
printf 'nan,0.5\n0.1,0.008\n0.2,0.002\n0.4,0.0004\n' > "$tmp/nan.csv"
study "$tmp/nan.toml" "$sa" "curve = \"$tmp/nan.csv\""
expect_error "first row nan,0.5 is not a header" "IM nan is not positive.*nan.csv:1" "$tmp/nan.toml"
study "$tmp/pair.toml" 'measure = "Sa"
period = "pair"
levels = [0.1, 0.2, 0.4]' "k0 = 1e-4
k = 2.5"
sed -i 's/^period = 0.9$/period = 0.005/; s/^period = 1.3$/period = 0.005/' "$tmp/pair.toml"
rc=0; timeout 30 "$bin" run "$tmp/pair.toml" --quiet > /dev/null 2> "$tmp/err" || rc=$?
# the buildings' own range refuses 0.005 s first; period = "pair" must never give a period outside [0.01, 20] s
[ "$rc" -eq 2 ] && grep -q "ERROR:" "$tmp/err" && ok "period = \"pair\" of 0.005 s buildings refused: $(cut -c1-150 "$tmp/err")" \
  || { fail "period pair 0.005 s: exit $rc"; cat "$tmp/err"; }
cat > "$tmp/sds.toml" <<TOML
title = "sds nan"
seed = 5
output = "$tmp/out.h5"
[records]
suite = "builtin"
synthetic_only = true
select = 3
[target_spectrum]
code = "ASCE 7-16"
sds = nan
sd1 = 0.6
TOML
expect_error "sds = nan" "sds = nan is not a finite number.*sds.toml:[0-9]+ \[target_spectrum\]\.sds.*give a finite number" "$tmp/sds.toml"

[ "$fails" -eq 0 ] || { echo "$fails failed"; exit 1; }
echo "all passed"
