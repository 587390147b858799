#!/usr/bin/env python3
"""Independent reference for the effective restitution of the contact laws (issue 2, kernel tests).

Integrates the scale-free single impact with SciPy (solve_ivp, DOP853, rtol 1e-12, terminal event at the
exit x = 0) -- no code shared with the C++ kernel or with the Boost.Odeint reference of
tests/test_kernel_impact.cpp, which integrates the dimensional two-mass problem instead.

Scale-free forms (x = delta / L, tau = t v0 / L, L = (meff v0^2 / kh)^(2/5) for the Hertz family,
L = v0 sqrt(meff / k) for Kelvin), x(0) = 0, x'(0) = 1; effective e = -x'(exit):
  hertzdamp   x'' = -max(0, x^n (1 + xibar x'))                  (muthukumar eq. 10)
  kelvin      x'' = -max(0, x + 2 zeta x')  for x > 0, zeta = -ln e / sqrt(pi^2 + ln^2 e)
  jankowski   x'' = -(x^1.5 + 2 zeta x^(1/4) x' [x' > 0]),
              zeta = 9 sqrt(5)/2 (1 - e^2) / (e (e (9 pi - 16) + 16))   (rc-buildings eqs 4-5)
  calibrated  hertzdamp with xibar solved (brentq) so that e_eff = e.

Usage: reference_restitution.py [--csv]   (--csv: "law,e_target,xibar_or_zeta,e_effective" lines)
"""
import math
import sys

from scipy.integrate import solve_ivp
from scipy.optimize import brentq

E_TARGETS = (0.3, 0.5, 0.65, 0.8, 0.95)
N = 1.5

XIBAR = {
    "lankarani-nikravesh": lambda e: 3.0 * (1.0 - e * e) / 4.0,
    "hunt-crossley": lambda e: 3.0 * (1.0 - e) / 2.0,
    "flores": lambda e: 8.0 * (1.0 - e) / (5.0 * e),
    "hu-guo": lambda e: 3.0 * (1.0 - e) / (2.0 * e),
    "gonthier": lambda e: (1.0 - e * e) / e,
}


def kelvin_zeta(e):
    le = math.log(e)
    return -le / math.sqrt(math.pi ** 2 + le * le)


def jankowski_zeta(e):
    return 9.0 * math.sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))


def rebound(acc):
    """Integrates x'' = acc(x, v) from (0, 1) to the exit x = 0 and returns the exit speed."""

    def rhs(_t, y):
        x, v = y
        return [v, acc(x, v) if x > 0.0 else 0.0]

    def exit_event(_t, y):
        return y[0]

    exit_event.terminal = True
    exit_event.direction = -1.0
    sol = solve_ivp(rhs, (0.0, 200.0), [0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=exit_event, first_step=1e-6)
    if sol.status != 1 or len(sol.t_events[0]) == 0:
        raise RuntimeError("impact did not end")
    return -sol.y_events[0][0][1]


def hertzdamp_e(xibar, n=N):
    return rebound(lambda x, v: -max(0.0, x ** n * (1.0 + xibar * v)))


def kelvin_e(e):
    z = kelvin_zeta(e)
    return rebound(lambda x, v: -max(0.0, x + 2.0 * z * v))


def jankowski_e(e):
    z = jankowski_zeta(e)
    return rebound(lambda x, v: -(x ** 1.5 + (2.0 * z * x ** 0.25 * v if v > 0.0 else 0.0)))


def calibrated_xibar(e, n=N):
    if e == 1.0:
        return 0.0
    hi = 1.0
    while hertzdamp_e(hi, n) > e:
        hi *= 2.0
    return brentq(lambda xi: hertzdamp_e(xi, n) - e, 0.0, hi, xtol=1e-14, rtol=1e-14)


def table():
    rows = []
    for e in E_TARGETS:
        for law, f in XIBAR.items():
            xi = f(e)
            rows.append((law, e, xi, hertzdamp_e(xi)))
        rows.append(("kelvin", e, kelvin_zeta(e), kelvin_e(e)))
        rows.append(("jankowski", e, jankowski_zeta(e), jankowski_e(e)))
        xi = calibrated_xibar(e)
        rows.append(("calibrated", e, xi, hertzdamp_e(xi)))
    return rows


def main(argv):
    rows = table()
    if "--csv" in argv:
        for law, e, p, ee in rows:
            print(f"{law},{e:.17g},{p:.17g},{ee:.17g}")
        return 0
    print(f"{'law':<22}{'e target':>9}{'xibar/zeta':>14}{'e effective':>14}")
    for law, e, p, ee in rows:
        print(f"{law:<22}{e:>9.2f}{p:>14.8f}{ee:>14.9f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
