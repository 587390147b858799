#!/usr/bin/env bash
# tools/plot_study.py on a study in which no pair touches at some of the plotted gap ratios (k = 0 impacts):
# the Wilson interval's bounds must not fall a rounding error on the wrong side of k/n (matplotlib refused the
# negative yerr and the script crashed; issue 10). Both PNGs must be written. Then a pair study (both heights
# given): <prefix>-separation.png at 200 dpi (from `pounding report --csv`) and the --format svg copy. Needs Debian's python3-matplotlib,
# -h5py and -numpy: skipped (exit 77) without them, a failure under CI=true. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import matplotlib, h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with matplotlib, h5py and numpy (Debian: python3-matplotlib python3-h5py python3-numpy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# one synthetic record at a tenth of its PGA, 121 period pairs x 3 samples = 363 analyses: 363 is one of the
# sample sizes for which the unclipped lower Wilson bound at k = 0 comes out a few ulp above 0
cat > "$tmp/calm.toml" <<'TOML'
title = "plot test: weak shaking, no impacts at the larger gap ratios"
seed = 7
scene = "probability"

[records]
suite = "builtin"
synthetic_only = true
limit = 1
scale = 0.1

[structures]
samples_per_pair = 3
TOML
"$bin" run "$tmp/calm.toml" --out "$tmp/calm.h5" --quiet > "$tmp/calm.md"
# the case under test is present: a plotted gap ratio with no impacts, and the sample size above
"$py" - "$tmp/calm.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
pc = f["uncoupled/peak_closing"][()]
ok = f["uncoupled/status"][()].reshape(pc.shape) == 0
z = (pc / f["models/code_gap"][()][None, :])[ok]
k = {r: int(np.sum(z > r)) for r in (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)}
print(f"n = {z.size}, impacts per plotted gap ratio: {k}")
assert z.size == 363, z.size
assert k[1.0] == 0, "the test study must have a plotted gap ratio without impacts"
PY
MPLBACKEND=Agg "$py" "$src/tools/plot_study.py" "$tmp/calm.h5" --prefix "$tmp/calm" > "$tmp/plot.out"
for png in "$tmp/calm-probability.png" "$tmp/calm-periods.png"; do
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "FAIL: no PNG $png"; exit 1; }
done

# a pair study: the separation plot in metres, PNG at 200 dpi plus SVG
cat > "$tmp/pair.toml" <<'TOML'
title = "plot test: a pair"
seed = 7
scene = "probability"
[records]
suite = "builtin"
synthetic_only = true
limit = 6
[structures]
samples_per_pair = 20
[structures.building1]
period = {lognormal = {median = 0.9, cov = 0.15}}
height = 28.0
mass = 3.1e6
[structures.building2]
period = {lognormal = {median = 1.3, cov = 0.15}}
height = 42.0
mass = 4.7e6
[report]
bootstrap = 200
TOML
"$bin" run "$tmp/pair.toml" --out "$tmp/pair.h5" --quiet > "$tmp/pair.md"
MPLBACKEND=Agg "$py" "$src/tools/plot_study.py" "$tmp/pair.h5" --prefix "$tmp/pair" --format svg --pounding "$bin" \
  > "$tmp/pair.out"
png=$tmp/pair-separation.png
[ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "FAIL: no PNG $png"; exit 1; }
# 200 dpi: the pHYs chunk holds 200 / 0.0254 = 7874 pixels per metre on both axes (unit byte 1)
"$py" - "$png" <<'PY'
import struct, sys
b = open(sys.argv[1], "rb").read()
i = b.find(b"pHYs")
assert i > 0, "no pHYs chunk"
x, y, unit = struct.unpack(">IIB", b[i + 4:i + 13])
assert unit == 1 and round(x * 0.0254) == 200 and round(y * 0.0254) == 200, (x, y, unit)
PY
grep -q "<svg" "$tmp/pair-separation.svg" || { echo "FAIL: no SVG $tmp/pair-separation.svg"; exit 1; }
grep -q "pair-separation.svg" "$tmp/pair.out" || { echo "FAIL: written files not printed: $(cat "$tmp/pair.out")"; exit 1; }
echo "plot_study: ok ($(cat "$tmp/plot.out"); $(cat "$tmp/pair.out"))"
