#!/usr/bin/env bash
# [gaps] metres and [gaps] existing (issue 45 items 4 and 6):
#  1. a pair of fixed heights (d = 0.005 (20 + 30) = 0.25 m, one number) run with ratios and with metres = ratios x d
#     gives the same counts at every gap: the uncoupled verdicts (closing > gap) and the coupled runs' impacts per gap
#     (impacts scene), from the files and from the report's CSV; the metres file says its unit (/gaps unit = "m",
#     /gaps/axis, /impacts/gap_axis, /settings/gaps/metres) and its report says metres (no "x d");
#  2. a study with heights from the period-height rule (d varies per model) in metres counts closing > metres[g]
#     per model, as h5py counts it from the per-model closings; [outputs] per_model = false gives the same counts;
#  3. [gaps] existing: the report's P(pounding) at the existing gap equals the h5py count (closing > existing), in
#     metres and in ratio mode, and the code-rules table marks it;
#  4. bad input: one ERROR naming file:line and the key, exit 2, no results.
# Needs /usr/bin/python3 with h5py. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, expect_error
py=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }

pair() {  # <[gaps] lines> <scene>
  cat <<EOT
title = "a fixed pair, gaps in $2"
seed = 5
scene = "$3"
[records]
suite = "builtin"
synthetic_only = true
limit = 3
[structures]
samples_per_pair = 6
zeta = 0.05
alpha = 0.05
[structures.building1]
period = {lognormal = {median = 0.6, cov = 0.2}}
height = 20.0
mass = 2e6
yield_coefficient = 0.3
[structures.building2]
period = {lognormal = {median = 1.1, cov = 0.2}}
height = 30.0
mass = 3e6
yield_coefficient = 0.2
[gaps]
$1
[contact]
law = "hertzdamp"
EOT
}
# 1. ratios against metres = ratios x d (d = 0.25 m: x d is exact, yet the counts are compared, not the floats)
pair 'ratios = [0.05, 0.1, 0.2, 0.4]' ratios impacts > "$tmp/ratios.toml"
pair 'metres = [0.0125, 0.025, 0.05, 0.1]
existing = 0.03' metres impacts > "$tmp/metres.toml"
pair 'ratios = [0.05, 0.1, 0.2, 0.4]
existing = 0.03' "ratios with an existing gap" probability > "$tmp/ratios-existing.toml"
for s in ratios metres ratios-existing; do
  (cd "$tmp" && "$bin" run $s.toml --out $s.h5 > $s.md 2> $s.err) || { cat "$tmp/$s.err"; fail "$s.toml does not run"; }
  "$bin" report "$tmp/$s.h5" --csv > "$tmp/$s.csv"
done

# 1d. [outputs] histories on a metres axis: gap = 0.05 is the coupled run at 0.05 m, its peaks the study's bit for bit
sed 's/^\[contact\]/[outputs]\nhistories = [{ record = "EQ2", model = 1, gap = 0.05 }]\n\n[contact]/' "$tmp/metres.toml" \
  > "$tmp/hist.toml"
(cd "$tmp" && "$bin" run hist.toml --out hist.h5 --quiet > /dev/null 2> hist.err) || { cat "$tmp/hist.err"; fail "histories"; }
"$py" - "$tmp/hist.h5" <<'PY'
import sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
h = f["histories/1"].attrs
g = list(f["gaps/axis"][()]).index(0.05)
assert h["gap_m"] == 0.05 and "gap_ratio" not in h, dict(h)
k, m = int(h["record_row"]), int(h["model"])
for name in ("peak_force", "impact_count", "peak_u1", "peak_u2"):
    assert h[name] == f["impacts/" + name][()][k, m, g], (name, h[name], f["impacts/" + name][()][k, m, g])
print("histories at 0.05 m = the study's coupled run, bit for bit")
PY

# 2. heights from the period-height rule: d per model; the small synthetic study with metres and an existing gap
sed -e 's/^ratios = .*/metres = [0.01, 0.02, 0.04, 0.08]\nexisting = 0.03/' -e 's/^scene = .*/scene = "probability"/' \
  "$src/tests/data/study-small-synthetic.toml" > "$tmp/grid.toml"
sed 's/^\[analysis\]/[outputs]\nper_model = false\n\n[analysis]/' "$tmp/grid.toml" > "$tmp/grid-red.toml"
for s in grid grid-red; do
  (cd "$tmp" && "$bin" run $s.toml --out $s.h5 > $s.md 2> $s.err) || { cat "$tmp/$s.err"; fail "$s.toml does not run"; }
  "$bin" report "$tmp/$s.h5" --csv > "$tmp/$s.csv"
done

"$py" - "$tmp" <<'PY'
import csv, sys
import h5py, numpy as np
tmp = sys.argv[1]
def rows(name, table):
    return [r for r in csv.DictReader(open(f"{tmp}/{name}.csv")) if r["table"] == table]
def s(v):
    return v.decode() if isinstance(v, bytes) else str(v)

# 1. the same counts per gap
a, b = h5py.File(f"{tmp}/ratios.h5", "r"), h5py.File(f"{tmp}/metres.h5", "r")
d = a["models/code_gap"][()]
assert np.all(d == 0.25), d
assert "unit" not in a["gaps"].attrs and "ratios" in a["gaps"] and "gap_ratios" in a["impacts"]
assert s(b["gaps"].attrs["unit"]) == "m" and "ratios" not in b["gaps"] and s(b["gaps/axis"].attrs["units"]) == "m"
assert "gap_axis" in b["impacts"] and "gap_ratios" not in b["impacts"]
assert "metres" in b["settings/gaps"].attrs and "ratios" not in b["settings/gaps"].attrs
assert np.array_equal(b["gaps/metres"][()], np.repeat(b["gaps/axis"][()][None, :], d.size, axis=0))
pc_a, pc_b = a["uncoupled/peak_closing"][()], b["uncoupled/peak_closing"][()]
st_a, st_b = a["uncoupled/status"][()], b["uncoupled/status"][()]
assert np.array_equal(pc_a, pc_b) and np.array_equal(st_a, st_b)
gm = b["gaps/axis"][()]
ga = a["gaps/ratios"][()] * 0.25
ok = st_a == 0
for g in range(len(gm)):
    na, nb = int(np.sum(pc_a[ok] > ga[g])), int(np.sum(pc_b[ok] > gm[g]))
    assert na == nb, (g, na, nb)
    ia = a["impacts/impact_count"][()][..., g] > 0
    ib = b["impacts/impact_count"][()][..., g] > 0
    assert int(ia.sum()) == int(ib.sum()), (g, ia.sum(), ib.sum())
    assert np.array_equal(a["impacts/status"][()][..., g], b["impacts/status"][()][..., g])
hits = 0
for ra, rb in zip(rows("ratios", "total"), rows("metres", "total")):
    assert (ra["hits"], ra["n"]) == (rb["hits"], rb["n"]), (ra, rb)
    hits += int(ra["hits"])
assert len(rows("metres", "total")) == 4 and hits > 0, "no gap pounds: the comparison would prove nothing"
for ra, rb in zip(rows("ratios", "per_record"), rows("metres", "per_record")):
    assert (ra["hits"], ra["n"]) == (rb["hits"], rb["n"]), (ra, rb)

# 2. sampled heights in metres: closing > metres[g] per model
f = h5py.File(f"{tmp}/grid.h5", "r")
cg = f["models/code_gap"][()]
assert cg.min() < cg.max(), "d should vary per model"
pc, st = f["uncoupled/peak_closing"][()], f["uncoupled/status"][()]
ok = st == 0
gm = f["gaps/axis"][()]
tot = rows("grid", "total")
assert len(tot) == len(gm)
for g, r in enumerate(tot):
    want = int(np.sum(pc[ok] > gm[g]))
    assert int(r["hits"]) == want and int(r["n"]) == int(ok.sum()), (g, r, want)
    assert float(r["gap_ratio"]) == gm[g]
    # the reductions-only run counts the same
    red = h5py.File(f"{tmp}/grid-red.h5", "r")["reductions"]
    assert s(red.attrs["gap_unit"]) == "m"
    assert int(red["gap_hits"][()][:, g].sum()) == want, (g, red["gap_hits"][()][:, g].sum(), want)
per = rows("grid", "per_record")
N = len(per) // len(gm)  # independent records; a record's rows (its signs) are consecutive
P = pc.shape[0] // N
for i, r in enumerate(per):
    k, g = i // len(gm), i % len(gm)
    assert float(r["gap_ratio"]) == gm[g]
    want = int(np.sum((pc[k * P:(k + 1) * P] > gm[g])[ok[k * P:(k + 1) * P]]))
    assert int(r["hits"]) == want, (k, g, r, want)
# the curve is on the metres axis: P(closing > x) at x = curve_step c
for r in rows("grid", "curve")[:40]:
    x = float(r["gap_ratio"])
    want = np.sum(pc[ok] > x) / ok.sum()
    assert abs(float(r["probability"]) - want) < 1e-6, (x, r["probability"], want)

# 3. the existing gap: P(closing > existing), exact
for name in ("grid", "metres", "ratios-existing"):
    h = h5py.File(f"{tmp}/{name}.h5", "r")
    e = float(h["settings/gaps"].attrs["existing"])
    pc, ok = h["uncoupled/peak_closing"][()], h["uncoupled/status"][()] == 0
    want = int(np.sum(pc[ok] > e))
    ex = rows(name, "existing")
    assert len(ex) == 1 and int(ex[0]["hits"]) == want and int(ex[0]["n"]) == int(ok.sum()), (name, ex, want)
    assert abs(float(ex[0]["gap_m"]) - e) < 1e-12
    md = open(f"{tmp}/{name}.md").read()
    assert "## At the existing gap" in md, name
    line = md.split("## At the existing gap")[1].split("\n\n")[1]
    assert f"({want} of {int(ok.sum())} analyses" in line, (name, line, want)
print("ratios = metres x d at every gap; metres counts = h5py; existing = h5py")
PY

# 1b. fragility (stripes and the bisection IDA): the same pair in ratios and in metres = ratios x d (Python's product,
# the engine's, written exactly) gives the same capacities, observed counts and fits; the existing gap's curve is given
for s in fragility-pair fragility-pair-ida; do
  sed -e 's/^samples_per_pair = .*/samples_per_pair = 6/' -e 's/^\[records\]/[records]\nlimit = 5/' -e '/^output = /d' \
      -e 's/^bootstrap = .*/bootstrap = 100/' -e "s|^curve = \"|curve = \"$src/studies/|" "$src/studies/$s.toml" > "$tmp/$s.toml"
  (cd "$tmp" && "$bin" run $s.toml --out $s.h5 --quiet > /dev/null 2> $s.err) || { cat "$tmp/$s.err"; fail "$s (ratios)"; }
  m=$("$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); d = f['models/code_gap'][0]
print(', '.join(repr(float(x * d)) for x in f['gaps/ratios'][()]))" "$tmp/$s.h5")
  sed -e "s/^ratios = .*/metres = [$m]\nexisting = 0.175/" -e '/^curve_max = /d' "$tmp/$s.toml" > "$tmp/$s-m.toml"
  (cd "$tmp" && "$bin" run $s-m.toml --out $s-m.h5 > $s-m.md 2> $s-m.err) || { cat "$tmp/$s-m.err"; fail "$s (metres)"; }
  "$py" - "$tmp/$s.h5" "$tmp/$s-m.h5" <<'PY'
import sys
import h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
assert b["fragility"].attrs["gap_units"] in ("m", b"m") and np.array_equal(b["fragility/gaps"][()], b["gaps/axis"][()])
for name in ("fragility/theta", "fragility/beta", "fragility/observed_z", "fragility/observed_n", "ida/capacity"):
    if name in a:
        assert np.array_equal(a[name][()], b[name][()], equal_nan=True), name
assert np.allclose(a["fragility/gaps_m"][()], b["fragility/gaps"][()], rtol=0, atol=1e-15)
print(sys.argv[2], "= the ratio study's fits")
PY
  grep -q 'existing = 0.175 m: its fragility is the row 0.175 m' "$tmp/$s-m.md" || fail "$s: no fragility at the existing gap"
done

# 1c. systems: a bridge (the joint at the reference gap d takes the study gap, every other joint its gap + offset) and
# a pair of 3-storey shear buildings of fixed heights, in ratios and in metres = ratios x d: every peak and impact count
# bit for bit (the gaps are the same doubles)
sed -e 's/^limit = .*/limit = 2/' "$src/tests/data/bridge/study-four-frame.toml" > "$tmp/bridge.toml"
pair 'ratios = [0.05, 0.1, 0.2, 0.4]' "ratios, shear" impacts |
  sed -e 's/^yield_coefficient = 0.3$/&\nmodel = "shear"\nstoreys = 5\nstorey_height = 4.0/' \
      -e 's/^yield_coefficient = 0.2$/&\nmodel = "shear"\nstoreys = 6\nstorey_height = 5.0/' > "$tmp/shear.toml"
for s in bridge shear; do
  (cd "$tmp" && "$bin" run $s.toml --out $s.h5 --quiet > /dev/null 2> $s.err) || { cat "$tmp/$s.err"; fail "$s (ratios)"; }
  m=$("$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); d = f['models/code_gap'][0]
print(', '.join(repr(float(x * d)) for x in f['gaps/ratios'][()]))" "$tmp/$s.h5")
  sed -e "s/^ratios = .*/metres = [$m]/" "$tmp/$s.toml" > "$tmp/$s-m.toml"
  (cd "$tmp" && "$bin" run $s-m.toml --out $s-m.h5 > $s-m.md 2> $s-m.err) || { cat "$tmp/$s-m.err"; fail "$s (metres)"; }
  "$py" - "$tmp/$s.h5" "$tmp/$s-m.h5" <<'PY'
import sys
import h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
assert a.attrs["format_version"] == 3, "not a system"
assert np.all(a["models/code_gap"][()] == a["models/code_gap"][0]), "d varies"
n = 0
for group in ("uncoupled", "impacts"):
    for name in a[group]:
        if name in ("gap_ratios", "gap_axis"):
            continue
        assert np.array_equal(a[group][name][()], b[group][name][()], equal_nan=True), f"{group}/{name}"
        n += 1
hits = int((a["impacts/impact_count"][()] > 0).sum())
assert hits > 0, "no impacts: the comparison would prove nothing"
print(f"{sys.argv[2]}: {n} datasets bit for bit, {hits} pounding analyses")
PY
done
grep -q 'gap of the joint(s) at d = 0.0127 m' "$tmp/bridge-m.md" || fail "the bridge's metres are not explained"

# the report speaks metres on a metres axis, ratios x d otherwise
grep -q '| gap m | models with impact' "$tmp/metres.md" || fail "the total table's header is not in metres"
grep -q '| gap ratio | models with impact' "$tmp/ratios.md" || fail "the ratio study's header changed"
grep -q '## Separation advice in metres' "$tmp/grid.md" || fail "the grid study's advice is not in metres"
grep -q '| record | synthetic | PGA g | 0.0125 m |' "$tmp/metres.md" || fail "Table 2's headers are not in metres"
if grep -q 'x d\b' "$tmp/grid.md"; then fail "a metres report speaks of x d: $(grep -n 'x d\b' "$tmp/grid.md" | head -3)"; fi
grep -q '| existing 0.03 m | as built |' "$tmp/metres.md" || fail "the code-rules table does not mark the existing gap"
grep -q '| \*\*existing 0.03 m\*\* | as built |' "$tmp/grid.md" || fail "the grid's code rules do not mark the existing gap"

# 4. bad input
fails=0
base=$(pair 'ratios = [0.1]' x probability | sed '/^\[gaps\]/,$d')
expect_error both 'gaps.*metres' "$base
[gaps]
ratios = [0.1, 0.2]
metres = [0.02, 0.04]"
expect_error negative 'gaps.*metres' "$base
[gaps]
metres = [-0.02, 0.04]"
expect_error increasing 'strictly increasing.*gaps.*metres' "$base
[gaps]
metres = [0.04, 0.02]"
expect_error absurd 'gaps.*metres' "$base
[gaps]
metres = [0.02, 6.0]"
expect_error empty 'gaps.*metres' "$base
[gaps]
metres = []"
expect_error existing 'gaps.*existing' "$base
[gaps]
metres = [0.02, 0.04]
existing = -0.01"
grep -q ':[0-9]* \[gaps\]' "$tmp/negative.out" || fail "the error does not name file:line: $(cat "$tmp/negative.out")"
[ "$fails" -eq 0 ] || exit 1
echo "PASS"
