#!/usr/bin/env bash
# [contact] gap_offsets and levels in studies (docs/architecture.md §2.7.1; shear buildings and rows):
#  1. gap_offsets: every level's coupled gap is the study gap + its offset (levels beyond the list: 0); the
#     probability scene stays exact: an analysis touches at g exactly when max over elements of (uncoupled closing -
#     offset) > g, which is /uncoupled/peak_closing; /system/element_gap_offset holds the offsets; the run at 1 and 2
#     ranks is bit-identical; offsets of 0 change no result bit;
#  2. levels = "top": one element per pair of neighbours (the lower roof), D = its closing;
#  3. bad input: negative or absurd offsets, an unknown levels name, either key for an SDOF pair: one ERROR naming
#     file:line and the key, exit 2, nothing written.
# Synthetic records only. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, expect_error
# quick-storeys (9-16 storeys, impacts scene) with every model rerun with contact
sed 's/^\[contact\]/[analysis]\nskip_untouched = false\n\n[contact]/' "$src/studies/quick-storeys.toml" > "$tmp/base.toml"
grep -q '^e = 0.65' "$tmp/base.toml"

# 1. offsets: level 1..3 +3 cm, +1 cm, 0; 4..8 +2 cm; above 8: 0
sed 's/^e = 0.65/e = 0.65\ngap_offsets = [0.03, 0.01, 0.0, 0.02, 0.02, 0.02, 0.02, 0.02]/' "$tmp/base.toml" > "$tmp/off.toml"
"$bin" run "$tmp/base.toml" --out "$tmp/base.h5" --quiet > /dev/null 2>&1
"$bin" run "$tmp/off.toml" --out "$tmp/off.h5" --quiet > /dev/null 2>&1
timeout 120 mpirun -np 2 "$bin" run "$tmp/off.toml" --out "$tmp/off2.h5" --quiet > /dev/null 2>&1
cmp "$tmp/off.h5" "$tmp/off2.h5"
/usr/bin/python3 - "$tmp/base.h5" "$tmp/off.h5" <<'PY'
import sys, h5py, numpy as np
b, f = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
R, M = f["uncoupled/peak_closing"].shape
G = len(f["impacts/gap_ratios"])
x, d = f["impacts/gap_ratios"][()], f["models/code_gap"][()]
level = f["system/element_level"][()]
off = f["system/element_gap_offset"][()]
want = np.array([[0.03, 0.01, 0.0, 0.02, 0.02, 0.02, 0.02, 0.02][l - 1] if l <= 8 else 0.0 for l in level])
assert np.array_equal(off, want), (off, want)
el = f["uncoupled/peak_closing_elements"][()]
# the uncoupled run does not depend on the gap: the raw closings are the base study's bit for bit
assert np.array_equal(el, b["uncoupled/peak_closing_elements"][()], equal_nan=True)
D = np.nanmax(el - off[None, None, :], axis=2)
assert np.array_equal(D, f["uncoupled/peak_closing"][()])
assert (D < b["uncoupled/peak_closing"][()]).any()
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
assert (f["impacts/status"][()] == 0).all()
touch = D[:, :, None] > x[None, None, :] * d[None, :, None]
assert np.array_equal(touch, cnt > 0), (touch.sum(), (cnt > 0).sum())
assert 0 < touch.sum() < touch.size
# the first impact happens at a level whose own uncoupled closing exceeds its own gap (before it the coupled run
# is the uncoupled one)
ec = f["impacts/element_impact_count"][()].reshape(R, M, G, -1)
t1 = f["impacts/element_t_first_impact"][()].reshape(R, M, G, -1)
own = el[:, :, None, :] - off[None, None, None, :] > (x[None, None, :] * d[None, :, None])[:, :, :, None]
first = np.where(np.isnan(t1), np.inf, t1)
k = np.argmin(first, axis=3)
hit = np.isfinite(np.min(first, axis=3))
assert np.take_along_axis(own, k[..., None], axis=3)[..., 0][hit].all()
pen = f["impacts/element_peak_penetration"][()].reshape(R, M, G, -1)
assert (np.nan_to_num(pen) >= 0).all()
fewer = (cnt > 0).sum(), (b["impacts/impact_count"][()] > 0).sum()
assert fewer[0] < fewer[1], fewer
print(f"offsets: {fewer[0]} of {touch.size} analyses pound (without offsets {fewer[1]})")
PY
sed 's/^e = 0.65/e = 0.65\ngap_offsets = [0.0]/' "$tmp/base.toml" > "$tmp/zero.toml"
"$bin" run "$tmp/zero.toml" --out "$tmp/zero.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 - "$tmp/base.h5" "$tmp/zero.h5" <<'PY'
import sys, h5py, numpy as np
b, f = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
for g in ("uncoupled", "impacts"):
    for k in b[g]:
        if isinstance(b[g][k], h5py.Dataset):
            assert np.array_equal(b[g][k][()], f[g][k][()], equal_nan=True), (g, k)
print("offsets of 0: every uncoupled and impacts dataset bit for bit")
PY
sed 's/^e = 0.65/e = 0.65\ngap_offsets = [10.0]/' "$tmp/base.toml" > "$tmp/far.toml"
"$bin" run "$tmp/far.toml" --out "$tmp/far.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 - "$tmp/far.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
lv = f["system/element_level"][()]
el, off = f["uncoupled/peak_closing_elements"][()], f["system/element_gap_offset"][()]
assert (off[lv == 1] == 10.0).all() and (off[lv > 1] == 0.0).all()
assert np.array_equal(f["uncoupled/peak_closing"][()], np.nanmax(el - off, axis=2))
print("a 10 m offset at level 1: level 1 never decides; the others as without it")
PY

# 2. levels = "top": the lower roof only
sed 's/^e = 0.65/e = 0.65\nlevels = "top"/' "$tmp/base.toml" > "$tmp/top.toml"
"$bin" run "$tmp/top.toml" --out "$tmp/top.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 - "$tmp/base.h5" "$tmp/top.h5" <<'PY'
import sys, h5py, numpy as np
b, f = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
el_b, el_t = b["uncoupled/peak_closing_elements"][()], f["uncoupled/peak_closing_elements"][()]
have = ~np.isnan(el_t)
assert (have.sum(axis=2) == 1).all(), "one element (the lower roof) per analysis"
# the lower roof is the highest level the base study's analysis has: the same closing there
top_b = np.array([[row[~np.isnan(row)][-1] for row in m] for m in el_b])
assert np.array_equal(np.nanmax(el_t, axis=2), top_b)
assert np.array_equal(f["uncoupled/peak_closing"][()], top_b)
assert (top_b <= b["uncoupled/peak_closing"][()]).all()
print("levels = top: the lower roof's closing decides")
PY

# 3. bad input
fails=0
body=$(cat "$tmp/base.toml")
expect_error offset_negative '\[contact\].gap_offsets' "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\ngap_offsets = [0.01, -0.02]/')"
expect_error offset_absurd '\[contact\].gap_offsets' "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\ngap_offsets = [50.0]/')"
expect_error offset_text '\[contact\].gap_offsets' "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\ngap_offsets = ["a"]/')"
expect_error levels_name 'unknown levels .middle.*\[contact\].levels, write levels = "common" or "top"' \
  "$(echo "$body" | sed 's/^e = 0.65/e = 0.65\nlevels = "middle"/')"
pair=$(sed 's/^model = "shear"/model = "sdof"/; s/^storey_height = 3.2/storey_height = 3.2/' "$tmp/base.toml")
expect_error offsets_pair 'gap_offsets is given, and the study is a pair of SDOF buildings.*\[contact\].gap_offsets, give the buildings storeys' \
  "$(echo "$pair" | sed 's/^e = 0.65/e = 0.65\ngap_offsets = [0.01]/')"
expect_error levels_pair 'levels is given, and the study is a pair of SDOF buildings.*\[contact\].levels' \
  "$(echo "$pair" | sed 's/^e = 0.65/e = 0.65\nlevels = "top"/')"
[ $fails -eq 0 ]
echo "1 passed, 0 failed"
