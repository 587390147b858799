#!/usr/bin/env bash
# tools/bridge_joint.py (issue 26 §2, docs/bridge-joint.md) on 4 realisations per case: identical spans under
# uniform input never close the joint (P = 0 at every gap > 0: the spans move in phase -- fails if the uniform
# run used the other support's record or the spans differed), under spatially varying input they always do at
# gap 0 and the probability never rises with the gap; different spans (T2 = 0.7 s) pound under uniform input too.
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import numpy, scipy' 2>/dev/null ||
  skip_or_fail "needs $py with numpy and scipy (Debian: python3-numpy python3-scipy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
"$py" "$src/tools/bridge_joint.py" --pounding "$bin" --out "$tmp/bj" --realisations 4 --gaps 0,0.05,0.1,0.2 > /dev/null
awk -F, 'NR > 1 {
  if ($2 > 0 && $4 != 0) { print "uniform input closed the joint of identical spans: " $0; bad = 1 }
  if ($2 == 0 && $3 != 1) { print "spatially varying input left gap 0 open: " $0; bad = 1 }
  if ($1 == prev && $3 > last + 1e-12) { print "P rises with the gap: " $0; bad = 1 }
  prev = $1; last = $3 } END { exit bad }' "$tmp/bj/bridge-joint.csv" || fail "identical spans (above)"
[ "$(grep -c ',' "$tmp/bj/bridge-joint.csv")" = 21 ] || fail "want 5 cases x 4 gaps + header: $(cat "$tmp/bj/bridge-joint.csv")"
"$py" "$src/tools/bridge_joint.py" --pounding "$bin" --out "$tmp/bj" --realisations 4 --gaps 0 --period2 0.7 > /dev/null
awk -F, 'NR > 1 && $4 != 1 { print "different spans under uniform input did not close gap 0: " $0; bad = 1 } END { exit bad }' \
  "$tmp/bj/bridge-joint.csv" || fail "different spans (above)"
echo "bridge_joint: ok"
