#!/usr/bin/env bash
# Per-joint gap offsets of a row ([contact] joint_gap_offsets = [...], m per joint left to right; issue 25 §2 rows,
# docs/rows.md):
#  1. quick-row with joint_gap_offsets = [0, 0.04] is bit-identical at 1 and 2 ranks, batch width 1 and
#     skip_untouched = false;
#  2. the probability scene stays exact: /system/element_gap_offset holds 0.04 on joint 2|3's element and 0 on 1|2's;
#     uncoupled/peak_closing = max over elements of (closing - offset); with skip_untouched = false every analysis
#     runs coupled and an analysis has impacts at gap g exactly when that D > g (first passage) -- among them analyses
#     whose joint 2|3 closes past g but within g + 0.04 while joint 1|2 stays open: no impact, which a coupled run
#     without the offset would break; the results differ from the study without offsets;
#  3. bad input: a pair, the wrong count, a negative offset: one ERROR naming the key, exit 2, no results.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$PWD/unused.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, expect_error
fail() { echo "FAIL: $*"; exit 1; }

sed 's/^e = 0.65/e = 0.65\njoint_gap_offsets = [0.0, 0.04]/' "$src/studies/quick-row.toml" > "$tmp/joints.toml"
grep -q '^joint_gap_offsets' "$tmp/joints.toml" || fail "joints.toml: no joint_gap_offsets line"
study=$tmp/joints.toml
study_invariance
"$bin" run "$src/studies/quick-row.toml" --out "$tmp/plain.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 - "$tmp/full.h5" "$tmp/plain.h5" <<'PY'
import sys, h5py, numpy as np
f, plain = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
off = f["system/element_gap_offset"][()]
want = np.array([0.04 if l.startswith("2|3") else 0.0 for l in labels])
assert np.array_equal(off, want), (labels, off)
ec = f["uncoupled/peak_closing_elements"][()]            # [R, M, E]
D = f["uncoupled/peak_closing"][()]                      # [R, M]
ok = f["uncoupled/status"][()] == 0
assert np.array_equal(np.max(ec - off, axis=-1)[ok], D[ok]), "peak_closing is not max(closing - offset)"
d = f["models/code_gap"][()]                             # [M]
ratios = f["impacts/gap_ratios"][()]
count = f["impacts/impact_count"][()]                    # [R, M, G]
elem = f["impacts/element_impact_count"][()]             # [R, M, G, E]
j2 = np.array([l.startswith("2|3") for l in labels])
between = 0
for gi, x in enumerate(ratios):
    g = x * d[None, :]
    touch = D > g
    c = count[:, :, gi]
    assert np.array_equal((c > 0)[ok], touch[ok]), f"x = {x}: impacts where D <= g, or none where D > g"
    # joint 2|3 closes past g but within its offset, and nothing else touches: no impact anywhere (coupled runs
    # without the offset would have impacts there)
    raw = np.max(ec[:, :, j2], axis=-1)
    quiet = ok & (raw > g) & ~touch
    assert (c[quiet] == 0).all() and (elem[:, :, gi][quiet] == 0).all()
    between += int(quiet.sum())
assert between > 0, "no analysis has joint 2|3's closing within the offset: the test cannot tell"
assert not np.array_equal(f["impacts/impact_count"][()], plain["impacts/impact_count"][()]), "the offsets changed nothing"
print(f"ok   exact with joint offsets: {between} (analysis, gap) cases with joint 2|3's closing in (g, g + 0.04], "
      f"the rest open, and no impact; D = max(closing - offset)")
PY

fails=0
body=$(cat "$src/studies/quick-row.toml")
expect_error pair 'joint_gap_offsets is given, and the study is a pair.*\[contact\].joint_gap_offsets' \
  "$(echo "$body" | sed -e 's/^buildings = 3/buildings = 2/' -e '/^\[structures.building3\]/,/^period = /d' \
       -e 's/^e = 0.65/e = 0.65\njoint_gap_offsets = [0.01]/')"
expect_error count 'joint_gap_offsets has 1 values, and the row of 3 buildings has 2 joints.*\[contact\].joint_gap_offsets' \
  "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\njoint_gap_offsets = [0.01]/')"
expect_error negative '\[contact\].joint_gap_offsets' "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\njoint_gap_offsets = [0.01, -0.01]/')"
[ $fails -eq 0 ] || exit 1
