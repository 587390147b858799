#!/usr/bin/env bash
# A contact far too stiff for the time step makes the touching pairs diverge (stability guard): they are
# excluded with a visible count and their identity, never counted as "no impact"; the uncoupled
# probability table is unaffected. Synthetic twin of study-small.toml (no ../shared needed).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed -e 's/^law = "hertzdamp"/law = "linear"\nstiffness = 1e14/' \
    -e 's/^samples_per_pair = 8/samples_per_pair = 2/' "$src/tests/data/study-small-synthetic.toml" > "$tmp/stiff.toml"
# far more than max_excluded_fraction (0.1 %) of the analyses diverge: the run says so with exit code 3
rc=0; "$bin" run "$tmp/stiff.toml" --out "$tmp/stiff.h5" --quiet > "$tmp/stiff.md" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || { echo "FAIL: exit code $rc (want 3: too many excluded analyses)"; exit 1; }
/usr/bin/python3 - "$tmp/stiff.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
R, M = f["uncoupled/peak_closing"].shape
G = len(f["impacts/gap_ratios"])
st = f["impacts/status"][()].reshape(R, M, G)
pc = f["uncoupled/peak_closing"][()]
d = f["models/code_gap"][()]
cnt = f["impacts/impact_count"][()].reshape(R, M, G)
touch = pc[:, :, None] > f["impacts/gap_ratios"][()][None, None, :] * d[None, :, None]
assert (st[touch] != 0).all(), "a touching pair with a hopeless contact stiffness was returned as a result"
assert (st[~touch] == 0).all()
assert (cnt[st != 0] == -1).all() and np.isnan(f["impacts/peak_force"][()].reshape(R, M, G)[st != 0]).all()
print(f"{(st != 0).sum()} diverged (record, model, gap) analyses, all of them touching pairs")
PY
grep -q "| 0.1 | .* | .* | .* | .* | .* | .* | [1-9][0-9]* |" "$tmp/stiff.md"   # excluded column of the impacts table
grep -q "excluded analyses: \*\*[1-9][0-9]*\*\* of [0-9]* (.*): uncoupled (diverged or non-finite) 0 of " "$tmp/stiff.md"  # uncoupled runs are all fine
grep -q "Excluded coupled analyses (diverged or non-finite, never counted as results): \*\*[1-9]" "$tmp/stiff.md"
grep -q "at gap ratio 0.1: diverged" "$tmp/stiff.md"

# Resolution guard: a contact stiff enough to be under-resolved at the default step (h = 2.5 ms) but stable runs
# to the end; those analyses are marked coarse (status 3, numbers kept, h omega_c above the limit), excluded with
# coarse = "exclude" like diverged ones (exit 3 past max_excluded_fraction), and the advice brings them under the
# limit (the default, "refine", reruns them: cli.study_refine).
sed -e 's/^law = "hertzdamp"/law = "linear"\nstiffness = 1e11/' -e 's/^\[analysis\]/[analysis]\ncoarse = "exclude"/' \
    -e 's/^samples_per_pair = 8/samples_per_pair = 2/' "$src/tests/data/study-small-synthetic.toml" > "$tmp/coarse.toml"
rc=0; "$bin" run "$tmp/coarse.toml" --out "$tmp/coarse.h5" --quiet > "$tmp/coarse.md" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || { echo "FAIL: coarse run exit code $rc (want 3: coarse analyses excluded past the fraction)"; exit 1; }
grep -q "^coarse: [1-9][0-9]* analyses (max h·ω_c 0\.[3-9][0-9]*, limit 0.304); excluded from the statistics (\[analysis\] coarse = \"exclude\"; \"refine\" runs them again" "$tmp/coarse.md"
adv=$(sed -n 's/.*\[analysis\] substeps = \([0-9]*\) (or max_dt.*/\1/p' "$tmp/coarse.md")
[ -n "$adv" ] || { echo "FAIL: no substeps advice"; cat "$tmp/coarse.md"; exit 1; }
grep -q "at gap ratio .*: coarse" "$tmp/coarse.md"
/usr/bin/python3 - "$tmp/coarse.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
st, hw = f["impacts/status"][()], f["impacts/h_omega_contact"][()]
F = f["impacts/peak_force"][()]
assert (st == 3).any() and not (st == 1).any(), np.bincount(st.ravel())
assert (hw[st == 3] > 0.304).all() and (hw[st == 0] <= 0.304).all(), "status coarse <=> h omega_c over the limit"
assert np.isfinite(F[st == 3]).all(), "a coarse analysis keeps its numbers"
print(f"{(st == 3).sum()} coarse analyses, h omega_c up to {np.nanmax(hw):.3f}")
PY
# the advice works: at that many substeps nothing is coarse
sed "s/^\[analysis\]/[analysis]\nsubsteps = $adv/" "$tmp/coarse.toml" > "$tmp/fine.toml"
"$bin" run "$tmp/fine.toml" --out "$tmp/fine.h5" --quiet > "$tmp/fine.md" 2>/dev/null
grep -q "^coarse: 0 analyses (max h·ω_c 0\.[0-2][0-9]*, limit 0.304)$" "$tmp/fine.md"
# coarse = "keep": the same analyses counted and reported, kept in the statistics (no exclusion, exit 0)
sed 's/^coarse = "exclude"/coarse = "keep"/' "$tmp/coarse.toml" > "$tmp/keep.toml"
"$bin" run "$tmp/keep.toml" --out "$tmp/keep.h5" --quiet > "$tmp/keep.md" 2>/dev/null
grep -q "^coarse: [1-9][0-9]* analyses .*kept in the statistics" "$tmp/keep.md"
grep -q "| 0.1 | .* | 0 |$" "$tmp/keep.md"   # excluded column of the impacts table
echo "1 passed, 0 failed"
