#!/usr/bin/env bash
# docs/stability.csv (free-vibration stability limits per stepper, `pounding accuracy stability`) regenerated in
# full by the current engine (~1 s, no records needed) and compared with the stored evidence: a docs number that
# no longer matches the engine fails the suite (issue 12). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin" accuracy stability --no-stiff --out "$tmp/stability.csv" > /dev/null
python3 "$src/tests/docs/compare_csv.py" "$src/docs/stability.csv" "$tmp/stability.csv" --key stepper,zeta \
  --rtol 1e-6 --min-rows 8
