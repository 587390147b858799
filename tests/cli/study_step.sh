#!/usr/bin/env bash
# A study of shear buildings without [analysis] substeps / max_dt chooses a step its structures can follow
# (check_shear_steps): the quick storeys study with 1 m storeys (30-50 storeys, omega_max far above the record step's
# reach) runs instead of stopping with "give [analysis] substeps >= 7"; the chosen max_dt is stored in the results
# (/settings max_dt and the scene's reason) and printed; the results equal those of the same study with that max_dt
# written in the file (bit for bit but the settings that name how the step came about, and [analysis] coarse, whose
# default is "refine" for a chosen step and "exclude" for a given one). Given substeps = 1 it still
# stops before any work with the step that would do. A study that was stable (the shipped quick storeys study) keeps
# its step: no "step:" in its reason.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py' 2>/dev/null || { echo "SKIPPED: needs $py with h5py"; [ "${CI:-}" = true ] && exit 1; exit 77; }
cd "$tmp"
sed -e 's/^storey_height = 3.2/storey_height = 1.0/' -e 's/^scene = "impacts"/scene = "probability"/' \
    -e 's/^output = .*/output = "auto.h5"/' "$src/studies/quick-storeys.toml" > auto.toml
"$bin" run auto.toml > auto.out 2> auto.err || fail "the study without a step: exit $?: $(cat auto.err)"
grep -q 'step: max_dt = 0.00152 s, chosen for the shear buildings. stability (sample (0, 0, 5) needs h < 0.001522 s; the record step 0.01 s needs 7 substeps' auto.out auto.err ||
  fail "the run does not say which step it chose: $(grep -ih step auto.out auto.err | head -3)"
"$py" - auto.h5 <<'PY' || fail "the chosen step is not stored"
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    def find(name):
        for where in (f.attrs, f["settings"].attrs if "settings" in f else {}):
            if name in where: return where[name]
        hits = []
        f.visititems(lambda n, o: hits.append(o.attrs[name]) if name in o.attrs else None)
        return hits[0] if hits else None
    dt = float(find("max_dt"))
    reason = find("scene_reason")
    reason = reason.decode() if isinstance(reason, bytes) else str(reason)
    assert abs(dt - 0.00152) < 1e-12, dt
    assert "max_dt = 0.00152 s, chosen" in reason, reason
PY
# the same study with that max_dt given: the same results
sed -e 's/^output = .*/output = "given.h5"/' -e 's/^\[analysis\]$/[analysis]\nmax_dt = 0.00152/' auto.toml > given.toml
grep -q '^max_dt = 0.00152' given.toml || printf '\n[analysis]\nmax_dt = 0.00152\n' >> given.toml
"$bin" run given.toml --quiet > /dev/null || fail "the study with max_dt = 0.00152: exit $?"
# coarse: its default follows whether the step was given ("refine" when chosen, "exclude" when given)
"$py" "$src/tests/cli/compare_results.py" auto.h5 given.h5 --ignore=study_text,scene_reason,output,coarse > cmp.txt ||
  fail "chosen and given max_dt differ: $(head -20 cmp.txt)"
echo "ok   chosen step 0.00152 s: results equal the same study with max_dt = 0.00152"
# given substeps = 1: refused before any work, with the step that would do
sed -e 's/^output = .*/output = "one.h5"/' auto.toml > one.toml
printf '\n[analysis]\nsubsteps = 1\n' >> one.toml
grep -c '^\[analysis\]' one.toml | grep -qx 1 || fail "the test's study has two [analysis] tables"
set +e; "$bin" run one.toml --quiet > one.out 2> one.err; rc=$?; set -e
[ $rc -eq 2 ] || fail "substeps = 1 given: exit $rc, want 2"
grep -q 'ERROR: .*too long for the shear buildings.*give \[analysis\] substeps >= 7' one.err || fail "substeps = 1: $(cat one.err)"
[ ! -e one.h5 ] || fail "substeps = 1: a results file was written"
echo "ok   substeps = 1 given: refused, 'give [analysis] substeps >= 7'"
# a stable study keeps its step and says nothing of it
sed -e 's/^output = .*/output = "quick.h5"/' "$src/studies/quick-storeys.toml" > quick.toml
"$bin" run quick.toml > quick.out 2>&1 || fail "quick-storeys: exit $?"
! grep -q 'chosen for the shear buildings' quick.out || fail "quick-storeys had its step changed"
echo "study_step: ok"
