#!/usr/bin/env bash
# [contact] restitution in studies (issue 26 §3): e(v0), the restitution at each impact's latched approach velocity,
# in the coupled runs of a study (impacts scene, Hertzdamp, central difference): an SDOF pair, and (4.) systems:
#  1. a lane of the study is `pounding simulate` with the same pair, gap, step and --restitution-* options, bit for
#     bit (impact counts, peak forces, peak displacements, impacts outside the valid range) at every gap;
#  2. the key acts: the same study with e = 0.65 instead gives other impacts; the preset form
#     restitution = "lindsay2011" reads; impacts/restitution_outside carries units and the report says the count;
#  and bit-identical results at 1 and 2 MPI ranks, batch width 1 and with skip_untouched = false;
#  3. bad input: one ERROR naming the key (file:line), exit 2, no results written -- e beside the curve, a law,
#     stepper or scene that does not take it, a moat (its own e), a bridge joint's own restitution, an unknown preset,
#     two curves, bad units, valid or table;
#  4. a bridge study's lane equals simulate --bridge --restitution-* bit for bit, invariant over ranks/threads/batch;
#     a shear-building study takes the curve.
# Needs /usr/bin/python3 with h5py. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, bad_run
py=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }
awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
       a = 0.15 * sin(2 * 3.14159265 * 0.9 * t) + 0.10 * sin(2 * 3.14159265 * 3.1 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
curve='{polynomial = [0.9979, -0.0838, 0.0011, -0.0012], units = "m/s", valid = [0.2, 3.13]}'
study() {  # <contact lines> > study
  cat <<EOT
title = "e(v0) in a pair study"
seed = 7
scene = "impacts"
[records]
files = ["rec.txt"]
units = "g"
polarity = "recorded"
[structures]
samples_per_pair = 1
zeta = 0.05
alpha = 0.05
[structures.building1]
period = 0.5
height = 20.0
mass = 2e6
yield_coefficient = 0.3
[structures.building2]
period = 1.2
height = 30.0
mass = 3e6
yield_coefficient = 0.2
[gaps]
ratios = [0.05, 0.2, 0.5]
[contact]
law = "hertzdamp"
$1
EOT
}
study "restitution = $curve" > "$tmp/s.toml"
(cd "$tmp" && "$bin" run s.toml --out s.h5 > s.md 2> s.err) || { cat "$tmp/s.err"; fail "the study with restitution does not run"; }
study 'e = 0.65' > "$tmp/e.toml"
(cd "$tmp" && "$bin" run e.toml --out e.h5 --quiet > /dev/null 2>&1) || fail "the study with e does not run"
study 'restitution = "lindsay2011"' > "$tmp/p.toml"
(cd "$tmp" && "$bin" run p.toml --out p.h5 --quiet > /dev/null 2>&1) || fail "the study with the preset does not run"

# bits for any rank count, batch width, skip_untouched (the hook is each UnitComputer's own)
study=$tmp/s.toml
study_invariance

# 1, 2
"$py" - "$tmp" "$bin" <<'PY'
import json, subprocess, sys
import h5py, numpy as np
tmp, binary = sys.argv[1:3]
f, e, p = (h5py.File(f"{tmp}/{n}.h5", "r") for n in ("s", "e", "p"))
M = {k: f["models/" + k][0] for k in ("k1", "k2", "fy1", "fy2", "m1", "m2", "kh")}
out = f["impacts/restitution_outside"]
assert out.attrs["units"] in ("1", b"1"), dict(out.attrs)
assert "restitution" in f["settings/contact"].attrs and "restitution" not in e["settings/contact"].attrs
assert "restitution_outside" not in e["impacts"]  # a study with e: the file as before
dt = f["records/dt"][0] / int(np.ceil(f["records/dt"][0] / f.attrs["max_dt"] - 1e-9))
touched = 0
for g, gap in enumerate(f["gaps/metres"][0]):
    cmd = [binary, "simulate", "--record", f"{tmp}/rec.txt", "--gap", repr(gap), "--alpha", "0.05", "--zeta", "0.05",
           "--kh", repr(M["kh"]), "--contact", "hertzdamp", "--dt", repr(dt), "--json",
           "--restitution-polynomial", "0.9979,-0.0838,0.0011,-0.0012", "--restitution-valid", "0.2,3.13"]
    for b in ("1", "2"):
        cmd += [f"--m{b}", repr(M["m" + b]), f"--k{b}", repr(M["k" + b]), f"--fy{b}", repr(M["fy" + b])]
    o = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
    pairs = [("impact_count", o["impact_count"], f["impacts/impact_count"][0, 0, g]),
             ("peak_force", o["peak_force"], f["impacts/peak_force"][0, 0, g]),
             ("peak_u1", o["peak_u1"][0], f["impacts/peak_u1"][0, 0, g]),
             ("peak_u2", o["peak_u2"][0], f["impacts/peak_u2"][0, 0, g]),
             ("restitution_outside", o.get("restitution_outside_valid", 0), out[0, 0, g])]
    for name, a, b in pairs:
        assert a == b, (g, name, a, b)  # bit for bit
    touched += o["impact_count"] > 0
    if o["impact_count"] > 0:
        assert f["impacts/peak_force"][0, 0, g] != e["impacts/peak_force"][0, 0, g], (g, "e(v0) changed nothing")
        assert p["impacts/peak_force"][0, 0, g] != e["impacts/peak_force"][0, 0, g], (g, "the preset changed nothing")
assert touched >= 2 and out[0, 0, 0] > 0, (touched, out[()])  # impacts at two gaps, some outside [0.2, 3.13] m/s
print("study lanes = simulate --restitution-*, bit for bit at", len(f["gaps/metres"][0]), "gaps; outside:", out[()].ravel())
PY
grep -q "^Each impact took e(v0).*: [0-9]* of [0-9]* impacts" "$tmp/s.md" || grep -q "[0-9]* of [0-9]* impacts (analyses not excluded) had an approach velocity outside" "$tmp/s.md" ||
  fail "the report does not count the impacts outside the valid range: $(grep -n 'e(v0)' "$tmp/s.md")"

# 4. systems (bridge26): [contact] restitution in a bridge study -- the four-frame test bridge of cli.study_bridge
# (without joint 2's own restitution) under a stronger two-tone record, gap ratio 1 (the file's joint gaps): a lane equals `simulate --bridge` with the
# same --restitution-* options bit for bit (per-joint impact counts and peak forces, every frame's peak, the impacts
# outside the valid range summed over the joints and per joint: impacts/element_restitution_outside, and the report's
# per-joint list); the key acts (e = 0.6 gives other forces); results invariant over
# ranks, threads, batch width and skip_untouched. A shear-building study takes the curve too (its forces differ from
# the constant e's; restitution_outside written).
bstudy=$src/tests/data/bridge/study-four-frame.toml
awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
       a = 0.35 * sin(2 * 3.14159265 * 1.1 * t) + 0.2 * sin(2 * 3.14159265 * 2.3 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$tmp/brec.txt"
sed -n '/^\[bridge\]/,/^\[contact\]/p' "$bstudy" | sed -e '/^\[bridge\]/d' -e '/^\[contact\]/d' -e '/^restitution = [0-9.]*$/d' -e 's/^\[\(\[*\)bridge\./[\1/' > "$tmp/bridge.toml"
bridge_study() {  # <contact line> > study
  sed -e 's/^suite = "builtin"/files = ["brec.txt"]\nunits = "g"/' -e '/^limit = /d' -e 's/^polarity = "both"/polarity = "recorded"/' \
      -e 's/^ratios = .*/ratios = [1.0]/' -e '/^restitution = [0-9.]*$/d' -e "s|^e = 0.6\$|$1|" "$bstudy"
}
bridge_study "restitution = $curve" > "$tmp/bs.toml"
bridge_study "e = 0.6" > "$tmp/be.toml"
grep -q "^restitution = " "$tmp/bs.toml" || fail "no restitution in the bridge study"
(cd "$tmp" && "$bin" run bs.toml --out bs.h5 > bs.md 2> bs.err) || fail "the bridge study with restitution does not run: $(cat "$tmp/bs.err")"
grep -q "^Each impact took e(v0).* 1 of [0-9]* impacts (analyses not excluded) had an approach velocity outside" "$tmp/bs.md" ||
  fail "the bridge report does not count the impacts outside the valid range: $(grep -n 'e(v0)' "$tmp/bs.md")"
(cd "$tmp" && "$bin" run be.toml --out be.h5 --quiet > /dev/null 2>&1) || fail "the bridge study with e does not run"
"$bin" simulate --record "$tmp/brec.txt" --bridge "$tmp/bridge.toml" --contact hertzdamp --kh 2e9 --dt 0.0025 --json \
  --restitution-polynomial 0.9979,-0.0838,0.0011,-0.0012 --restitution-valid 0.2,3.13 > "$tmp/bsim.json"
"$py" - "$tmp/bs.h5" "$tmp/be.h5" "$tmp/bsim.json" "$tmp/bs.md" <<'PY'
import json, sys, h5py, numpy as np
f, e, o = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), json.load(open(sys.argv[3]))
cnt = list(f["impacts/element_impact_count"][()].ravel())
assert cnt == [l["impacts"] for l in o["levels"]], (cnt, [l["impacts"] for l in o["levels"]])
assert list(f["impacts/element_peak_force"][()].ravel()) == [l["peak_force"] for l in o["levels"]]
for b in (1, 2, 3, 4):
    assert f[f"impacts/peak_u{b}"][()].ravel()[0] == max(o[f"peak_u{b}"]), b
out = f["impacts/restitution_outside"][()].ravel()[0]
assert out == o["restitution_outside_valid"], (out, o["restitution_outside_valid"])
assert min(cnt) > 0 and out > 0, (cnt, out)  # every joint hit, some impacts outside [0.2, 3.13] m/s
# per joint ([R, M, G, E]): simulate's per-level counts, summing to the total; the report lists them by joint
per = f["impacts/element_restitution_outside"]
assert per.attrs["units"] in ("1", b"1") and per.shape[-1] == len(cnt), per.shape
assert list(per[()].ravel()) == [l["restitution_outside"] for l in o["levels"]], (per[()], o["levels"])
assert sum(per[()].ravel()) == out
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
study_gap = [f["system/group_study_gap"][g] for g in f["system/element_group"][()]]
want = ", ".join(f"{l} {n}" for l, n, s in zip(labels, per[()].ravel(), study_gap) if s)
md = open(sys.argv[4]).read()
assert f"Impacts outside the valid range per contact element: {want}." in md, (want, [l for l in md.splitlines() if "per contact element" in l])
assert "element_restitution_outside" not in e["impacts"]
assert "restitution_outside" not in e["impacts"]
assert list(e["impacts/element_peak_force"][()].ravel()) != list(f["impacts/element_peak_force"][()].ravel()), "e(v0) changed nothing"
print("bridge study lane = simulate --bridge --restitution-*: impacts", cnt, "outside", out)
PY
study=$tmp/bs.toml
rm -f "$tmp"/r0.h5 "$tmp"/r1.h5 "$tmp"/r2.h5 "$tmp"/narrow.h5 "$tmp"/full.h5  # the pair study's (another study's files)
study_invariance
study "restitution = $curve" | sed 's/^height = 20.0/height = 20.0\nmodel = "shear"\nstorey_height = 4.0/; s/^height = 30.0/height = 30.0\nmodel = "shear"\nstorey_height = 3.0/' > "$tmp/sh.toml"
study 'e = 0.65' | sed 's/^height = 20.0/height = 20.0\nmodel = "shear"\nstorey_height = 4.0/; s/^height = 30.0/height = 30.0\nmodel = "shear"\nstorey_height = 3.0/' > "$tmp/she.toml"
for x in sh she; do with_analysis 'substeps = 8' "$tmp/$x.toml" "$tmp/$x.8" && mv "$tmp/$x.8" "$tmp/$x.toml"; done  # h omega_c
(cd "$tmp" && "$bin" run sh.toml --out sh.h5 --quiet > /dev/null 2> sh.err) || fail "the shear study with restitution does not run: $(cat "$tmp/sh.err")"
(cd "$tmp" && "$bin" run she.toml --out she.h5 --quiet > /dev/null 2>&1) || fail "the shear study with e does not run"
"$py" - "$tmp/sh.h5" "$tmp/she.h5" <<'PY'
import sys, h5py, numpy as np
f, e = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
c = f["impacts/impact_count"][()]
assert (c > 0).any(), "the shear study never pounds"
assert f["impacts/restitution_outside"].attrs["units"] in ("1", b"1")
touched = c > 0
assert not np.array_equal(f["impacts/peak_force"][()][touched], e["impacts/peak_force"][()][touched]), "e(v0) changed nothing"
print("shear study with e(v0): impacts", c.ravel(), "outside", f["impacts/restitution_outside"][()].ravel())
PY

# 3. bad input
study "e = 0.6
restitution = $curve" > "$tmp/b1.toml"
bad_run "e and restitution both given.*b1.toml:[0-9]* \[contact\].e" b1.toml
study "restitution = $curve" | sed 's/^law = "hertzdamp"/law = "kelvin"\nstiffness = 1e9/' > "$tmp/b2.toml"
bad_run "hertzdamp.*b2.toml:[0-9]* \[contact\].restitution" b2.toml
study "restitution = $curve" | sed 's/^scene = "impacts"/scene = "probability"/' > "$tmp/b3.toml"
bad_run "impacts scene.*b3.toml:[0-9]* \[contact\].restitution" b3.toml
printf '[analysis]\nstepper = "rk4"\n' | cat <(study "restitution = $curve") - > "$tmp/b4.toml"
bad_run "central-difference.*b4.toml:[0-9]* \[contact\].restitution" b4.toml
study 'restitution = "lindsay2012"' > "$tmp/b5.toml"
bad_run "unknown restitution preset 'lindsay2012'.*b5.toml:[0-9]* \[contact\].restitution" b5.toml
study 'restitution = {polynomial = [0.9, -0.1], table = [[0.5, 0.9], [3.0, 0.7]]}' > "$tmp/b6.toml"
bad_run "more than one curve.*\[contact\].restitution" b6.toml
study 'restitution = {polynomial = [0.9, -0.1], units = "km/h"}' > "$tmp/b7.toml"
bad_run "unknown velocity units 'km/h'.*\[contact.restitution\].units" b7.toml
study 'restitution = {polynomial = [0.9, -0.1], valid = [3.0, 1.0]}' > "$tmp/b8.toml"
bad_run "valid is not.*\[contact.restitution\].valid" b8.toml
study 'restitution = {table = [[0.5, 0.9], [3.0]]}' > "$tmp/b9.toml"
bad_run "not a list of points.*\[contact.restitution\].table" b9.toml
study 'restitution = {table = [[3.0, 0.9], [0.5, 0.7]]}' > "$tmp/b10.toml"
bad_run "not usable.*\[contact.restitution\].table" b10.toml
study 'restitution = {preset = "lindsay2011", valid = [0.1, 2.0]}' > "$tmp/b11.toml"
bad_run "preset carries its own.*\[contact.restitution\].valid" b11.toml
study "restitution = $curve" | sed 's/^height = 20.0/height = 20.0\nmodel = "shear"\nstorey_height = 4.0\nisolation = {bearing = "linear", base_mass = 3.0e5, k_eff = 1.0e6, zeta_eff = 0.0}\nmoat = {gap = 0.05}/; s/^height = 30.0/height = 30.0\nmodel = "shear"\nstorey_height = 3.0/' > "$tmp/b12.toml"
bad_run "building 1 has a moat.*b12.toml:[0-9]* \[contact\].restitution" b12.toml
bridge_study "restitution = $curve" | sed 's/^gap = 0.0127$/gap = 0.0127\nrestitution = 0.5/' > "$tmp/b13.toml"
bad_run "gives its own restitution.*\[bridge.joint1\].restitution" b13.toml
echo "study e(v0): simulate agreement, the key acts, report, bad input"
