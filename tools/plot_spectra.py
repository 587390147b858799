#!/usr/bin/env python3
"""Plot response spectra written by `pounding records spectrum` with the suite's mean, like Fig. 4 of
stochastic-pounding-monte-carlo.txt (5 %-damped elastic pseudo-acceleration spectra and their mean).

    pounding records spectrum --suite default --records-dir ../shared/records/real -o suite.csv
    tools/plot_spectra.py suite.csv -o suite.png [--normalize] [--logx]

Real records are drawn solid, synthetic stand-ins dashed (the CSV's `#kind` row says which); the mean
(arithmetic, as in the paper) is thick black, the mean +- one standard deviation shaded.

A selection written by `pounding records select ... -o selection.csv` (detected from its header
`period_s,target_g,mean_g,...`) is drawn as the target (thick), each scaled record (thin), the mean of the
scaled records (thick black), the rule's line (90 % or 100 % of the target, dashed) and the period range
(shaded); --loglog for logarithmic axes:

    pounding records select --asce7 1.0,0.6,8 --period 1.0 --directory ../shared/records/real -o sel.csv
    tools/plot_spectra.py sel.csv -o sel.png --loglog

A results file (.h5) of a study with [records] select = N and [target_spectrum] is drawn the same way from its
/selection group (target, each chosen record scaled by f_i F, their mean, the rule's line); h5py reads it:

    pounding run studies/fragility-select.toml && tools/plot_spectra.py fragility-select.h5 -o sel.png --loglog
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pounding_plots  # noqa: E402  (the figures live there: one module, no copy)

if __name__ == "__main__":
    pounding_plots.main_spectra(doc=__doc__)
