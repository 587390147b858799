"""pounding.fragility and pounding.hazard: the engine's fits and rates, checked against published numbers and SciPy.

Baker's worked example and the edge cases: ../shared/research/fragility-and-codes.md sections 1.3 and 1.4 (Baker 2015,
Earthquake Spectra 31(1); numbers computed there with SciPy 1.10 and a second method); the data are copied here so
the test runs without ../shared.
"""
import math

import numpy as np
import pytest

import pounding
from conftest import need

BAKER_IM = [0.2, 0.3, 0.4, 0.6, 0.7, 0.8, 0.9, 1.0]
BAKER_Z = [0, 0, 0, 4, 6, 13, 12, 16]


def test_baker_worked_example():
    f = pounding.fragility.fit(BAKER_IM, [40] * 8, BAKER_Z)
    assert f.status == "ok" and f.ok
    assert f.theta == pytest.approx(1.076116, abs=1e-5)
    assert f.beta == pytest.approx(0.429237, abs=1e-5)
    assert f.neg_log_likelihood == pytest.approx(10.797705, abs=1e-5)  # with the binomial constants
    assert f.se_log_theta == pytest.approx(0.070974, abs=1e-5)         # expected information
    assert f.se_beta == pytest.approx(0.082104, abs=1e-5)
    # the note's fitted P at the stripes; its first entry, printed "4.0e-5", is Phi(ln(0.2/theta)/beta) = 4.42e-5
    fitted = [4.42e-5, 1.46e-3, 1.057e-2, 0.08676, 0.15821, 0.24486, 0.33857, 0.43215]
    assert f(np.array(BAKER_IM)) == pytest.approx(fitted, rel=2e-3)


def test_separation_and_non_identifiability_are_flagged():
    none = pounding.fragility.fit([0.2, 0.4, 0.6], [40] * 3, [0, 0, 0])
    assert none.status == "no_pounding" and math.isnan(none.theta)
    assert none.bound == pytest.approx(1 - 0.05 ** (1 / 120), rel=1e-12)  # rule of three over all 120 trials
    sep = pounding.fragility.fit([0.2, 0.4, 0.6, 0.8], [40] * 4, [0, 0, 40, 40])
    assert sep.status == "separated" and math.isnan(sep.beta)
    assert sep.bracket == pytest.approx((0.4, 0.6))
    assert pounding.fragility.fit([0.5, 1.0, 2.0], [40] * 3, [0, 40, 40]).status == "separated"
    assert pounding.fragility.fit([0.5, 1.0], [40, 40], [40, 40]).status == "all_pounded"
    with pytest.raises(ValueError, match="2 distinct"):  # one stripe: the ridge Phi(-ln theta / beta) = 0.25
        pounding.fragility.fit([1.0], [40], [10])
    exact = pounding.fragility.fit([0.5, 1.0], [40, 40], [10, 30])  # closed form
    assert exact.theta == pytest.approx(math.sqrt(0.5), abs=1e-6)
    assert exact.beta == pytest.approx(math.log(2) / (2 * 0.674489750196082), abs=1e-6)
    with pytest.raises(ValueError):
        pounding.fragility.fit([0.5, 1.0], [40, 40], [10, 41])  # z > n


def test_ida_moments_and_censored():
    caps = [0.45, 0.62, 0.71, 0.78, 0.86, 0.95, 1.08, 1.21, 1.40, 1.73]
    theta, beta = pounding.fragility.fit_moments(caps)
    assert (theta, beta) == pytest.approx((0.912339, 0.400317), abs=1e-6)
    f = pounding.fragility.fit_ida(caps)
    assert (f.theta, f.beta) == pytest.approx((0.912339, 0.400317), abs=1e-6)
    cens = [c if c <= 1.2 else math.inf for c in caps]  # three records not pounded by IM_max = 1.2
    g = pounding.fragility.fit_ida(cens, censored_at=1.2)
    assert (g.theta, g.beta) == pytest.approx((0.934698, 0.417307), abs=1e-5)


def test_hazard_rate_closed_form_and_scipy():
    integrate = need("scipy.integrate")
    stats = need("scipy.stats")
    k0, k, theta, beta = 1e-4, 2.5, 0.6, 0.45
    r = pounding.hazard.rate(theta, beta, (k0, k), years=50)
    cornell = k0 * theta ** -k * math.exp(k * k * beta * beta / 2)
    assert r["rate"] == pytest.approx(cornell, rel=1e-12)
    assert r["probability"] == pytest.approx(-math.expm1(-cornell * 50), rel=1e-12)
    # a table: lambda_P = int P(x) |dlambda/dx| dx by SciPy quad on the log-log interpolated curve (independent)
    im = np.array([0.05, 0.1, 0.2, 0.4, 0.8, 1.6])
    rate = np.array([2e-2, 8e-3, 2.5e-3, 6e-4, 1e-4, 1.2e-5])

    def dlam(x):  # the piecewise power law's derivative, end segments extended
        j = min(max(np.searchsorted(im, x) - 1, 0), len(im) - 2)
        kk = -math.log(rate[j + 1] / rate[j]) / math.log(im[j + 1] / im[j])
        return kk * rate[j] * (x / im[j]) ** -kk / x

    f = lambda u: stats.norm.cdf(math.log(math.exp(u) / theta) / beta) * dlam(math.exp(u)) * math.exp(u)
    pts = np.log(im)
    pieces = [(-40.0, pts[0])] + list(zip(pts[:-1], pts[1:])) + [(pts[-1], 10.0)]
    ref = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in pieces)
    got = pounding.hazard.rate(theta, beta, {"im": im, "rate": rate})
    assert got["rate"] == pytest.approx(ref, rel=1e-8)
    assert 0 < got["tail_share"] < 1


def test_risk_targeted_gap_meets_its_target():
    rng = np.random.default_rng(2015)
    levels = np.array([0.1, 0.2, 0.4, 0.8, 1.6])
    # peak closing proportional to the IM with a lognormal record-to-record spread
    d = levels[:, None, None] * np.exp(0.4 * rng.standard_normal((1, 30, 20))) * 0.25
    curve = (1e-4, 2.0)
    t = pounding.hazard.risk_targeted_gap(d, levels, curve, probability=0.02, years=50, bootstrap=200, seed=3)
    assert t["status"] == "ok"
    target = pounding.hazard.rate_for_probability(0.02, 50)
    fits = pounding.fragility.fit_stripes(d, levels, [t["gap"], t["gap"] * 0.98])
    rates = [pounding.hazard.rate(f.theta, f.beta, curve)["rate"] for f in fits]
    assert rates[0] <= target * (1 + 1e-9) < rates[1]
    assert t["ci"][0] <= t["gap"] <= t["ci"][1]
    with pytest.raises(ValueError, match="one of them"):
        pounding.hazard.risk_targeted_gap(d, levels, curve)


def test_ctrl_c_stops_a_long_bootstrap():
    """Ctrl-C reaches the bootstrap: 10^5 replicates over 20 gaps (minutes of work) raise KeyboardInterrupt within a
    second of SIGINT."""
    import os
    import signal
    import threading
    import time
    rng = np.random.default_rng(7)
    levels = np.array([0.1, 0.2, 0.4, 0.8, 1.6])
    d = levels[:, None, None] * np.exp(0.4 * rng.standard_normal((1, 40, 50))) * 0.25
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        pounding.fragility.fit_stripes(d, levels, np.linspace(0.05, 0.5, 20), bootstrap=100_000, threads=1)
    took = time.monotonic() - t0
    timer.join()
    assert took < 2.5, f"KeyboardInterrupt {took:.2f} s after the call (SIGINT at 0.5 s)"
