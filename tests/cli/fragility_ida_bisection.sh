#!/usr/bin/env bash
# The bisection IDA of yielding pairs (issue 14 part 2, method = "ida"), checked against what it must equal:
#   1. a bilinear pair that never yields (Cy = 5) takes the bisection path; its capacities must bracket the exact
#      capacities of the linear path (the elastic twin of the same models: IM x gap / peak closing at scale 1,
#      itself checked against SciPy in cli.fragility_linear) -- every bracket [lo, hi] x IM contains the exact value
#      (1e-9 relative), it is censored exactly when the exact value lies beyond the record's cap, and the fitted
#      theta and beta agree (0.5 %, 2 %);
#   2. a yielding pair: the hunt is the MSA stripes' own analysis (bit-identical runs of the scaled record), so for
#      every (record, model, gap) MSA must pound at the stripe whose factor ends the bracket and must not pound at
#      any stripe at or below its lower end, censored capacities never pounded in MSA, and every bracket is within
#      the tolerance; at each stripe the IDA's count of capacities <= level is at least MSA's count (first
#      crossing: they differ only by "resurrections", counted and printed);
#   1b. with the default scale_elastic the elastic lanes skip the bisection: their capacity is the hunt anchor's
#      linear extrapolation, equal to the exact one to 1e-9, with fewer analyses;
#   3. batch width 7 and 256 give the same bits (1, 2 and 3 ranks: cli.fragility_ranks);
#   4. the cost against the stripes (analyses per model-record) is printed, not asserted.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py python3-numpy)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

study() {  # name method hysteresis-block
  cat > "$1.toml" <<TOML
title = "ida $1"
seed = 1414
scene = "probability"
output = "$1.h5"
[records]
suite = "builtin"
synthetic_only = true
limit = 12
[structures]
samples_per_pair = 40
zeta = 0.05
alpha = 0.05
$3
[structures.building1]
period = {lognormal = {median = 0.9, cov = 0.15}}
height = 28.0
mass = 3.1e6
$4
[structures.building2]
period = {lognormal = {median = 1.3, cov = 0.15}}
height = 42.0
mass = 4.7e6
$5
[gaps]
ratios = [0.25, 0.5, 1.0, 1.5]
[report]
bootstrap = 200
[intensity]
measure = "Sa"
period = "pair"
levels = [0.05, 0.1, 0.2, 0.3, 0.45, 0.7, 1.0, ${6:-1.5}]
max_scale = ${7:-10}
method = "$2"
$([ "$2" = ida ] && echo "tolerance = 0.002")
${8:-}
TOML
  "$bin" run "$1.toml" > "$1.log" 2>&1 || { cat "$1.log"; exit 1; }
}
# max_scale 3 and a top level beyond every record's reach: both paths censor at IM x 3 (<= 4.8 g, below the Cy = 5 g
# at which the stiff twin would yield)
study elastic ida 'hysteresis = "elastic"' '' '' 6.0 3
# scale_elastic = false: the stiff twin bisects like a yielding pair; with the default its elastic lanes take the
# exact linear capacity from the hunt's anchor instead (checked below as well)
study stiff ida '' 'yield_coefficient = 5.0' 'yield_coefficient = 5.0' 6.0 3 '[analysis]
scale_elastic = false'
study stiffx ida '' 'yield_coefficient = 5.0' 'yield_coefficient = 5.0' 6.0 3
study yield ida '' 'yield_coefficient = {lognormal = {median = 0.15, cov = 0.2}}' 'yield_coefficient = {lognormal = {median = 0.10, cov = 0.2}}'
study msa msa '' 'yield_coefficient = {lognormal = {median = 0.15, cov = 0.2}}' 'yield_coefficient = {lognormal = {median = 0.10, cov = 0.2}}'
# batch width 7 instead of 256: other sub-batches in the bisection, the same bits (lanes are independent)
sed -e 's/^output = "yield.h5"/output = "yield7.h5"/' yield.toml > yield7.toml
printf '[analysis]\nbatch = 7\n' >> yield7.toml
"$bin" run yield7.toml > yield7.log 2>&1 || { cat yield7.log; exit 1; }
grep -q "IDA of yielding buildings" stiff.log
grep -q "IDA on a linear pair" elastic.log

"$py" - <<'PY'
import h5py, numpy as np
ok = True
def fail(msg):
    global ok
    ok = False
    print("FAIL:", msg)

# 1. never-yielding bilinear (bisection) against the exact linear capacities
E, S = h5py.File("elastic.h5", "r"), h5py.File("stiff.h5", "r")
im = S["intensity/im"][:]
assert np.array_equal(im, E["intensity/im"][:])
d = S["models/code_gap"][:]
assert np.array_equal(d, E["models/code_gap"][:])
assert np.array_equal(S["models/T1"][:], E["models/T1"][:])
D1 = E["uncoupled/peak_closing"][:]                # [records, models] at scale 1, elastic
gaps = S["ida/gaps"][:]
lo, hi, cap = S["ida/scale_lo"][:], S["ida/scale_hi"][:], S["ida/cap"][:]
tol = S["ida"].attrs["tolerance"]
n_in = n_cens = 0
for g, x in enumerate(gaps):
    exact = (x * d[None, :] / D1)                   # scale factor at first contact, exact for a linear pair
    capf = (cap / im)[:, None] * np.ones_like(exact)
    cens = np.isinf(hi[:, :, g])
    beyond = exact > capf * (1 + 1e-9)
    within = exact < capf * (1 - 1e-9)
    if np.any(cens & within): fail(f"gap {x}: censored although the exact capacity is below the cap")
    if np.any(~cens & beyond): fail(f"gap {x}: a bracket although the exact capacity is beyond the cap")
    f = ~cens
    if np.any(np.isnan(lo[:, :, g])): fail(f"gap {x}: excluded analyses")
    inside = (exact[f] > lo[:, :, g][f] * (1 - 1e-9)) & (exact[f] <= hi[:, :, g][f] * (1 + 1e-9))
    if not inside.all(): fail(f"gap {x}: {np.sum(~inside)} brackets miss the exact capacity")
    if np.any(hi[:, :, g][f] > lo[:, :, g][f] * (1 + tol) * (1 + 1e-12)): fail(f"gap {x}: a bracket wider than the tolerance")
    n_in += f.sum(); n_cens += cens.sum()
print(f"linear: {n_in} brackets contain the exact capacity, {n_cens} censored exactly where it lies beyond the cap")
# the default (scale_elastic): elastic lanes take the anchor's linear capacity, no bisection, to rounding
X = h5py.File("stiffx.h5", "r")
xl, xh = X["ida/scale_lo"][:], X["ida/scale_hi"][:]
fin = np.isfinite(xh)
if not np.array_equal(fin, np.isfinite(hi)): fail("scale_elastic changed which capacities are censored")
n_exact = n_bis = 0
for g, x in enumerate(gaps):
    exact = x * d[None, :] / D1
    f = fin[:, :, g]
    one = f & (xl[:, :, g] == xh[:, :, g])      # no bisection: the linear extrapolation
    rel = np.abs(xh[:, :, g][one] / exact[one] - 1).max(initial=0)
    if rel > 1e-9: fail(f"gap {x}: the elastic capacity is off by {rel:.1e}")
    bis = f & ~one                               # yielded by the hunt's factor (Cy 5 at up to 4.8 g): bisected
    inside = (exact[bis] > xl[:, :, g][bis] * (1 - 1e-9)) & (exact[bis] <= xh[:, :, g][bis] * (1 + 1e-9))
    if not inside.all(): fail(f"gap {x}: a bisected bracket misses the exact capacity")
    n_exact += int(one.sum()); n_bis += int(bis.sum())
a_b, a_x = S["ida"].attrs["analyses_total"], X["ida"].attrs["analyses_total"]
print(f"scale_elastic: {n_exact} capacities from the linear extrapolation (exact to 1e-9), {n_bis} bisected (the "
      f"buildings yield at the factor that closed the bracket); {a_x} analyses instead of {a_b}")
if n_exact < 0.9 * (n_exact + n_bis): fail("fewer than 90 % of the stiff pair's capacities were extrapolated")
if not a_x < a_b: fail("no analyses saved")

# both censor at IM max_scale here, so the fits (moments, or the censored MLE) see the same data to the tolerance
if not np.allclose(cap, im * 3.0, rtol=1e-12): fail("the bisection's caps are not IM x max_scale")
for g, x in enumerate(gaps):
    te, ts = E["fragility/theta"][g], S["fragility/theta"][g]
    be, bs = E["fragility/beta"][g], S["fragility/beta"][g]
    print(f"gap {x}: theta {te:.5g} (linear) vs {ts:.5g} (bisection), beta {be:.4f} vs {bs:.4f}")
    if not (abs(ts / te - 1) < 0.005 and abs(bs / be - 1) < 0.02): fail(f"gap {x}: fits differ")

# batch width does not change a bit
A, B = h5py.File("yield.h5", "r"), h5py.File("yield7.h5", "r")
for k in ("ida/scale_lo", "ida/scale_hi", "ida/analyses", "ida/cap", "fragility/theta", "fragility/beta"):
    if not np.array_equal(A[k][()], B[k][()], equal_nan=True): fail(f"{k} differs between batch 256 and 7")

# 2. yielding: the hunt against the stripes
Y, M = h5py.File("yield.h5", "r"), h5py.File("msa.h5", "r")
levels = M["intensity/levels"][:]
scale = M["intensity/scale"][:]                     # [stripes, records]
dropped = M["intensity/dropped"][:]
D = M["uncoupled/peak_closing"][:]                  # [stripes, records, models]
st = M["uncoupled/status"][:]
lo, hi = Y["ida/scale_lo"][:], Y["ida/scale_hi"][:]
assert np.array_equal(Y["intensity/im"][:], M["intensity/im"][:])
R, Mn = lo.shape[0], lo.shape[1]
resurrect = at_max = 0
max_scale = Y["ida"].attrs["max_scale"]
for g, x in enumerate(Y["ida/gaps"][:]):
    pound = (D > x * d[None, None, :]) & (st == 0)   # d is the same models' code gap
    for r in range(R):
        fs = scale[:, r]
        for m in range(Mn):
            l, h = lo[r, m, g], hi[r, m, g]
            if np.isnan(l): fail(f"excluded ({r},{m},{g})"); continue
            if np.isinf(h):
                if pound[~dropped[:, r].astype(bool), r, m].any(): fail(f"censored but MSA pounds ({r},{m},{x})")
                continue
            if h > l * (1 + 0.002) * (1 + 1e-12): fail("bracket too wide")
            s_hi = np.where(fs >= h * (1 - 1e-12))[0][0]      # the hunt factor that closed the bracket
            if fs[s_hi] > max_scale:                           # it was max_scale itself: no MSA stripe there
                at_max += 1
            elif not pound[s_hi, r, m]: fail(f"MSA does not pound at the bracket's hunt factor ({r},{m},{x})")
            below = fs <= l * (1 + 1e-12)
            if pound[below, r, m].any(): fail(f"MSA pounds below the first crossing ({r},{m},{x})")
            resurrect += int((~pound[s_hi:, r, m] & (dropped[s_hi:, r] == 0)).sum())
    # counts: IDA capacities <= level versus MSA poundings at each stripe
    cap_ida = Y["ida/capacity"][:, :, g]
    for s, lev in enumerate(levels):
        z_ida = int(np.sum(cap_ida <= lev))
        z_msa = int(pound[s][dropped[s] == 0].sum())
        if z_ida < z_msa: fail(f"stripe {lev} gap {x}: IDA count {z_ida} below MSA {z_msa}")
print(f"yielding: hunt consistent with MSA ({at_max} brackets closed at max_scale, beyond the stripes); {resurrect} (record, model, gap, stripe) cells above a first crossing "
      "that MSA counts as not pounding (resurrections)")
a_ida = Y["ida"].attrs["analyses_total"]
a_msa = int(((M["uncoupled/scaled"][()] == 0) & (st != 254)).sum())   # the analyses MSA really ran
print(f"cost: IDA {a_ida} uncoupled analyses ({a_ida / (R * Mn):.1f} per model-record) vs MSA {a_msa} "
      f"({a_msa / (R * Mn):.1f} per model-record): ratio {a_ida / a_msa:.2f}")
raise SystemExit(0 if ok else 1)
PY
echo "fragility_ida_bisection: ok"
