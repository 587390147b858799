#!/usr/bin/env python3
"""Independent SciPy reference for a linear base-isolated shear building (tests/physics/test_isolation.cpp).
None of the engine's code: the superstructure's fixed-base matrices Ms, Ks, Cs = a0 Ms + a1 Ks act on the floors'
displacements RELATIVE TO THE BASE, x = u_s - 1 u_b (Kelly's formulation; Naeim & Kelly 1999 ch. 2), so in the
engine's coordinates u = [u_b, u_1..u_n] (relative to the ground) K = T' Ks T + k_b e0 e0', C = T' Cs T + c_b e0 e0',
M = diag(m_b, Ms) with T = [-1 | I]. Then
  modes:    scipy.linalg.eigh(K, M) -> "omega j value" (rad/s), j from 1
  response: M u'' + C u' + K u = -M 1 ag(t), ag linear between record samples, scipy.signal.lsim (interp=True) on
            the grid dt/substeps -> "peak_u dof value", "final_u dof value" (dof 0 = the base).
Usage: reference_isolation.py INPUT.json OUTPUT.txt
INPUT: {"m_base": kg, "k_b": N/m, "c_b": N s/m, "m": [kg], "k": [N/m], "a0": 1/s, "a1": s,
        "dt": s, "ag": [m/s^2], "substeps": int}   (ag empty: modes only)
"""
import json
import sys

import numpy as np
from scipy import linalg, signal


def assemble(d):
    m = np.array(d["m"], float)
    k = np.array(d["k"], float)
    n = len(m)
    Ks = np.zeros((n, n))
    for i in range(n):  # storey i joins floor i-1 (the base for i = 0) and floor i
        Ks[i, i] += k[i]
        if i > 0:
            Ks[i - 1, i - 1] += k[i]
            Ks[i - 1, i] -= k[i]
            Ks[i, i - 1] -= k[i]
    Ms = np.diag(m)
    Cs = d["a0"] * Ms + d["a1"] * Ks
    T = np.hstack([-np.ones((n, 1)), np.eye(n)])
    e0 = np.zeros((n + 1, n + 1))
    e0[0, 0] = 1.0
    K = T.T @ Ks @ T + d["k_b"] * e0
    C = T.T @ Cs @ T + d["c_b"] * e0
    M = np.diag(np.concatenate([[d["m_base"]], m]))
    return M, K, C


def main():
    d = json.load(open(sys.argv[1]))
    M, K, C = assemble(d)
    out = []
    w2 = linalg.eigh(K, M, eigvals_only=True)
    for j, v in enumerate(w2):
        out.append(f"omega {j + 1} {np.sqrt(v):.17g}")
    ag = np.array(d.get("ag", []), float)
    if len(ag):
        n = M.shape[0]
        s = int(d["substeps"])
        h = d["dt"] / s
        t = np.arange((len(ag) - 1) * s + 1) * h
        agf = np.interp(t, np.arange(len(ag)) * d["dt"], ag)
        Mi = np.linalg.inv(M)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])
        B = np.concatenate([np.zeros(n), -np.ones(n)]).reshape(-1, 1)
        Cout = np.hstack([np.eye(n), np.zeros((n, n))])
        _, y, _ = signal.lsim((A, B, Cout, np.zeros((n, 1))), agf, t, interp=True)
        for i in range(n):
            out.append(f"peak_u {i} {np.max(np.abs(y[:, i])):.17g}")
            out.append(f"final_u {i} {y[-1, i]:.17g}")
    open(sys.argv[2], "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
