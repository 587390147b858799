#!/usr/bin/env python3
"""Independent ELF design of a building (ASCE 7-16 ch. 12.8), the reference for tests/inventory/test_elf.cpp.

Written from the standard's clauses, not from src/inventory/elf.cpp: Ta (12.8.2.1, Table 12.8-2 SI), Cu (Table
12.8-1), Cs (12.8.1.1), k and Fx (12.8.3), Vx (12.8.4); the storey stiffnesses proportional to Vx scaled to the
period with scipy's generalised symmetric eigensolver; strengths Omega0 x factor x Vx; P-Delta k - P/h.

  tools/elf_reference.py --system rc-smf --storeys 5 --storey-height 3.2 --floor-mass 4.5e5 \
      --sds 1.0 --sd1 0.6 --s1 0.6 --tl 8 --r 8 --omega0 3 --ct 0.0466 --x 0.9
prints one line per quantity, "name value" with 10 significant digits.
"""
import argparse

import numpy as np
from scipy.linalg import eigh

G = 9.80665


def cu_of(sd1):
    pts = [(0.1, 1.7), (0.15, 1.6), (0.2, 1.5), (0.3, 1.4), (0.4, 1.4)]
    if sd1 <= 0.1:
        return 1.7
    if sd1 >= 0.4:
        return 1.4
    return float(np.interp(sd1, [p[0] for p in pts], [p[1] for p in pts]))


def cs_of(sds, sd1, s1, tl, t, r, ie):
    cs = sds / (r / ie)
    cs = min(cs, sd1 / (t * r / ie) if t <= tl else sd1 * tl / (t * t * r / ie))
    cs = max(cs, 0.044 * sds * ie, 0.01)
    if s1 >= 0.6:
        cs = max(cs, 0.5 * s1 / (r / ie))
    return cs


def first_omega(m, k):
    n = len(m)
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] += k[i]
        if i > 0:
            K[i - 1, i - 1] += k[i]
            K[i - 1, i] -= k[i]
            K[i, i - 1] -= k[i]
    w2 = eigh(K, np.diag(m), eigvals_only=True)
    return np.sqrt(w2.min())


def main():
    p = argparse.ArgumentParser()
    for name in ("storey-height", "floor-mass", "sds", "sd1", "s1", "tl", "r", "omega0", "ct", "x"):
        p.add_argument("--" + name, type=float, required=True)
    p.add_argument("--storeys", type=int, required=True)
    p.add_argument("--ie", type=float, default=1.0)
    p.add_argument("--factor", type=float, default=1.0)
    p.add_argument("--alpha", type=float, default=0.05)
    p.add_argument("--system", default="")
    a = p.parse_args()
    n = a.storeys
    h = np.full(n, a.storey_height)
    z = np.cumsum(h)
    m = np.full(n, a.floor_mass)
    ta = a.ct * z[-1] ** a.x
    t = cu_of(a.sd1) * ta
    cs = cs_of(a.sds, a.sd1, a.s1, a.tl, t, a.r, a.ie)
    w = G * m.sum()
    v = cs * w
    k = 1.0 if t <= 0.5 else 2.0 if t >= 2.5 else 1 + (t - 0.5) / 2
    wh = G * m * z ** k
    fx = v * wh / wh.sum()
    vx = np.cumsum(fx[::-1])[::-1]
    kk = vx * (2 * np.pi / t / first_omega(m, vx)) ** 2
    vy = a.omega0 * a.factor * vx
    P = np.cumsum((G * m)[::-1])[::-1]
    kg = P / h
    out = dict(Ta=ta, Cu=cu_of(a.sd1), T=t, Cs=cs, W=w, V=v, k=k)
    for i in range(n):
        out[f"Fx{i + 1}"] = fx[i]
        out[f"Vx{i + 1}"] = vx[i]
        out[f"K{i + 1}"] = kk[i]
        out[f"Vy{i + 1}"] = vy[i]
        out[f"Kpd{i + 1}"] = kk[i] - kg[i]
        out[f"alpha_pd{i + 1}"] = (a.alpha * kk[i] - kg[i]) / (kk[i] - kg[i])
        out[f"Vy_pd{i + 1}"] = vy[i] * (kk[i] - kg[i]) / kk[i]
    out["T_check"] = 2 * np.pi / first_omega(m, kk)
    for key, val in out.items():
        print(f"{key} {val:.10g}")


if __name__ == "__main__":
    main()
