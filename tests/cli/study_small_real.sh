#!/usr/bin/env bash
# The real-record variant of the small study (tests/data/study-small.toml: two PEER files from
# ../shared/records/real, read through [records] files): both records load as real recordings, and 1 rank and
# `mpirun -np 2` give bit-identical results. The other study tests run on its synthetic twin.
# Without ../shared it is skipped (exit 77), under CI=true it fails. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# the study names its records relative to itself (../../../shared/...); point them at $real instead
sed "s|\.\./\.\./\.\./shared/records/real|$real|g" "$src/tests/data/study-small.toml" > "$tmp/study.toml"
"$bin" run "$tmp/study.toml" --out "$tmp/r1.h5" --quiet > "$tmp/r1.md"
mpirun -np 2 "$bin" run "$tmp/study.toml" --out "$tmp/r2.h5" --quiet > /dev/null
/usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/r1.h5" "$tmp/r2.h5"
/usr/bin/python3 - "$tmp/r1.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
ids = sorted(s.decode() if isinstance(s, bytes) else s for s in f["records/id"][()])
assert ids == ["LomaPrieta_1989_Capitola_000", "SuperstitionHills_1987_PoeRoadTemp_270"], ids
assert (f["records/synthetic"][()] == 0).all(), "a real record was replaced by a synthetic one"
print("real records:", ids)
PY
echo "1 passed, 0 failed"
