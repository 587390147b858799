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
# The report's tables (Table 2 per record, Table 3 with Wilson intervals, the cubic of eq. 10, the separation
# advice and the code rules) are the README's numbers: they must match the stored report to the last printed
# digit (results are bit-identical for any rank count). A deliberate change regenerates the stored file:
#   mpirun -np 2 build/pounding run studies/quick.toml --out /tmp/q.h5 --quiet > /tmp/q.md
#   sed -n '/^## Probability of at least one impact per record/,$p' /tmp/q.md > tests/data/report/quick_report_tables.md
sed -n '/^## Probability of at least one impact per record/,$p' "$tmp/quick.md" > "$tmp/tables.md"
if [[ ${POUNDING_KERNEL_ARCH:-native} == OFF ]]; then
  # the stored report was computed with FMA contraction (as the kernel digests); without it a verdict on the
  # edge may flip, so the exact comparison does not apply to this build
  echo "skip: exact tables (POUNDING_KERNEL_ARCH=OFF: no FMA contraction, the stored report needs it)"
elif ! diff -u "$src/tests/data/report/quick_report_tables.md" "$tmp/tables.md" > "$tmp/tables.diff"; then
  echo "FAIL: the quick study's report tables differ from tests/data/report/quick_report_tables.md:"
  head -40 "$tmp/tables.diff"
  exit 1
else
  echo "ok:   Table 2, Table 3, cubic, separation and code-rule tables identical to the stored report"
fi
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
echo "2 passed, 0 failed"
