#!/usr/bin/env bash
# Bad [intensity] and [hazard] sections fail before any work (issue 14): exit 2, one " ERROR:" line naming the
# file, line and key (a hazard CSV: its own file:line), no results file and no checkpoint left behind.
# Args: <pounding binary> <source dir>
set -uo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
impacts=$(cat "$src/tests/data/study-small-synthetic.toml")  # scene = "impacts"
body=$(echo "$impacts" | sed 's/^scene = "impacts"/scene = "probability"/')
fails=0; passes=0
expect_error() {  # name, pattern expected in the message, sections appended to the base study
  local name=$1 pattern=$2
  printf '%s\n%s\n' "$body" "$3" > "$tmp/$name.toml"
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" --quiet > "$tmp/$name.out" 2>&1
  local rc=$?
  if [ $rc -ne 2 ] || ! grep -q "ERROR:" "$tmp/$name.out" || ! grep -q -- "$pattern" "$tmp/$name.out" \
     || [ -e "$tmp/$name.h5" ] || [ -e "$tmp/$name.h5.ckpt" ]; then
    echo "FAIL $name (rc $rc):"; cat "$tmp/$name.out"; fails=$((fails+1))
  else
    echo "ok   $name: $(grep ERROR "$tmp/$name.out")"; passes=$((passes+1))
  fi
}
I='[intensity]
measure = "Sa"
period = 1.0'
expect_error levels_order 'strictly increasing.*\[intensity\].levels' "$I
levels = [0.2, 0.1, 0.3]"
expect_error levels_missing '\[intensity\].levels' "$I"
expect_error level_absurd 'levels.*out of range' "$I
levels = [0.1, 50.0]"
expect_error one_stripe 'at least two stripes' "$I
levels = [0.3]"
expect_error sa_no_period 'Sa needs a period' '[intensity]
measure = "Sa"
levels = [0.1, 0.2]'
expect_error sa_avg_one_period 'Sa_avg needs at least two periods' '[intensity]
measure = "Sa_avg"
periods = [1.0]
levels = [0.1, 0.2]'
expect_error pga_period 'PGA takes no period' '[intensity]
measure = "PGA"
period = 1.0
levels = [0.1, 0.2]'
expect_error bad_measure 'unknown measure .PGD.' '[intensity]
measure = "PGD"
levels = [0.1, 0.2]'
expect_error max_scale 'max_scale' "$I
levels = [0.1, 0.2]
max_scale = 0.5"
expect_error ida_tolerance 'tolerance.*out of range' "$I
levels = [0.1, 0.2]
method = \"ida\"
tolerance = 0.9"
expect_error msa_tolerance 'tolerance is for method = \"ida\"' "$I
levels = [0.1, 0.2]
tolerance = 0.01"
expect_error hazard_alone '\[hazard\] needs fragility curves' '[hazard]
k0 = 1e-4
k = 2.5'
expect_error hazard_both 'both a curve and a power law' "$I
levels = [0.1, 0.2]
[hazard]
curve = \"h.csv\"
k0 = 1e-4
k = 2.5"
printf 'Sa_g,annual_rate\n0.1,0.01\n0.2,0.02\n' > "$tmp/up.csv"
expect_error hazard_increasing 'must decrease.*up.csv:3' "$I
levels = [0.1, 0.2]
[hazard]
curve = \"up.csv\""
expect_error hazard_missing 'cannot read the hazard curve' "$I
levels = [0.1, 0.2]
[hazard]
curve = \"nowhere.csv\""
expect_error hazard_target 'target = 1e-09 is out of range.*\[hazard\].target.*\[0.0001, 99\]' "$I
levels = [0.1, 0.2]
[hazard]
k0 = 1e-4
k = 2.5
target = 1e-9"
expect_error hazard_years 'years = 0 is out of range.*\[hazard\].years' "$I
levels = [0.1, 0.2]
[hazard]
k0 = 1e-4
k = 2.5
years = 0"
expect_error hazard_slope 'k = -2 is out of range.*\[hazard\].k' "$I
levels = [0.1, 0.2]
[hazard]
k0 = 1e-4
k = -2"
# a hazard table wholly above or below the stripes (here in thousandths of g, and in g/1000): the rate would be all
# extrapolation (issue 24, item 4: 177 poundings a year, "100 % from beyond the hazard table", exit 0)
printf 'Sa_g,annual_rate\n100,0.1\n300,0.01\n1000,0.001\n' > "$tmp/high.csv"
expect_error hazard_above 'covers IM 100 to 1000, wholly above the stripes. levels 0.1 to 0.2.*\[hazard\].curve.*units' "$I
levels = [0.1, 0.2]
[hazard]
curve = \"high.csv\""
printf 'Sa_g,annual_rate\n0.0001,0.1\n0.0003,0.01\n0.001,0.001\n' > "$tmp/low.csv"
expect_error hazard_below 'wholly below the stripes' "$I
levels = [0.1, 0.2]
[hazard]
curve = \"low.csv\""
body=$impacts expect_error impacts_scene 'runs in the probability scene' "$I
levels = [0.1, 0.2]"
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
