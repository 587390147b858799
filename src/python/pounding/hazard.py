"""Annual rate of pounding and the risk-targeted separation: the engine's hazard integration (analysis/hazard.hpp,
stripes.hpp), exact for a lognormal fragility on a power-law or tabulated hazard curve.

A curve is (k0, k) for lambda(x) = k0 x^-k, or (im, rate) arrays (straight in log-log between the points, the end
segments extended as power laws; `tail_share` says how much of the rate came from beyond the table), or a dict /
DataFrame with columns im and rate.
"""
import numpy as np

from . import _core

__all__ = ["as_curve", "probability_in_years", "rate", "rate_closed_form", "rate_for_probability",
           "risk_targeted_gap"]


def as_curve(curve):
    if curve is None:
        return None
    if isinstance(curve, dict) or hasattr(curve, "columns"):
        return (np.asarray(curve["im"], float), np.asarray(curve["rate"], float))
    a, b = curve
    if np.ndim(a) == 0 and np.ndim(b) == 0:
        return (float(a), float(b))
    return (np.asarray(a, float), np.asarray(b, float))


def rate(theta, beta, curve, years=50.0):
    """lambda_P = integral P(pound | x) |d lambda(x)| for P = Phi(ln(x/theta)/beta): dict rate (per year),
    tail_share, probability (1 - exp(-rate years))."""
    return _core.analysis.rate(float(theta), float(beta), as_curve(curve), years)


def rate_closed_form(k0, k, theta, beta):
    """Cornell et al. (2002): k0 theta^-k exp(k^2 beta^2 / 2)."""
    return _core.analysis.rate_closed_form(k0, k, theta, beta)


def probability_in_years(rate, years):
    return _core.analysis.probability_in_years(rate, years)


def rate_for_probability(p, years):
    return _core.analysis.rate_for_probability(p, years)


def risk_targeted_gap(demands, levels, curve, probability=None, years=50.0, *, lambda_target=None, bootstrap=2000,
                      confidence=0.95, seed=1, threads=0):
    """The smallest gap whose annual pounding rate meets the target, from MSA demands[stripe, record, model] (peak
    closing without contact, in the gap unit you want the answer in) at IM levels: a dict gap, ci (percentile
    record bootstrap), jackknife_ci, advice (the separation to advise), rate, status ("ok", "below range",
    "above range"), note. Give probability (e.g. 0.02 in `years`) or lambda_target (per year)."""
    if (probability is None) == (lambda_target is None):
        raise ValueError("risk_targeted_gap: give probability (in `years`) or lambda_target, one of them")
    if lambda_target is None:
        lambda_target = rate_for_probability(probability, years)
    return _core.analysis.risk_targeted_gap(np.asarray(demands, float), np.asarray(levels, float), as_curve(curve),
                                            lambda_target, bootstrap, confidence, seed, years, threads)
