#!/usr/bin/env bash
# Shear buildings in studies ([structures] model = "shear", issue 25 §6, docs/architecture.md §2.6.2, §2.7.1):
#  1. studies/quick-storeys.toml gives bit-identical results at 1 and 2 MPI ranks, at batch width 1 and its
#     default, and with skip_untouched = false (every model rerun with contact: the first passage of systems);
#  2. its coupled runs touch exactly where the uncoupled D = max over levels of the peak closing exceeds the gap;
#  3. model = "shear" with one storey per building is the SDOF study bit for bit (the results differ only in the
#     settings that name the model);
#  4. bad shear keys get one ERROR naming file:line and the key, exit 2, before any work.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
study=$src/studies/quick-storeys.toml
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance

# 1. ranks, batch width, skip_untouched
study_invariance

# 2. touch <=> D > gap, in the run where every model is run with contact; both outcomes occur
/usr/bin/python3 - "$tmp/full.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
R, M = f["uncoupled/peak_closing"].shape
G = len(f["impacts/gap_ratios"])
D = f["uncoupled/peak_closing"][()]
d = f["models/code_gap"][()]
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
ok = (f["uncoupled/status"][()].reshape(R, M) == 0)[:, :, None] & (f["impacts/status"][()].reshape(R, M, G) == 0)
touch = D[:, :, None] > f["impacts/gap_ratios"][()][None, None, :] * d[None, :, None]
assert ok.all(), "failed analyses"
assert np.array_equal(touch, cnt > 0), (touch.sum(), (cnt > 0).sum())
assert 0 < touch.sum() < touch.size, touch.sum()
print(f"{touch.sum()} of {touch.size} analyses touch, coupled and uncoupled agree")
# results format 3: the per-floor and per-element rows agree with the [R, M] totals (NaN above a shorter roof)
assert f.attrs["format_version"] == 3
u = f["uncoupled"]
for b in (1, 2):
    fl = u[f"peak_u_floors{b}"][()]
    assert fl.shape == (R, M, 16) and np.array_equal(np.nanmax(fl, axis=2), u[f"peak_u{b}"][()])
    assert np.isnan(fl).any() and not np.isnan(fl[:, :, :9]).any()  # 9 to 16 storeys
assert np.array_equal(np.nanmax(u["peak_closing_elements"][()], axis=2), D)
ec = f["impacts/element_impact_count"][()].reshape(R, M, G, -1)
assert np.array_equal(np.where(ec < 0, 0, ec).sum(axis=3), cnt)
ef = f["impacts/element_peak_force"][()].reshape(R, M, G, -1)
assert np.array_equal(np.nanmax(ef, axis=3), f["impacts/peak_force"][()].reshape(R, M, G))
# the storeys vary per sample (9 to 16 at 3.2 m): the heights span more than one storey count
h = np.concatenate([f["models/h1"][()], f["models/h2"][()]])
assert len(set(np.maximum(1, np.round(h / 3.2)).astype(int))) >= 3
PY

# 3. one storey each: the SDOF study's numbers
base=$src/tests/data/study-small-synthetic.toml
"$bin" run "$base" --out "$tmp/sdof.h5" --quiet > /dev/null 2>&1
sed 's/^samples_per_pair = 8/samples_per_pair = 8\nmodel = "shear"\n[structures.building1]\nstoreys = 1\n[structures.building2]\nstoreys = 1/' \
  "$base" > "$tmp/one.toml"
"$bin" run "$tmp/one.toml" --out "$tmp/one.h5" --quiet > /dev/null 2>&1
cmp "$tmp/sdof.h5" "$tmp/one.h5" --ignore=study_text,output,model,stiffness_profile,storey_height,storeys --allow-added

# 4. bad input
fails=0
body=$(cat "$study")
expect_error model_name ':22 \[structures\].model, write model = "sdof" or "shear"' \
  "$(echo "$body" | sed 's/^model = "shear"/model = "frame"/')"
expect_error storey_height_zero ':23 \[structures\].storey_height' \
  "$(echo "$body" | sed 's/^storey_height = 3.2/storey_height = 0/')"
expect_error storey_height_sdof 'below 2 m for an SDOF building.*:23 \[structures\].storey_height' \
  "$(echo "$body" | sed -e 's/^model = "shear"/model = "sdof"/' -e 's/^storey_height = 3.2/storey_height = 0.1/')"
expect_error floor_mass_sdof 'floor_mass is given for an SDOF building.*\[structures.building1\].floor_mass' \
  "$(echo "$body" | sed -e 's/^model = "shear"/model = "sdof"/' -e 's/^\[gaps\]/[structures.building1]\nfloor_mass = 1e5\n\n[gaps]/')"
expect_error floor_mass_range '\[structures.building2\].floor_mass' \
  "$(echo "$body" | sed 's/^\[gaps\]/[structures.building2]\nfloor_mass = -5\n\n[gaps]/')"
expect_error storey_stiffness_range '\[structures.building1\].storey_stiffness' \
  "$(echo "$body" | sed 's/^\[gaps\]/[structures.building1]\nstorey_stiffness = 1e15\n\n[gaps]/')"
expect_error profile '\[structures\].stiffness_profile, write stiffness_profile = "uniform" or "shear"' \
  "$(echo "$body" | sed 's/^model = "shear"/model = "shear"\nstiffness_profile = "parabolic"/')"
expect_error storeys_zero '\[structures.building2\].storeys' \
  "$(echo "$body" | sed 's/^\[gaps\]/[structures.building2]\nstoreys = 0\n\n[gaps]/')"
# different storey heights run (refused before floors against columns, docs/floor-contact.md): building2's 3.0 m
# floors meet building1's 3.2 m columns and the other way round; the probability scene stays exact (D > g <=> pounds)
echo "$body" | sed 's/^\[gaps\]/[structures.building2]\nstorey_height = 3.0\n\n[gaps]/' > "$tmp/storey_heights.toml"
if "$bin" run "$tmp/storey_heights.toml" --out "$tmp/storey_heights.h5" --quiet > "$tmp/storey_heights.out" 2>&1 &&
   /usr/bin/python3 - "$tmp/storey_heights.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
assert "column 0-1/level 1" in labels and "level 1/column 1-2" in labels, labels
xl, xr = f["system/element_left_xi"][()], f["system/element_right_xi"][()]
assert abs(xl[labels.index("column 0-1/level 1")] - 3.0 / 3.2) < 1e-12, xl
assert abs(xr[labels.index("level 1/column 1-2")] - 0.2 / 3.0) < 1e-12, xr
cnt = f["impacts/element_impact_count"][()]
assert cnt.max() > 0, "no impacts"
print("ok   storey_heights: 3.2 / 3.0 m storeys run,", len(labels), "elements, e.g.", ", ".join(labels[:4]))
PY
then :; else echo "FAIL storey_heights:"; cat "$tmp/storey_heights.out"; fails=$((fails+1)); fi
expect_error level_tolerance_negative '\[contact\].level_tolerance' \
  "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "hertzdamp"\nlevel_tolerance = -0.1/')"
expect_error shape_functions_name ':32 \[contact\].shape_functions, write shape_functions = "linear" or "cubic"' \
  "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "hertzdamp"\nshape_functions = "quadratic"/')"
expect_error level_tolerance_half 'not below half the smallest storey height (1 m).*:32 \[contact\].level_tolerance, give level_tolerance < 0.5 m' \
  "$(echo "$body" | sed -e 's/^law = "hertzdamp"/law = "hertzdamp"\nlevel_tolerance = 0.6/' -e 's/^storey_height = 3.2/storey_height = 1.0/')"
b1() { echo "$body" | sed "s/^\[gaps\]/[structures.building1]\n$1\n\n[gaps]/"; }
expect_error isolation_sdof 'isolation is given for an SDOF building.*\[structures.building1\].isolation' \
  "$(b1 'model = "sdof"\nisolation = {bearing = "linear", k_eff = 1e6}')"
expect_error bearing_name ':28 \[structures.building1.isolation\].bearing, write bearing = "linear", "lead-rubber", "friction-pendulum" or "bouc-wen"' \
  "$(b1 'isolation = {bearing = "rubber-duck", k_eff = 1e6}')"
expect_error keff_missing 'the linear bearing has no k_eff.*\[structures.building1.isolation\].k_eff' \
  "$(b1 'isolation = {bearing = "linear", base_mass = 1e5}')"
expect_error lrb_keff 'k_eff is not a key of a lead-rubber bearing' \
  "$(b1 'isolation = {bearing = "lead-rubber", k_eff = 1e6, k1 = 1e7, k2 = 1e6, qd = 1e5}')"
expect_error lrb_k2 'k2 = 2e+07 N/m is not below k1.*\[structures.building1.isolation\].k2' \
  "$(b1 'isolation = {bearing = "lead-rubber", k1 = 1e7, k2 = 2e7, qd = 1e5}')"
expect_error moat_alone 'a moat is given for a building without isolation.*\[structures.building1\].moat' \
  "$(b1 'moat = {gap = 0.1}')"
expect_error moat_gap_missing 'the moat has no gap' \
  "$(b1 'isolation = {bearing = "linear", k_eff = 1e6}\nmoat = {e = 0.5}')"
expect_error moat_law_none 'law = "none" is not a contact law for a moat wall.*\[structures.building1.moat\].law' \
  "$(b1 'isolation = {bearing = "linear", k_eff = 1e6}\nmoat = {gap = 0.1, law = "none"}')"
expect_error moat_linear_no_k "the moat's law 'linear' needs a stiffness" \
  "$(b1 'isolation = {bearing = "linear", k_eff = 1e6}\nmoat = {gap = 0.1, law = "linear"}')"
expect_error stereomechanical ':[0-9]* \[contact\].law, choose a force law' \
  "$(echo "$body" | sed 's/^law = "hertzdamp"/law = "stereomechanical"/')"
# the stepper's damped stability limit the check uses, against the spectral radius of its one-step matrix
/usr/bin/python3 "$src/tools/stability_damped_cd.py" > /dev/null
expect_error stepper ':[0-9]* \[analysis\].stepper, write stepper = "central-difference"' \
  "$(echo "$body" | sed 's/^\[contact\]/[analysis]\nstepper = "nigam-jennings"\n\n[contact]/')"
# 1 m storeys (30-50 storeys) at the record step 0.01 s: beyond central difference for some sample, found before
# any unit runs (Gershgorin's bounds on M^-1 K0 and M^-1 C with the stepper's damped limit, tools/
# stability_damped_cd.py; measured 2026-11-26: substeps 2, 3, 4, 6 diverge in 64, 64, 62, 8 of the 64 analyses), with
# the step given ([analysis] substeps = 1; without it the study chooses a stable step: cli.study_step)
expect_error step_too_long 'too long for the shear buildings: sample .*\[analysis\] substeps / max_dt, give \[analysis\] substeps >= 7' \
  "$(echo "$body" | sed -e 's/^scene = "impacts"/scene = "probability"/' -e 's/^storey_height = 3.2/storey_height = 1.0/' \
       -e 's/^\[contact\]/[analysis]\nsubsteps = 1\n\n[contact]/')"
[ $fails -eq 0 ]
# and the step it advises runs every analysis (exit 0: none diverged)
echo "$body" | sed -e 's/^scene = "impacts"/scene = "probability"/' -e 's/^storey_height = 3.2/storey_height = 1.0/' \
  -e 's/^\[contact\]/[analysis]\nsubsteps = 7\n\n[contact]/' > "$tmp/advised.toml"
"$bin" run "$tmp/advised.toml" --out "$tmp/advised.h5" --quiet > /dev/null 2>&1
echo "1 passed, 0 failed"
