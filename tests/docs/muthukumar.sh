#!/usr/bin/env bash
# docs/muthukumar.csv and docs/muthukumar_sensitivity.csv (docs/validation.md) regenerated in part with the
# current engine: `validate-muthukumar --levels/--ratios` reproduces the stored rows of that band and ratio
# exactly (the band means are sums over the same records in the same order), so sampled rows are compared
# with tests/docs/compare_csv.py. The sampled selections:
#   docs/muthukumar.csv                  high band (5 records), T1/T2 = 0.3, the 7 models
#   docs/muthukumar_sensitivity.csv      all records, T2 = 2 s, Kelvin x 0.5: high band, T1/T2 = 0.5
#                                        matched records, T2 = 0.5 s, Kelvin x 2: high band (3 records), T1/T2 = 0.3
# Tolerance: the CSVs hold 5 significant digits; rtol 2e-4 leaves room for the last-digit rounding of a lane
# computed in a batch of another width, and catches any change of the physics, the records or the selection.
# Also: a bad option is refused (exit 2, the option named, no CSV written).
#   muthukumar.sh <pounding binary> <source dir>     (exit 77: skipped, no real records)
set -euo pipefail
bin=$1
src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmp_py="$src/tests/docs/compare_csv.py"
run() { "$bin" accuracy --records-dir "$real" validate-muthukumar "$@" > /dev/null; }
fail=0

run --levels high --ratios 0.3 --out "$tmp/main.csv"
python3 "$cmp_py" "$src/docs/muthukumar.csv" "$tmp/main.csv" --key level,period_ratio,model,e \
  --tol disp_amp=2e-4 --tol acc_amp=2e-4 --min-rows 7 || fail=1

sens() {  # <records set> <T2> <kelvin scale> <level> <ratio>
  local sel=()
  [ "$1" = all ] || sel=(--records "$1")
  run "${sel[@]}" --T2 "$2" --kelvin-scale "$3" --levels "$4" --ratios "$5" --out "$tmp/s.csv"
  { echo "records_set,T2,kelvin_scale,$(head -1 "$tmp/s.csv")"; tail -n +2 "$tmp/s.csv" | sed "s/^/$1,$2,$3,/"; } \
    > "$tmp/sens_$1.csv"
  python3 "$cmp_py" "$src/docs/muthukumar_sensitivity.csv" "$tmp/sens_$1.csv" \
    --key records_set,T2,kelvin_scale,level,period_ratio,model,e --tol disp_amp=2e-4 --tol acc_amp=2e-4 \
    --min-rows 7 || fail=1
}
sens all 2 0.5 high 0.5
sens matched 0.5 2 high 0.3

# bad input: exit 2, the option named, nothing written
set +e
run --ratios 0.4 --out "$tmp/bad.csv" 2> "$tmp/err"
rc=$?
set -e
if [ $rc -ne 2 ] || ! grep -q -- "--ratios" "$tmp/err" || [ -e "$tmp/bad.csv" ]; then
  echo "FAIL: --ratios 0.4 gave exit $rc, stderr: $(cat "$tmp/err")"
  fail=1
fi
exit $fail
