#!/usr/bin/env python3
"""Benchmark: pounding.analyze throughput against the C++ kernel bench, and SciPy for perspective (issue 28).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_analyze.py --pounding build/pounding [--pairs 100000]

Workload: `pounding bench`'s (workloads/workloads.hpp benchmark_batch: bilinear pairs, Hertzdamp, central difference,
the built-in 40 s sweep at 0.005 s = 8000 steps). Interleaved rounds, each: the C++ bench (one thread, one batch of
256 pairs, its median of 3 repeats), then analyze() on `--pairs` pairs with threads=1 (the binding's overhead:
batching, copies, validation of every pair, result dicts) and with every core, and pounding.run_batch (one
kernel call on every pair, the binding's thinnest path). ns per pair-step from wall time and
from process CPU time (on a loaded machine compare the CPU columns). Then SciPy solve_ivp (RK45, rtol 1e-8,
max_step = the record step, the Hertzdamp force of muthukumar eq. 10 with the same xibar) on the first
`--scipy-pairs` pairs (default 100), reported in ns per pair-step (wall and process CPU) and as the CPU hours it
would take for all pairs.
Prints a Markdown table. A benchmark, not a test: nothing here asserts a time.
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import time

import numpy as np

import pounding


def cpp_bench(exe, substeps):
    out = subprocess.run([exe, "bench", "--width", "256", "--repeats", "3", "--substeps", str(substeps)],
                         capture_output=True, text=True, check=True).stdout
    return float(re.search(r"ns_per_pair_step_median: ([0-9.]+)", out).group(1))


def tile(pairs, n):
    reps = -(-n // len(pairs["m1"]))
    return {k: np.tile(v, reps)[:n] for k, v in pairs.items()}


def kernel_run(pairs, rec, substeps):
    """pounding.run_batch: one kernel call on every pair (no batching, no threads, no up-front validation)."""
    w0, c0 = time.perf_counter(), time.process_time()
    pounding.run_batch(pairs, rec.acc, rec.dt, contact="hertzdamp", substeps=substeps)
    return time.perf_counter() - w0, time.process_time() - c0


def python_run(pairs, rec, threads, substeps):
    w0, c0 = time.perf_counter(), time.process_time()
    r = pounding.analyze(pairs, rec, contact="hertzdamp", substeps=substeps, threads=threads, batch=256)
    w, c = time.perf_counter() - w0, time.process_time() - c0
    assert (r["status"] != pounding.Status.diverged).all()
    return w, c


def scipy_pairs(pairs, rec, count, xibar, n_exp=1.5):
    from scipy.integrate import solve_ivp
    t_rec = rec.dt * np.arange(rec.npts)
    ag = rec.acc
    w0, c0 = time.perf_counter(), time.process_time()
    for i in range(count):
        p = {k: v[i] for k, v in pairs.items()}
        v0 = [0.0]  # approach velocity latched at the onset (muthukumar eq. 10)

        def spring(u, k, fy, alpha, state):
            # bilinear kinematic hardening, updated at each accepted call (adequate for a throughput estimate)
            f = state[0] + k * (u - state[1])
            ymax = fy * (1 - alpha) + alpha * k * u
            ymin = -fy * (1 - alpha) + alpha * k * u
            f = min(max(f, ymin), ymax)
            state[0], state[1] = f, u
            return f

        s1, s2 = [0.0, 0.0], [0.0, 0.0]

        def rhs(t, y):
            u1, v1, u2, v2 = y
            a = np.interp(t, t_rec, ag)
            d = u1 - u2 - p["gap"]
            F = 0.0
            if d > 0:
                if v0[0] == 0.0:
                    v0[0] = max(v1 - v2, 1e-6)
                F = max(p["kc"] * d ** n_exp * (1 + xibar * (v1 - v2) / v0[0]), 0.0)
            else:
                v0[0] = 0.0
            f1 = spring(u1, p["k1"], p["fy1"], p["alpha1"], s1)
            f2 = spring(u2, p["k2"], p["fy2"], p["alpha2"], s2)
            return [v1, (-p["c1"] * v1 - f1 - F) / p["m1"] - a, v2, (-p["c2"] * v2 - f2 + F) / p["m2"] - a]

        solve_ivp(rhs, (0, t_rec[-1]), [0, 0, 0, 0], method="RK45", rtol=1e-8, atol=1e-10, max_step=rec.dt)
    return time.perf_counter() - w0, time.process_time() - c0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pounding", default="build/pounding")
    ap.add_argument("--pairs", type=int, default=100000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--substeps", type=int, default=1)
    ap.add_argument("--scipy-pairs", type=int, default=100)
    a = ap.parse_args()
    ag = pounding.testing.builtin_motion(0.005, 40.0)
    rec = pounding.Record(ag / 9.80665, 0.005, name="builtin-sweep")
    steps = (rec.npts - 1) * a.substeps
    pairs = tile(pounding.testing.benchmark_batch(256), a.pairs)
    per = a.pairs * steps * 1e-9
    rows = {"cpp": [], "k_wall": [], "k_cpu": [], "py1_wall": [], "py1_cpu": [], "pyN_wall": [], "pyN_cpu": []}
    for _ in range(a.rounds):
        rows["cpp"].append(cpp_bench(a.pounding, a.substeps))
        w, c = kernel_run(pairs, rec, a.substeps)
        rows["k_wall"].append(w / per), rows["k_cpu"].append(c / per)
        w, c = python_run(pairs, rec, 1, a.substeps)
        rows["py1_wall"].append(w / per), rows["py1_cpu"].append(c / per)
        w, c = python_run(pairs, rec, 0, a.substeps)
        rows["pyN_wall"].append(w / per), rows["pyN_cpu"].append(c / per)
    med = {k: statistics.median(v) for k, v in rows.items()}
    print(f"{a.pairs} pairs x {steps} steps (40 s at 0.005 s, substeps {a.substeps}), hertzdamp, central difference, "
          f"{a.rounds} interleaved rounds, medians; {os.cpu_count()} hardware threads, load {os.getloadavg()[0]:.1f}")
    print("\n| run | ns per pair-step (wall) | ns per pair-step (CPU) | wall for all pairs s |\n|---|---|---|---|")
    print(f"| C++ `pounding bench` (1 thread, 256 pairs) | {med['cpp']:.3f} | | {med['cpp'] * per:.2f} |")
    print(f"| run_batch, one kernel call | {med['k_wall']:.3f} | {med['k_cpu']:.3f} | {med['k_wall'] * per:.2f} |")
    print(f"| analyze, threads=1 | {med['py1_wall']:.3f} | {med['py1_cpu']:.3f} | {med['py1_wall'] * per:.2f} |")
    print(f"| analyze, threads=0 (all) | {med['pyN_wall']:.3f} | {med['pyN_cpu']:.3f} | {med['pyN_wall'] * per:.2f} |")
    print(f"\nbinding overhead (analyze threads=1 wall / C++ bench wall - 1): {med['py1_wall'] / med['cpp'] - 1:+.1%}; "
          f"per round {[f'{p / c - 1:+.1%}' for p, c in zip(rows['py1_wall'], rows['cpp'])]}")
    print(f"binding overhead in CPU time (analyze threads=1 / run_batch - 1): {med['py1_cpu'] / med['k_cpu'] - 1:+.1%}; "
          f"per round {[f'{p / c - 1:+.1%}' for p, c in zip(rows['py1_cpu'], rows['k_cpu'])]}")
    if a.scipy_pairs > 0:
        try:
            import scipy  # noqa: F401
        except ImportError:
            print("SciPy not installed: no SciPy comparison")
            return
        xibar = 3 * (1 - 0.65 ** 2) / 4  # lankarani-nikravesh at e = 0.65 (benchmark_batch's e)
        w, c = scipy_pairs(pairs, rec, a.scipy_pairs, xibar)
        ns, ns_cpu = w / (a.scipy_pairs * steps) * 1e9, c / (a.scipy_pairs * steps) * 1e9
        print(f"\nSciPy solve_ivp RK45 on {a.scipy_pairs} pairs: {w:.1f} s wall, {c:.1f} s CPU; {ns:.0f} ns per "
              f"pair-step wall ({ns / med['py1_wall']:.0f} x analyze threads=1), {ns_cpu:.0f} ns CPU "
              f"({ns_cpu / med['py1_cpu']:.0f} x analyze threads=1 in CPU time); all {a.pairs} pairs would take "
              f"{ns_cpu * a.pairs * steps * 1e-9 / 3600:.1f} h of CPU")


if __name__ == "__main__":
    sys.exit(main())
