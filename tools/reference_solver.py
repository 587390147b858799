#!/usr/bin/python3
"""Independent reference solutions of the 2-DOF pounding problem (SciPy, not the engine).

Integrates the same equations as the kernel (muthukumar-desroches-2006-hertzdamp.txt eq. 1)

    m1 a1 + c1 v1 + fs1(u1) + F = -m1 ag(t),   m2 a2 + c2 v2 + fs2(u2) - F = -m2 ag(t)

with scipy.integrate.solve_ivp (DOP853 by default, rtol 1e-10) one record interval at a time, so that the
ground acceleration is exactly linear inside every call, and with event functions that stop the integration
exactly where the right-hand side changes form:

  * bilinear kinematic hardening: elastic -> yielding when fs reaches alpha k u +/- (1 - alpha) fy, and
    yielding -> elastic when the velocity changes sign (unloading); the elastic branch is anchored there;
  * contact onset (delta = u1 - u2 - gap crosses 0 upwards; Hertzdamp latches v0 = max(ddelta, v0_min)
    there; the stereomechanical law applies eq. 2 there) and separation (delta crosses 0 downwards);
  * the instant a damped law's force would turn tensile (Kelvin kc delta + ck ddelta = 0, Hertzdamp
    1 + xibar ddelta / v0 = 0): from there to separation the force is held at zero (non-tensile laws).

Peaks are taken at located extrema (non-terminal events): peak closing where ddelta = 0, peak |u_i| where
v_i = 0, peak force where dF/dt = 0, plus every segment end. The contact parameters are computed here from
their published formulas (Kelvin: impact-stiffness paper eqs 2-3; Hertzdamp xibar: the named damping laws;
the calibrated law solves the scale-free single impact with solve_ivp and brentq).

Input: a models CSV written by `pounding accuracy models` (one row per case: record, law, parameters) and the
ground motions it wrote beside it (`<record>.ag`: dt on the first line, then m/s^2 samples).
Output: the same rows with ref_peak_closing, ref_peak_force, ref_impact_count, ref_peak_u1, ref_peak_u2.

    /usr/bin/python3 tools/reference_solver.py MODELS.csv OUT.csv [--jobs 2] [--method DOP853] [--rtol 1e-10]
"""
import argparse
import csv
import math
import multiprocessing
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


# --- contact parameters from their published formulas ------------------------------------------------
def kelvin_ck(kc, e, meff):
    le = math.log(e)
    xi = -le / math.sqrt(math.pi ** 2 + le * le)  # impact-stiffness paper eq. 3
    return 2.0 * xi * math.sqrt(kc * meff)       # eq. 2


def single_impact_restitution(xi, n=1.5):
    """Rebound speed of x'' = -x^n (1 + xi x'), x(0) = 0, x'(0) = 1 (scale-free Hertzdamp impact)."""
    def f(t, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** n * (1.0 + xi * y[1])]

    def sep(t, y):
        return y[0]
    sep.terminal, sep.direction = True, -1
    # the force cannot turn tensile before separation for xi >= 0 (1 + xi x' > 0 unless x' < -1/xi)
    r = solve_ivp(f, (0.0, 50.0), [0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14, events=sep,
                  first_step=1e-6)
    return -r.y_events[0][0][1]


_calib_cache = {}


def hertzdamp_xibar(law, e, n=1.5):
    if law == "lankarani-nikravesh":
        return 3.0 * (1.0 - e * e) / 4.0
    if law == "hunt-crossley":
        return 1.5 * (1.0 - e)
    if law == "flores":
        return 8.0 * (1.0 - e) / (5.0 * e)
    if law == "hu-guo":
        return 1.5 * (1.0 - e) / e
    if law == "gonthier":
        return (1.0 - e * e) / e
    if law == "calibrated":
        key = (e, n)
        if key not in _calib_cache:
            _calib_cache[key] = 0.0 if e >= 1.0 else brentq(
                lambda x: single_impact_restitution(x, n) - e, 0.0, 50.0, xtol=1e-13)
        return _calib_cache[key]
    raise ValueError("unknown damping law " + law)


def untriggered_near_zero(f, tiny):
    """Event values within +-tiny count as not yet crossed. solve_ivp detects a crossing from the step-end state
    but brackets the root on the dense interpolant; where an event function sits at round-off (a relative
    velocity of two bodies at rest is +-1e-18) the two can disagree in sign and brentq fails (seen with RK45,
    Radau and LSODA). Snapping |g| < tiny to the not-crossed side makes both see the same sign; tiny is far
    below anything physical (1e-14 m, m/s)."""
    if f.direction == 0:
        return f
    side = -1.0 if f.direction > 0 else 1.0

    def g(t, y):
        v = f(t, y)
        return side * tiny if abs(v) < tiny else v
    g.terminal, g.direction = f.terminal, f.direction
    return g


# --- one case --------------------------------------------------------------------------------------
class Case:
    def __init__(self, row, ag, dt):
        g = lambda k: float(row[k])
        self.m = [g("m1"), g("m2")]
        self.k = [g("k1"), g("k2")]
        self.c = [g("c1"), g("c2")]
        self.fy = [g("fy1"), g("fy2")]
        self.alpha = [g("alpha1"), g("alpha2")]
        self.ak = [self.alpha[i] * self.k[i] for i in range(2)]
        self.qy = [(1.0 - self.alpha[i]) * self.fy[i] for i in range(2)]
        self.elastic = [not math.isfinite(self.fy[i]) for i in range(2)]
        self.gap, self.kc, self.e = g("gap"), g("kc"), g("e")
        self.law, self.damping = row["law"], row["damping"]
        self.n, self.v0_min = g("n"), g("v0_min")
        self.meff = self.m[0] * self.m[1] / (self.m[0] + self.m[1])
        self.cd = 0.0
        if self.law == "kelvin":
            self.cd = kelvin_ck(self.kc, self.e, self.meff)
        elif self.law == "hertzdamp":
            self.cd = hertzdamp_xibar(self.damping, self.e, self.n)
        self.ag, self.dt = ag, dt


def solve_case(case, method="DOP853", rtol=1e-10):
    C = case
    law = C.law
    force_law = law in ("linear", "kelvin", "hertz", "hertzdamp")
    damped = law in ("kelvin", "hertzdamp")
    # discrete state: per structure 'e' (elastic, anchored at ua, fsa), '+' or '-' (on the yield surface)
    smode = ["e", "e"]
    anchor = [(0.0, 0.0), (0.0, 0.0)]
    cmode = "open"  # 'open', 'closed', 'clamped'
    v0 = C.v0_min

    def fs(i, u):
        if C.elastic[i]:
            return C.k[i] * u
        if smode[i] == "e":
            return anchor[i][1] + C.k[i] * (u - anchor[i][0])
        return C.ak[i] * u + (C.qy[i] if smode[i] == "+" else -C.qy[i])

    def raw_force(d, dd):
        dp = d if d > 0.0 else 0.0
        if law == "linear":
            return C.kc * dp
        if law == "kelvin":
            return C.kc * dp + C.cd * dd
        if law == "hertz":
            return C.kc * dp ** C.n
        if law == "hertzdamp":
            return C.kc * dp ** C.n * (1.0 + C.cd * dd / v0)
        return 0.0

    def force(y):
        if cmode != "closed":
            return 0.0
        return raw_force(y[0] - y[2] - C.gap, y[1] - y[3])

    # ground acceleration on the current interval: ag0 + s (t - t0)
    seg = [0.0, 0.0, 0.0]

    def rhs(t, y):
        ag = seg[1] + seg[2] * (t - seg[0])
        F = force(y)
        a1 = -ag - (C.c[0] * y[1] + fs(0, y[0]) + F) / C.m[0]
        a2 = -ag - (C.c[1] * y[3] + fs(1, y[2]) - F) / C.m[1]
        return [y[1], a1, y[3], a2]

    # event functions (built per mode)
    def ev_yield_up(i):
        f = lambda t, y: fs(i, y[2 * i]) - (C.ak[i] * y[2 * i] + C.qy[i])
        f.terminal, f.direction = True, 1
        return f

    def ev_yield_dn(i):
        f = lambda t, y: fs(i, y[2 * i]) - (C.ak[i] * y[2 * i] - C.qy[i])
        f.terminal, f.direction = True, -1
        return f

    def ev_unload(i, direction):
        f = lambda t, y: y[2 * i + 1]
        f.terminal, f.direction = True, direction
        return f

    def ev_delta(direction):
        f = lambda t, y: y[0] - y[2] - C.gap
        f.terminal, f.direction = True, direction
        return f

    def ev_raw(direction):
        if law == "kelvin":
            f = lambda t, y: C.kc * (y[0] - y[2] - C.gap) + C.cd * (y[1] - y[3])
        else:
            f = lambda t, y: 1.0 + C.cd * (y[1] - y[3]) / v0
        f.terminal, f.direction = True, direction
        return f

    # non-terminal extremum locators
    ev_close = lambda t, y: y[1] - y[3]
    ev_close.terminal, ev_close.direction = False, -1
    ev_v1 = lambda t, y: y[1]
    ev_v1.terminal, ev_v1.direction = False, 0
    ev_v2 = lambda t, y: y[3]
    ev_v2.terminal, ev_v2.direction = False, 0

    def ev_dF(t, y):  # dF/dt in contact
        d, dd = y[0] - y[2] - C.gap, y[1] - y[3]
        a = rhs(t, y)
        ddd = a[1] - a[3]
        dp = d if d > 0.0 else 0.0
        if law == "linear":
            return C.kc * dd
        if law == "kelvin":
            return C.kc * dd + C.cd * ddd
        if law == "hertz":
            return C.kc * C.n * dp ** (C.n - 1.0) * dd
        # hertzdamp
        return C.kc * (C.n * dp ** (C.n - 1.0) * dd * (1.0 + C.cd * dd / v0) + dp ** C.n * C.cd * ddd / v0)
    ev_dF.terminal, ev_dF.direction = False, -1

    def events():
        terminal = []
        for i in range(2):
            if C.elastic[i]:
                continue
            if smode[i] == "e":
                terminal += [("yu", i, ev_yield_up(i)), ("yd", i, ev_yield_dn(i))]
            elif smode[i] == "+":
                terminal.append(("ul", i, ev_unload(i, -1)))
            else:
                terminal.append(("ul", i, ev_unload(i, 1)))
        if law != "none":
            if cmode == "open":
                terminal.append(("on", 0, ev_delta(1)))
            else:
                terminal.append(("off", 0, ev_delta(-1)))
                if damped:
                    terminal.append(("clamp", 0, ev_raw(-1)) if cmode == "closed" else ("unclamp", 0, ev_raw(1)))
        extra = [ev_close, ev_v1, ev_v2]
        if force_law and cmode == "closed":
            extra.append(ev_dF)
        return terminal, extra

    def tiny(kind):  # round-off band of each event function, in its own units
        if kind in ("clamp", "unclamp") and law == "kelvin":
            return 1e-14 * C.kc  # N
        if kind == "dF":
            return 1e-14 * C.kc  # N/s, generous
        if kind in ("yu", "yd"):
            return 1e-14 * max(C.k)  # N
        return 1e-14  # m, m/s, or dimensionless

    peak = {"close": -math.inf, "F": 0.0, "u1": 0.0, "u2": 0.0}
    impacts = 0

    def observe(y):
        peak["close"] = max(peak["close"], y[0] - y[2])
        peak["u1"] = max(peak["u1"], abs(y[0]))
        peak["u2"] = max(peak["u2"], abs(y[2]))
        peak["F"] = max(peak["F"], force(y))

    y = np.zeros(4)
    observe(y)
    ag = C.ag
    nrec = len(ag)
    atol = np.array([1e-13, 1e-12, 1e-13, 1e-12])
    for j in range(nrec - 1):
        t0, t1 = j * C.dt, (j + 1) * C.dt
        seg[0], seg[1], seg[2] = t0, ag[j], (ag[j + 1] - ag[j]) / C.dt
        t = t0
        guard = 0
        while t < t1:
            guard += 1
            if guard > 10000:
                raise RuntimeError("event loop does not advance at t = %g" % t)
            term, extra = events()
            evs = [untriggered_near_zero(f, tiny(kind)) for kind, _, f in term] + \
                [untriggered_near_zero(f, tiny("dF" if f is ev_dF else "")) for f in extra]
            r = solve_ivp(rhs, (t, t1), y, method=method, rtol=rtol, atol=atol, events=evs)
            if r.status < 0:
                raise RuntimeError(r.message)
            for k in range(len(term), len(evs)):
                for ye in r.y_events[k]:
                    observe(ye)
            y = r.y[:, -1].copy()
            t = r.t[-1]
            observe(y)
            if r.status == 1:  # a terminal event: switch the mode at the located instant
                fired = [(r.t_events[k][0], k) for k in range(len(term)) if len(r.t_events[k])]
                _, k = min(fired)
                kind, i, _ = term[k]
                if kind == "yu":
                    smode[i] = "+"
                elif kind == "yd":
                    smode[i] = "-"
                elif kind == "ul":
                    anchor[i] = (y[2 * i], fs(i, y[2 * i]))  # on the yield surface, before switching
                    smode[i] = "e"
                elif kind == "on":
                    dd = y[1] - y[3]
                    if law == "stereomechanical":
                        if dd > 0.0:  # muthukumar eq. 2
                            M = C.m[0] + C.m[1]
                            y[1] -= (1.0 + C.e) * C.m[1] * dd / M
                            y[3] += (1.0 + C.e) * C.m[0] * dd / M
                            impacts += 1
                            # a yielding structure whose velocity the jump reversed unloads at once
                            for i2 in range(2):
                                if smode[i2] != "e" and (y[2 * i2 + 1] < 0.0) == (smode[i2] == "+"):
                                    anchor[i2] = (y[2 * i2], fs(i2, y[2 * i2]))
                                    smode[i2] = "e"
                    else:
                        cmode = "closed"
                        v0 = max(dd, C.v0_min)
                        impacts += 1
                elif kind == "off":
                    cmode = "open"
                elif kind == "clamp":
                    cmode = "clamped"
                elif kind == "unclamp":
                    cmode = "closed"
                observe(y)
            else:
                break
    return {"ref_peak_closing": peak["close"], "ref_peak_force": peak["F"], "ref_impact_count": impacts,
            "ref_peak_u1": peak["u1"], "ref_peak_u2": peak["u2"]}


# --- driver -----------------------------------------------------------------------------------------
_AG = {}


def load_ag(path):
    if path not in _AG:
        with open(path) as f:
            dt = float(f.readline())
            _AG[path] = (np.array([float(x) for x in f if x.strip()]), dt)
    return _AG[path]


def work(args):
    row, agdir, method, rtol = args
    ag, dt = load_ag(os.path.join(agdir, row["record"] + ".ag"))
    t0 = time.perf_counter()
    res = solve_case(Case(row, ag, dt), method, rtol)
    res["ref_seconds"] = time.perf_counter() - t0
    out = dict(row)
    out.update(res)
    return out


def fmt_field(key, value):
    """Numbers in their shortest round-trip form (so a rerun reproduces the stored CSV, timings aside)."""
    if key == "ref_seconds":
        return "%.3f" % value
    if key in ("model", "ref_impact_count"):
        return str(value)
    try:
        return repr(float(value))
    except (TypeError, ValueError):
        return value


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("models")
    ap.add_argument("out")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--method", default="DOP853", choices=["DOP853", "Radau", "RK45"])
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--limit", type=int, default=0, help="only the first N rows (smoke test)")
    ap.add_argument("--rows", default="", help="only these 0-based data rows, comma-separated (regeneration test)")
    a = ap.parse_args()
    with open(a.models) as f:
        rows = list(csv.DictReader(f))
    if a.rows:
        try:
            picked = [int(x) for x in a.rows.split(",")]
        except ValueError:
            sys.exit("reference_solver.py: --rows takes 0-based row numbers separated by commas, got '%s'" % a.rows)
        bad = [i for i in picked if not 0 <= i < len(rows)]
        if bad:
            sys.exit("reference_solver.py: --rows %s outside 0..%d (%s)" % (bad, len(rows) - 1, a.models))
        rows = [rows[i] for i in picked]
    if a.limit:
        rows = rows[:a.limit]
    agdir = os.path.dirname(os.path.abspath(a.models))
    jobs = [(r, agdir, a.method, a.rtol) for r in rows]
    t0 = time.perf_counter()
    if a.jobs > 1:
        with multiprocessing.Pool(a.jobs) as pool:
            res = pool.map(work, jobs, chunksize=1)
    else:
        res = [work(j) for j in jobs]
    fields = list(rows[0].keys()) + ["ref_peak_closing", "ref_peak_force", "ref_impact_count", "ref_peak_u1",
                                     "ref_peak_u2", "ref_seconds"]
    tmp = a.out + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for r in res:
            w.writerow({k: fmt_field(k, v) for k, v in r.items()})
    os.replace(tmp, a.out)
    print("%d cases, %.1f s (%s, rtol %g)" % (len(res), time.perf_counter() - t0, a.method, a.rtol),
          file=sys.stderr)


if __name__ == "__main__":
    main()
