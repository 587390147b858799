#!/usr/bin/python3
"""Plots of a fragility study (a study with [intensity], optionally [hazard]): reads the results file with h5py
only -- the engine is not needed. Debian's python3-numpy, python3-h5py and python3-matplotlib.
  <prefix>-fragility.png  per gap, P(pound | IM = x) = Phi(ln(x / theta) / beta) over the IM, the observed fractions
                          z / n at the stripes with 95 % Wilson intervals, and the curves at theta_lo and theta_hi
                          (beta fixed; the bootstrap interval of theta, NOT a band for the curve). Gaps whose fit is
                          not ok show the observed points only, marked "(no fit: status)".
  <prefix>-fit.png        goodness of fit: observed fraction versus fitted P at every (gap, stripe), 1:1 line
  <prefix>-rate.png       (when /hazard exists) annual rate of pounding and P(pounding in `years`) versus the
                          separation (metres for a pair study, ratio of d otherwise): the rate-versus-separation
                          curve, the per-gap rates with their bootstrap intervals, the target line and the
                          risk-targeted separation with its interval; beside it the hazard curve, log-log
Every figure: PNG at 200 dpi, plus each --format given (svg, pdf).
Usage: tools/plot_fragility.py RESULTS.h5 [-o out/study] [--format svg pdf] [--gaps 0.5 1.0] [--linear]"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pounding_plots  # noqa: E402  (the figures live there: one module, no copy)

if __name__ == "__main__":
    pounding_plots.main_fragility(doc=__doc__)
