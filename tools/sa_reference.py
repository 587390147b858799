#!/usr/bin/env python3
"""Independent reference for `pounding records im`: PGA, PGV and 5 %-damped Sa of one record with SciPy,
using none of the engine's code.

    tools/sa_reference.py RECORD.AT2 --periods 0.2,0.5,1.0 [--damping 0.05] [--dt DT]

Reads a PEER-style AT2 (line 4 holds NPTS and DT, values in g after it) or a two-column time/acceleration
(g) text file. The ground acceleration is taken as linear between samples, as the engine does:
  PGA  max |ag| (g);
  PGV  max |v|, v = the trapezoid integral (scipy.integrate.cumulative_trapezoid), exact for that signal (m/s);
  Sa   w^2 max |u| / g for u'' + 2 zeta w u' + w^2 u = -ag, solved with scipy.signal.lsim (first-order hold:
       exact for a piecewise-linear input) on the record resampled at h <= T/200 (linear interpolation
       reproduces the same signal), so the sampled peak is within (pi/200)^2/2 = 0.012 % of the continuous one.
       Two periods of zeros follow the record (the late free-vibration peak of a long-period oscillator;
       the engine runs one period, and a damped free vibration peaks within its first period).
Prints "PGA <g>", "PGV <m/s>" and one "Sa <T> <g>" line per period.
"""
import argparse
import re
import sys

import numpy as np
from scipy import integrate, signal

G = 9.80665


def read_record(path, dt_arg):
    lines = open(path, encoding="latin-1").read().splitlines()
    if len(lines) > 4:
        m = re.search(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([0-9.Ee+-]+)", lines[3], re.I)
        if m:
            values = np.array([float(x) for line in lines[4:] for x in line.replace(",", " ").split()])
            return float(m.group(2)), values
    rows = [line.replace(",", " ").split() for line in lines if line.strip() and line.lstrip()[0] not in "#%!"]
    if all(len(r) == 2 for r in rows):
        t = np.array([float(r[0]) for r in rows])
        return float(t[1] - t[0]), np.array([float(r[1]) for r in rows])
    if dt_arg is None:
        sys.exit(f"{path}: neither an AT2 nor a two-column file; give --dt for one column")
    return dt_arg, np.array([float(x) for r in rows for x in r])


def sa(ag, dt, period, zeta):
    w = 2 * np.pi / period
    ag = np.concatenate([ag, np.zeros(int(np.ceil(2 * period / dt)) + 1)])
    t = np.arange(len(ag)) * dt
    sub = max(1, int(np.ceil(200 * dt / period)))
    tf = np.arange((len(ag) - 1) * sub + 1) * (dt / sub)
    agf = np.interp(tf, t, ag)
    sys_ = signal.StateSpace([[0, 1], [-w * w, -2 * zeta * w]], [[0], [-1]], [[1, 0]], [[0]])
    _, u, _ = signal.lsim(sys_, agf, tf, interp=True)
    return w * w * np.max(np.abs(u)) / G


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("record")
    ap.add_argument("--periods", default="", help="comma-separated periods (s)")
    ap.add_argument("--damping", type=float, default=0.05)
    ap.add_argument("--dt", type=float, default=None, help="time step of a one-column file (s)")
    a = ap.parse_args()
    dt, ag_g = read_record(a.record, a.dt)
    ag = ag_g * G
    print(f"PGA {np.max(np.abs(ag_g)):.12g}")
    v = integrate.cumulative_trapezoid(ag, dx=dt, initial=0)
    print(f"PGV {np.max(np.abs(v)):.12g}")
    for p in [float(x) for x in a.periods.split(",") if x]:
        print(f"Sa {p:g} {sa(ag, dt, p, a.damping):.12g}")


if __name__ == "__main__":
    main()
