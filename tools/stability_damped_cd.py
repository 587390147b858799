#!/usr/bin/python3
"""Stability of the system stepper's central difference with viscous damping (include/pounding/physics/steppers/
system_central_difference.hpp, step 1: vh = v + h/2 a, u += h vh, vp = vh + h/2 a, a = -omega^2 u - c vp,
v = vh + h/2 a): the largest h with spectral radius <= 1 of its one-step matrix on (u, v, a), for one mode, against
the closed form h omega = 2 (sqrt(1 + (2 zeta)^2) - 2 zeta) (i.e. h^2 omega^2 + 4 h (2 zeta omega) = 4) that
study/system_block.cpp's check_shear_steps uses. Prints a table; exits 1 when they disagree beyond 1e-9.
(The textbook 2 (sqrt(1 + zeta^2) - zeta) holds for a central-difference velocity; this stepper's predictor
velocity doubles the damping's effect.)"""
import sys

import numpy as np


def radius(h, w, c):
    A = np.zeros((3, 3))
    for k in range(3):
        u, v, a = np.eye(3)[k]
        vh = v + h / 2 * a
        u1 = u + h * vh
        vp = vh + h / 2 * a
        a1 = -w * w * u1 - c * vp
        A[:, k] = [u1, vh + h / 2 * a1, a1]
    return max(abs(np.linalg.eigvals(A)))


def h_max(w, c):
    lo, hi = 0.0, 10.0 / w
    for _ in range(80):
        m = 0.5 * (lo + hi)
        lo, hi = (m, hi) if radius(m, w, c) <= 1 + 1e-12 else (lo, m)
    return lo


bad = 0
print("zeta  h_max*omega(numeric)  closed form")
for z in [0.0, 0.01, 0.05, 0.2, 0.5, 1.0, 2.0, 5.0]:
    w = 3.7
    num = h_max(w, 2 * z * w) * w
    closed = 2 * (np.sqrt(1 + 4 * z * z) - 2 * z)
    print(f"{z:5.2f}  {num:.12f}  {closed:.12f}")
    bad += abs(num - closed) > 1e-9 * max(1.0, closed)
sys.exit(1 if bad else 0)
