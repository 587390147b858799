#!/usr/bin/env bash
# `pounding sample` output against SciPy (code this project did not write): KS tests of h (uniform), rho
# (lognormal) and mbar (truncated lognormal, via scipy.stats.truncnorm on ln mbar), the truncated mean by
# numerical integration, chi-square of the aspect ratios, eqs (5)-(9) on every row; then the Fig. 3 plot tool.
# Usage: bash sample_stats.sh <pounding binary> <source dir>
set -euo pipefail
bin=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$bin" sample "$src/studies/paper-structures.toml" --pair 1.25,1.0 --n 50000 --out "$tmp/p.csv" > /dev/null
"$py" - "$tmp/p.csv" <<'PY'
import sys, numpy as np
from scipy import stats, integrate
lines = [l for l in open(sys.argv[1]) if not l.startswith("#")]
names = lines[0].strip().split(",")
d = np.loadtxt(lines[1:], delimiter=",")
c = {n: d[:, j] for j, n in enumerate(names)}
n = len(d)
ok = True
def check(name, p):
    global ok
    print(f"{name}: p = {p:.4f}")
    ok &= p > 1e-3
# h at T = 1.25 s: uniform on [max(30, (1.25/0.08)^(4/3)), 50]; at T = 1.00 s on [30, 50]
lo = max(30.0, (1.25 / 0.08) ** (4 / 3))
check("KS h1 ~ U[%.4f, 50]" % lo, stats.kstest(c["h1"], stats.uniform(lo, 50 - lo).cdf).pvalue)
check("KS h2 ~ U[30, 50]", stats.kstest(c["h2"], stats.uniform(30, 20).cdf).pvalue)
s2 = np.log(1 + 0.068 ** 2)
rho = stats.lognorm(s=np.sqrt(s2), scale=np.exp(np.log(1800) - s2 / 2))
check("KS rho ~ lognormal(1800, 6.8 %)", stats.kstest(np.r_[c["rho1"], c["rho2"]], rho.cdf).pvalue)
sig = np.sqrt(np.log(1.04)); mu = np.log(0.6) - sig ** 2 / 2
za, zb = (np.log(0.4) - mu) / sig, (np.log(0.8) - mu) / sig
tn = stats.truncnorm(za, zb, loc=mu, scale=sig)
mb = np.r_[c["mbar1"], c["mbar2"]]
check("KS ln mbar ~ truncnorm", stats.kstest(np.log(mb), tn.cdf).pvalue)
mean_quad = integrate.quad(lambda x: x * tn.pdf(np.log(x)) / x, 0.4, 0.8)[0]
se = mb.std() / np.sqrt(mb.size)
print(f"mbar mean {mb.mean():.5f}, quadrature {mean_quad:.5f}, se {se:.5f}")
ok &= abs(mb.mean() - mean_quad) < 4.5 * se
counts = [np.sum(c["aspect1"] == a) for a in (1, 2, 3)]
check(f"chi-square aspect1 {counts}", stats.chisquare(counts).pvalue)
T = c["T1"]
ok &= np.allclose(c["k1"], 4 * np.pi ** 2 * c["m1"] / T ** 2, rtol=1e-15, atol=0)
ok &= np.allclose(2 * np.pi * np.sqrt(c["m1"] / c["k1"]), T, rtol=1e-15, atol=0)
ok &= np.allclose(c["c1"], 0.1 * np.sqrt(c["k1"] * c["m1"]), rtol=1e-15, atol=0)
ok &= np.allclose(c["m1"], c["mbar1"] * c["rho1"] * c["r1"] ** 2 * c["h1"], rtol=1e-15, atol=0)
ok &= np.allclose(c["fy1"], c["k1"] * 0.02 * c["h1"] / 6, rtol=1e-14, atol=0)
ok &= np.allclose(c["d"], 0.005 * (c["h1"] + c["h2"]), rtol=1e-15, atol=0)
R1, R2 = (3 * c["m1"] / (4 * np.pi * 2400)) ** (1 / 3), (3 * c["m2"] / (4 * np.pi * 2400)) ** (1 / 3)
kh = 4 / (3 * 2 * (1 - 0.15 ** 2) / 24.86e9) * np.sqrt(R1 * R2 / (R1 + R2))
ok &= np.allclose(c["kh"], kh, rtol=1e-13, atol=0)
print("identities and distributions:", "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
# the Fig. 3 tool, from CSV and from HDF5
"$bin" sample "$src/studies/paper-structures.toml" --n 64 --out "$tmp/all.h5" > /dev/null
"$bin" sample "$src/studies/paper-structures.toml" --n 64 --out "$tmp/all.csv" > /dev/null
"$py" "$src/tools/plot_mass_distribution.py" "$tmp/all.csv" --out "$tmp/m_csv.png" > "$tmp/t_csv"
"$py" "$src/tools/plot_mass_distribution.py" "$tmp/all.h5" --out "$tmp/m_h5.png" > "$tmp/t_h5"
cmp -s "$tmp/t_csv" <(sed "s|m_h5.png|m_csv.png|" "$tmp/t_h5") || { echo "FAIL: CSV and HDF5 tables differ"; exit 1; }
[ "$(head -c 8 "$tmp/m_csv.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "FAIL: no PNG"; exit 1; }
[ "$(grep -c '^ *1\.[0-9][05] ' "$tmp/t_csv")" -eq 11 ] || { echo "FAIL: not 11 periods in the table"; exit 1; }
echo "sample_stats: ok"
