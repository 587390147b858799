#!/usr/bin/env bash
# Per-level answers in the report: two shear buildings of different storey heights (3 m and 4 m storeys: floor to
# floor at 12 m, floor to column elsewhere) in an impacts study. The run's report, `pounding report` and its CSV give
# per contact element and gap ratio P(hit) with the Wilson interval, the peak force given a hit (median, 84th
# percentile), the struck column's shears below and above the contact point, and per floor the peak absolute
# acceleration amplification (median, 84th percentile) -- each equal to a hand computation with h5py and numpy from
# the results file (numpy.quantile's default, the Wilson interval's formula, xi from /system).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null || { echo "needs $py with h5py and numpy"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/levels.toml" <<'EOT'
title = "Per-level answers: 5 storeys of 3 m beside 5 storeys of 4 m"
seed = 4511
scene = "impacts"
[records]
suite = "builtin"
synthetic_only = true
limit = 3
polarity = "recorded"
[structures]
model = "shear"
samples_per_pair = 6
zeta = 0.05
alpha = 0.05
[structures.building1]
period = {lognormal = {median = 0.5, cov = 0.2}}
height = 15.0
storeys = 5
storey_height = 3.0
mass = 1.5e6
yield_coefficient = {lognormal = {median = 0.3, cov = 0.2}}
[structures.building2]
period = {lognormal = {median = 0.8, cov = 0.2}}
height = 20.0
storeys = 5
storey_height = 4.0
mass = 2.0e6
yield_coefficient = {lognormal = {median = 0.2, cov = 0.2}}
[gaps]
ratios = [0.05, 0.2, 0.5]
[contact]
law = "hertzdamp"
damping_law = "lankarani-nikravesh"
e = 0.65
[analysis]
substeps = 8
[report]
bootstrap = 200
EOT
"$bin" run "$tmp/levels.toml" --out "$tmp/levels.h5" --quiet > "$tmp/run.md" 2> "$tmp/run.log" || { cat "$tmp/run.log"; exit 1; }
"$bin" report "$tmp/levels.h5" > "$tmp/report.md"
"$bin" report "$tmp/levels.h5" --csv > "$tmp/report.csv"
"$py" - "$tmp" <<'PY'
import csv, math, re, sys
import h5py, numpy as np
tmp = sys.argv[1]
f = h5py.File(f"{tmp}/levels.h5", "r")
s = f["system"]
labels = [x.decode() for x in s["element_label"][()]]
lk = [x.decode() for x in s["element_left_kind"][()]]
rk = [x.decode() for x in s["element_right_kind"][()]]
xi = [s["element_left_xi"][e] if lk[e] == "interpolated" else s["element_right_xi"][e] if rk[e] == "interpolated" else None
      for e in range(len(labels))]
assert any(x is not None for x in xi) and any(x is None for x in xi), ("needs floor-to-column and floor-to-floor", labels)
count = f["impacts/element_impact_count"][()]        # [R, M, G, E]
force = f["impacts/element_peak_force"][()]
R, M, G, E = count.shape
ratios = f["gaps/ratios"][()]
iok = f["impacts/status"][()] == 0                    # [R, M, G]
uok = f["uncoupled/status"][()] == 0                  # [R, M]
total = f["impacts/impact_count"][()]

def wilson(k, n, z=1.959963984540054):
    p = k / n
    c = (p + z * z / (2 * n)) / (1 + z * z / n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return c - h, c + h

def close(a, b):
    return abs(a - b) <= 1e-12 * max(abs(a), abs(b))

rows = list(csv.DictReader(open(f"{tmp}/report.csv")))
def row(table, x, name):
    got = [r for r in rows if r["table"] == table and float(r["gap_ratio"]) == x and r["name"] == name]
    assert len(got) == 1, (table, x, name, got)
    return got[0]

md = open(f"{tmp}/report.md").read()
assert open(f"{tmp}/run.md").read().count("## Per contact level") == 1
assert "## Per contact level: impacts, peak forces, column shears" in md
kn = lambda v: f"{v / 1e3:.4g}"
checked = partial = shears = 0
for e in range(E):
    for g in range(G):
        ok = iok[:, :, g]
        n = int(ok.sum())
        hit = ok & (count[:, :, g, e] > 0)
        k = int(hit.sum())
        r = row("level", ratios[g], labels[e])
        assert (int(r["hits"]), int(r["n"])) == (k, n), (labels[e], ratios[g], r, k, n)
        lo, hi = wilson(k, n)
        assert abs(float(r["lo"]) - lo) < 1e-6 and abs(float(r["hi"]) - hi) < 1e-6, (r, lo, hi)
        if k == 0:
            assert not [x for x in rows if x["table"] == "level_force" and x["name"] == labels[e] and float(x["gap_ratio"]) == ratios[g]]
            continue
        partial += 0 < k < n
        fv = force[:, :, g, e][hit]
        q50, q84 = np.quantile(fv, 0.5), np.quantile(fv, 0.84)
        r = row("level_force", ratios[g], labels[e])
        assert int(r["n"]) == k and close(float(r["lo"]), q50) and close(float(r["hi"]), q84), (r, q50, q84)
        if xi[e] is not None:
            x = xi[e]
            below, above = (1 - x) ** 2 * (1 + 2 * x), x * x * (3 - 2 * x)
            for t, c in (("level_shear_below", below), ("level_shear_above", above)):
                r = row(t, ratios[g], labels[e])
                assert close(float(r["lo"]), c * q50) and close(float(r["hi"]), c * q84), (r, c * q50, c * q84)
            cell = f"| {kn(below * q50)}, {kn(below * q84)} | {kn(above * q50)}, {kn(above * q84)} |"
            assert cell in md, (labels[e], ratios[g], cell)
            shears += 1
        # the Markdown row, to its printed digits
        cell = f"| {100 * k / n:.2f}% | [{100 * lo:.2f}%, {100 * hi:.2f}%] | {k} of {n} | {kn(q50)} | {kn(q84)} |"
        assert cell in md, (labels[e], ratios[g], cell)
        checked += 1
assert checked >= 6 and shears >= 4 and partial >= 3, (checked, shears, partial)
# floors: peak absolute acceleration with / without pounding over the analyses that pounded
floors = 0
for b in (1, 2):
    unc = f[f"uncoupled/peak_acc_floors{b}"][()]      # [R, M, F]
    imp = f[f"impacts/peak_acc_floors{b}"][()]        # [R, M, G, F]
    for g in range(G):
        basis = uok & iok[:, :, g] & (total[:, :, g] > 0)
        for fl in range(unc.shape[-1]):
            w, c = unc[:, :, fl][basis], imp[:, :, g, fl][basis]
            keep = (w > 0) & np.isfinite(c)
            a = c[keep] / w[keep]
            if not len(a):
                continue
            r = row("floor_acc", ratios[g], f"building{b} floor {fl + 1}")
            q50, q84 = np.quantile(a, 0.5), np.quantile(a, 0.84)
            assert int(r["n"]) == len(a) and close(float(r["lo"]), q50) and close(float(r["hi"]), q84), (r, q50, q84)
            want = rf"\| building{b} \| {fl + 1} \| {ratios[g]:g}d[^|]* \| {q50:.3g} \| {q84:.3g} \| {len(a)} \|"
            assert re.search(want, md), (b, fl, g, want)
            floors += 1
pounded = sum(bool((uok & iok[:, :, g] & (total[:, :, g] > 0)).any()) for g in range(G))
assert pounded >= 2 and floors == 2 * 5 * pounded, (floors, pounded)
assert len([r for r in rows if r["table"] == "floor_acc"]) == floors
print(f"report_levels: {checked} element x gap rows ({shears} with column shears), {floors} floor rows equal h5py/numpy")
PY
echo "1 passed, 0 failed"
