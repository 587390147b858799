#!/usr/bin/env bash
# Fragility studies of shear buildings (issue 25: [intensity] with model = "shear"; studies/fragility-storeys.toml,
# small: 3 synthetic records x 2 signs, 6 models):
#  1. MSA (stripes) and IDA (bisection) give bit-identical results without mpirun, on 1 and 2 ranks, on one thread
#     and at batch width 2;
#  2. the stripes' shortcut is the model trait (SystemBlock::scales_linearly): linear shear buildings (hysteresis =
#     "elastic") take every stripe above the lowest from the lowest one's run, and every peak -- per building, per
#     floor (displacement, drift, absolute acceleration) and per contact element -- equals the run of every stripe
#     (scale_elastic = false) to 1e-12 relative; yielding ones: the analyses run are bit-identical to the full run,
#     some above the lowest stripe are scaled (storeys still elastic) and some run;
#  3. one lane of one stripe is `pounding simulate` with the same shear buildings on the record times the stripe's
#     factor, bit for bit (every floor's peak |u|, drift and closing at every level); the IDA's final brackets hold
#     the first contact: simulate at scale_lo does not reach the gap, at scale_hi it does;
#  4. the report and the HTML report have the fragility fit, the hazard and the risk-targeted separation, their
#     numbers checked against the HDF5 file (tests/cli/report_html_check.py, numpy);
#  5. bad input: one ERROR each, before any work.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, with_analysis, expect_error
py=${POUNDING_PYTHON:-/usr/bin/python3}
fail() { echo "FAIL: $*"; exit 1; }

small() {  # the shipped study, small; $1: extra sed expression
  sed -e 's/^samples_per_pair = 20 /samples_per_pair = 6 /' -e 's/^limit = 10/limit = 3/' -e '/^output = /d' \
      -e 's/^bootstrap = 2000/bootstrap = 200/' -e "s|^curve = \"example-hazard.csv\"|curve = \"$src/studies/example-hazard.csv\"|" \
      -e "${1:-b}" "$src/studies/fragility-storeys.toml"
}
run() { "$bin" run "$tmp/$1.toml" --out "$tmp/$1.h5" --quiet "${@:2}" > "$tmp/$1.log" 2>&1 || { cat "$tmp/$1.log"; fail "$1 did not run"; }; }

# 1. invariance, MSA and IDA
small > "$tmp/msa.toml"
small 's/^max_scale = 10/max_scale = 10\nmethod = "ida"\ntolerance = 0.01/' > "$tmp/ida.toml"
for m in msa ida; do
  run $m
  cp "$tmp/$m.toml" "$tmp/${m}_t1.toml" && run ${m}_t1 --threads 1
  timeout 120 mpirun -np 1 "$bin" run "$tmp/$m.toml" --out "$tmp/${m}_r1.h5" --quiet > /dev/null 2>&1
  timeout 120 mpirun -np 2 "$bin" run "$tmp/$m.toml" --out "$tmp/${m}_r2.h5" --quiet > /dev/null 2>&1
  with_analysis 'batch = 2' "$tmp/$m.toml" "$tmp/${m}_b2.toml" && run ${m}_b2
  for o in t1 r1 r2; do cmp "$tmp/$m.h5" "$tmp/${m}_$o.h5" --ignore=output; done
  cmp "$tmp/$m.h5" "$tmp/${m}_b2.h5" --ignore=study_text,batch,output
done
"$py" - "$tmp/msa.h5" "$tmp/ida.h5" <<'PY'
import sys, h5py, numpy as np
msa, ida = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
assert msa.attrs["format_version"] == 3 and "fragility" in msa and "hazard" in msa
assert (msa["uncoupled/status"][()] != 1).all(), "diverged analyses"
assert np.isfinite(msa["fragility/theta"][()]).sum() >= 3, msa["fragility/theta"][()]
assert np.isfinite(ida["fragility/theta"][()]).sum() >= 3, ida["fragility/theta"][()]
lo, hi = ida["ida/scale_lo"][()], ida["ida/scale_hi"][()]
found = np.isfinite(hi)
assert found.any() and (lo[found] <= hi[found]).all()
assert (hi[found & (lo < hi)] <= lo[found & (lo < hi)] * 1.01 * (1 + 1e-12)).all(), "a bracket wider than the tolerance"
print("msa, ida: bits equal over threads, ranks (1, 2), batch width; theta msa",
      np.round(msa["fragility/theta"][()], 3).tolist(), "ida", np.round(ida["fragility/theta"][()], 3).tolist())
PY

# 2. the linear-scaling trait against every stripe run
with_analysis 'scale_elastic = false' "$tmp/msa.toml" "$tmp/msa_full.toml" && run msa_full
small 's/^alpha = 0.05/hysteresis = "elastic"/' > "$tmp/el.toml" && run el
with_analysis 'scale_elastic = false' "$tmp/el.toml" "$tmp/el_full.toml" && run el_full
"$py" - "$tmp" <<'PY'
import sys, h5py, numpy as np
tmp = sys.argv[1]
rows = ["peak_u1", "peak_u2", "peak_closing", "peak_u_floors1", "peak_u_floors2", "peak_drift1", "peak_drift2",
        "peak_acc_floors1", "peak_acc_floors2", "peak_closing_elements"]
for fast, full, elastic in (("msa", "msa_full", False), ("el", "el_full", True)):
    A, B = h5py.File(f"{tmp}/{fast}.h5", "r"), h5py.File(f"{tmp}/{full}.h5", "r")
    sa, sb = A["uncoupled/status"][()], B["uncoupled/status"][()]
    assert np.array_equal(sa, sb), "statuses differ"
    use = sa == 0
    flag = A["uncoupled/scaled"][()]
    assert not flag[0].any(), "the lowest stripe was scaled"
    assert not B["uncoupled/scaled"][()].any(), "scale_elastic = false scaled"
    ran = (flag == 0) & use
    worst = 0.0
    for name in rows:
        x, y = A["uncoupled/" + name][()], B["uncoupled/" + name][()]
        u = use.reshape(use.shape + (1,) * (x.ndim - use.ndim)) & np.isfinite(y)
        u = np.broadcast_to(u, x.shape)
        assert np.array_equal(np.isnan(x), np.isnan(y)), name
        rel = (np.abs(x - y) / np.maximum(np.abs(y), 1e-300))[u]
        worst = max(worst, rel.max())
        assert rel.max() <= 1e-12, (fast, name, rel.max())
        r = np.broadcast_to(ran.reshape(ran.shape + (1,) * (x.ndim - ran.ndim)), x.shape)
        assert np.array_equal(x[r], y[r], equal_nan=True), (fast, name, "an analysis run differs from the full run")
    n_scaled = int(flag[use].sum())
    assert n_scaled > 0, "nothing scaled: the test would not see a wrong scaling"
    if elastic:
        assert flag[1:][use[1:]].all(), "a linear shear building ran a stripe above the lowest"
    else:
        assert ran[1:].any(), "no yielding analysis ran above the lowest stripe"
    for k in ("theta", "beta"):
        assert np.allclose(A["fragility/" + k][()], B["fragility/" + k][()], rtol=1e-9, equal_nan=True), k
    print(f"{fast}: {n_scaled} of {int(use.sum())} analyses scaled; largest relative difference from the full run {worst:.1e}")
PY

# 3. a lane is pounding simulate: fixed storeys (floor_mass, storey_stiffness), one text record, both signs off
awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
       a = 0.12 * sin(2 * 3.14159265 * 0.9 * t) * exp(-0.15 * t) + 0.06 * sin(2 * 3.14159265 * 2.3 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
fixed() {
  small "$1" | sed -e 's/^suite = "builtin"/files = ["rec.txt"]\npolarity = "recorded"/' -e '/^synthetic_only/d' -e '/^limit = /d' \
    -e 's/^samples_per_pair = 6 /samples_per_pair = 2 /' \
    -e 's/^mass = 3.1e6/mass = 3.1e6\nfloor_mass = 3.875e5\nstorey_stiffness = 6e8/' \
    -e 's/^mass = 4.7e6/mass = 4.7e6\nfloor_mass = 3.9e5\nstorey_stiffness = 4e8/'
}
fixed 's/^max_scale = 10/max_scale = 10\n\n[analysis]\nscale_elastic = false/' > "$tmp/one.toml"
fixed 's/^max_scale = 10/max_scale = 10\nmethod = "ida"\ntolerance = 0.02/' > "$tmp/one_ida.toml"
(cd "$tmp" && run one && run one_ida)
sim() {  # factor out.json
  "$py" -c "
import sys
f = float(sys.argv[1])
for line in open(sys.argv[2]):
    t, a = line.split()
    print(t, repr(f * (float(a) * 9.80665)))" "$1" "$tmp/rec.txt" > "$tmp/scaled.txt"
  "$bin" simulate --record "$tmp/scaled.txt" --units m/s2 --contact none --zeta 0.05 --alpha 0.05 \
    --storeys1 8 --storey-mass1 3.875e5 --storey-stiffness1 6e8 --storey-height1 3.5 \
    --storeys2 12 --storey-mass2 3.9e5 --storey-stiffness2 4e8 --storey-height2 3.5 --json > "$2"
}
stripe_factor=$("$py" -c "import h5py; print(repr(float(h5py.File('$tmp/one.h5', 'r')['intensity/scale'][6, 0])))")
sim "$stripe_factor" "$tmp/lane.json"
"$py" - "$tmp/one.h5" "$tmp/lane.json" <<'PY'
import sys, json, h5py, numpy as np
f, j = h5py.File(sys.argv[1], "r"), json.load(open(sys.argv[2]))
u = f["uncoupled"]
assert list(u["peak_u_floors1"][6, 0, 0]) == j["peak_u1"], (u["peak_u_floors1"][6, 0, 0], j["peak_u1"])
assert list(u["peak_u_floors2"][6, 0, 0]) == j["peak_u2"]
assert list(u["peak_drift1"][6, 0, 0]) == j["peak_drift1"] and list(u["peak_drift2"][6, 0, 0]) == j["peak_drift2"]
assert list(u["peak_closing_elements"][6, 0, 0]) == [l["peak_closing"] for l in j["levels"]]
assert u["peak_closing"][6, 0, 0] == max(l["peak_closing"] for l in j["levels"])
assert max(j["peak_drift1"]) > 0.02 / 6 * 3.5, "the lane should yield at this stripe (else test a higher one)"
print("stripe 7, record 1, model 1 = pounding simulate on the record x", f["intensity/scale"][6, 0], ": peak closing",
      round(u["peak_closing"][6, 0, 0], 4), "m")
PY
# the IDA's brackets: up to 3 bisected (model, gap) of record 1, each checked at both ends
check_ida_brackets "$tmp/one_ida.h5"

# 4. report and HTML report
"$bin" report "$tmp/msa.h5" > "$tmp/msa.md"
for h in "## Risk-targeted separation" "## Fragility per gap" "## Site hazard" "## Stripes and scale factors"; do
  grep -q "^$h" "$tmp/msa.md" || fail "the report has no '$h'"
done
"$bin" report "$tmp/ida.h5" > "$tmp/ida.md"  # to a file: grep -q would close a pipe under pipefail
grep -q "^## Risk-targeted separation" "$tmp/ida.md" || fail "the IDA report has no risk-targeted separation"
"$bin" report "$tmp/msa.h5" --html "$tmp/msa.html" > /dev/null 2>&1 || fail "report --html"
for h in "Risk-targeted separation" "Fragility per gap" "Site hazard"; do
  grep -q "<h[23][^>]*>$h" "$tmp/msa.html" || fail "the HTML report has no '$h'"
done
# its numbers against the Markdown and against theta and the separation recomputed from the HDF5 file with numpy
for m in msa ida; do
  "$bin" report "$tmp/$m.h5" > "$tmp/$m.md" && "$bin" report "$tmp/$m.h5" --html "$tmp/$m.html" > /dev/null 2>&1
  "$py" "$src/tests/cli/report_html_check.py" "$tmp/$m.h5" "$tmp/$m.md" "$tmp/$m.html" || fail "$m: HTML report check"
done

# 5. bad input
fails=0
body=$(cat "$tmp/msa.toml")
expect_error stereomechanical ':[0-9]* \[contact\].law, choose a force law' \
  "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "stereomechanical"/')"
expect_error stepper ':[0-9]* \[analysis\].stepper, write stepper = "central-difference"' \
  "$(echo "$body" | sed 's/^\[contact\]/[analysis]\nstepper = "nigam-jennings"\n\n[contact]/')"
expect_error scene_impacts 'runs in the probability scene' \
  "$(echo "$body" | sed 's/^scene = "probability"/scene = "impacts"/')"
# (a row, refused here before, runs: cli.fragility_rows)
[ $fails -eq 0 ]
echo "fragility with shear buildings: invariance, the scaling trait, simulate agreement, IDA brackets, report, bad input"
