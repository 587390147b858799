#!/usr/bin/env bash
# studies/four-frame-bridge.toml (issue 26 §1, Muthukumar & DesRoches 2006; docs/bridges.md "The four-frame bridge
# study"):
#  1. every number of the study file is the paper's, converted here independently from kips, inches and seconds
#     (1 kip = 4448.2216152605 N, g = 9.80665 m/s^2, 1 in = 0.0254 m), and the records are scaled to PGA 0.5 g;
#  2. it runs (two of its records, the paper's gap only): frames F1-F4 and joints 1-3 in /system, F1 under a record
#     and F4 under the reversed one equal by symmetry (F2, F3 likewise), no excluded analysis, every hinge hit, the restrainers' slack the hinge gap.
# Needs ../shared (the Loma Prieta records). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
py=/usr/bin/python3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
study=$src/studies/four-frame-bridge.toml

"$py" - "$study" "$real" <<'PY'
import sys, tomllib, math
s = tomllib.load(open(sys.argv[1], "rb"))
kip, g, inch = 4448.2216152605, 9.80665, 0.0254
fr = s["bridge"]["frame"]
assert [f["label"] for f in fr] == ["F1", "F2", "F3", "F4"]
for f, W, T, Fy in zip(fr, (2880, 7080, 7080, 2880), (0.47, 1.12, 1.12, 0.47), (774, 1824, 1824, 774)):
    assert abs(f["mass"] / (W * kip / g) - 1) < 1e-5, (f["mass"], W * kip / g)
    assert f["period"] == T and f["zeta"] == 0.05 and f["hysteresis"] == "q-hyst"
    assert abs(f["yield_force"] / (Fy * kip) - 1) < 1e-5, (f["yield_force"], Fy * kip)
for j, half in zip(s["bridge"]["joint"], (1, 0.5, 1)):
    assert j["gap"] == 0.5 * inch
    r, b = j["restrainer"], j["bearing"]
    assert abs(r["stiffness"] / (half * 200 * kip / inch) - 1) < 1e-5 and abs(r["yield_force"] / (half * 840 * kip) - 1) < 1e-5
    assert r["alpha"] == 0.05 and r["slack"] == j["gap"]
    assert abs(b["stiffness"] / (6 * kip / inch) - 1) < 1e-5 and abs(b["yield_force"] / (2.4 * kip) - 1) < 1e-5 and b["alpha"] == 0.33
# k_h = 888 kN/mm^1.5 in N/m^1.5
assert abs(s["contact"]["stiffness"] / (888e3 / 1e-3 ** 1.5) - 1) < 1e-3
# Caltrans SDC K_abut = 28.7 kN/mm/m x w x (h / 1.676 m) is the paper's 2600 kips/in
a = s["bridge"]["abutment"]["left"]
assert abs(28.73e3 / 1e-3 * a["width"] * a["height"] / 1.676 / (2600 * kip / inch) - 1) < 2e-3
# every record at PGA 0.5 g (MANIFEST.tsv's PGA)
man = {l.split("\t")[0]: float(l.split("\t")[8]) for l in open(sys.argv[2] + "/MANIFEST.tsv") if not l.startswith("file")}
for e in s["records"]["files"]:
    name = e["path"].split("/")[-1]
    assert abs(e["scale"] * man[name] - 0.5) < 2e-4, (name, e["scale"] * man[name])
print("four-frame-bridge.toml: the paper's numbers in SI")
PY

sed -e "s#\.\./\.\./shared/records/real#$real#" -e 's/^ratios = .*/ratios = [1.0]/' "$study" |
  awk '/^files = \[/ { print; n = 0; next } /^  \{path/ { if (n++ < 2) print; next } { print }' > "$tmp/ff.toml"
(cd "$tmp" && "$bin" run ff.toml --out ff.h5 --quiet > /dev/null 2> err.txt) || { cat "$tmp/err.txt"; exit 1; }
"$py" - "$tmp/ff.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
dec = lambda a: [s.decode() if isinstance(s, bytes) else s for s in a]
assert dec(f["system/building_label"][()]) == ["F1", "F2", "F3", "F4"], dec(f["system/building_label"][()])
assert dec(f["system/element_label"][()]) == ["joint 1", "joint 2", "joint 3"]
R = f["uncoupled/peak_closing"].shape[0]
assert R == 4, R  # 2 records x 2 signs
assert (f["uncoupled/status"][()] == 0).all() and (f["impacts/status"][()] == 0).all()
u = {b: f[f"impacts/peak_u{b}"][()].ravel() for b in (1, 2, 3, 4)}
# a symmetric bridge: F1 under a record is F4 under the reversed record (rows 2r, 2r + 1), F2 likewise F3
assert np.allclose(u[1][0::2], u[4][1::2], rtol=1e-6) and np.allclose(u[2][0::2], u[3][1::2], rtol=1e-6), u
ec = f["impacts/element_impact_count"][()].reshape(R, 3)
assert (ec > 0).all(), ec
print("F1 peaks", np.round(u[1], 4), "F2 peaks", np.round(u[2], 4), "hinge impacts", ec.tolist())
PY
echo "four-frame bridge study: the paper's numbers, runs"
