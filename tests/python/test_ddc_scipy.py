#!/usr/bin/env python3
"""ctest python.ddc_scipy: DDC's correlation coefficient against an independent white-noise integral (issue 23, 4).

The DDC rule sqrt(u1^2 + u2^2 - 2 rho u1 u2) takes rho as the correlation of the two buildings' responses to the
same white-noise ground motion. Here rho is computed with none of our code: SciPy quad of the cross-spectrum of the
two SDOF transfer functions H_i(w) = 1 / (w_i^2 - w^2 + 2 i z_i w_i w),

    rho = integral_0^inf Re(H1 conj(H2)) dw / sqrt(integral |H1|^2 dw * integral |H2|^2 dw),

and compared with pounding.analysis.ddc_rho (the closed form of Der Kiureghian 1981) to 1e-9 relative over periods
either way round, ratios up to 4 and damping ratios from 1 % to 20 %. Before the fix ddc_rho paired each damping
ratio with the wrong building (0.023121 instead of 0.027456 at T 1.0 / 1.5 s, damping 5 % / 2 %).
Needs numpy and scipy: skipped (exit 77) without them, a failure under CI=true. Exit 0 pass, 1 fail.
"""
import math
import os
import sys


def in_ci():
    return os.environ.get("CI", "") not in ("", "0", "false", "no")


try:
    import numpy as np
    from scipy import integrate
except ImportError as e:
    print(f"{'FAIL (CI set, so not skipped)' if in_ci() else 'SKIPPED'}: needs numpy and scipy ({e})")
    sys.exit(1 if in_ci() else 77)

import pounding


def white_noise_rho(T1, T2, z1, z2):
    w1, w2 = 2 * math.pi / T1, 2 * math.pi / T2

    def H(w, wi, zi):
        return 1.0 / (wi * wi - w * w + 2j * zi * wi * w)

    lo, hi = sorted((w1, w2))
    # split at both resonances (narrow peaks) and far above them; the tail decays as w^-4
    edges = [0.0, 0.5 * lo, lo, math.sqrt(lo * hi), hi, 2 * hi, 8 * hi]

    def integral(f):
        total = sum(integrate.quad(f, a, b, limit=400, epsabs=0, epsrel=1e-13)[0] for a, b in zip(edges, edges[1:]))
        return total + integrate.quad(f, edges[-1], np.inf, limit=400, epsabs=0, epsrel=1e-13)[0]

    cross = integral(lambda w: (H(w, w1, z1) * np.conj(H(w, w2, z2))).real)
    a = integral(lambda w: abs(H(w, w1, z1)) ** 2)
    b = integral(lambda w: abs(H(w, w2, z2)) ** 2)
    return cross / math.sqrt(a * b)


def main():
    cases = [(1.0, 1.5, 0.05, 0.02), (1.0, 1.3, 0.05, 0.02), (1.0, 2.0, 0.05, 0.02), (1.5, 1.0, 0.05, 0.02),
             (0.75, 1.25, 0.02, 0.07), (0.9, 1.3, 0.05, 0.05), (0.3, 1.2, 0.10, 0.03), (2.0, 0.5, 0.01, 0.20),
             (1.0, 1.05, 0.05, 0.02), (1.2, 1.2, 0.05, 0.02)]
    bad = 0
    for T1, T2, z1, z2 in cases:
        got = pounding.analysis.ddc_rho(T1, T2, z1, z2)
        want = white_noise_rho(T1, T2, z1, z2)
        rel = abs(got - want) / want
        ok = rel < 1e-9
        bad += not ok
        print(f"T1 {T1:<5} T2 {T2:<5} zeta1 {z1:<5} zeta2 {z2:<5} ddc_rho {got:.12f}  SciPy quad {want:.12f}  "
              f"rel {rel:.1e} {'ok' if ok else 'FAIL'}")
    if bad:
        print(f"FAIL: {bad} of {len(cases)} cases differ from the white-noise integral")
        return 1
    print(f"ddc_rho matches SciPy's white-noise integral in all {len(cases)} cases")
    return 0


if __name__ == "__main__":
    sys.exit(main())
