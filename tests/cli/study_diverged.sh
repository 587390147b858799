#!/usr/bin/env bash
# A contact far too stiff for the time step makes the touching pairs diverge (stability guard): they are
# excluded with a visible count and their identity, never counted as "no impact"; the uncoupled
# probability table is unaffected. Synthetic twin of study-small.toml (no ../shared needed).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed -e 's/^law = "hertzdamp"/law = "linear"\nstiffness = 1e14/' \
    -e 's/^samples_per_pair = 8/samples_per_pair = 2/' "$src/tests/data/study-small-synthetic.toml" > "$tmp/stiff.toml"
# far more than max_excluded_fraction (0.1 %) of the analyses diverge: the run says so with exit code 3
rc=0; "$bin" run "$tmp/stiff.toml" --out "$tmp/stiff.h5" --quiet > "$tmp/stiff.md" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || { echo "FAIL: exit code $rc (want 3: too many excluded analyses)"; exit 1; }
/usr/bin/python3 - "$tmp/stiff.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
R, M = f["uncoupled/peak_closing"].shape
G = len(f["impacts/gap_ratios"])
st = f["impacts/status"][()].reshape(R, M, G)
pc = f["uncoupled/peak_closing"][()]
d = f["models/code_gap"][()]
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
touch = pc[:, :, None] > f["impacts/gap_ratios"][()][None, None, :] * d[None, :, None]
assert (st[touch] != 0).all(), "a touching pair with a hopeless contact stiffness was returned as a result"
assert (st[~touch] == 0).all()
assert (cnt[st != 0] == -1).all() and np.isnan(f["impacts/peak_force"][()].reshape(R, M, G)[st != 0]).all()
print(f"{(st != 0).sum()} diverged (record, model, gap) analyses, all of them touching pairs")
PY
grep -q "| 0.1 | .* | .* | .* | .* | .* | .* | [1-9][0-9]* |" "$tmp/stiff.md"   # excluded column of the impacts table
grep -q "excluded (diverged or non-finite) analyses: \*\*0\*\*" "$tmp/stiff.md"  # uncoupled runs are all fine
grep -q "Excluded coupled analyses (diverged or non-finite, never counted as results): \*\*[1-9]" "$tmp/stiff.md"
grep -q "at gap ratio 0.1: diverged" "$tmp/stiff.md"
echo "1 passed, 0 failed"
