#!/usr/bin/env bash
# The README's main job (studies/quick.toml, synthetic stand-ins of the paper's suite) on 2 ranks. The same
# suite resolved to the real records of ../shared/records/real is study_quick_real.sh.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpirun -np 2 "$bin" run "$src/studies/quick.toml" --out "$tmp/quick.h5" --quiet > "$tmp/quick.md" 2> "$tmp/quick.err"
grep -q "25 records (25 synthetic stand-ins, 0 real)" "$tmp/quick.md"
grep -q "record EQ13: synthetic stand-in" "$tmp/quick.err"
/usr/bin/python3 - "$tmp/quick.h5" <<'PY'
import sys, h5py, numpy as np
q = h5py.File(sys.argv[1], "r")
pc = q["uncoupled/peak_closing"][()]
d = q["models/code_gap"][()]
ok = q["uncoupled/status"][()].reshape(pc.shape) == 0
assert ok.all(), "diverged lanes in the quick study"
p = [np.mean(pc[ok.reshape(pc.shape)] > x * np.broadcast_to(d, pc.shape)[ok]) for x in (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)]
assert all(a >= b for a, b in zip(p, p[1:])), p          # probability falls with the gap
assert 0.3 < p[0] < 0.99 and p[-1] < 0.05, p            # pounding at 0.1 d common, rare at the code gap
print("quick: P =", [round(100 * x, 2) for x in p], "%")
PY
echo "1 passed, 0 failed"
