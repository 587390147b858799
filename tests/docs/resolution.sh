#!/usr/bin/env bash
# docs/resolution.csv and docs/resolution_limits.csv (`pounding accuracy resolution`: one free impact per stepper x
# force law swept over h omega_c 0.01..2, the resolution guard's limits) regenerated in full (~0.5 s) and compared
# with the stored evidence; the limits exactly. The code's table equals them: AccuracyStability.
# ResolutionLimitsEqualTheMeasurement. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin" accuracy resolution --out "$tmp/resolution.csv" --limits-out "$tmp/limits.csv" > /dev/null
python3 "$src/tests/docs/compare_csv.py" "$src/docs/resolution.csv" "$tmp/resolution.csv" --key scheme,law,steps \
  --rtol 1e-6 --tol force_error=1e-4:1e-9 --tol e_error=1e-4:1e-9 --min-rows 1000
python3 "$src/tests/docs/compare_csv.py" "$src/docs/resolution_limits.csv" "$tmp/limits.csv" --key scheme,law \
  --rtol 0 --tol first_over_h_omega=1e-6 --min-rows 25
