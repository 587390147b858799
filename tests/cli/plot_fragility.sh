#!/usr/bin/env bash
# tools/plot_fragility.py on a small copy of studies/fragility-pair.toml (20 models per record, 200 bootstrap
# replicates, the hazard curve by absolute path): <prefix>-fragility.png, -fit.png and -rate.png are written, are
# PNGs at 200 dpi of more than a few KB, --format svg adds the SVGs, and the written names are printed. A results
# file without /fragility (a plain probability study) and a missing file each exit non-zero with a message naming
# the file. Needs Debian's python3-matplotlib, -h5py and -numpy: skipped (exit 77) without them, a failure under
# CI=true. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import matplotlib, h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with matplotlib, h5py and numpy (Debian: python3-matplotlib python3-h5py python3-numpy; tools/setup.sh installs them)"
tool=$src/tools/plot_fragility.py
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# the example fragility study, small; every sed must have matched (a renamed key would silently run the big study)
sed -e 's/^samples_per_pair = 200 /samples_per_pair = 20 /' -e 's/^bootstrap = 2000$/bootstrap = 200/' \
    -e "s|^output = .*|output = \"$tmp/fp.h5\"|" -e "s|^curve = \"example-hazard.csv\"|curve = \"$src/studies/example-hazard.csv\"|" \
    "$src/studies/fragility-pair.toml" > "$tmp/fp.toml"
for want in '^samples_per_pair = 20 ' '^bootstrap = 200$' "^output = \"$tmp/fp.h5\"" "^curve = \"$src/studies/"; do
  grep -q "$want" "$tmp/fp.toml" || fail "studies/fragility-pair.toml changed: no line '$want' after the edit"
done
"$bin" run "$tmp/fp.toml" --quiet > "$tmp/fp.md"
[ -f "$tmp/fp.h5" ] || fail "pounding run wrote no $tmp/fp.h5"

MPLBACKEND=Agg "$py" "$tool" "$tmp/fp.h5" -o "$tmp/out/fp" > "$tmp/plot.out"
for kind in fragility fit rate; do
  png=$tmp/out/fp-$kind.png
  [ -f "$png" ] || fail "no $png (printed: $(cat "$tmp/plot.out"))"
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "not a PNG: $png"
  size=$(wc -c < "$png")
  [ "$size" -gt 20000 ] || fail "$png is only $size bytes: an empty figure?"
  grep -q "fp-$kind.png" "$tmp/plot.out" || fail "fp-$kind.png not printed: $(cat "$tmp/plot.out")"
  # 200 dpi: the pHYs chunk holds 200 / 0.0254 = 7874 pixels per metre on both axes (unit byte 1)
  "$py" - "$png" <<'PY'
import struct, sys
b = open(sys.argv[1], "rb").read()
i = b.find(b"pHYs")
assert i > 0, "no pHYs chunk"
x, y, unit = struct.unpack(">IIB", b[i + 4:i + 13])
assert unit == 1 and round(x * 0.0254) == 200 and round(y * 0.0254) == 200, (x, y, unit)
PY
done

# a rate whose bootstrap interval lies above it (a percentile interval need not hold the point estimate: a rate near
# its cap, as a red team found): the rate figure is drawn, not dropped with "'yerr' must not contain negative values"
cp "$tmp/fp.h5" "$tmp/cap.h5"
"$py" - "$tmp/cap.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    h = f["hazard"]
    for v, lo in (("annual_rate", "rate_lo"), ("probability", "probability_lo")):
        x = h[v][()]
        x[0] = 0.9 * h[lo][()][0]
        h[v][...] = x
PY
MPLBACKEND=Agg "$py" "$tool" "$tmp/cap.h5" -o "$tmp/cap/fp" > "$tmp/cap.out" 2>&1 || fail "a rate below its interval: $(cat "$tmp/cap.out")"
[ -f "$tmp/cap/fp-rate.png" ] || fail "a rate below its interval: no rate figure ($(cat "$tmp/cap.out"))"

# --format svg, and --gaps: a subset of the study's gaps
MPLBACKEND=Agg "$py" "$tool" "$tmp/fp.h5" -o "$tmp/svg/fp" --format svg --gaps 0.5 1.0 > "$tmp/svg.out"
for kind in fragility fit rate; do
  grep -q "<svg" "$tmp/svg/fp-$kind.svg" || fail "no SVG $tmp/svg/fp-$kind.svg"
  grep -q "fp-$kind.svg" "$tmp/svg.out" || fail "fp-$kind.svg not printed: $(cat "$tmp/svg.out")"
done
# a gap the study does not have: refused, naming the study's gaps
if MPLBACKEND=Agg "$py" "$tool" "$tmp/fp.h5" -o "$tmp/bad" --gaps 0.3 > "$tmp/gap.out" 2>&1; then
  fail "--gaps 0.3 (not a gap of the study) was accepted"
fi
grep -q "0.25 0.5 0.75 1 1.5 2" "$tmp/gap.out" || fail "--gaps 0.3 message does not list the gaps: $(cat "$tmp/gap.out")"

# not a fragility study: a plain probability study (one synthetic record, 3 samples per pair) has no /fragility
cat > "$tmp/plain.toml" <<'TOML'
title = "plot_fragility test: not a fragility study"
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
"$bin" run "$tmp/plain.toml" --out "$tmp/plain.h5" --quiet > "$tmp/plain.md"
if MPLBACKEND=Agg "$py" "$tool" "$tmp/plain.h5" -o "$tmp/plain" > "$tmp/plain.out" 2>&1; then
  fail "a results file without /fragility was accepted: $(cat "$tmp/plain.out")"
fi
grep -q "plain.h5 has no /fragility group" "$tmp/plain.out" || fail "unclear message: $(cat "$tmp/plain.out")"
grep -q "\[intensity\]" "$tmp/plain.out" || fail "the message does not say what to run: $(cat "$tmp/plain.out")"
! ls "$tmp"/plain-*.png > /dev/null 2>&1 || fail "figures written for a file without /fragility"

# a missing file
if MPLBACKEND=Agg "$py" "$tool" "$tmp/missing.h5" > "$tmp/missing.out" 2>&1; then
  fail "a missing file was accepted"
fi
grep -q "missing.h5: no such file" "$tmp/missing.out" || fail "unclear message: $(cat "$tmp/missing.out")"
grep -q "Traceback" "$tmp/missing.out" "$tmp/plain.out" && fail "a traceback instead of a message"

echo "plot_fragility: ok ($(cat "$tmp/plot.out"); $(cat "$tmp/svg.out"))"
