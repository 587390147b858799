#!/usr/bin/env bash
# Issue 45 item 5: [outputs] histories, the time histories of chosen analyses of a study (study/histories.hpp).
#  1. An SDOF pair study in the impacts scene (3 synthetic records, 3 x 3 period pairs, 4 samples, 3 gaps) with a
#     named coupled analysis (record by id, model by row), a named uncoupled one (record by row, model by pair and
#     sample) and { worst = 3 }: /histories/1..5 hold t, ag, u, a_abs, force with units; each history's peaks (status,
#     peak_u1, peak_u2, peak_closing or impact_count, peak_force) equal the study's per-model values BIT FOR BIT, its
#     series' largest force equals its peak force and its largest |u| its peak |u|; the worst 3 are the 3 largest peak
#     forces; the report lists them; every other dataset and attribute equals the same study without the key
#     (compare_results.py: /histories and its setting are the only additions); 2 MPI ranks write the same file.
#  2. The probability scene: { worst = 2 } picks the 2 largest peak closing / code gap; peaks bit for bit.
#  3. Shear buildings (quick-storeys in small): a named coupled and the worst 2, peaks bit for bit (D over the floors,
#     impacts summed over the elements, the largest force), the series' largest force per element the peak.
#  4. Bad selections are refused before any work (exit 2, one ERROR naming the entry and the fix, no results file, no
#     checkpoint): an unknown record, a model beyond the study, a gap not among the ratios, a coupled run in the
#     probability scene, worst with a record, worst with per_model = false, a fragility study, histories that would
#     not fit in the memory available (POUNDING_TEST_MEMORY_AVAILABLE).
# Needs /usr/bin/python3 with numpy and h5py. Synthetic records only. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import numpy, h5py' 2>/dev/null || skip_or_fail "needs $py with numpy and h5py"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cd "$tmp"

pair_study() {  # pair_study <scene> <histories line or ""> > study text
  cat <<EOF
title = "histories test"
seed = 20240917
scene = "$1"
output = "out.h5"

[records]
suite = "builtin"
synthetic_only = true
limit = 3
polarity = "recorded"

[structures]
periods = [1.0, 1.25, 1.5]
samples_per_pair = 4

[gaps]
ratios = [0.1, 0.3, 0.5]

[contact]
law = "hertzdamp"
damping_law = "lankarani-nikravesh"
e = 0.65

[report]
bootstrap = 0

[outputs]
$2
EOF
}

# ---- 1. impacts scene: named + worst, bit for bit
pair_study impacts "" > plain.toml
pair_study impacts 'histories = [{ record = "EQ2", model = 5, gap = 0.1 }, { record = 0, pair = [1, 2], sample = 3, gap = "uncoupled" }, { worst = 3 }]' > hist.toml
"$bin" run plain.toml --out plain.h5 > plain.log 2>&1 || fail "plain run: exit $? $(tail -3 plain.log)"
"$bin" run hist.toml --out hist.h5 > hist.log 2>&1 || fail "histories run: exit $? $(tail -3 hist.log)"
grep -q "histories: 5 analyses rerun with the recorder" hist.log || fail "no progress line: $(grep -i histor hist.log)"
grep -q "WARNING" hist.log && fail "a warning: $(grep WARNING hist.log)"
grep -q "Stored time histories" hist.log || fail "the run's report does not list the histories"
"$bin" report hist.h5 > report.md || fail "report: exit $?"
grep -q "^## Stored time histories" report.md || fail "pounding report does not list the histories"
[ "$(grep -c '^| [1-5] | ' report.md)" = 5 ] || fail "report: not 5 history rows: $(grep -A8 'Stored time' report.md)"
"$py" "$src/tests/cli/compare_results.py" plain.h5 hist.h5 --allow-added --ignore=study_text > cmp.log ||
  fail "the histories changed other results: $(head -20 cmp.log)"
"$py" - hist.h5 <<'PY' || fail "impacts histories against the study"
import sys
import h5py, numpy as np

def same(a, b):
    return a == b or (np.isnan(a) and np.isnan(b))

with h5py.File(sys.argv[1], "r") as f:
    H = f["histories"]
    assert H.attrs["count"] == 5, H.attrs["count"]
    ids = [x.decode() if isinstance(x, bytes) else x for x in f["records/id"][()]]
    ratios = f["gaps/ratios"][()]
    force = f["impacts/peak_force"][()]
    st = f["impacts/status"][()]
    for n in range(1, 6):
        g = H[str(n)]
        a = g.attrs
        for name, unit in (("t", "s"), ("ag", "m/s^2"), ("u", "m"), ("a_abs", "m/s^2"), ("force", "N")):
            assert g[name].attrs["units"] == unit, (n, name, g[name].attrs["units"])
        r, m = int(a["record_row"]), int(a["model"])
        assert ids[r] == a["record"]
        assert f["models/i1"][m] == a["i1"] and f["models/i2"][m] == a["i2"] and f["models/sample"][m] == a["sample"]
        u, F, t = g["u"][()], g["force"][()], g["t"][()]
        assert u.shape == (2, len(t)) and F.shape == (1, len(t)), (u.shape, F.shape)
        assert t[0] == 0.0 and abs(t[1] - a["dt_s"]) < 1e-15
        if a["run"] == "coupled":
            k = int(np.argmin(np.abs(ratios - a["gap_ratio"])))
            grp = f["impacts"]
            names = ("status", "impact_count", "peak_force", "peak_u1", "peak_u2")
            idx = (r, m, k)
            assert a["gap_m"] == a["gap_ratio"] * f["models/code_gap"][m]
            assert F.max() == a["peak_force"], (n, F.max(), a["peak_force"])
        else:
            grp = f["uncoupled"]
            names = ("status", "peak_closing", "peak_u1", "peak_u2")
            idx = (r, m)
            assert (u[0] - u[1]).max() == a["peak_closing"], (n, (u[0] - u[1]).max(), a["peak_closing"])
        for name in names:
            want = grp[name][idx]
            assert same(float(a[name]), float(want)), (n, name, a[name], want)
        assert np.abs(u[0]).max() == a["peak_u1"] and np.abs(u[1]).max() == a["peak_u2"], n
    first = H["1"].attrs
    assert first["record"] == "EQ2" and first["model"] == 5 and first["gap_ratio"] == 0.1, dict(first)
    second = H["2"].attrs
    assert second["record_row"] == 0 and second["i1"] == 1 and second["i2"] == 2 and second["sample"] == 3
    assert second["run"] == "uncoupled"
    # the worst 3: the largest peak forces of the file (ok or coarse analyses)
    flat = np.where(np.isfinite(force) & (st != 1) & (st != 2), force, -np.inf).ravel()
    top = np.argsort(-flat, kind="stable")[:3]
    got = [(int(H[str(n)].attrs["record_row"]), int(H[str(n)].attrs["model"]),
            int(np.argmin(np.abs(ratios - H[str(n)].attrs["gap_ratio"])))) for n in (3, 4, 5)]
    want = [tuple(int(x) for x in np.unravel_index(i, force.shape)) for i in top]
    assert got == want, (got, want)
    assert H["3"].attrs["peak_force"] > 0
print("ok   impacts scene: 5 histories, peaks bit for bit, worst 3 by force")
PY

# 2 ranks (rank 0 reruns the histories after the others' units): the same file, histories included
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mpirun -np 2 "$bin" run hist.toml --out np2.h5 > np2.log 2>&1 || fail "2 ranks: exit $? $(tail -3 np2.log)"
"$py" "$src/tests/cli/compare_results.py" hist.h5 np2.h5 > cmp2.log || fail "2 ranks differ: $(head -20 cmp2.log)"
echo "ok   2 ranks: the same file"

# ---- 2. probability scene: worst by closing / code gap
pair_study probability 'histories = { worst = 2 }' > prob.toml
"$bin" run prob.toml --out prob.h5 > prob.log 2>&1 || fail "probability run: exit $? $(tail -3 prob.log)"
"$py" - prob.h5 <<'PY' || fail "probability histories"
import sys
import h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    D, st, d = f["uncoupled/peak_closing"][()], f["uncoupled/status"][()], f["models/code_gap"][()]
    x = np.where(st == 0, D / d[None, :], -np.inf).ravel()
    top = np.argsort(-x, kind="stable")[:2]
    for n, i in zip((1, 2), top):
        a = f["histories"][str(n)].attrs
        r, m = np.unravel_index(i, D.shape)
        assert (a["record_row"], a["model"]) == (r, m), (n, a["record_row"], a["model"], r, m)
        assert a["run"] == "uncoupled" and a["peak_closing"] == D[r, m], n
        u = f["histories"][str(n)]["u"][()]
        assert (u[0] - u[1]).max() == a["peak_closing"]
print("ok   probability scene: worst 2 by peak closing / code gap, bit for bit")
PY

# ---- 3. shear buildings
sed -e 's/^samples_per_pair = 8/samples_per_pair = 2/' -e 's/^output = .*/output = "storeys.h5"/' \
    "$src/studies/quick-storeys.toml" > storeys.toml
printf '\n[outputs]\nhistories = [{ record = 1, model = 3, gap = 0.05 }, { worst = 2 }]\n' >> storeys.toml
"$bin" run storeys.toml --out storeys.h5 > storeys.log 2>&1 || fail "storeys run: exit $? $(tail -3 storeys.log)"
grep -q "WARNING: a stored history" storeys.log && fail "storeys: $(grep WARNING storeys.log)"
"$py" - storeys.h5 <<'PY' || fail "shear-building histories against the study"
import sys
import h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    ratios = f["gaps/ratios"][()]
    n_hist = f["histories"].attrs["count"]
    assert n_hist >= 2, n_hist
    for n in range(1, n_hist + 1):
        g = f["histories"][str(n)]
        a = g.attrs
        r, m = int(a["record_row"]), int(a["model"])
        k = int(np.argmin(np.abs(ratios - a["gap_ratio"])))
        for name in ("status", "impact_count", "peak_force", "peak_u1", "peak_u2"):
            want = f["impacts"][name][r, m, k]
            assert a[name] == want or (np.isnan(a[name]) and np.isnan(want)), (n, name, a[name], want)
        F, u = g["force"][()], g["u"][()]
        names = [x.decode() if isinstance(x, bytes) else x for x in g["dof_names"][()]]
        assert u.shape[0] == len(names) > 2 and F.shape[0] == len(g["element_names"][()]) >= 1
        assert F.max() == a["peak_force"], (n, F.max(), a["peak_force"])
        b1 = [i for i, x in enumerate(names) if x.startswith("b1_")]
        assert np.abs(u[b1]).max() == a["peak_u1"], n
        assert g["u"].attrs["units"] == "m" and g["force"].attrs["units"] == "N"
print(f"ok   shear buildings: {n_hist} histories, peaks bit for bit")
PY

# ---- 4. bad selections: refused before any work
bad() {  # bad <text> <histories line> [scene] [extra section]
  local want=$1 line=$2 scene=${3:-impacts}
  pair_study "$scene" "$line" > bad.toml
  [ -z "${4:-}" ] || printf '%b\n' "$4" >> bad.toml
  rm -f bad.h5 bad.h5.ckpt
  set +e; "$bin" run bad.toml --out bad.h5 > bad.out 2> bad.err; local rc=$?; set -e
  [ $rc -eq 2 ] || fail "$line: exit $rc, want 2 ($(tail -2 bad.err))"
  [ "$(grep -c 'ERROR' bad.err)" = 1 ] || fail "$line: not one ERROR line: $(cat bad.err)"
  grep -q "ERROR: .*$want" bad.err || fail "$line: the error does not say '$want': $(cat bad.err)"
  grep -q "bad.toml:[0-9]*" bad.err || fail "$line: the error names no file:line: $(cat bad.err)"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.ckpt ] || fail "$line: left a results file or checkpoint"
  grep -q "units" bad.out bad.err && fail "$line: units ran"
  echo "ok   refused: $want"
}
bad 'record "NOPE" is not one of' 'histories = [{ record = "NOPE", model = 0, gap = 0.1 }]'
bad 'model = 36 is beyond the study' 'histories = [{ record = 0, model = 36, gap = 0.1 }]'
bad 'gap = 0.2 is not one of the study' 'histories = [{ record = 0, model = 0, gap = 0.2 }]'
bad 'names its run' 'histories = [{ record = 0, model = 0 }]'
bad 'pair = \[3, 0\] is not a period pair' 'histories = [{ record = 0, pair = [3, 0], sample = 0, gap = 0.1 }]'
bad 'a coupled run, and the probability scene' 'histories = [{ record = 0, model = 0, gap = 0.1 }]' probability
bad 'worst = N chooses its analyses' 'histories = [{ worst = 2, record = 0 }]'
bad 'per_model = false' $'histories = { worst = 2 }\nper_model = false' probability
bad 'not available in a fragility study' 'histories = [{ record = 0, model = 0 }]' probability \
    '[intensity]\nmeasure = "PGA"\nlevels = [0.1, 0.2, 0.3]'
POUNDING_TEST_MEMORY_AVAILABLE=1e9 bad 'the 100 time histories need up to' 'histories = { worst = 100 }' impacts \
    '[analysis]\nfree_vibration = 200'
echo "PASS"
