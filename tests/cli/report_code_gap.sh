#!/usr/bin/env bash
# The report follows the study's own code gap coefficient (issue 11, R6; issue 13): with
# code_gap_coefficient = 0.01 the texts and the coefficient rule's row name 0.01 (not Standard 2800's 0.005), a
# grid study (heights from the period-height rule) gives no separation in metres, and the old [report] h1/h2
# (made-up heights for metres) are refused with a message naming the file, line and the fix.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/c.toml" <<'TOML'
title = "coefficient"
seed = 5
[records]
suite = "builtin"
synthetic_only = true
limit = 3
[structures]
samples_per_pair = 8
code_gap_coefficient = 0.01
[report]
targets = [50, 10]
TOML
"$bin" run "$tmp/c.toml" --out "$tmp/c.h5" --quiet > "$tmp/c.md" 2>/dev/null
grep -q "d = 0.01 (h1 + h2)" "$tmp/c.md" || { echo "FAIL: the text does not name 0.01"; exit 1; }
grep -q "| coefficient rule | \[structures\] code_gap_coefficient | 0.01 (h1 + h2) |" "$tmp/c.md" ||
  { echo "FAIL: the code rule row does not name 0.01"; cat "$tmp/c.md"; exit 1; }
if grep -q "Standard 2800" "$tmp/c.md"; then echo "FAIL: a 0.01 coefficient is called Standard 2800"; exit 1; fi
if grep -qi "separation m\|empirical m" "$tmp/c.md"; then echo "FAIL: a grid study printed metres"; exit 1; fi
rows=$(grep -c '^| \(50\|10\)% | ' "$tmp/c.md")
[ "$rows" -eq 2 ] || { echo "FAIL: expected 2 advice rows in gap ratios, got $rows"; cat "$tmp/c.md"; exit 1; }

# [report] h1/h2 are refused, naming the key, its line and what to write instead
echo "h1 = 30" >> "$tmp/c.toml"  # the last table is [report]
if "$bin" run "$tmp/c.toml" --out "$tmp/d.h5" --quiet > /dev/null 2> "$tmp/err"; then
  echo "FAIL: [report] h1 accepted"; exit 1
fi
grep -q "c.toml:[0-9]*.*\[report\].h1" "$tmp/err" && grep -q "\[structures.building1\] height" "$tmp/err" ||
  { echo "FAIL: the h1 error does not name the key and the fix:"; cat "$tmp/err"; exit 1; }
[ ! -e "$tmp/d.h5" ] || { echo "FAIL: a refused study left a results file"; exit 1; }
echo "coefficient 0.01 named in the text and the rule row; no metres for a grid study; [report] h1 refused"
