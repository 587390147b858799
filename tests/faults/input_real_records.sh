#!/usr/bin/env bash
# Issue 10.4: the new record limits (finite values, DT in [1e-4, 0.1] s, NPTS equal to the data, at least 2 s,
# PGA at most 5 g) accept every real record in ../shared/records/real: `records show` reads all of them
# without an error or a warning, and a study over the whole directory (one model each) loads them all.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
src=$2
real=${POUNDING_REAL_RECORDS:-$src/../shared/records/real}
if [ ! -f "$real/MANIFEST.tsv" ]; then
  case "${CI:-}" in
    "" | 0 | false | no) echo "SKIP: needs the real records in ../shared/records/real; see README"; exit 77 ;;
    *) echo "FAIL: CI=$CI but the real records are not in $real"; exit 1 ;;
  esac
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

files=()
while IFS= read -r f; do files+=("$f"); done < <(find "$real" -maxdepth 1 -type f \( -iname '*.at2' -o -iname '*.txt' \) | sort)
want=$(($(wc -l < "$real/MANIFEST.tsv") - 1))
[ "${#files[@]}" = "$want" ] || { echo "FAIL: ${#files[@]} record files but MANIFEST.tsv lists $want"; exit 1; }

rc=0
"$bin" records show "${files[@]}" > "$tmp/show" 2> "$tmp/err" || rc=$?
[ "$rc" = 0 ] || { echo "FAIL: records show exit $rc: $(head -c 400 "$tmp/err")"; exit 1; }
[ ! -s "$tmp/err" ] || { echo "FAIL: records show warned: $(head -c 400 "$tmp/err")"; exit 1; }
[ "$(($(wc -l < "$tmp/show") - 1))" = "$want" ] || { echo "FAIL: records show printed $(wc -l < "$tmp/show") lines"; exit 1; }

printf 'seed = 1\n[records]\ndirectory = "%s"\n[structures]\nperiods = [1.0]\nsamples_per_pair = 1\n' "$real" > "$tmp/all.toml"
rc=0
"$bin" run "$tmp/all.toml" --out "$tmp/all.h5" --quiet > "$tmp/out" 2> "$tmp/err" || rc=$?
[ "$rc" = 0 ] || { echo "FAIL: study over every real record: exit $rc: $(head -c 400 "$tmp/err")"; exit 1; }
grep -q "($want records" "$tmp/err" "$tmp/out" || { echo "FAIL: the study did not load $want records: $(head -c 300 "$tmp/err")"; exit 1; }
echo "input_real_records: all $want real records pass the record limits"
