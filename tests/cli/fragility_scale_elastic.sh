#!/usr/bin/env bash
# [analysis] scale_elastic (multiple stripes): a model whose buildings stay elastic takes the lowest stripe's peaks
# times the ratio of the scale factors instead of a run. Checked against every model run (scale_elastic = false):
#   - a yielding pair (the README's example pair, 25 synthetic records, 60 models, 10 Sa stripes): every peak
#     (|u1|, |u2|, closing) of every (stripe, record, model) within 1e-12 relative of the full run's, statuses equal,
#     the fragility counts at every gap and stripe equal and theta, beta equal to 1e-9; the analyses flagged run
#     (/uncoupled/scaled = 0) bit-identical to the full run, some above the lowest stripe scaled and some run;
#   - an elastic pair: every analysis above the lowest stripe is scaled, and the same checks.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py python3-numpy)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
base=$(sed -e 's/^samples_per_pair = 200 .*/samples_per_pair = 60/' -e 's|^curve = "example-hazard.csv"|curve = "'"$src"'/studies/example-hazard.csv"|' \
       -e '/^output = /d' "$src/studies/fragility-pair.toml")
run() {  # name, extra text appended
  printf '%s\n%s\n' "$base" "$2" > "$1.toml"
  "$bin" run "$1.toml" --out "$1.h5" > "$1.log" 2>&1 || { cat "$1.log"; exit 1; }
}
run fast ''
run full '[analysis]
scale_elastic = false'
elastic_base=$(echo "$base" | sed -e '/^yield_coefficient/d' -e 's/^alpha = 0.05/hysteresis = "elastic"/')
base=$elastic_base
run efast ''
run efull '[analysis]
scale_elastic = false'
grep -q "takes the lowest stripe's peaks" fast.log
grep -q "every model is analysed at every stripe" full.log

"$py" - <<'PY'
import h5py, numpy as np
ok = True
def check(a, b, elastic):
    global ok
    A, B = h5py.File(a + ".h5", "r"), h5py.File(b + ".h5", "r")
    sa, sb = A["uncoupled/status"][()], B["uncoupled/status"][()]
    if not np.array_equal(sa, sb): print("FAIL: statuses differ"); ok = False
    use = sa == 0
    differ = 0
    for name in ("peak_u1", "peak_u2", "peak_closing"):
        x, y = A["uncoupled/" + name][()], B["uncoupled/" + name][()]
        rel = np.abs(x - y)[use] / np.maximum(np.abs(y[use]), 1e-300)
        print(f"{a}: {name} max relative difference {rel.max():.2e}")
        if rel.max() > 1e-12: print(f"FAIL: {name} differs by {rel.max():.2e}"); ok = False
        differ = max(differ, int(np.sum(x[use] != y[use])))
    flag = A["uncoupled/scaled"][()]                  # 1: scaled from the lowest stripe, 0: run
    ran = (flag == 0) & use
    for name in ("peak_u1", "peak_u2", "peak_closing"):
        x, y = A["uncoupled/" + name][()], B["uncoupled/" + name][()]
        if not np.array_equal(x[ran], y[ran]): print(f"FAIL: {name} of analyses run differs from the full run"); ok = False
    n_scaled, n_counted = int(flag[use].sum()), int(use.sum())
    print(f"{a}: {n_scaled} of {n_counted} analyses scaled, {differ} peaks differ from the full run in last bits")
    if flag[0].any(): print("FAIL: the lowest stripe (the anchor) was scaled"); ok = False
    if n_scaled == 0: print("FAIL: nothing was scaled (the test would not see a wrong scaling)"); ok = False
    if elastic and not flag[1:][use[1:]].all(): print("FAIL: an elastic pair ran a stripe above the lowest"); ok = False
    if not elastic and not (ran[1:].any()): print("FAIL: no yielding analysis ran above the lowest stripe"); ok = False
    for k in ("observed_n", "observed_z"):
        if not np.array_equal(A["fragility/" + k][()], B["fragility/" + k][()]): print(f"FAIL: {k} differ"); ok = False
    for k in ("theta", "beta"):
        x, y = A["fragility/" + k][()], B["fragility/" + k][()]
        if not np.allclose(x, y, rtol=1e-9, atol=0, equal_nan=True): print(f"FAIL: {k} {x} vs {y}"); ok = False
check("fast", "full", False)
check("efast", "efull", True)
raise SystemExit(0 if ok else 1)
PY
echo "fragility_scale_elastic: ok"
