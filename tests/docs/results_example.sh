#!/usr/bin/env bash
# docs/results-format.md's example (tools/results_example.py, h5py alone) against the engine: on a reduced copy
# of studies/quick.toml (the same 25 synthetic records, 2 samples per period pair) the script's Table 3 must equal
# the one `pounding run` prints to the last printed digit, and its separation in metres must be the order
# statistic it claims to be (at most floor(t n) analyses exceed it, more exceed anything smaller).
# Needs /usr/bin/python3 with h5py and numpy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py python3-numpy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed -e "s|^suite = \"\\.\\./records/|suite = \"$src/records/|" -e 's/^samples_per_pair = 32/samples_per_pair = 2/' \
  "$src/studies/quick.toml" > "$tmp/quick.toml"
grep -q "^samples_per_pair = 2$" "$tmp/quick.toml" && grep -q "^suite = \"$src/records/" "$tmp/quick.toml" ||
  { echo "FAIL: studies/quick.toml no longer has the lines this test edits"; exit 1; }
"$bin" run "$tmp/quick.toml" --out "$tmp/q.h5" --quiet > "$tmp/report.md"
# Table 3's rows: gap ratio, models with impact, probability
rows() { grep -E '^\| [0-9.]+ \| [0-9]+ / [0-9]+ \| ([0-9.]+%|n/a) \|' | cut -d'|' -f2-4; }
sed -n '/^## Total probability of pounding (Table 3)/,/^## /p' "$tmp/report.md" | rows > "$tmp/engine.txt"
"$py" "$src/tools/results_example.py" "$tmp/q.h5" --targets 10 5 1 0.1 > "$tmp/example.md"
sed -n '/^Table 3/,/^Separation/p' "$tmp/example.md" | rows > "$tmp/script.txt"
[ "$(wc -l < "$tmp/engine.txt")" -eq 6 ] || { echo "FAIL: no Table 3 in the report"; cat "$tmp/report.md"; exit 1; }
# the test study must exercise the comparison: a different count at every gap ratio
[ "$(cut -d'|' -f2 "$tmp/engine.txt" | sort -u | wc -l)" -eq 6 ] ||
  { echo "FAIL: the test study's Table 3 is degenerate"; cat "$tmp/engine.txt"; exit 1; }
if ! diff -u "$tmp/engine.txt" "$tmp/script.txt"; then
  echo "FAIL: tools/results_example.py's Table 3 differs from pounding's"
  exit 1
fi
echo "ok:   Table 3 from h5py equals pounding's ($(wc -l < "$tmp/engine.txt") gap ratios)"
"$py" - "$tmp/q.h5" "$src/tools" "$tmp/example.md" <<'PY'
import sys, h5py, numpy as np
sys.path.insert(0, sys.argv[2])
import results_example as ex
f = h5py.File(sys.argv[1], "r")
pc = f["uncoupled/peak_closing"][()]
z = pc[f["uncoupled/status"][()] == 0]
n = z.size
for t in (0.10, 0.05, 0.01, 0.001):
    s = ex.separation(f, t)
    allowed = int(np.floor(t * n))
    above = int((z > s).sum())
    smaller = np.nextafter(s, 0.0)
    assert above <= allowed < int((z > smaller).sum()), (t, s, above, allowed)
    print(f"ok:   separation at {100 * t:g}%: {s:.4f} m, exceeded by {above} of {n} (floor(t n) = {allowed})")
text = open(sys.argv[3]).read()
assert f"| 10% | {ex.separation(f, 0.10):.4f} |" in text, text
PY
echo "1 passed, 0 failed"
