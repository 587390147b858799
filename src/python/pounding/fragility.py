"""Lognormal fragility fits P(pound | IM = x) = Phi(ln(x / theta) / beta): the engine's code (analysis/fragility.hpp,
stripes.hpp), not a Python copy.

fit(im, n, z): Baker (2015) multiple-stripe MLE, probit IRLS. Data without a finite MLE are flagged, never fitted
into garbage: status "no_pounding" (every z = 0; `bound` = the one-sided 95 % upper bound on P), "all_pounded",
"separated" (beta -> 0; `bracket` holds theta's range), "decreasing", "not_converged". theta and beta are NaN
unless status == "ok". One stripe or fewer than 2 distinct levels (not identifiable) raise ValueError.
"""
import math
from dataclasses import dataclass, field

import numpy as np

from . import _core

__all__ = ["Fit", "fit", "fit_ida", "fit_moments", "fit_stripes", "probability"]


@dataclass
class Fit:
    status: str
    theta: float
    beta: float
    se_log_theta: float = math.nan
    se_beta: float = math.nan
    neg_log_likelihood: float = math.nan
    iterations: int = 0
    bracket: tuple = (math.nan, math.nan)
    bound: float = 0.0
    message: str = ""
    extra: dict = field(default_factory=dict)  # fit_ida / fit_stripes: intervals, rates, gap

    @property
    def ok(self):
        return self.status == "ok"

    def __call__(self, x):
        """The fitted P at IM x (NaN unless ok)."""
        return probability(x, self.theta, self.beta) if self.ok else np.full(np.shape(x), np.nan)


def _fit(d):
    keys = ("status", "theta", "beta", "se_log_theta", "se_beta", "neg_log_likelihood", "iterations", "bracket",
            "bound", "message")
    return Fit(**{k: d[k] for k in keys}, extra={k: v for k, v in d.items() if k not in keys})


def fit(im, n, z):
    """Baker's MSA maximum-likelihood fit of stripes at IM levels im with n analyses and z poundings each."""
    return _fit(_core.analysis.fit_msa(np.asarray(im, float), np.asarray(n, float), np.asarray(z, float)))


def fit_moments(capacities):
    """IDA by moments (Baker eqs. 2-3): theta = exp(mean ln c), beta = sample sd of ln c (n - 1): (theta, beta)."""
    return _core.analysis.fit_moments(np.asarray(capacities, float))


def fit_ida(capacities, censored_at=None, *, bootstrap=0, confidence=0.95, seed=1, curve=None, years=50.0):
    """IDA fit of one capacity per record (the IM at first pounding; inf: none up to censored_at). Without
    censoring: the method of moments; with censored capacities: the censored lognormal MLE (truncated IDA).
    bootstrap > 0 adds percentile intervals over records (extra['theta_ci'], extra['beta_ci']); a hazard curve
    adds the annual rate (extra['annual_rate'])."""
    return _fit(_core.analysis.fit_ida(np.asarray(capacities, float), censored_at, bootstrap, confidence, seed,
                                       _curve(curve), years))


def fit_stripes(demands, levels, gaps, *, bootstrap=0, confidence=0.95, seed=1, curve=None, years=50.0, threads=0):
    """The fragility study's MSA fit per gap from raw demands[stripe, record, model] (peak closing without contact,
    in the gaps' unit; NaN = not counted): one Fit per gap, with record-cluster bootstrap intervals."""
    fits = _core.analysis.fit_stripes(np.asarray(demands, float), np.asarray(levels, float),
                                      np.asarray(gaps, float), bootstrap, confidence, seed, _curve(curve), years,
                                      threads)
    return [_fit(d) for d in fits]


def probability(x, theta, beta):
    """Phi(ln(x / theta) / beta); beta = 0 is the step at theta."""
    x = np.asarray(x, float)
    if beta == 0:
        return (x >= theta).astype(float)
    u = np.log(x / theta) / beta
    return 0.5 * np.vectorize(math.erfc)(-u / math.sqrt(2.0))


def _curve(curve):
    from .hazard import as_curve
    return as_curve(curve)
