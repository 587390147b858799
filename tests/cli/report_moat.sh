#!/usr/bin/env bash
# An isolated building in a moat (issue 45 item 2; studies/isolated-moat.toml, made smaller): the report answers the
# probability that the base hits its moat, and the file says what it needs to check it.
#  1. /system/element_gap_offset holds the moat gap (0.10 m) at both walls, 0 at the floors (docs/results-format.md:
#     "a group that is not study-gap: the whole gap"; it held 0);
#  2. the run's report, `pounding report` and its CSV give P(moat impact) without pounding and at each gap ratio, equal to
#     a hand count with h5py: an analysis hits its moat when a wall's uncoupled peak closing passes the moat gap, and at
#     gap ratio x when its coupled run counted an impact at a wall -- and impacts/element_impact_count holds the
#     uncoupled run's impacts at the walls for an analysis not rerun at x (it held 0 there); with the Wilson interval
#     on n analyses;
#  3. the HTML report's answer box quotes the moat table;
#  4. the pair figure's x-axis covers the advice and every code rule when they lie beyond the curve's end (curve_max
#     0.5 d here; it stopped at the curve's end and cut them off): tests/cli/plot_layout.py --pair-report.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy, matplotlib' 2>/dev/null || skip_or_fail "needs $py with h5py, numpy and matplotlib"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed -e 's/^samples_per_pair = .*/samples_per_pair = 2/' -e 's/^\[records\]$/[records]\nlimit = 12/' -e '/^output = /d' \
    -e 's/^curve_max = .*/curve_max = 0.5/' "$src/studies/isolated-moat.toml" > "$tmp/moat.toml"
grep -q '^moat = {gap = 0.10}' "$tmp/moat.toml"
"$bin" run "$tmp/moat.toml" --out "$tmp/moat.h5" --quiet > "$tmp/run.md" 2> "$tmp/run.log" || { cat "$tmp/run.log"; exit 1; }
"$bin" report "$tmp/moat.h5" > "$tmp/report.md"
"$bin" report "$tmp/moat.h5" --csv > "$tmp/report.csv"
"$bin" report "$tmp/moat.h5" --html "$tmp/report.html"
"$py" - "$tmp" <<'PY'
import csv, math, re, sys
import h5py, numpy as np
tmp = sys.argv[1]
f = h5py.File(f"{tmp}/moat.h5", "r")
s = f["system"]
labels = [x.decode() for x in s["element_label"][()]]
off = s["element_gap_offset"][()]
walls = [e for e, l in enumerate(labels) if "moat" in l]
assert len(walls) == 2, labels
assert all(off[e] == 0.10 for e in walls), ("the moat walls' element_gap_offset is not the moat gap", list(zip(labels, off)))
assert all(off[e] == 0.0 for e in range(len(labels)) if e not in walls), list(zip(labels, off))
closing = f["uncoupled/peak_closing_elements"][()]           # [R, M, E]
ok = f["uncoupled/status"][()] == 0                            # [R, M]
R, M, E = closing.shape
G = f["impacts/gap_ratios"][()]
count = f["impacts/element_impact_count"][()]                  # [R, M, G, E]
iok = f["impacts/status"][()].reshape(R, M, len(G)) == 0
D = f["uncoupled/peak_closing"][()]
d = f["models/code_gap"][()]
hit = (closing[..., walls] > 0.10).any(-1)
want = {"": (int(hit[ok].sum()), int(ok.sum()))}
for g, x in enumerate(G):
    h = (count[:, :, g][..., walls] > 0).any(-1)
    untouched = ok & ~(D > x * d[None, :])
    # not rerun at x: the wall rows are the uncoupled run's (they held 0)
    assert np.array_equal(h[untouched], hit[untouched]), f"x = {x}: element_impact_count at the walls of analyses not rerun"
    want[f"{x:g}"] = (int(h[iok[:, :, g]].sum()), int(iok[:, :, g].sum()))
print("moat impacts (hits, n) by gap ratio ('' = without pounding):", want)
assert 0 < want[""][0] < want[""][1], "the test needs some analyses in the moat and some not"

def wilson(k, n, z=1.959963984540054):
    p = k / n
    c = (p + z * z / (2 * n)) / (1 + z * z / n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return c - h, c + h

rows = [r for r in csv.DictReader(open(f"{tmp}/report.csv")) if r["table"] == "moat"]
got = {r["gap_ratio"]: (int(r["hits"]), int(r["n"])) for r in rows}
assert got == want, (got, want)
for r in rows:
    lo, hi = wilson(int(r["hits"]), int(r["n"]))
    assert abs(float(r["lo"]) - lo) < 1e-6 and abs(float(r["hi"]) - hi) < 1e-6, (r, lo, hi)
    assert float(r["gap_m"]) == 0.10 and r["name"] == "building1", r
for name in ("run.md", "report.md"):
    md = open(f"{tmp}/{name}").read()
    assert "## Moat walls: probability that the isolated base hits its moat" in md, name
    k, n = want[""]
    row = f"| building1 | 0.100 | without pounding | **{100 * k / n:.2f}%** |"
    assert row in md, (name, row)
    x = f"{G[-1]:g}"
    k, n = want[x]
    assert re.search(rf"\| building1 \| 0\.100 \| with pounding at {re.escape(x)}d[^|]* \| \*\*{100 * k / n:.2f}%\*\* \|", md), name
html = open(f"{tmp}/report.html").read()
answer = html[html.index('<section class="answer"'):html.index("</section>", html.index('<section class="answer"'))]
assert "Probability that the isolated base hits its moat walls" in answer and "without pounding" in answer, answer[-2000:]
print("report_moat: moat gap in /system, P(moat impact) in the run's report, report, CSV and answer box")
PY
# the figure: advice beyond the curve's end (curve_max 0.5 d) stays in view with its label
"$py" - "$tmp/report.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
g = max(float(r["gap_m"]) for r in rows if r["table"] == "curve_band")
far = [float(r["hi"]) for r in rows if r["table"] == "separation"] + [float(r["gap_m"]) for r in rows if r["table"] == "code_rule"]
assert max(far) > g, f"the test needs advice or a rule beyond the curve's end ({g} m): {far}"
PY
MPLBACKEND=Agg "$py" "$src/tests/cli/plot_layout.py" --pair-report "$tmp/report.csv" -- "$src/tools/plot_study.py" \
  "$tmp/moat.h5" --prefix "$tmp/fig" --pounding "$bin"
echo "1 passed, 0 failed"
