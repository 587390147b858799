#!/usr/bin/env bash
# studies/quick.toml's suite with real_dir = ../shared/records/real: exactly the four records present there
# resolve to real files, the other 21 stay synthetic stand-ins. Without ../shared it is skipped (exit 77),
# under CI=true it fails. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed -e "s|^synthetic_only = true|real_dir = \"$real\"|" -e 's/^samples_per_pair = 32/samples_per_pair = 2/' \
    -e "s|\.\./records/|$src/records/|" "$src/studies/quick.toml" > "$tmp/real.toml"
"$bin" run "$tmp/real.toml" --out "$tmp/real.h5" --quiet > "$tmp/real.md" 2>/dev/null
grep -q "25 records (21 synthetic stand-ins, 4 real)" "$tmp/real.md"
/usr/bin/python3 - "$tmp/real.h5" <<'PY'
import sys, h5py
r = h5py.File(sys.argv[1], "r")
ids = [s.decode() if isinstance(s, bytes) else s for s in r["records/id"][()]]
real = [i for i, s in zip(ids, r["records/synthetic"][()]) if s == 0]
assert sorted(real) == ["EQ15", "EQ2", "EQ3", "EQ6"], real
print("real records:", real)
PY
echo "1 passed, 0 failed"
