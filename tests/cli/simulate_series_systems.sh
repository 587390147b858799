#!/usr/bin/env bash
# `pounding simulate --series` for systems (physics::run_system_recorded, physics/system_series.hpp): a 3- against a
# 5-storey pair pounding at three levels under a generated record (the step chosen by simulate: 0.01/6 s), an
# isolated building in a moat, and the four-frame bridge. The series holds every integration step from t = 0 (rows =
# steps + 1, spaced by the run's integration_dt_s); its peaks equal the run's peaks bit for bit (|u| per DOF = peak_u,
# |a_abs| per DOF = peak_abs_acc x g, F per element = the level's peak force); the run's --json output is the same
# bytes with and without --series; the HDF5 form gives every numeric dataset its units. A system run by Newmark is
# refused with one error naming --series.
# Needs /usr/bin/python3 with numpy and h5py: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, sim, bad
"$py" -c 'import h5py' 2>/dev/null || skip_or_fail "needs $py with h5py"
"$py" - "$tmp/rec.txt" <<'PY'
import sys
import numpy as np
rng = np.random.default_rng(4512)
t = np.arange(1001) * 0.01
f, ph = rng.uniform(0.5, 4.0, 40), rng.uniform(0, 2 * np.pi, 40)
a = np.sin(2 * np.pi * f[:, None] * t[None, :] + ph[:, None]).sum(axis=0)
a *= np.minimum(1.0, (t / 1.5) ** 2) * np.where(t > 6.0, np.exp(-0.8 * (t - 6.0)), 1.0)
np.savetxt(sys.argv[1], np.column_stack([t, a * 0.35 / np.abs(a).max()]), fmt="%.8f")
PY
check() {  # <name> <simulate options...>: --series CSV and H5 against the run's own --json peaks
  local name=$1; shift
  sim "$@" --json > "$tmp/$name.json" || fail "$name: exit $?"
  sim "$@" --json --series "$tmp/$name.csv" > "$tmp/$name.s.json" || fail "$name --series: exit $?"
  cmp -s "$tmp/$name.json" "$tmp/$name.s.json" || fail "$name: --series changed the run's output"
  sim "$@" --series "$tmp/$name.h5" > /dev/null || fail "$name --series .h5: exit $?"
  "$py" - "$tmp/$name.s.json" "$tmp/$name.csv" "$tmp/$name.h5" "$name" <<'PY' || fail "$name: series against the run"
import json, sys
import h5py, numpy as np
d = json.load(open(sys.argv[1]))
a = np.genfromtxt(sys.argv[2], delimiter=",", names=True)
name = sys.argv[4]
h = d["integration_dt_s"]
steps = round(d["analysis_duration_s"] / h)
assert len(a) == steps + 1, (len(a), steps)
assert np.all(np.abs(np.diff(a["t_s"]) - h) < 1e-12 * max(1.0, a["t_s"][-1])), "t is not spaced by the step"
checked = 0
for key in d:
    if not key.startswith("peak_u") or key.startswith("peak_u_"): continue
    b = int(key[len("peak_u"):])
    want_u, want_a = d[key], d[f"peak_abs_acc{b}_g"]
    cols = sorted((n for n in a.dtype.names if n.startswith(f"u_b{b}_")), key=lambda n: int(n.split("_")[2]))
    # the report's floors: an isolated body's base (its DOF 1) is reported apart (peak_bearing_u)
    if len(cols) == len(want_u) + 1: cols = cols[1:]
    assert len(cols) == len(want_u), (b, cols, want_u)
    for c, w in zip(cols, want_u):
        assert np.abs(a[c]).max() == w, (c, np.abs(a[c]).max(), w)
        acc = "a_abs_" + c[2:-2] + "_m_s2"
        got = np.abs(a[acc]).max() / 9.80665
        assert got == want_a[cols.index(c)], (acc, got, want_a[cols.index(c)])
        checked += 1
forces = [n for n in a.dtype.names if n.startswith("F_")]
for lv, n in zip(d["levels"], forces):
    assert a[n].max() == lv["peak_force"] or (lv["impacts"] == 0 and a[n].max() == 0), (n, a[n].max(), lv["peak_force"])
with h5py.File(sys.argv[3], "r") as f:
    g = f["series"]
    for k in ("t", "ag", "u", "a_abs", "force"):
        assert "units" in g[k].attrs, f"/series/{k} has no units"
    assert g["u"].shape == (len(g["dof_names"]), steps + 1) and g["force"].shape[1] == steps + 1
    assert np.array_equal(g["u"][...][0], a[[n for n in a.dtype.names if n.startswith("u_")][0]])
print(f"ok   {name}: {steps + 1} rows at h = {h:.6g} s, {checked} floors and {len(forces)} elements equal the run's peaks")
PY
}
check pair --storeys1 3 --storeys2 5 --contact hertzdamp --kh 5e9 --gap 0.02 --elastic
check isolated --storeys1 3 --storeys2 5 --isolation1 lead-rubber --bearing-k1-1 4e7 \
  --bearing-k2-1 4e6 --bearing-qd1 2e5 --moat-gap1 0.05 --gap 0.3
check bridge --bridge "$src/tests/data/bridge/four-frame.toml"
bad "series" --storeys1 3 --storeys2 5 --stepper newmark --series "$tmp/n.csv"
[ ! -e "$tmp/n.csv" ] || fail "a refused run wrote its series"
echo "simulate_series_systems: ok"
