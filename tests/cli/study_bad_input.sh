#!/usr/bin/env bash
# Bad study files fail before any work: exit 2, one " ERROR:" line naming file:line and key, no results
# file and no checkpoint left behind. Synthetic twin of study-small.toml (no ../shared needed).
# Args: <pounding binary> <source dir>
set -uo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
base="$tmp/base.toml"
cp "$src/tests/data/study-small-synthetic.toml" "$base"
fails=0; passes=0
expect_error() {  # name, pattern expected in the message, study text
  local name=$1 pattern=$2
  printf '%s\n' "$3" > "$tmp/$name.toml"
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" --quiet > "$tmp/$name.out" 2>&1
  local rc=$?
  if [ $rc -ne 2 ] || ! grep -q "ERROR:" "$tmp/$name.out" || ! grep -q -- "$pattern" "$tmp/$name.out" \
     || [ -e "$tmp/$name.h5" ] || [ -e "$tmp/$name.h5.ckpt" ]; then
    echo "FAIL $name (rc $rc):"; cat "$tmp/$name.out"; fails=$((fails+1))
  else
    echo "ok   $name: $(grep ERROR "$tmp/$name.out")"; passes=$((passes+1))
  fi
}
body=$(cat "$base")
expect_error gap_zero 'ratios' "$(echo "$body" | sed 's/^ratios = .*/ratios = [0.0, 0.5]/')"
expect_error gap_negative 'ratios' "$(echo "$body" | sed 's/^ratios = .*/ratios = [-0.1, 0.5]/')"
expect_error unknown_key 'unknown key .colour' "$(echo "$body" | sed 's/^\[contact\]/[contact]\ncolour = 3/')"
expect_error wrong_type ':.*e must be a number' "$(echo "$body" | sed 's/^e = 0.65/e = "high"/')"
expect_error e_range 'e = 1.5 is out of range' "$(echo "$body" | sed 's/^e = 0.65/e = 1.5/')"
expect_error missing_record 'no_such_record' "$(echo "$body" | sed 's|^suite = "builtin"|files = ["no_such_record.AT2"]|')"
expect_error empty_suite 'no records' "$(echo "$body" | sed 's|^suite = "builtin"|files = []|')"
expect_error height_rule 'T' "$(echo "$body" | sed 's/^samples_per_pair = 8/samples_per_pair = 8\nperiods = [0.5, 1.0]/')"
expect_error no_seed 'seed' "$(echo "$body" | sed '/^seed = /d')"
expect_error bad_law 'law' "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "glue"/')"
expect_error syntax 'syntax' "$(echo "$body" | sed 's/^\[gaps\]/[gaps/')"
expect_error bad_stepper 'unknown stepper' "$(echo "$body" | sed 's/^batch = 3/stepper = "euler"\nbatch = 3/')"
expect_error bad_coarse ':26 \[analysis\].coarse, use "refine".*"exclude".*"keep"' \
  "$(echo "$body" | sed 's/^batch = 3/coarse = "drop"\nbatch = 3/')"
expect_error bad_polarity '\[records\].polarity, use "both".*"recorded"' \
  "$(echo "$body" | sed 's|^suite = "builtin"|suite = "builtin"\npolarity = "negative"|')"
expect_error scale_negative 'scale' "$(echo "$body" | sed 's|^suite = "builtin"|suite = "builtin"\nscale = -1|')"
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
