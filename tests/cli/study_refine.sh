#!/usr/bin/env bash
# [analysis] coarse = "refine" (issue 45 item 1), the default of a study that gives no step: a coupled analysis the
# resolution guard marks coarse is run again alone at a shorter step (physics::choose_step, as simulate without --dt).
#  1. Two shear buildings (tests/lib/shear_pair_study.sh) with a stiff Hertzdamp contact (kh 1e11 N/m^1.5) at the
#     impacts scene's default step (record step 0.01 s / 4): coarse = "exclude" excludes every coupled analysis (status
#     3, exit 3); the default refines them all: none excluded, exit 0, impacts/substeps above the study's 4, the run
#     and the report say how many and at which substeps, and each refined analysis's peak force is, bit for bit,
#     `pounding simulate --dt` at its step and within 2 % of simulate at a 20 us step (measured 0.15-1.02 %; the
#     coarse runs were 6-9 % off).
#     [outputs] histories reruns a refined analysis at its own substeps (its peaks the stored ones).
#  2. Bits: the quick storeys study with that contact (about 100 refined analyses among 384, SDOF and shear lanes of
#     every topology) gives the same file on 1 process, mpirun -np 1 and -np 2, with batch = 1 and with skip_untouched
#     = false; the analyses that were not coarse keep the bits of coarse = "exclude"; and the SDOF pair kernel's coupled
#     runs (the small synthetic study, linear contact 1e11 N/m) refine alike on 1 and 2 processes.
#  3. A study that gives max_dt keeps coarse = "exclude" (its step is the user's), and an unknown policy is refused.
# Synthetic records only. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp, study_invariance, with_analysis
. "$src/tests/lib/shear_pair_study.sh"  # sine_record, shear_pair_study
fail() { echo "FAIL: $*"; exit 1; }
py=/usr/bin/python3
"$py" -c 'import h5py' 2>/dev/null || { echo "SKIPPED: needs $py with h5py"; [ "${CI:-}" = true ] && exit 1; exit 77; }

# 1. exclude against refine, and simulate
sine_record "$tmp/rec.txt" 0.25 0.9 0.10 3.1
shear_pair_study "$tmp/refine.toml" 'title="stiff contact"' 'contact.stiffness=1e11' 'analysis.max_dt='
shear_pair_study "$tmp/exclude.toml" 'title="stiff contact"' 'contact.stiffness=1e11' 'analysis.max_dt=' \
  'analysis.coarse="exclude"'
rc=0; "$bin" run "$tmp/exclude.toml" --out "$tmp/exclude.h5" > "$tmp/exclude.out" 2>&1 || rc=$?
[ $rc -eq 3 ] || fail "coarse = \"exclude\": exit $rc, want 3 (every coupled analysis excluded): $(tail -3 "$tmp/exclude.out")"
grep -q "^coarse: 4 analyses (max h·ω_c 0\.8[0-9]*, limit 0.274); excluded from the statistics" "$tmp/exclude.out" ||
  fail "coarse = \"exclude\": $(grep -a '^coarse' "$tmp/exclude.out")"
"$bin" run "$tmp/refine.toml" --out "$tmp/refine.h5" > "$tmp/refine.out" 2>&1 || fail "refine: exit $?: $(tail -3 "$tmp/refine.out")"
grep -q "^coarse: 0 analyses (max h·ω_c 0\.2[0-7][0-9]*, limit 0.274); refined: 4 analyses run again at a shorter step (16 substeps)$" \
  "$tmp/refine.out" || fail "refine: the run does not say what it refined: $(grep -a '^coarse' "$tmp/refine.out")"
"$bin" report "$tmp/refine.h5" > "$tmp/refine.md"
grep -q "coupled (coarse, diverged or non-finite) 0 of 4; refined: 4 analyses run again at a shorter step (16 substeps)$" \
  "$tmp/refine.md" || fail "the report's excluded line: $(grep 'excluded analyses' "$tmp/refine.md")"
grep -q '^coarse = "refine"' <("$py" -c "
import h5py, sys; print('coarse = \"' + h5py.File(sys.argv[1], 'r')['settings/analysis'].attrs['coarse'] + '\"')" "$tmp/refine.h5") ||
  fail "/settings/analysis coarse is not refine"
echo "ok   kh 1e11: exclude -> 4 of 4 coupled analyses excluded (exit 3); refine -> 0 excluded, 4 refined at 16 substeps"
sim() {  # the study's pair: 3 storeys (0.78 s) beside 5 (1.22 s), uniform 3e5 kg and 9.80665e7 N/m, zeta 0.05
  "$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storey-mass1 3e5 --storey-stiffness1 9.80665e7 --storeys2 5 \
    --storey-mass2 3e5 --storey-stiffness2 9.80665e7 --elastic --zeta 0.05 --contact hertzdamp --e 0.5 --kh 1e11 --json "$@"
}
for g in 0.0128 0.0256 0.064 0.128; do  # the study's gaps: ratios 0.1, 0.2, 0.5, 1 of d = 0.128 m
  sim --gap $g --dt 0.000625 > "$tmp/at-$g.json"   # the refined step: record step 0.01 s / 16
  sim --gap $g --dt 0.00002 > "$tmp/fine-$g.json"
done
"$py" - "$tmp" <<'PY'
import json, sys
import h5py, numpy as np
tmp = sys.argv[1]
ex, rf = h5py.File(f"{tmp}/exclude.h5", "r"), h5py.File(f"{tmp}/refine.h5", "r")
st_ex, st = ex["impacts/status"][()].ravel(), rf["impacts/status"][()].ravel()
n = rf["impacts/substeps"][()].ravel()
assert (st_ex == 3).all() and (st == 0).all(), (st_ex, st)
assert (n == 16).all() and rf["impacts/substeps"].attrs["units"] == "1", n
assert (rf["impacts/h_omega_contact"][()].ravel() <= 0.274).all()
worst = 0.0
for k, g in enumerate(["0.0128", "0.0256", "0.064", "0.128"]):
    at, fine = json.load(open(f"{tmp}/at-{g}.json")), json.load(open(f"{tmp}/fine-{g}.json"))
    f, f_ex = rf["impacts/peak_force"][()].ravel()[k], ex["impacts/peak_force"][()].ravel()[k]
    assert f == at["peak_force"], (g, f, at["peak_force"])
    assert rf["impacts/impact_count"][()].ravel()[k] == at["impact_count"]
    err, err_ex = abs(f / fine["peak_force"] - 1), abs(f_ex / fine["peak_force"] - 1)
    assert err < 0.02 and err_ex > 2 * err, (g, err, err_ex)
    worst = max(worst, err)
    print(f"ok   gap {g} m: refined peak force {f / 1e6:.4f} MN == simulate --dt 0.000625; {100 * err:.2f} % from "
          f"--dt 2e-5 ({fine['peak_force'] / 1e6:.4f} MN); the coarse run's was {100 * err_ex:.1f} % off")
PY

# [outputs] histories of a refined analysis: rerun at its own substeps, its peaks equal to the stored ones
cp "$tmp/refine.toml" "$tmp/hist.toml"
printf '\n[outputs]\nhistories = [{ record = 0, model = 0, gap = 0.5 }]\n' >> "$tmp/hist.toml"
"$bin" run "$tmp/hist.toml" --out "$tmp/hist.h5" > "$tmp/hist.out" 2>&1 || fail "histories: exit $?: $(tail -3 "$tmp/hist.out")"
! grep -q WARNING "$tmp/hist.out" || fail "histories: $(grep WARNING "$tmp/hist.out")"
"$py" - "$tmp/hist.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
h, g = f["histories/1"].attrs, list(f["impacts/gap_ratios"][()]).index(0.5)
assert h["substeps"] == f["impacts/substeps"][()].ravel()[g] == 16, (h["substeps"], f["impacts/substeps"][()])
assert h["peak_force"] == f["impacts/peak_force"][()].ravel()[g] and h["status"] == 0, (h["peak_force"], h["status"])
print(f"ok   the history of the refined analysis at gap ratio 0.5: 16 substeps, peak force {h['peak_force']:.6g} N as stored")
PY

# 2. bits: ranks, batch width, skip_untouched; the analyses that were not coarse as with "exclude"
sed -e 's/^e = 0.65/e = 0.65\nstiffness = 1e11/' -e 's/^output = .*/output = "qs.h5"/' "$src/studies/quick-storeys.toml" > "$tmp/qs.toml"
study=$tmp/qs.toml
study_invariance  # fails the script (set -e) on the first difference
with_analysis 'coarse = "exclude"' "$study" "$tmp/qs-exclude.toml"
"$bin" run "$tmp/qs-exclude.toml" --out "$tmp/qs-exclude.h5" --quiet > /dev/null 2>&1 || true
check_kept() {  # check_kept <exclude.h5> <refine.h5>: every dataset equal where "exclude" had no coarse analysis
  "$py" - "$1" "$2" <<'PY'
import sys
import h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
st = a["impacts/status"][()]
coarse, bad, n = st == 3, [], 0
def visit(name, y):
    global n
    if not isinstance(y, h5py.Dataset) or name.startswith("timing/") or name == "impacts/substeps":
        return
    x, y = a[name][()], y[()]
    if name.startswith("impacts/") and x.shape[:st.ndim] == st.shape:
        x, y = x[~coarse], y[~coarse]
    if x.shape != y.shape or not (np.array_equal(x, y, equal_nan=True) if x.dtype.kind == "f" else np.array_equal(x, y)):
        bad.append(name)
    n += 1
b.visititems(visit)
assert not bad, bad
assert coarse.sum() > 0 and (b["impacts/status"][()][coarse] == 0).all(), np.bincount(b["impacts/status"][()][coarse])
assert (b["impacts/substeps"][()][coarse] > b["impacts/substeps"][()][~coarse].max()).all()
print(f"ok   {coarse.sum()} coarse analyses refined to status 0; {n} datasets equal to coarse = \"exclude\" elsewhere")
PY
}
check_kept "$tmp/qs-exclude.h5" "$tmp/r0.h5"
echo "ok   quick storeys, kh 1e11: 1 process == mpirun -np 1 == -np 2 == batch 1 == skip_untouched false"
# the SDOF pair kernel's coupled runs
sed -e 's/^law = "hertzdamp"/law = "linear"\nstiffness = 1e11/' -e 's/^samples_per_pair = 8/samples_per_pair = 2/' \
  "$src/tests/data/study-small-synthetic.toml" > "$tmp/sp.toml"
"$bin" run "$tmp/sp.toml" --out "$tmp/sp1.h5" > "$tmp/sp.out" 2>&1 || fail "SDOF pairs: exit $?"
grep -q "^coarse: 0 analyses .*; refined: [1-9][0-9]* analyses" "$tmp/sp.out" || fail "SDOF pairs: $(grep -a '^coarse' "$tmp/sp.out")"
timeout 120 mpirun -np 2 "$bin" run "$tmp/sp.toml" --out "$tmp/sp2.h5" --quiet > /dev/null 2>&1
cmp "$tmp/sp1.h5" "$tmp/sp2.h5" || fail "SDOF pairs: 1 and 2 processes differ"
with_analysis 'coarse = "exclude"' "$tmp/sp.toml" "$tmp/sp-exclude.toml"
"$bin" run "$tmp/sp-exclude.toml" --out "$tmp/sp-exclude.h5" --quiet > /dev/null 2>&1 || true
check_kept "$tmp/sp-exclude.h5" "$tmp/sp1.h5"
echo "ok   SDOF pairs, linear 1e11: $(grep -ao 'refined: [0-9]* analyses[^;]*' "$tmp/sp.out" | head -1); 1 == 2 processes"

# 3. a given step keeps "exclude"; an unknown policy
shear_pair_study "$tmp/given.toml" 'title="stiff contact, max_dt given"' 'contact.stiffness=1e11' 'analysis.max_dt=0.0025'
rc=0; "$bin" run "$tmp/given.toml" --out "$tmp/given.h5" > "$tmp/given.out" 2>&1 || rc=$?
[ $rc -eq 3 ] && grep -q '^coarse: 4 analyses .*excluded from the statistics (\[analysis\] coarse = "exclude"; "refine" runs them' \
  "$tmp/given.out" || fail "max_dt given: exit $rc, $(grep -a '^coarse' "$tmp/given.out")"
echo "ok   max_dt = 0.0025 given: coarse = \"exclude\" (4 excluded, exit 3), the line names \"refine\""
shear_pair_study "$tmp/bad.toml" 'title="bad policy"' 'analysis.coarse="finer"'
bad_run 'unknown coarse policy .finer.*\[analysis\]\.coarse.*"refine"' bad.toml
echo "ok   coarse = \"finer\": refused"
echo "study_refine: ok"
