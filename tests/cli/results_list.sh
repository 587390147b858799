#!/usr/bin/env bash
# `pounding results FILE` lists every dataset of a results file with its type, shape, units and description; a
# pair study's file is format 2 with no /system and no per-floor dataset (format 3 is for other systems: its
# listing is checked by Results.InventoryListsEveryDatasetWithShapeAndUnits); a file that is not HDF5 is one
# clear error, exit 2. Runs on the synthetic study (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin" run "$src/tests/data/study-small-synthetic.toml" --out "$tmp/r.h5" --quiet > /dev/null
"$bin" results "$tmp/r.h5" > "$tmp/list.txt"
head -1 "$tmp/list.txt" | grep -q "^$tmp/r.h5: format 2, [0-9]* datasets" || { head -3 "$tmp/list.txt"; exit 1; }
grep -Eq '^/uncoupled/peak_closing +f64 +\[[0-9]+,[0-9]+\] +m +peak closing' "$tmp/list.txt"
grep -Eq '^/impacts/impact_count +i32 +\[[0-9]+,[0-9]+,6\] +1 ' "$tmp/list.txt"  # 6 gap ratios
grep -Eq '^/records/id +string +\[[0-9]+\] +1 ' "$tmp/list.txt"
if grep -Eq '^/system/|peak_u_floors|element_' "$tmp/list.txt"; then echo "format 3 items in a pair's file"; exit 1; fi
# one line per dataset (path, type, shape, units, description), each with units and description
n=$(head -1 "$tmp/list.txt" | sed 's/.*format 2, \([0-9]*\) datasets.*/\1/')
[ "$(($(wc -l < "$tmp/list.txt") - 2))" -eq "$n" ]
if awk 'NR > 2 && ($4 == "-" || $5 == "-")' "$tmp/list.txt" | grep -q .; then echo "a dataset without units"; exit 1; fi
# not a results file
echo "not hdf5" > "$tmp/bad.h5"
set +e
"$bin" results "$tmp/bad.h5" > "$tmp/out.txt" 2> "$tmp/err.txt"; rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "exit $rc"; cat "$tmp/err.txt"; exit 1; }
grep -q "ERROR: cannot open HDF5 file" "$tmp/err.txt"
[ ! -s "$tmp/out.txt" ]
echo "1 passed, 0 failed"
