#!/usr/bin/env bash
# The report's separations in metres use the study's own code gap coefficient (issue 11, R6): with
# code_gap_coefficient = 0.01, h1 = 30 m, h2 = 40 m, "empirical m" = x * 0.01 * 70 (it used 0.005), and the
# texts name the coefficient. Args: <pounding binary> <source dir>
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
h1 = 30
h2 = 40
targets = [50, 10]
TOML
"$bin" run "$tmp/c.toml" --out "$tmp/c.h5" --quiet > "$tmp/c.md" 2>/dev/null
grep -q "g = x 0.01 (h1 + h2)" "$tmp/c.md" || { echo "FAIL: the separation text does not name 0.01"; exit 1; }
grep -q "| code gap | 0.01 (h1 + h2) |" "$tmp/c.md" || { echo "FAIL: the code rule row does not name 0.01"; exit 1; }
rows=$(awk -F'|' '/^\| (50|10)% \|/ { x = $3 + 0; m = $4 + 0; want = x * 0.01 * 70;
  if (m < want - 0.0011 || m > want + 0.0011) { print "FAIL: x " x " gives " m " m, want " want; bad = 1 } n++ }
  END { if (bad) exit 1; print n }' "$tmp/c.md")
[ "$rows" -eq 2 ] || { echo "FAIL: expected 2 separation rows, got $rows"; cat "$tmp/c.md"; exit 1; }
echo "empirical metres = x * 0.01 * (h1 + h2) on $rows rows"
