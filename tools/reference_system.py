#!/usr/bin/env python3
"""Independent SciPy reference for systems of shear buildings (the system stepper's checks,
tests/physics/test_system_scipy.cpp). None of the engine's code: the matrices are assembled here from the storey
masses, stiffnesses and Rayleigh coefficients, with the DOFs numbered body by body (the engine numbers them level
by level), and results are keyed by (body, floor).

  linear:    M u'' + C u' + K u = -M 1 ag(t), ag linear between record samples (zero after the record), solved by
             scipy.signal.lsim on the state-space model (interp=True: exact for piecewise-linear input) on the
             finest grid of the engine, then sampled on each coarser grid.
  nonlinear: the same buildings pounding at floor-to-floor elements with Hertzdamp,
             F = kc delta^n max(1 + xibar ddelta / v0, 0) for delta > 0 (muthukumar eq. 10), v0 = max(approach
             speed, v0_min) latched at the exact contact onset; solve_ivp (DOP853, rtol 1e-11) record interval by
             record interval (ag is smooth inside one), with terminal events at every element's onset and
             separation, restarting after each with the new latch (the clamp's kink at the tensile instant is
             left to the error control: the force stays continuous there).

Usage: reference_system.py INPUT.json OUTPUT.txt
INPUT: {"mode": "linear"|"nonlinear", "dt": s, "ag": [m/s^2], "duration": s, "substeps": [ints],
        "bodies": [{"m": [kg], "k": [N/m], "a0": 1/s, "a1": s}],
        "contacts": [{"left": [body, floor], "right": [body, floor], "gap": m, "kc": N/m^n, "n": 1.5, "e": e,
                      "v0_min": m/s}]}   (floors 1-based, xibar = 3 (1 - e^2) / 4, Lankarani-Nikravesh)
OUTPUT lines: "peak_u S body floor value", "final_u S body floor value" for every grid S (substeps per record
step); nonlinear also "impacts element count" (continuous onsets) and "peak_force S element value" (sampled on
grid S).
"""
import json
import sys

import numpy as np
from scipy import integrate, signal


def assemble(bodies):
    dofs = []  # (body, floor)
    for b, body in enumerate(bodies):
        for f in range(len(body["m"])):
            dofs.append((b, f + 1))
    n = len(dofs)
    M = np.zeros((n, n))
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    base = 0
    for body in bodies:
        m = np.array(body["m"], float)
        k = np.array(body["k"], float)
        nb = len(m)
        Kb = np.zeros((nb, nb))
        for i in range(nb):  # storey i joins floor i-1 (ground for i = 0) and floor i
            Kb[i, i] += k[i]
            if i > 0:
                Kb[i - 1, i - 1] += k[i]
                Kb[i - 1, i] -= k[i]
                Kb[i, i - 1] -= k[i]
        sl = slice(base, base + nb)
        M[sl, sl] = np.diag(m)
        K[sl, sl] = Kb
        C[sl, sl] = body["a0"] * np.diag(m) + body["a1"] * Kb
        base += nb
    return dofs, M, K, C


def grid(cfg):
    dt, smax = cfg["dt"], max(cfg["substeps"])
    h = dt / smax
    nsteps = int(round(cfg["duration"] / h))
    t = np.arange(nsteps + 1) * h
    ag = np.asarray(cfg["ag"], float)
    trec = np.arange(len(ag)) * dt
    agf = np.interp(t, trec, ag, right=0.0)
    return t, agf, smax


def write_peaks(out, cfg, dofs, u, smax):
    for s in cfg["substeps"]:
        sub = u[:: smax // s]
        for i, (b, f) in enumerate(dofs):
            out.write(f"peak_u {s} {b} {f} {np.max(np.abs(sub[:, i])):.17g}\n")
            out.write(f"final_u {s} {b} {f} {sub[-1, i]:.17g}\n")


def linear(cfg, out):
    dofs, M, K, C = assemble(cfg["bodies"])
    n = len(dofs)
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])
    B = np.concatenate([np.zeros(n), -np.ones(n)])[:, None]
    Cout = np.hstack([np.eye(n), np.zeros((n, n))])
    t, agf, smax = grid(cfg)
    _, y, _ = signal.lsim((A, B, Cout, np.zeros((n, 1))), agf, t, interp=True)
    write_peaks(out, cfg, dofs, y.reshape(len(t), n), smax)


class Pounding:
    def __init__(self, cfg):
        self.dofs, self.M, self.K, self.C = assemble(cfg["bodies"])
        self.n = len(self.dofs)
        self.Mi = 1.0 / np.diag(self.M)
        index = {d: i for i, d in enumerate(self.dofs)}
        self.el = []
        for c in cfg["contacts"]:
            self.el.append(dict(L=index[tuple(c["left"])], R=index[tuple(c["right"])], gap=c["gap"], kc=c["kc"],
                                n=c["n"], xi=0.75 * (1.0 - c["e"] ** 2), v0_min=c["v0_min"]))
        self.active = [False] * len(self.el)
        self.v0 = [1.0] * len(self.el)

    def delta(self, e, y):
        el = self.el[e]
        return y[el["L"]] - y[el["R"]] - el["gap"], y[self.n + el["L"]] - y[self.n + el["R"]]

    def force(self, e, y):
        if not self.active[e]:
            return 0.0
        d, dd = self.delta(e, y)
        el = self.el[e]
        return el["kc"] * max(d, 0.0) ** el["n"] * max(1.0 + el["xi"] * dd / self.v0[e], 0.0)

    def rhs(self, t, y, a0, a1, t0, t1):
        u, v = y[: self.n], y[self.n:]
        ag = a0 + (a1 - a0) * (t - t0) / (t1 - t0)
        f = -self.C @ v - self.K @ u
        for e, el in enumerate(self.el):
            F = self.force(e, y)
            f[el["L"]] -= F
            f[el["R"]] += F
        return np.concatenate([v, f * self.Mi - ag])

    def events(self):
        evs = []
        for e in range(len(self.el)):
            def gap_ev(t, y, *args, e=e):
                return self.delta(e, y)[0]
            gap_ev.terminal = True
            gap_ev.direction = -1.0 if self.active[e] else 1.0
            evs.append(gap_ev)
        return evs


def nonlinear(cfg, out):
    P = Pounding(cfg)
    t, agf, smax = grid(cfg)
    h = t[1] - t[0]
    dt = cfg["dt"]
    nrec = int(round(cfg["duration"] / dt))
    ag = np.asarray(cfg["ag"], float)
    agr = np.concatenate([ag, np.zeros(max(0, nrec + 2 - len(ag)))])
    y = np.zeros(2 * P.n)
    U = np.zeros((len(t), P.n))
    Fg = np.zeros((len(t), len(P.el)))
    impacts = [0] * len(P.el)
    for k in range(nrec):
        t0, t1 = k * dt, (k + 1) * dt
        ta = t0
        while ta < t1 - 1e-15:
            sol = integrate.solve_ivp(P.rhs, (ta, t1), y, method="DOP853", rtol=1e-11, atol=1e-14,
                                      events=P.events(), dense_output=True, args=(agr[k], agr[k + 1], t0, t1))
            tb = sol.t[-1]
            j0, j1 = int(np.ceil(ta / h - 1e-9)), int(np.floor(tb / h + 1e-9))
            for j in range(max(j0, 0), min(j1, len(t) - 1) + 1):
                yj = sol.sol(t[j])
                U[j] = yj[: P.n]
                for e in range(len(P.el)):
                    Fg[j, e] = P.force(e, yj)
            y = sol.y[:, -1].copy()
            if sol.status == 1:  # an event: the element whose gap closed or opened flips its state
                for e in range(len(P.el)):
                    if len(sol.t_events[e]) == 0:
                        continue
                    P.active[e] = not P.active[e]
                    if P.active[e]:
                        impacts[e] += 1
                        P.v0[e] = max(P.delta(e, y)[1], P.el[e]["v0_min"])
            ta = tb
    write_peaks(out, cfg, P.dofs, U, smax)
    for e in range(len(P.el)):
        out.write(f"impacts {e} {impacts[e]}\n")
        for s in cfg["substeps"]:
            out.write(f"peak_force {s} {e} {np.max(Fg[:: smax // s, e]):.17g}\n")


def main():
    cfg = json.load(open(sys.argv[1]))
    with open(sys.argv[2], "w") as out:
        (linear if cfg["mode"] == "linear" else nonlinear)(cfg, out)


if __name__ == "__main__":
    main()
