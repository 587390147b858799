#!/usr/bin/env bash
# docs.restitution (issue 12): docs/restitution.csv is what the current engine prints. Regenerates sampled rows
# (`pounding accuracy restitution --laws ... --targets ...`: the same single free impact through the kernel,
# rk4, as the full table) and compares them with the stored CSV (tests/docs/compare_csv.py). Then plants the
# smallest printed change in one stored cell per law and checks that the comparison fails.
#
# Tolerance: e_effective is deterministic (the kernel is bit-identical, ctest KernelDigests) and printed to 8
# significant digits: rtol 1e-6 passes only the same value to ~6 digits (the docs quote 3; a non-FMA build's
# round-off, ~1e-12, stays far inside); clamps (the count of clamped steps) exactly. Needs no records: the impact is a free one.
# Usage: restitution.sh <pounding binary> <source dir>
set -uo pipefail
bin=${1:?pounding binary}
src=${2:?source dir}
. "$src/tests/lib/needs_real_records.sh"  # for scaled_timeout only
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stored="$src/docs/restitution.csv"
laws=lankarani-nikravesh,hunt-crossley,flores,hu-guo,gonthier,calibrated,ye,three-spring,jankowski,kelvin
targets=0.1,0.3,0.65,0.95
nrows=40
compare() {
  python3 "$src/tests/docs/compare_csv.py" "$1" "$work/rows.csv" --key law,e_target --cols e_effective,clamps \
    --rtol 1e-6 --tol clamps=0:0 --min-rows "$nrows"
}

if ! timeout "$(scaled_timeout 120)" "$bin" accuracy restitution --laws "$laws" --targets "$targets" \
    --out "$work/rows.csv" >"$work/out" 2>"$work/err"; then
  echo "FAIL: accuracy restitution --laws --targets failed: $(cat "$work/err")"
  exit 1
fi
if ! compare "$stored"; then
  echo "FAIL: docs/restitution.csv differs from the current engine; regenerate it (docs/accuracy.md section 3)"
  exit 1
fi
echo "ok:   $nrows rows of docs/restitution.csv regenerate"

# negative control: e_effective of one row per law, one unit of its 6th significant digit (1e-6..1e-5
# relative, just above the tolerance)
fails=0
for law in ${laws//,/ }; do
  python3 "$src/tests/docs/plant.py" "$stored" "$work/planted.csv" --where "law=$law,e_target=0.65" --col e_effective --digit 6 ||
    { echo "FAIL: cannot plant in $law"; fails=$((fails + 1)); continue; }
  if compare "$work/planted.csv" >"$work/cmp"; then
    echo "FAIL: a planted change in $law e_effective at 0.65 was not detected"
    fails=$((fails + 1))
  else
    echo "ok:   planted change detected: $(grep '^DIFF' "$work/cmp")"
  fi
done
[[ $fails -eq 0 ]]
