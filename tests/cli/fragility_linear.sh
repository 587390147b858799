#!/usr/bin/env bash
# A fragility study whose answers are known independently (issue 14), on a LINEAR pair (both buildings elastic,
# lognormal periods) under 12 generated records, with a power-law hazard:
#   - stripes: every record is scaled by level / IM exactly, and for linear buildings the peak closing at each
#     stripe is the scale factor times the record's own (1e-9 relative): the stripes are the scaled records;
#   - MSA = IDA on the data: a model pounds at stripe level x exactly when its IDA capacity IM x gap / D1 is
#     below x, so every stripe's observed count equals the count of IDA capacities below the level (exact), and
#     the two fitted fragilities agree (theta within 5 %, beta within 10 %: the MLE over 12 stripes and the moments
#     of the capacities are different estimators of the same sample; measured 2 % and 4 %). The stripes must reach
#     past the medians: with levels only up to 0.8 g the MSA fit sees the lower tail alone and gave theta 0.80 vs
#     0.90 and beta 0.29 vs 0.48 at 1.0 d (the report warns when theta lies beyond the highest stripe);
#   - the MSA fit is the maximum of Baker's binomial likelihood: SciPy's Nelder-Mead on the stored counts gives
#     the same theta and beta (1e-4);
#   - the annual rate equals Cornell et al. (2002)'s closed form k0 theta^-k exp(k^2 beta^2 / 2) (1e-6), and the
#     IDA's risk-targeted gap equals x* = (1/theta1) [k0 exp(k^2 beta^2 / 2) / lambda_target]^(1/k) (1e-4);
#   - Sa at the pair's period comes from the engine; the scale factors are checked against it, and Sa itself
#     against SciPy in cli.intensity_scipy;
#   - [records] polarity = "both" (issue 23; the studies above say "recorded"): a record's reversed copy has the
#     same IM bit for bit, its recorded rows are the recorded study's bits, MSA counts 2 x R x M analyses per
#     stripe, and the jackknife of the risk-targeted gap leaves out a record WITH BOTH SIGNS (closed form over
#     R records of 2 M capacities each, not 2 R rows).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import scipy, h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with scipy, h5py and numpy (Debian: python3-scipy python3-h5py python3-numpy)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
"$py" - "$bin" <<'PY'
import subprocess, sys, h5py, numpy as np
from scipy import signal, optimize, stats

bin_ = sys.argv[1]
dt, n = 0.01, 1500
rng = np.random.default_rng(14)
t = np.arange(n) * dt
env = np.minimum(1, t / 2) * np.exp(-np.maximum(0, t - 7) / 3)
files = []
for k in range(12):
    b, a = signal.butter(2, [0.2 + 0.05 * k, 5.0], btype="band", fs=1 / dt)
    ag = signal.lfilter(b, a, rng.standard_normal(n)) * env
    ag *= (0.1 + 0.03 * k) / np.max(np.abs(ag))
    name = f"r{k}.AT2"
    with open(name, "w") as f:
        f.write("generated for fragility_linear.sh\nband-limited noise\nACCELERATION TIME SERIES IN UNITS OF G\n")
        f.write(f"NPTS= {n}, DT= {dt:.4f} SEC\n")
        for i in range(0, n, 5):
            f.write("".join(f"{v:16.8e}" for v in ag[i:i + 5]) + "\n")
    files.append(name)
levels = [0.05, 0.1, 0.15, 0.2, 0.3, 0.45, 0.6, 0.8, 1.1, 1.5, 2.0, 3.0]
k0, kk = 4e-4, 2.5

def study(name, method, polarity="recorded"):
    text = f'''title = "linear fragility"
seed = 5
scene = "probability"
output = "{name}.h5"
[records]
files = {files!r}
polarity = "{polarity}"
[structures]
samples_per_pair = 40
hysteresis = "elastic"
[structures.building1]
period = {{lognormal = {{median = 0.9, cov = 0.2}}}}
height = 28.0
mass = 2.0e6
[structures.building2]
period = {{lognormal = {{median = 1.3, cov = 0.2}}}}
height = 42.0
mass = 3.0e6
[gaps]
ratios = [0.5, 1.0]
[analysis]
stepper = "nigam-jennings"
[report]
bootstrap = 200
[intensity]
measure = "Sa"
period = "pair"
levels = {levels!r}
max_scale = 100
method = "{method}"
[hazard]
k0 = {k0}
k = {kk}
'''.replace("'", '"')
    open(f"{name}.toml", "w").write(text)
    subprocess.run([bin_, "run", f"{name}.toml", "--quiet"], check=True, stdout=subprocess.DEVNULL)
    return h5py.File(f"{name}.h5", "r")

msa, ida = study("msa", "msa"), study("ida", "ida")
S, R = len(levels), len(files)
im = msa["intensity/im"][()]
scale = msa["intensity/scale"][()]
assert np.array_equal(im, ida["intensity/im"][()])
assert np.allclose(scale, np.array(levels)[:, None] / im[None, :], rtol=1e-15, atol=0), "scale = level / IM"
pc = msa["uncoupled/peak_closing"][()]          # [stripes, records, models]
d1 = ida["uncoupled/peak_closing"][()]          # [records, models], at the records' own intensity
assert pc.shape[:2] == (S, R) and d1.shape[0] == R and pc.shape[2] == d1.shape[1]
rel = np.max(np.abs(pc - scale[:, :, None] * d1[None]) / (scale[:, :, None] * d1[None]))
print(f"stripes: peak closing = scale x the record's own, largest relative difference {rel:.2e}")
assert rel < 1e-9, rel

d = msa["models/code_gap"][()]
gaps = msa["fragility/gaps"][()]
for k, x in enumerate(gaps):
    cap = im[:, None] * x * d[None, :] / d1          # IDA capacity of every (record, model)
    want = [(cap < L).sum() for L in levels]
    got = msa["fragility/observed_z"][k]
    assert list(got) == want and all(msa["fragility/observed_n"][k] == cap.size), (x, got, want)
    # Baker's likelihood, maximised independently
    z, nn = np.array(want), np.full(S, cap.size)
    def nll(p):
        th, be = np.exp(p[0]), np.exp(p[1])
        q = np.clip(stats.norm.cdf(np.log(np.array(levels) / th) / be), 1e-300, 1 - 1e-16)
        return -np.sum(z * np.log(q) + (nn - z) * np.log1p(-q))
    th0 = np.exp(np.mean(np.log(cap)))
    res = optimize.minimize(nll, [np.log(th0), np.log(0.5)], method="Nelder-Mead",
                            options=dict(xatol=1e-10, fatol=1e-12, maxiter=20000))
    th_s, be_s = np.exp(res.x)
    th_m, be_m = msa["fragility/theta"][k], msa["fragility/beta"][k]
    th_i, be_i = ida["fragility/theta"][k], ida["fragility/beta"][k]
    print(f"gap {x} d: MSA theta {th_m:.5f} beta {be_m:.5f} | SciPy MLE {th_s:.5f} {be_s:.5f} | IDA {th_i:.5f} {be_i:.5f}")
    assert abs(th_m / th_s - 1) < 1e-4 and abs(be_m / be_s - 1) < 1e-4, "MSA fit is not the likelihood maximum"
    lc = np.log(cap.ravel())
    assert abs(th_i / np.exp(lc.mean()) - 1) < 1e-9 and abs(be_i / lc.std(ddof=1) - 1) < 1e-9, "IDA moments"
    assert abs(th_m / th_i - 1) < 0.05 and abs(be_m / be_i - 1) < 0.10, "MSA and IDA disagree"
    for f, th, be in ((msa, th_m, be_m), (ida, th_i, be_i)):
        lam = k0 * th ** -kk * np.exp(kk * kk * be * be / 2)
        got = f["hazard/annual_rate"][k]
        assert abs(got / lam - 1) < 1e-6, (got, lam)
        assert abs(f["hazard/probability"][k] - (1 - np.exp(-lam * 50))) < 1e-9
print("annual rates equal Cornell's closed form (1e-6)")
# IDA's risk-targeted gap in closed form: theta(x) = x theta1, beta constant
th1 = ida["fragility/theta"][list(gaps).index(1.0)]
be = ida["fragility/beta"][0]
lt = -np.log(1 - 0.02) / 50
xstar = (k0 * np.exp(kk * kk * be * be / 2) / lt) ** (1 / kk) / th1
got = ida["hazard"].attrs["target_gap"]
print(f"IDA risk-targeted gap {got:.6f} d, closed form {xstar:.6f} d; MSA {msa['hazard'].attrs['target_gap']:.6f} d")
assert abs(got / xstar - 1) < 1e-4, (got, xstar)
assert abs(msa["hazard"].attrs["target_gap"] / xstar - 1) < 0.15
# its jackknife over records, in closed form: without record j, theta1 and beta are the moments of the other
# records' ln capacities at gap 1, x*_(j) as above; se = sqrt((R-1)/R sum (ln x*_(j) - mean)^2), Student t
c1 = np.log(im[:, None] * d[None, :] / d1)      # ln capacity at gap ratio 1, [records, models]
lnx = []
for j in range(R):
    rest = np.delete(c1, j, axis=0).ravel()
    lnx.append(np.log((k0 * np.exp(kk * kk * rest.var(ddof=1) / 2) / lt) ** (1 / kk) / np.exp(rest.mean())))
lnx = np.array(lnx)
se = np.sqrt((R - 1) / R * np.sum((lnx - lnx.mean()) ** 2))
q = stats.t.ppf(0.975, R - 1)
h = ida["hazard"].attrs
print(f"IDA jackknife: se of ln x* {h['target_gap_jack_se']:.6f} (closed form {se:.6f}), interval "
      f"[{h['target_gap_jack_lo']:.5f}, {h['target_gap_jack_hi']:.5f}] d, bootstrap [{h['target_gap_lo']:.5f}, "
      f"{h['target_gap_hi']:.5f}] d, advice {h['target_gap_advice']:.5f} d")
assert abs(h["target_gap_jack_se"] / se - 1) < 1e-3, (h["target_gap_jack_se"], se)
assert abs(h["target_gap_jack_hi"] / (got * np.exp(q * se)) - 1) < 1e-4
assert abs(h["target_gap_jack_lo"] / (got * np.exp(-q * se)) - 1) < 1e-4
assert h["target_gap_advice"] == max(h["target_gap_hi"], h["target_gap_jack_hi"])
# the per-gap annual rate's jackknife for linear IDA in closed form: lambda_(j) = k0 theta_(j)^-k exp(k^2 beta_(j)^2/2)
for k, x in enumerate(gaps):
    lam_j = []
    for j in range(R):
        rest = np.delete(c1, j, axis=0).ravel() + np.log(x)
        lam_j.append(k0 * np.exp(-kk * rest.mean()) * np.exp(kk * kk * rest.var(ddof=1) / 2))
    ln = np.log(lam_j)
    se_r = np.sqrt((R - 1) / R * np.sum((ln - ln.mean()) ** 2))
    lam = ida["hazard/annual_rate"][k]
    assert abs(ida["hazard/rate_jack_hi"][k] / (lam * np.exp(q * se_r)) - 1) < 1e-9, (x, ida["hazard/rate_jack_hi"][k])
    assert abs(ida["hazard/rate_jack_lo"][k] / (lam * np.exp(-q * se_r)) - 1) < 1e-9
    assert ida["hazard/rate_jack_lo"][k] < lam < ida["hazard/rate_jack_hi"][k]
    assert msa["hazard/rate_jack_lo"][k] < msa["hazard/annual_rate"][k] < msa["hazard/rate_jack_hi"][k]
print("IDA per-gap rate jackknife = closed form (1e-9)")
for f in (msa, ida):
    a = f["hazard"].attrs
    assert a["target_gap_jack_lo"] < a["target_gap"] < a["target_gap_jack_hi"], dict(a)
    assert abs(a["target_gap_m_advice"] / a["target_gap_advice"] - d[0]) < 1e-12 * d[0] or np.isnan(a["target_gap_m_advice"])
# a file written before the jackknife (its attributes and datasets removed) still reports: the bootstrap's end
import shutil
shutil.copy("ida.h5", "old.h5")
with h5py.File("old.h5", "r+") as f:
    for k in [k for k in f["hazard"].attrs if "jack" in k or "advice" in k]:
        del f["hazard"].attrs[k]
    for k in [k for k in f["hazard"] if "jack" in k]:
        del f["hazard"][k]
rep = subprocess.run([bin_, "report", "old.h5"], check=True, capture_output=True, text=True).stdout
want = f"advice: at least {ida['hazard'].attrs['target_gap_m_hi']:.3f} m** (the upper end)"  # a pair: metres
assert want in rep and "jackknife" not in rep, (want, rep[:2000])
print("a file without the jackknife: the report advises the bootstrap's upper end")

# polarity "both": two analyses per record, resampled and left out together
idab, msab = study("ida_both", "ida", "both"), study("msa_both", "msa", "both")
imb = idab["intensity/im"][()]
assert np.array_equal(imb[0::2], im) and np.array_equal(imb[1::2], im), "a reversed record has the same IM"
assert list(idab["records/polarity"][()]) == [1, -1] * R
d1b = idab["uncoupled/peak_closing"][()]        # [2 R, models]
assert np.array_equal(d1b[0::2], d1), "the recorded rows are the recorded study's bits"
assert not np.array_equal(d1b[1::2], d1b[0::2])
assert all(msab["fragility/observed_n"][0] == 2 * R * d1.shape[1])
c1b = np.log(im.repeat(2)[:, None] * d[None, :] / d1b).reshape(R, -1)  # [records, 2 models]: both signs together
lnx = []
for j in range(R):
    rest = np.delete(c1b, j, axis=0).ravel()
    lnx.append(np.log((k0 * np.exp(kk * kk * rest.var(ddof=1) / 2) / lt) ** (1 / kk) / np.exp(rest.mean())))
lnx = np.array(lnx)
se = np.sqrt((R - 1) / R * np.sum((lnx - lnx.mean()) ** 2))
hb = idab["hazard"].attrs
print(f"polarity both: IDA jackknife se of ln x* {hb['target_gap_jack_se']:.6f}, closed form over {R} records with "
      f"both signs {se:.6f}; x* {hb['target_gap']:.5f} d (recorded only {got:.5f} d)")
assert abs(hb["target_gap_jack_se"] / se - 1) < 1e-3, (hb["target_gap_jack_se"], se)
rep = subprocess.run([bin_, "report", "ida_both.h5"], check=True, capture_output=True, text=True).stdout
assert "record polarity: **both**" in rep and f"- {R} records, " in rep, rep[:3000]
print("polarity both: one IM per record, recorded rows unchanged, jackknife over records with both signs")
PY
echo "1 passed, 0 failed"
