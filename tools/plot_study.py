#!/usr/bin/python3
"""Plots from a pounding results file (h5py + matplotlib, Debian's python3 packages).
Pair studies (/settings/structures heights_specified == 1, both buildings' heights given):
  <prefix>-separation.png   probability of at least one impact versus separation in metres, with the bootstrap
                            band, the code rules and the separation advice -- all read from the engine's own
                            `pounding report RESULTS.h5 --csv`, so the figure and the report agree
Grid studies:
  <prefix>-probability.png  probability of at least one impact versus gap ratio: the continuous curve,
                            the study's gap ratios with 95 % Wilson intervals, the cubic fit, and (when the study
                            compares with "stochastic-pounding", or does not say) the paper's Table 3 and eq. 10
  <prefix>-periods.png      T1 x T2 heat map of the probability at one gap ratio
Bridge studies ([bridge]; /settings/bridge):
  <prefix>-joints.png       probability of pounding at each joint versus its gap in metres (the share of analyses
                            whose uncoupled closing there exceeds the gap), the coupled runs' share with an impact
                            at the study's joint gaps (Wilson 95 %, clustered by record), any joint at the
                            study's gaps, the targets
Every figure: PNG at 200 dpi, plus each --format given (svg, pdf).
Usage: tools/plot_study.py RESULTS.h5 [--prefix out/study] [--ratio 0.3] [--format svg pdf] [--pounding BIN]
       [--with OTHER.h5]  (a bridge study: the same bridge under the other input; adds PREFIX-inputs.png)"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pounding_plots  # noqa: E402  (the figures live there: one module, no copy)

if __name__ == "__main__":
    pounding_plots.main_study(doc=__doc__)
