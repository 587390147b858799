#!/usr/bin/env bash
# Every rank selects the same records bit for bit ([records] select, load_study_records): a selecting study
# (tests/data/study-select-pair.toml, 11 of the builtin synthetic suite to ASCE 7-16) writes the same datasets and
# /selection attributes at 1 and 2 MPI ranks. Needs h5py. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null || skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
{ cat "$src/tests/data/study-select-pair.toml"
  printf '[records]\nsuite = "builtin"\nsynthetic_only = true\nselect = 11\n'
  printf '[target_spectrum]\ncode = "ASCE 7-16"\nsds = 1.0\nsd1 = 0.6\ntl = 8.0\n'
} > "$tmp/s.toml"
mpirun -np 1 "$bin" run "$tmp/s.toml" --out "$tmp/r1.h5" --quiet > /dev/null
mpirun -np 2 "$bin" run "$tmp/s.toml" --out "$tmp/r2.h5" --quiet > /dev/null
"$py" - "$tmp/r1.h5" "$tmp/r2.h5" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1]), h5py.File(sys.argv[2])
names = []
a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) and not n.startswith(("settings", "timing")) else None)  # timing: seconds
assert "selection/scale" in names, names
bad = [n for n in names if not np.array_equal(a[n][()], b[n][()], equal_nan=a[n].dtype.kind == "f")]
assert not bad, ("1 and 2 ranks differ", bad)
assert dict(a["selection"].attrs) == dict(b["selection"].attrs)
print(f"study_select_ranks: ok, 1 and 2 ranks: {len(names)} datasets bit-identical")
PY
