#!/usr/bin/env python3
"""Independent SciPy references for systems of bodies (issue 25; docs/architecture.md §2.8): none of the engine's code.
One module for what were tools/reference_mdof.py, reference_system.py and reference_isolation.py (their linear
parts shared: stick_stiffness, state_space), plus the smooth isolators. Subcommands:

  modes, response, selftest   shear buildings: modes, Rayleigh, linear response (below, "mdof")
  system IN OUT               systems of shear buildings, linear and pounding (below, "system")
  isolation IN OUT            a linear base-isolated building, Kelly's assembly (below, "isolation")
  smooth IN OUT               a building on a friction-pendulum or Bouc-Wen isolator (below, "smooth")
  row IN OUT | row selftest   a row of n buildings pounding their neighbours (below, "row")

---- mdof ----
Independent reference for shear buildings (issue 25 §5; docs/architecture.md §2.8): modes, Rayleigh ratios and
the linear response to a ground acceleration, with NumPy/SciPy and none of the engine's code.

Floors bottom first; floor i has mass m_i (kg), storey i (between floor i and the one below) stiffness k_i (N/m);
M = diag(m), K_ii = k_i + k_{i+1}, K_{i,i+1} = -k_{i+1} (../shared/research/systems-and-bridges.md §1).

    tools/reference_systems.py modes --masses 2e5,2e5,1.5e5 --stiffnesses 3e8,2.5e8,2e8 [--zeta 0.05] [--rayleigh-modes 1,2]
    tools/reference_systems.py modes --input building.json
        (building.json: {"masses": [...], "stiffnesses": [...], "zeta": 0.05, "rayleigh_modes": [1, 2]}, or a
        list of such objects, answered by a list.) Modes by scipy.linalg.eigh(K, M); Gamma_j = L_j/M_j of the roof-normalised shape, M*_j = L_j^2/M_j,
        M*_j / sum m; Rayleigh a0, a1 on the two modes (Chopra: a0 = 2 wi wj (zi wj - zj wi)/(wj^2 - wi^2),
        a1 = 2 (zj wj - zi wi)/(wj^2 - wi^2)) and each mode's zeta_n = a0/(2 w_n) + a1 w_n/2; one storey:
        zeta itself (c = 2 zeta sqrt(k m)). Prints one JSON object with the keys of `pounding modes --json`:
        storeys, masses, stiffnesses, total_mass, damping {kind, modes, zeta, a0, a1}, modes [{mode, period,
        frequency, omega, gamma, effective_mass, effective_mass_ratio, cumulative_ratio, zeta, shape (roof = 1, or
        largest |value| = 1 for a mode confined below the roof: roof value < 1e-6 of its largest)}].

    tools/reference_systems.py response --input building.json [--method lsim|modal|both] [--substeps N]
                                     [--series out.csv]
        Linear response to the ground acceleration, M u'' + C u' + K u = -M 1 ag (u relative to the ground),
        from rest. building.json: {"masses": [...], "stiffnesses": [...],
          "damping": {"rayleigh": {"modes": [1, 2], "zeta": 0.05}} | {"modal": {"zeta": [z1, z2, ...]}}
                     (modal: per mode from mode 1, the last value repeating; default Rayleigh 1, 2 with 0.05),
          and the motion: "dt" (s) with "ag" (m/s^2), or "record": a PEER AT2 file (g), with optional
          "scale" (a factor on ag) and "duration" (s; zeros after the record, default the record's length)}.
        The ground acceleration is linear between samples. lsim: scipy.signal.lsim on the state-space model
        [u, v] (first-order hold: exact for a piecewise-linear input); modal: each mode's SDOF
        q'' + 2 zeta_j w_j q' + w_j^2 q = -Gamma_j ag by lsim, u = sum phi_j q_j (exact for classical damping,
        which Rayleigh and modal damping are). --substeps N samples the output N times per record step
        (the input stays the same piecewise-linear signal), so peaks are the continuous ones within ~(pi/N/20)^2.
        Prints JSON: {method: {peak_u: [per floor, m], peak_drift: [per storey, m], peak_abs_acc: [per floor,
        m/s^2], peak_base_shear (N), time_of_peak_roof (s)}} and, with both, "max_rel_difference".
        --series writes t, ag, u_1..u_n, a_abs_1..a_abs_n of the first method as CSV.

    tools/reference_systems.py selftest
        The reference against closed forms: eigh against the uniform stick's omega_j = 2 sqrt(k/m)
        sin((2j-1) pi / (2(2n+1))); a damped SDOF under a step in ag against its closed-form response, by lsim
        and modal; lsim against modal on a 3-storey building under noise. Exit 1 on a failure.

---- system ----
Independent SciPy reference for systems of shear buildings (the system stepper's checks,
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

Usage: tools/reference_systems.py system INPUT.json OUTPUT.txt
INPUT: {"mode": "linear"|"nonlinear", "dt": s, "ag": [m/s^2], "duration": s, "substeps": [ints],
        "bodies": [{"m": [kg], "k": [N/m], "a0": 1/s, "a1": s}],
        (a body may give "modal_zeta": [z1, z2, ...] instead of a0/a1: classical modal damping
         C = M Phi diag(2 z_j w_j / M_j) Phi' M from scipy.linalg.eigh, the last ratio repeating)
        "contacts": [{"left": [body, floor], "right": [body, floor], "gap": m, "kc": N/m^n, "n": 1.5, "e": e,
                      "v0_min": m/s}]}   (floors 1-based, xibar = 3 (1 - e^2) / 4, Lankarani-Nikravesh)
       A side may instead be a column, {"column": [body, lo, hi], "xi": x} (a floor striking the column between
       floors lo and hi = lo + 1 of body, lo = 0 the ground): x_side = (1 - x) u_lo + x u_hi (u_0 = 0), and the
       contact force acts on floors lo and hi with the same weights (work-consistent, SB §3).
OUTPUT lines: "peak_u S body floor value", "final_u S body floor value" for every grid S (substeps per record
step); nonlinear also "impacts element count" (continuous onsets) and "peak_force S element value" (sampled on
grid S).

---- isolation ----
Independent SciPy reference for a linear base-isolated shear building (tests/physics/test_isolation.cpp).
None of the engine's code: the superstructure's fixed-base matrices Ms, Ks, Cs = a0 Ms + a1 Ks act on the floors'
displacements RELATIVE TO THE BASE, x = u_s - 1 u_b (Kelly's formulation; Naeim & Kelly 1999 ch. 2), so in the
engine's coordinates u = [u_b, u_1..u_n] (relative to the ground) K = T' Ks T + k_b e0 e0', C = T' Cs T + c_b e0 e0',
M = diag(m_b, Ms) with T = [-1 | I]. Then
  modes:    scipy.linalg.eigh(K, M) -> "omega j value" (rad/s), j from 1
  response: M u'' + C u' + K u = -M 1 ag(t), ag linear between record samples, scipy.signal.lsim (interp=True) on
            the grid dt/substeps -> "peak_u dof value", "final_u dof value" (dof 0 = the base).
Usage: tools/reference_systems.py isolation INPUT.json OUTPUT.txt
INPUT: {"m_base": kg, "k_b": N/m, "c_b": N s/m, "m": [kg], "k": [N/m], "a0": 1/s, "a1": s,
        "dt": s, "ag": [m/s^2], "substeps": int}   (ag empty: modes only)
       ("modal_zeta": [z1, ...] instead of a0/a1: the fixed-base superstructure's classical modal C_s, as in
        "system"; the assembly is then C = T' C_s T + c_b e0 e0' all the same)

---- smooth ----
A base-isolated shear building (Kelly's assembly of "isolation", the bearing's viscous c_b = 0) on a smooth
hysteretic isolator at the base DOF: F_b = k u_b + Q(v_b) z, Q(v) = Q_fast - (Q_fast - Q_slow) exp(-rate |v|),
u_y z' = (A - |z|^eta (gamma + beta sgn(z v_b))) v_b (Wen 1976, beta on the |v| term) -- the friction pendulum is
k = W/R, Q = mu W, A = 1, beta = gamma = 0.5, eta = 2; Bouc-Wen k = alpha k0, Q = (1 - alpha) k0 u_y. The state
[u, v, z, E] (E' = Q z v_b, the hysteretic part's work) by solve_ivp (DOP853, rtol 1e-10, atol 1e-13) record
interval by record interval (ag linear inside one), sampled on each grid dt/S.
Usage: tools/reference_systems.py smooth INPUT.json OUTPUT.txt
INPUT: {"m_base", "m": [kg], "k": [N/m], "a0", "a1", "bearing": {"k", "q_slow", "q_fast", "rate", "uy", "A", "beta",
        "gamma", "eta"}, "dt", "ag": [m/s^2], "duration": s, "substeps": [ints]}
OUTPUT lines: "peak_u S dof value", "final_u S dof value" (dof 0 the base), "peak_bearing_force S value",
"e_hysteretic value" (E at the end minus the recoverable Q z^2 u_y / (2 A), J), "final_z value".

---- row ----
A row of n shear buildings (an SDOF is a stick of one) left to right, each pounding its neighbours at the floors
both have (floor f of building b against floor f of building b+1, f <= the lower one's storeys; equal storey
heights), with "system"'s nonlinear solver (Hertzdamp, Lankarani-Nikravesh xibar = 3 (1 - e^2) / 4; e = 1 and
n = 1.5 is pure Hertz, e = 1 and n = 1 a linear spring), and initial velocities. The uncoupled run (no contact) of
the same row is solved too, so each building's amplification (coupled / uncoupled peak |u| over its floors) is
the reference's own (../shared/research/systems-and-bridges.md §4).
Usage: tools/reference_systems.py row INPUT.json OUTPUT.txt
INPUT: "system"'s keys without "contacts" and "mode", plus "gap" (m, every joint) or "gaps" ([per joint]), "kc",
       "n", "e", "v0_min", and optional "v_initial": [[per floor] per body] (m/s), "ag" may be all zeros.
OUTPUT lines: "system"'s ("peak_u S body floor value", "final_u ...", "impacts element count", "peak_force S element
value"; elements in the order joint by joint, floors bottom up), plus "final_v body floor value" (the finest grid),
"peak_u_uncoupled S body floor value", "amplification S body value", "momentum_initial value", "momentum_final value".
    tools/reference_systems.py row selftest
        T4.1 (SB §4): three equal free masses at zero gaps, mass 1 moving at v0 toward 2 (touching 3), Hertz and
        linear contacts: final velocities / v0 (-0.0709523537, 0.0764030391, 0.9945493146) and (-0.1302616951,
        0.1502295694, 0.9800321256) to 1e-6, momentum and energy to 1e-9; exit 1 on a failure.
"""
import argparse
import json
import math
import re
import sys

import numpy as np
from scipy import integrate, linalg, signal

G = 9.80665


def stick_stiffness(k):
    """K of one shear stick on the ground: storey i joins floor i-1 (the ground for i = 0) and floor i."""
    k = np.asarray(k, float)
    n = len(k)
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] += k[i]
        if i > 0:
            K[i - 1, i - 1] += k[i]
            K[i - 1, i] -= k[i]
            K[i, i - 1] -= k[i]
    return K


def state_space(M, C, K):
    """x = [u, v], x' = A x + B ag for M u'' + C u' + K u = -M 1 ag."""
    n = M.shape[0]
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])
    B = np.concatenate([np.zeros(n), -np.ones(n)]).reshape(-1, 1)
    return A, B, Mi


def lsim_displacements(M, C, K, t, ag):
    """u(t) (len(t) x n) from rest, ag piecewise linear (lsim interp=True: first-order hold, exact for it)."""
    n = M.shape[0]
    A, B, _ = state_space(M, C, K)
    Cout = np.hstack([np.eye(n), np.zeros((n, n))])
    _, y, _ = signal.lsim((A, B, Cout, np.zeros((n, 1))), ag, t, interp=True)
    return y.reshape(len(t), n)

def matrices(m, k):
    m = np.asarray(m, float)
    k = np.asarray(k, float)
    n = len(m)
    if len(k) != n or n == 0:
        sys.exit(f"reference_systems: {n} masses but {len(k)} stiffnesses")
    return np.diag(m), stick_stiffness(k)


def modes(m, k, with_roof=False):
    """omega (ascending), Phi (columns, roof = 1, or largest |value| = 1 for a mode whose roof value is below 1e-6
    of its largest, as `pounding modes` does), Gamma of those shapes, M*, M*/sum m."""
    M, K = matrices(m, k)
    w2, phi = linalg.eigh(K, M)
    peak = np.max(np.abs(phi), axis=0)
    roof = np.abs(phi[-1, :]) >= 1e-6 * peak  # else a mode confined below the roof: scaled to its largest value
    largest = phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])]
    phi = phi / np.where(roof, phi[-1, :], largest)
    ones = np.ones(len(m))
    L = phi.T @ M @ ones
    Mj = np.einsum("ij,ik,kj->j", phi, M, phi)
    gamma = L / Mj
    meff = L * L / Mj
    out = (np.sqrt(w2), phi, gamma, meff, meff / np.sum(m))
    return out + (roof,) if with_roof else out


def rayleigh(wi, zi, wj, zj):
    den = wj * wj - wi * wi
    return 2 * wi * wj * (zi * wj - zj * wi) / den, 2 * (zj * wj - zi * wi) / den


def mode_ratios(m, omega, zeta, pair):
    if len(m) == 1:
        return {"kind": "sdof", "zeta": zeta, "a0": 2 * zeta * omega[0], "a1": 0.0}, [zeta]
    i, j = pair
    a0, a1 = rayleigh(omega[i - 1], zeta, omega[j - 1], zeta)
    return ({"kind": "rayleigh", "modes": [i, j], "zeta": zeta, "a0": a0, "a1": a1},
            [a0 / (2 * w) + a1 * w / 2 for w in omega])


def modes_json(m, k, zeta=0.05, pair=(1, 2)):
    omega, phi, gamma, meff, ratio, roof = modes(m, k, with_roof=True)
    damping, zetas = mode_ratios(m, omega, zeta, pair)
    out = {"storeys": len(m), "masses": list(map(float, m)), "stiffnesses": list(map(float, k)),
           "total_mass": float(np.sum(m)), "damping": damping, "modes": []}
    cum = np.cumsum(ratio)
    for j in range(len(m)):
        out["modes"].append({"mode": j + 1, "period": 2 * math.pi / omega[j], "frequency": omega[j] / (2 * math.pi),
                             "omega": omega[j], "gamma": gamma[j], "effective_mass": meff[j],
                             "effective_mass_ratio": ratio[j], "cumulative_ratio": cum[j], "zeta": zetas[j],
                             "shape_normalisation": "roof" if roof[j] else "largest", "shape": list(phi[:, j])})
    return out


def damping_matrix(m, k, spec):
    """C and the per-mode ratios for {"rayleigh": {...}} or {"modal": {...}}."""
    M, K = matrices(m, k)
    omega, phi, *_ = modes(m, k)
    n = len(m)
    spec = spec or {"rayleigh": {"modes": [1, 2], "zeta": 0.05}}
    if "modal" in spec:
        z = list(spec["modal"]["zeta"])
        z = np.array([z[min(j, len(z) - 1)] for j in range(n)], float)
        Mj = np.einsum("ij,ik,kj->j", phi, M, phi)
        C = M @ phi @ np.diag(2 * z * omega / Mj) @ phi.T @ M
        return C, z
    r = spec["rayleigh"]
    zeta = float(r.get("zeta", 0.05))
    if n == 1:
        return np.array([[2 * zeta * math.sqrt(k[0] * m[0])]]), np.array([zeta])
    i, j = r.get("modes", [1, 2])
    a0, a1 = rayleigh(omega[i - 1], zeta, omega[j - 1], zeta)
    return a0 * M + a1 * K, a0 / (2 * omega) + a1 * omega / 2


def read_at2(path):
    lines = open(path, encoding="latin-1").read().splitlines()
    mt = re.search(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([0-9.Ee+-]+)", lines[3], re.I)
    if not mt:
        sys.exit(f"{path}: line 4 has no NPTS= ..., DT= ...")
    values = np.array([float(x) for line in lines[4:] for x in line.replace(",", " ").split()])
    return float(mt.group(2)), values[: int(mt.group(1))] * G


def motion(spec):
    if "record" in spec:
        dt, ag = read_at2(spec["record"])
    else:
        dt, ag = float(spec["dt"]), np.asarray(spec["ag"], float)
    ag = ag * float(spec.get("scale", 1.0))
    duration = float(spec.get("duration", dt * (len(ag) - 1)))
    steps = int(round(duration / dt)) + 1
    if steps > len(ag):
        ag = np.concatenate([ag, np.zeros(steps - len(ag))])
    return dt, ag[:steps]


def fine_grid(dt, ag, substeps):
    t = np.arange(len(ag)) * dt
    tf = np.linspace(0.0, t[-1], (len(ag) - 1) * substeps + 1)
    return tf, np.interp(tf, t, ag)  # the same piecewise-linear signal


def response_lsim(m, k, C, t, ag):
    M, K = matrices(m, k)
    n = len(m)
    A, B, Mi = state_space(M, C, K)
    Cout = np.eye(2 * n)
    _, y, _ = signal.lsim((A, B, Cout, np.zeros((2 * n, 1))), ag, t, interp=True)
    y = y.reshape(len(t), 2 * n)
    u, v = y[:, :n], y[:, n:]
    acc_abs = -(Mi @ (K @ u.T + C @ v.T)).T  # u''+ag = -M^-1 (K u + C v)
    return u, acc_abs


def response_modal(m, k, zetas, t, ag):
    omega, phi, gamma, *_ = modes(m, k)
    n = len(m)
    u = np.zeros((len(t), n))
    acc_abs = np.zeros((len(t), n))
    for j in range(n):
        w, z = omega[j], zetas[j]
        sys_j = (np.array([[0.0, 1.0], [-w * w, -2 * z * w]]), np.array([[0.0], [-gamma[j]]]),
                 np.eye(2), np.zeros((2, 1)))
        _, q, _ = signal.lsim(sys_j, ag, t, interp=True)
        q = q.reshape(len(t), 2)
        u += np.outer(q[:, 0], phi[:, j])
        acc_abs += np.outer(-(w * w * q[:, 0] + 2 * z * w * q[:, 1]), phi[:, j])
    return u, acc_abs


def peaks(m, k, t, u, acc_abs):
    drift = np.diff(np.hstack([np.zeros((len(t), 1)), u]), axis=1)
    base_shear = k[0] * drift[:, 0]  # the first storey's spring force (damping forces excluded)
    return {"peak_u": list(np.max(np.abs(u), axis=0)), "peak_drift": list(np.max(np.abs(drift), axis=0)),
            "peak_abs_acc": list(np.max(np.abs(acc_abs), axis=0)),
            "peak_base_shear": float(np.max(np.abs(base_shear))),
            "time_of_peak_roof": float(t[np.argmax(np.abs(u[:, -1]))])}


def response(b, method="lsim", substeps=1, series=None):
    m, k = np.asarray(b["masses"], float), np.asarray(b["stiffnesses"], float)
    C, zetas = damping_matrix(m, k, b.get("damping"))
    dt, ag = motion(b)
    t, agf = fine_grid(dt, ag, substeps)
    out, first = {}, None
    for name in (["lsim", "modal"] if method == "both" else [method]):
        u, acc = response_lsim(m, k, C, t, agf) if name == "lsim" else response_modal(m, k, zetas, t, agf)
        out[name] = peaks(m, k, t, u, acc)
        if first is None:
            first = (u, acc)
    if method == "both":
        a, b2 = out["lsim"], out["modal"]
        out["max_rel_difference"] = max(abs(x - y) / max(abs(x), 1e-300)
                                        for key in ("peak_u", "peak_drift", "peak_abs_acc")
                                        for x, y in zip(a[key], b2[key]))
    if series:
        u, acc = first
        with open(series, "w") as f:
            n = len(m)
            f.write("t,ag," + ",".join(f"u_{i + 1}" for i in range(n)) + "," +
                    ",".join(f"a_abs_{i + 1}" for i in range(n)) + "\n")
            for r in range(len(t)):
                f.write(",".join(repr(float(x)) for x in [t[r], agf[r], *u[r], *acc[r]]) + "\n")
    return out


def selftest():
    bad = []

    def check(name, got, want, tol):
        err = float(np.max(np.abs(np.asarray(got) - np.asarray(want)) / np.maximum(np.abs(np.asarray(want)), 1e-300)))
        print(f"{name:<52} rel err {err:.2e} (tol {tol:g})")
        if not err <= tol:
            bad.append(name)

    for n in (1, 2, 5, 20):
        m, k = np.full(n, 1e5), np.full(n, 1e8)
        j = np.arange(1, n + 1)
        check(f"uniform stick n = {n}: omega", modes(m, k)[0],
              2 * np.sqrt(1e8 / 1e5) * np.sin((2 * j - 1) * np.pi / (2 * (2 * n + 1))), 1e-10)
    # SDOF under a step ag = a: u = -(a/w^2) (1 - e^{-z w t} (cos wd t + z/sqrt(1-z^2) sin wd t))
    m1, k1, z, a = 2e5, 8e7, 0.05, 1.5
    w = math.sqrt(k1 / m1)
    wd = w * math.sqrt(1 - z * z)
    dt = 0.01
    ag = np.full(801, a)
    t = np.arange(len(ag)) * dt
    exact = -(a / w ** 2) * (1 - np.exp(-z * w * t) * (np.cos(wd * t) + z / math.sqrt(1 - z * z) * np.sin(wd * t)))
    b = {"masses": [m1], "stiffnesses": [k1], "damping": {"rayleigh": {"zeta": z}}, "dt": dt, "ag": list(ag)}
    C, zetas = damping_matrix(np.array([m1]), np.array([k1]), b["damping"])
    u_l, _ = response_lsim(np.array([m1]), np.array([k1]), C, t, ag)
    u_m, _ = response_modal(np.array([m1]), np.array([k1]), zetas, t, ag)
    check("SDOF step, lsim against the closed form", u_l[1:, 0], exact[1:], 1e-7)
    check("SDOF step, modal against the closed form", u_m[1:, 0], exact[1:], 1e-7)
    rng = np.random.default_rng(25)
    noise = {"masses": [2e5, 2e5, 1.5e5], "stiffnesses": [3e8, 2.5e8, 2e8],
             "damping": {"rayleigh": {"modes": [1, 3], "zeta": 0.04}}, "dt": 0.01,
             "ag": list(signal.lfilter([1.0], [1.0, -0.9], rng.standard_normal(1500)))}
    r = response(noise, "both", 4)
    check("3 storeys under noise: lsim against modal (peaks)", r["lsim"]["peak_u"] + r["lsim"]["peak_abs_acc"],
          r["modal"]["peak_u"] + r["modal"]["peak_abs_acc"], 1e-8)
    # Q-Hyst: T5.5 of ../shared/research/systems-and-bridges.md (computed there) and the small-loop rules by hand
    t55 = qhyst_path(QHyst(1e8, 2e5, 0.05), [0.002, 0.006, 0.003, -0.002, -0.004, -0.001, 0, 0.003, 0.006, 0.008])
    check("Q-Hyst T5.5 defining cycle", t55, [2.0e5, 2.2e5, 46794.92, -2.0e5, -2.1e5, -36794.92, 12540.68, 116270.3,
                                               2.2e5, 2.3e5], 1e-6)
    ku = 1e8 * math.sqrt(0.002 / 0.007)  # d_m = 0.007
    f7 = 2e5 + 5e6 * 0.005
    u0 = 0.007 - f7 / ku
    kr = 2e5 / (u0 + 0.002)  # reloading towards (-d_y, -F_y): that side has not yielded
    want = [2e5 + 5e6 * 0.004, 2.2e5 - 1e8 * math.sqrt(1 / 3) * 0.002, 2.2e5 - 1e8 * math.sqrt(1 / 3) * 0.001, f7,
            f7 - ku * 0.0035, -kr * (u0 + 0.001), -kr * (u0 + 0.001) + ku * 0.001, -kr * (u0 + 0.0015)]
    check("Q-Hyst small loops (unloading and reloading lines)",
          qhyst_path(QHyst(1e8, 2e5, 0.05), [0.006, 0.004, 0.005, 0.007, 0.0035, -0.001, 0.0, -0.0015]), want, 1e-9)
    hg = HypGap(2.03e7, 2.03e7, 0.7, 3.26e5, 0.0254, 1, (-1, 0))  # T5.4: per metre of wall, gap 2.54 cm
    check("hyperbolic backfill envelope T5.4", [hg.envelope(x - 0.0254) for x in (0.03, 0.0354, 0.05, 0.1018)],
          [77783.6603, 141375.774, 240979.978, 358163.900], 1e-8)
    print("selftest:", "FAILED " + ", ".join(bad) if bad else "ok")
    return 1 if bad else 0


def numbers(text):
    return [float(x) for x in text.split(",")]


def system_assemble(bodies):
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
        Kb = stick_stiffness(k)
        sl = slice(base, base + nb)
        M[sl, sl] = np.diag(m)
        K[sl, sl] = Kb
        if "modal_zeta" in body:  # classical modal damping from scipy's eigenvectors (damping_matrix)
            C[sl, sl] = damping_matrix(m, k, {"modal": {"zeta": body["modal_zeta"]}})[0]
        else:
            C[sl, sl] = body.get("a0", 0.0) * np.diag(m) + body.get("a1", 0.0) * Kb
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


def system_linear(cfg, out):
    dofs, M, K, C = system_assemble(cfg["bodies"])
    t, agf, smax = grid(cfg)
    write_peaks(out, cfg, dofs, lsim_displacements(M, C, K, t, agf), smax)


class Pounding:
    def __init__(self, cfg):
        self.dofs, self.M, self.K, self.C = system_assemble(cfg["bodies"])
        self.n = len(self.dofs)
        self.Mi = 1.0 / np.diag(self.M)
        index = {d: i for i, d in enumerate(self.dofs)}
        self.el = []

        def side(s):
            # a floor [body, floor]: [(dof, 1)]; a column {"column": [body, lo, hi], "xi": x}: the point at x of the
            # way from floor lo (0: the ground, which does not move) to floor hi, linear shape functions
            if isinstance(s, dict):
                b, lo, hi = s["column"]
                x = float(s["xi"])
                out = [(index[(b, hi)], x)]
                if lo > 0:
                    out.insert(0, (index[(b, lo)], 1.0 - x))
                return out
            return [(index[tuple(s)], 1.0)]

        for c in cfg["contacts"]:
            self.el.append(dict(L=side(c["left"]), R=side(c["right"]), gap=c["gap"], kc=c["kc"],
                                n=c["n"], xi=0.75 * (1.0 - c["e"] ** 2), v0_min=c["v0_min"]))
        self.active = [False] * len(self.el)
        self.v0 = [1.0] * len(self.el)

    def x(self, ws, y, off=0):
        return sum(w * y[off + i] for i, w in ws)

    def delta(self, e, y):
        el = self.el[e]
        return (self.x(el["L"], y) - self.x(el["R"], y) - el["gap"],
                self.x(el["L"], y, self.n) - self.x(el["R"], y, self.n))

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
            for i, w in el["L"]:  # the force on each DOF of a side with the weights of its kinematics
                f[i] -= w * F
            for i, w in el["R"]:
                f[i] += w * F
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


def system_nonlinear(cfg, out):
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


def row_contacts(cfg):
    bodies = cfg["bodies"]
    gaps = cfg.get("gaps") or [cfg["gap"]] * (len(bodies) - 1)
    out = []
    for b in range(len(bodies) - 1):
        for f in range(1, min(len(bodies[b]["m"]), len(bodies[b + 1]["m"])) + 1):
            out.append(dict(left=[b, f], right=[b + 1, f], gap=gaps[b], kc=cfg["kc"], n=cfg["n"], e=cfg["e"],
                            v0_min=cfg["v0_min"], joint=b))
    out.sort(key=lambda c: (c["left"][1], c["joint"]))  # the engine's order: level by level, joints left to right
    return out


def row_solve(cfg, contacts):
    """The row with these contacts (none: uncoupled): U on the finest grid, forces, impacts, final state."""
    c = dict(cfg)
    c["contacts"] = contacts
    P = Pounding(c)
    t, agf, smax = grid(c)
    h = t[1] - t[0]
    dt = c["dt"]
    nrec = int(round(c["duration"] / dt))
    ag = np.asarray(c["ag"], float)
    agr = np.concatenate([ag, np.zeros(max(0, nrec + 2 - len(ag)))])
    y = np.zeros(2 * P.n)
    if "v_initial" in c:
        v = [x for body in c["v_initial"] for x in body]
        y[P.n:] = np.asarray(v, float)
    p0 = float(np.diag(P.M) @ y[P.n:])
    U = np.zeros((len(t), P.n))
    Fg = np.zeros((len(t), len(P.el)))
    impacts = [0] * len(P.el)
    for k in range(nrec):
        t0, t1 = k * dt, (k + 1) * dt
        ta = t0
        while ta < t1 - 1e-15:
            sol = integrate.solve_ivp(P.rhs, (ta, t1), y, method="DOP853", rtol=1e-11, atol=1e-14,
                                      events=P.events() if P.el else None, dense_output=True,
                                      args=(agr[k], agr[k + 1], t0, t1))
            tb = sol.t[-1]
            j0, j1 = int(np.ceil(ta / h - 1e-9)), int(np.floor(tb / h + 1e-9))
            for j in range(max(j0, 0), min(j1, len(t) - 1) + 1):
                yj = sol.sol(t[j])
                U[j] = yj[: P.n]
                for e in range(len(P.el)):
                    Fg[j, e] = P.force(e, yj)
            y = sol.y[:, -1].copy()
            if sol.status == 1:
                for e in range(len(P.el)):
                    if len(sol.t_events[e]) == 0:
                        continue
                    P.active[e] = not P.active[e]
                    if P.active[e]:
                        impacts[e] += 1
                        P.v0[e] = max(P.delta(e, y)[1], P.el[e]["v0_min"])
            ta = tb
    return P, t, smax, U, Fg, impacts, y, p0


def row_main(path_in, path_out):
    cfg = json.load(open(path_in))
    P, t, smax, U, Fg, impacts, y, p0 = row_solve(cfg, row_contacts(cfg))
    _, _, _, U0, _, _, _, _ = row_solve(cfg, [])
    with open(path_out, "w") as out:
        write_peaks(out, cfg, P.dofs, U, smax)
        for e in range(len(P.el)):
            out.write(f"impacts {e} {impacts[e]}\n")
            for s in cfg["substeps"]:
                out.write(f"peak_force {s} {e} {np.max(Fg[:: smax // s, e]):.17g}\n")
        for i, (b, f) in enumerate(P.dofs):
            out.write(f"final_v {b} {f} {y[P.n + i]:.17g}\n")
        for s in cfg["substeps"]:
            for i, (b, f) in enumerate(P.dofs):
                out.write(f"peak_u_uncoupled {s} {b} {f} {np.max(np.abs(U0[:: smax // s, i])):.17g}\n")
            for b in range(len(cfg["bodies"])):
                cols = [i for i, (bb, _) in enumerate(P.dofs) if bb == b]
                cu = np.max(np.abs(U[:: smax // s][:, cols]))
                uu = np.max(np.abs(U0[:: smax // s][:, cols]))
                out.write(f"amplification {s} {b} {cu / uu:.17g}\n")
        out.write(f"momentum_initial {p0:.17g}\n")
        out.write(f"momentum_final {float(np.diag(P.M) @ y[P.n:]):.17g}\n")


def row_selftest():
    """T4.1 (SB §4): three equal free masses, zero gaps, mass 1 at v0 toward 2 touching 3."""
    ok = True
    for law, n, want in (("hertz", 1.5, (-0.0709523537, 0.0764030391, 0.9945493146)),
                         ("linear", 1.0, (-0.1302616951, 0.1502295694, 0.9800321256))):
        for m, kc, v0 in ((1.0, 1e6, 1.0), (7.5, 3e7, 0.4)):  # the ratios do not depend on m, kc, v0
            bodies = [dict(m=[m], k=[0.0], a0=0.0, a1=0.0) for _ in range(3)]
            cfg = dict(bodies=bodies, gap=0.0, kc=kc, n=n, e=1.0, v0_min=1e-12, dt=0.01, duration=0.2,
                       substeps=[1], ag=[0.0] * 21, v_initial=[[v0], [0.0], [0.0]])
            P, t, smax, U, Fg, impacts, y, p0 = row_solve(cfg, row_contacts(cfg))
            v = y[P.n:] / v0
            e_kin = 0.5 * m * float(v @ v)
            err = max(abs(a - b) for a, b in zip(v, want))
            good = err < 1e-6 and abs(sum(v) - 1.0) < 1e-9 and abs(2 * e_kin / m - 1.0) < 1e-9
            print(f"row T4.1 {law} m={m} kc={kc} v0={v0}: v/v0 = {v[0]:.10f} {v[1]:.10f} {v[2]:.10f} "
                  f"(max error {err:.2e}), momentum {sum(v):.12f}, energy {2 * e_kin / m:.12f}: "
                  f"{'ok' if good else 'FAIL'}")
            ok = ok and good
    return 0 if ok else 1


def isolation_assemble(d):
    m = np.array(d["m"], float)
    k = np.array(d["k"], float)
    n = len(m)
    Ks = stick_stiffness(k)  # storey i joins floor i-1 (the base for i = 0) and floor i
    Ms = np.diag(m)
    if "modal_zeta" in d:  # classical modal damping of the fixed-base superstructure (damping_matrix, scipy eigh)
        Cs = damping_matrix(m, k, {"modal": {"zeta": d["modal_zeta"]}})[0]
    else:
        Cs = d["a0"] * Ms + d["a1"] * Ks
    T = np.hstack([-np.ones((n, 1)), np.eye(n)])
    e0 = np.zeros((n + 1, n + 1))
    e0[0, 0] = 1.0
    K = T.T @ Ks @ T + d["k_b"] * e0
    C = T.T @ Cs @ T + d["c_b"] * e0
    M = np.diag(np.concatenate([[d["m_base"]], m]))
    return M, K, C


def isolation_main(path_in, path_out):
    d = json.load(open(path_in))
    M, K, C = isolation_assemble(d)
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
        y = lsim_displacements(M, C, K, t, agf)
        for i in range(n):
            out.append(f"peak_u {i} {np.max(np.abs(y[:, i])):.17g}")
            out.append(f"final_u {i} {y[-1, i]:.17g}")
    open(path_out, "w").write("\n".join(out) + "\n")



class Smooth:
    """The smooth-isolated building of the "smooth" subcommand."""

    def __init__(self, d):
        self.M, self.K, self.C = isolation_assemble(dict(d, k_b=0.0, c_b=0.0))
        self.n = self.M.shape[0]
        self.Mi = 1.0 / np.diag(self.M)
        b = d["bearing"]
        self.k, self.qs, self.qf, self.rate = b["k"], b["q_slow"], b["q_fast"], b["rate"]
        self.uy, self.A, self.beta, self.gamma, self.eta = b["uy"], b["A"], b["beta"], b["gamma"], b["eta"]

    def strength(self, v):
        return self.qf - (self.qf - self.qs) * math.exp(-self.rate * abs(v))

    def rhs(self, t, y, a0, a1, t0, t1):
        n = self.n
        u, v, z = y[:n], y[n:2 * n], y[2 * n]
        ag = a0 + (a1 - a0) * (t - t0) / (t1 - t0)
        vb = v[0]
        q = self.strength(vb)
        f = -self.C @ v - self.K @ u
        f[0] -= self.k * u[0] + q * z
        az = abs(z)
        sgn = 1.0 if z * vb >= 0 else -1.0
        zdot = (self.A - az ** self.eta * (self.gamma + self.beta * sgn)) * vb / self.uy
        return np.concatenate([v, f * self.Mi - ag, [zdot, q * z * vb]])


def smooth_main(path_in, path_out):
    d = json.load(open(path_in))
    P = Smooth(d)
    n = P.n
    dt, smax = d["dt"], max(d["substeps"])
    h = dt / smax
    nrec = int(round(d["duration"] / dt))
    ag = np.asarray(d["ag"], float)
    agr = np.concatenate([ag, np.zeros(max(0, nrec + 2 - len(ag)))])
    t = np.arange(nrec * smax + 1) * h
    U = np.zeros((len(t), n))
    Fb = np.zeros(len(t))
    y = np.zeros(2 * n + 2)
    for k in range(nrec):
        t0, t1 = k * dt, (k + 1) * dt
        sol = integrate.solve_ivp(P.rhs, (t0, t1), y, method="DOP853", rtol=1e-10, atol=1e-13, dense_output=True,
                                  args=(agr[k], agr[k + 1], t0, t1))
        for j in range(k * smax, (k + 1) * smax + 1):
            yj = sol.sol(t[j])
            U[j] = yj[:n]
            Fb[j] = P.k * yj[0] + P.strength(yj[n]) * yj[2 * n]
        y = sol.y[:, -1].copy()
    z, E = y[2 * n], y[2 * n + 1]
    q_end = P.strength(y[n])
    with open(path_out, "w") as out:
        for s in d["substeps"]:
            sub = U[:: smax // s]
            for i in range(n):
                out.write(f"peak_u {s} {i} {np.max(np.abs(sub[:, i])):.17g}\n")
                out.write(f"final_u {s} {i} {sub[-1, i]:.17g}\n")
            out.write(f"peak_bearing_force {s} {np.max(np.abs(Fb[:: smax // s])):.17g}\n")
        out.write(f"e_hysteretic {E - q_end * z * z * P.uy / (2 * P.A):.17g}\n")
        out.write(f"final_z {z:.17g}\n")

def _sgn(x):
    return 1.0 if x >= 0 else -1.0


class QHyst:
    """Q-Hyst (Saiidi & Sozen 1979) written from its rules in ../shared/research/systems-and-bridges.md §5 (not the
    engine's code): a bilinear primary curve (k0, F_y, alpha k0 after d_y = F_y / k0); unloading from a loading branch
    at k_u = k0 (d_y / d_m)^beta (d_m = the largest |u| reached in either direction; k0 before yield); once the force
    crosses zero, reloading on a straight line towards the peak previously reached on the primary curve in the new
    direction ((±d_y, ±F_y) on a side not yet yielded), then the primary curve; a reversal on the unloading line before
    the force reaches zero retraces that line back to its reversal point and resumes the branch it left. Every branch is
    linear in u, so each switch is an event of (u, v): `events()` lists (g(u, v), direction, action) for the current
    branch and `switch(action, u)` takes it. Used by the ODE (frames) and by `qhyst_path` (a displacement path)."""

    def __init__(self, k0, fy, alpha=0.0, beta=0.5):
        self.k0, self.fy, self.alpha, self.beta = k0, fy, alpha, beta
        self.dy = fy / k0
        self.mode, self.dm, self.s = "virgin", 0.0, 1.0
        self.peak = {1.0: (self.dy, fy), -1.0: (-self.dy, -fy)}
        self.line, self.left = None, None
        self.counts = {}  # switches taken, by kind (reverse_primary, back_reload, ...): what a run exercised

    def backbone(self, u):
        a = abs(u)
        return _sgn(u) * (self.k0 * a if a <= self.dy else self.fy + self.alpha * self.k0 * (a - self.dy))

    def ku(self):
        return self.k0 * (self.dy / max(self.dm, self.dy)) ** self.beta

    def force(self, u):
        if self.mode in ("virgin", "primary"):
            return self.backbone(u)
        if self.mode == "unload":
            ur, fr, k = self.line
            return fr + k * (u - ur)
        u0, ut, ft = self.line  # reload
        return ft * (u - u0) / (ut - u0)

    def events(self):
        dy = self.dy
        if self.mode == "virgin":
            return [(lambda u, v: u - dy, 1, ("yield", 1.0)), (lambda u, v: -u - dy, 1, ("yield", -1.0))]
        if self.mode == "primary":
            s = self.s
            return [(lambda u, v: s * v, -1, ("reverse",))]
        if self.mode == "unload":
            ur, fr, k = self.line
            s, u0 = -_sgn(fr), ur - fr / k  # s: the direction the force falls in
            return [(lambda u, v: s * (u - u0), 1, ("zero", s)), (lambda u, v: -s * (u - ur), 1, ("back",))]
        u0, ut, ft = self.line
        s = _sgn(ft)
        return [(lambda u, v: s * (u - ut), 1, ("reach", s)), (lambda u, v: s * v, -1, ("reverse",))]

    def switch(self, action, u):
        kind = action[0]
        key = kind + {"reverse": "_" + self.mode, "back": "_" + (self.left or ("",))[0]}.get(kind, "")
        self.counts[key] = self.counts.get(key, 0) + 1
        if kind == "yield":
            self.mode, self.s = "primary", action[1]
        elif kind == "reverse":
            f = self.force(u)
            if self.mode == "primary":
                self.peak[self.s] = (u, f)
                self.dm = max(self.dm, abs(u))
                self.left = ("primary", self.s)
            else:
                self.left = ("reload", self.line)
            self.mode, self.line = "unload", (u, f, self.ku())
        elif kind == "zero":
            ur, fr, k = self.line
            ut, ft = self.peak[action[1]]
            self.mode, self.line = "reload", (ur - fr / k, ut, ft)
        elif kind == "back":
            if self.left[0] == "primary":
                self.mode, self.s = "primary", self.left[1]
            else:
                self.mode, self.line = "reload", self.left[1]
        elif kind == "reach":
            self.mode, self.s = "primary", action[1]
        self.dm = max(self.dm, abs(u))


def qhyst_path(q, path, steps=4000):
    """The force of Q-Hyst q at the end of each leg of a displacement path from 0 (quasi-static): each leg moves
    monotonically at unit speed; a leg against the previous direction is a velocity reversal; every event of the
    current branch is located by linear interpolation (the branches are linear in u) and taken there."""
    u, v, out = 0.0, 0.0, []
    for target in path:
        d = _sgn(target - u)
        if v != 0.0 and d != v:  # the velocity passes through zero: the reversal events fire
            for g, direction, action in q.events():
                if direction == -1 and g(u, v) > 0 and g(u, d) <= 0:
                    q.switch(action, u)
                    break
        v = d
        h = (target - u) / steps
        while abs(target - u) > 1e-15:
            nxt = u + h if abs(target - u) > abs(h) else target
            hit = None
            for g, direction, action in q.events():
                a, b = g(u, v), g(nxt, v)
                if (direction > 0 and a < 0 <= b) or (direction < 0 and a > 0 >= b):
                    x = u + (nxt - u) * a / (a - b)
                    if hit is None or d * (x - hit[0]) < 0:
                        hit = (x, action)
            if hit is None:
                u = nxt
            else:
                u = hit[0]
                q.switch(hit[1], u)
        out.append(q.force(u))
    return out

class HypGap:
    """A hyperbolic abutment backfill (OpenSees HyperbolicGapMaterial as ../shared/research/systems-and-bridges.md §5
    states it; not the engine's code): compression only past the gap, delta = x - gap; envelope
    F = delta / (1/K_max + R_f delta / F_ult); unloading and reloading on a line of slope K_ur from the largest delta
    reached (F_max = envelope there), F = max(0, F_max - K_ur (delta_max - delta)): the gap opens by the permanent set,
    and the envelope is rejoined at delta_max. x = side * d as for GapLink. Switches are events: onto the envelope at
    delta = delta_max, off it when the closing rate turns negative."""

    def __init__(self, kmax, kur, rf, fult, gap, side, dofs):
        self.kmax, self.kur, self.rf, self.fult, self.gap, self.side, self.dofs = kmax, kur, rf, fult, gap, side, dofs
        self.on, self.dmax, self.fmax = False, 0.0, 0.0
        self.s = gap  # the slack written out: where the unloading line meets F = 0

    def deformation(self, u):
        i, j = self.dofs
        return u[j] - (u[i] if i >= 0 else 0.0)

    def envelope(self, delta):
        return delta / (1.0 / self.kmax + self.rf * delta / self.fult) if delta > 0 else 0.0

    def force(self, u):
        delta = self.side * self.deformation(u) - self.gap
        if self.on:
            return self.envelope(delta)
        return max(0.0, self.fmax - self.kur * (self.dmax - delta))

    def event(self, t, y, n):
        u, v = y[:n], y[n:]
        if self.on:
            i, j = self.dofs
            return self.side * (v[j] - (v[i] if i >= 0 else 0.0))
        return self.side * self.deformation(u) - self.gap - self.dmax

    def direction(self):
        return -1 if self.on else 1

    def switch(self, y, n):
        delta = self.side * self.deformation(y[:n]) - self.gap
        if self.on:
            self.dmax, self.fmax, self.on = delta, self.envelope(delta), False
            self.s = self.gap + self.dmax - self.fmax / self.kur
        else:
            self.on = True


class GapLink:
    """A gap link written from its definition (../shared/research/systems-and-bridges.md §5; not the engine's code):
    x = side * d (d = u_j - u_i; side +1 engages as d grows past the gap, -1 as it falls below minus the gap);
    elastic branch F = max(0, k (x - s)) with the current slack s (initially the gap); yield on the straight envelope
    H(x) = F_y + alpha k (x - gap - F_y / k), i.e. F_y at first yield, then hardening alpha k; unloading from the
    envelope at k, leaving the slack s = x - F / k (the plastic elongation stays: a cable, OpenSees ElasticPPGap
    `damage`). Elastic when F_y is infinite. The two branches are smooth; switching between them is an event."""

    def __init__(self, k, fy, alpha, gap, side, dofs):
        self.k, self.fy, self.alpha, self.gap, self.side, self.dofs = k, fy, alpha, gap, side, dofs
        self.s, self.plastic = gap, False

    def deformation(self, u):
        i, j = self.dofs  # i = -1: the ground
        return u[j] - (u[i] if i >= 0 else 0.0)

    def envelope(self, x):
        return self.fy + self.alpha * self.k * (x - self.gap - self.fy / self.k)

    def force(self, u):  # F >= 0 (the link's own force; f = side F acts on j, -f on i)
        x = self.side * self.deformation(u)
        if self.plastic:
            return max(self.envelope(x), 0.0)
        return max(self.k * (x - self.s), 0.0)

    def event(self, t, y, n):
        u, v = y[:n], y[n:]
        x = self.side * self.deformation(u)
        if self.plastic:  # unloading: the rate of x turns negative
            i, j = self.dofs
            return self.side * (v[j] - (v[i] if i >= 0 else 0.0))
        if not math.isfinite(self.fy):
            return -1.0
        return self.k * (x - self.s) - self.envelope(x)  # reaches the envelope

    def direction(self):
        return -1 if self.plastic else 1

    def switch(self, y, n):
        x = self.side * self.deformation(y[:n])
        if self.plastic:
            self.s, self.plastic = x - max(self.envelope(x), 0.0) / self.k, False
        else:
            self.plastic = True


class Storey:
    """A yielding storey of a stick frame: bilinear with kinematic hardening, written from its definition (not the
    engine's code): d = u_j - u_i (i = -1: the ground); elastic branch f = k (d - d_p); the force stays within the
    bounds alpha k d +- (1 - alpha) F_y, on which it moves while the storey yields (plastic branch s = +-1:
    f = alpha k d + s (1 - alpha) F_y) until the storey's drift rate turns against s; then elastic again from there
    (d_p = d - f / k). Both branches are linear in u; each switch is an event (as GapLink's)."""

    def __init__(self, k, fy, alpha, dofs):
        self.k, self.fy, self.alpha, self.dofs = k, fy, alpha, dofs
        self.dp, self.s = 0.0, 0  # s = 0: elastic
        self.switches = 0

    def deformation(self, u):
        i, j = self.dofs
        return u[j] - (u[i] if i >= 0 else 0.0)

    def force(self, u):
        d = self.deformation(u)
        if self.s:
            return self.alpha * self.k * d + self.s * (1.0 - self.alpha) * self.fy
        return self.k * (d - self.dp)

    def event(self, t, y, n):
        u, v = y[:n], y[n:]
        if self.s:  # yielding: the drift rate turns against the yield direction
            i, j = self.dofs
            return self.s * (v[j] - (v[i] if i >= 0 else 0.0))
        d = self.deformation(u)
        return abs(self.k * (d - self.dp) - self.alpha * self.k * d) - (1.0 - self.alpha) * self.fy

    def direction(self):
        return -1 if self.s else 1

    def switch(self, y, n):
        u = y[:n]
        d = self.deformation(u)
        self.switches += 1
        if self.s:
            self.dp, self.s = d - self.force(u) / self.k, 0
        else:
            self.s = 1 if self.k * (d - self.dp) - self.alpha * self.k * d > 0 else -1


def bridge_main(path_in, path_out):
    """A chain of frames under one ground acceleration: SDOF frames (m, k, c; elastic, or Q-Hyst with "qhyst": {fy,
    alpha, beta} and k as k0) or elastic short shear sticks (m and k lists, bottom first, the deck last: M = diag(m),
    K of the stick on the ground, C Rayleigh's a0 M + a1 K at modes 1 and 2 with ratio "zeta" (default 0.05), or
    {"modal": {"zeta": [...]}} in "damping"; ../shared/research/systems-and-bridges.md §1), linear contact at the joints
    between neighbouring DECKS (F = kc max(u_deck k - u_deck k+1 - gap, 0)), tension-only restrainers with slack between
    the decks and compression-only abutments past their gap at the end decks, both elastic or yielding (GapLink: F_y,
    alpha; the slack grows by the plastic elongation), or hyperbolic abutments ("hyperbolic": {kmax, kur, rf, fult}:
    HypGap), integrated by solve_ivp (RK45, rtol 1e-10, max_step dt/20; the contact kinks resolved by the step limit,
    each switch of a link or a Q-Hyst frame between its branches located as an event and the integration restarted
    there). Writes peak |u| and final u per frame (its deck), peak |u| per DOF (frame-major, bottom first: peak_dof),
    peak |frame force| (its first storey's), impacts (closings on the dt/100 grid) and peak force per joint, peak
    restrainer and abutment forces, each link's peak deformation and final slack. A stick frame yields with "fy": [per
    storey, N] and "alpha" (bilinear storeys with kinematic hardening: Storey, its branch switches events as the
    links'; damping stays on the initial K); then peak_drift per DOF (|u - u of the DOF below|) and each storey's
    branch switches (storey_switches) are written too."""
    from scipy.integrate import solve_ivp
    d = json.load(open(path_in))
    fr, jo = d["frames"], d["joints"]
    nf = len(fr)
    levels = [len(f["m"]) if isinstance(f["m"], list) else 1 for f in fr]
    first = np.concatenate([[0], np.cumsum(levels)[:-1]]).astype(int)
    deck = [int(first[i] + levels[i] - 1) for i in range(nf)]
    n = int(sum(levels))
    m = np.zeros(n); Kg = np.zeros((n, n)); Cg = np.zeros((n, n))
    for i, f in enumerate(fr):
        a, b = first[i], first[i] + levels[i]
        if levels[i] == 1:
            mi = f["m"][0] if isinstance(f["m"], list) else f["m"]
            ki = f["k"][0] if isinstance(f["k"], list) else f["k"]
            m[a] = mi; Kg[a, a] = ki
            Cg[a, a] = f["c"] if "c" in f else 2 * f.get("zeta", 0.05) * math.sqrt(ki * mi)
        else:
            m[a:b] = f["m"]; Kg[a:b, a:b] = stick_stiffness(f["k"])
            spec = f.get("damping") or {"rayleigh": {"modes": [1, 2], "zeta": f.get("zeta", 0.05)}}
            Cg[a:b, a:b] = damping_matrix(f["m"], f["k"], spec)[0]
    k = np.array([Kg[first[i], first[i]] if levels[i] == 1 else 0.0 for i in range(nf)])
    dt, ag = d["dt"], np.array(d["ag"])
    T = dt * (len(ag) - 1)
    tg = dt * np.arange(len(ag))
    ab = d.get("abutments", {})
    inf = float("inf")
    rlinks = [GapLink(J["restrainer"]["k"], J["restrainer"].get("fy", inf), J["restrainer"].get("alpha", 0.0),
                      J["restrainer"]["slack"], 1, (deck[j], deck[j + 1])) if J.get("restrainer") else None
              for j, J in enumerate(jo)]
    def abutment(a, sgn, dof):
        if "hyperbolic" in a:
            h = a["hyperbolic"]
            return HypGap(h["kmax"], h.get("kur", h["kmax"]), h.get("rf", 0.7), h["fult"], a["gap"], sgn, (-1, dof))
        return GapLink(a["k"], a.get("fy", inf), a.get("alpha", 0.0), a["gap"], sgn, (-1, dof))
    alinks = [abutment(ab[side], sgn, dof) if side in ab else None
              for side, sgn, dof in (("left", -1, deck[0]), ("right", 1, deck[-1]))]
    links = [L for L in rlinks + alinks if L is not None]
    hyst = [QHyst(f["k"], f["qhyst"]["fy"], f["qhyst"].get("alpha", 0.0), f["qhyst"].get("beta", 0.5))
            if "qhyst" in f else None for f in fr]
    hyst_dof = {first[i]: h for i, h in enumerate(hyst) if h}  # Q-Hyst: SDOF frames only
    Kel = Kg.copy()
    for a_ in hyst_dof:
        Kel[a_, a_] = 0.0
    storeys = []  # yielding stick frames: their storeys leave K and act as Storey springs
    for i, f in enumerate(fr):
        if levels[i] > 1 and "fy" in f:
            a, b = first[i], first[i] + levels[i]
            Kel[a:b, a:b] = 0.0
            storeys += [Storey(f["k"][s_], f["fy"][s_], f.get("alpha", 0.0), (a + s_ - 1 if s_ else -1, a + s_))
                        for s_ in range(levels[i])]
    first_storey = {sp.dofs[1]: sp for sp in storeys if sp.dofs[0] < 0}

    def frame_forces(u):  # the first storey's force of each frame
        return np.array([hyst[i].force(u[first[i]]) if hyst[i] else
                         first_storey[first[i]].force(u) if first[i] in first_storey else
                         (Kg[first[i], first[i]] if levels[i] == 1 else fr[i]["k"][0]) * u[first[i]]
                         for i in range(nf)])

    def forces(u):
        q = Kel @ u
        for a_, h in hyst_dof.items():
            q[a_] += h.force(u[a_])
        for sp in storeys:
            fs = sp.force(u)
            q[sp.dofs[1]] += fs
            if sp.dofs[0] >= 0:
                q[sp.dofs[0]] -= fs
        F = np.zeros(nf - 1); R = np.zeros(nf - 1)
        for j, J in enumerate(jo):
            F[j] = J["kc"] * max(u[deck[j]] - u[deck[j + 1]] - J["gap"], 0.0)
            q[deck[j]] += F[j]; q[deck[j + 1]] -= F[j]
        for j, L in enumerate(rlinks):
            if L:
                R[j] = L.force(u); q[deck[j + 1]] += R[j]; q[deck[j]] -= R[j]
        A = [0.0, 0.0]
        for s_, L in enumerate(alinks):
            if L:
                A[s_] = L.force(u); q[L.dofs[1]] += L.side * A[s_]
        return q, F, R, A

    def rhs(t, y):
        u, v = y[:n], y[n:]
        q, _, _, _ = forces(u)
        return np.concatenate([v, -np.interp(t, tg, ag) - (q + Cg @ v) / m])

    te = np.linspace(0.0, T, 100 * (len(ag) - 1) + 1)
    rows, t0, y0 = [], 0.0, np.zeros(2 * n)
    Fs, Rs, As, Ds, Qs = [], [], [], [], []
    while True:
        events, owners = [], []
        for L in links + storeys:
            ev = (lambda L_: (lambda t, y: L_.event(t, y, n)))(L)
            ev.terminal, ev.direction = True, L.direction()
            events.append(ev); owners.append((L, None))
        for i, h in ((int(a_), h_) for a_, h_ in hyst_dof.items()):
            for g, direction, action in h.events():
                ev = (lambda g_, i_: (lambda t, y: g_(y[i_], y[n + i_])))(g, i)
                ev.terminal, ev.direction = True, direction
                events.append(ev); owners.append((h, (i, action)))
        grid = te[(te > t0) & (te <= T)] if rows else te[(te >= t0) & (te <= T)]
        sol = solve_ivp(rhs, (t0, T), y0, method="RK45", rtol=1e-10, atol=1e-13, max_step=dt / 20, t_eval=grid,
                        events=events or None, dense_output=False)
        for y in (sol.y.T if len(sol.t) else []):  # forces with the branches of this segment (none: no grid point)
            q, F, R, A = forces(y[:n])
            rows.append(y[:n]); Fs.append(F); Rs.append(R); As.append(A)
            Ds.append([L.side * L.deformation(y[:n]) for L in links])
            Qs.append(frame_forces(y[:n]))
        hit = [i for i, te_ in enumerate(sol.t_events or []) if len(te_)]
        if sol.status != 1 or not hit:
            break
        i = hit[0]
        t0, y0 = sol.t_events[i][0], sol.y_events[i][0].copy()
        # solve_ivp stops at the first terminal event: another owner's event at the same instant (a frame's velocity
        # reversal is its abutment's turn off the envelope) has its g at zero to rounding and would never fire after
        # the restart; take every such event with the first (one per owner)
        switched = set()
        for k_, ev in enumerate(events):
            owner, tag = owners[k_]
            g = ev(t0, y0)
            if id(owner) in switched or not (k_ == i or (g >= -1e-9 if ev.direction > 0 else g <= 1e-9)):
                continue
            switched.add(id(owner))
            if tag is None:
                owner.switch(y0, n)
            else:
                owner.switch(tag[1], y0[tag[0]])
    U = np.array(rows); Fs = np.array(Fs); Rs = np.array(Rs); As = np.array(As); Ds = np.array(Ds); Qs = np.array(Qs)
    with open(path_out, "w") as out:
        below = [-1 if g in first else g - 1 for g in range(n)]
        for g in range(n):
            out.write(f"peak_dof {g} {np.max(np.abs(U[:, g])):.17g}\n")
            drift = U[:, g] - (U[:, below[g]] if below[g] >= 0 else 0.0)
            out.write(f"peak_drift {g} {np.max(np.abs(drift)):.17g}\n")
        for sp in storeys:
            out.write(f"storey_switches {sp.dofs[1]} {sp.switches}\n")
        for i in range(nf):
            out.write(f"peak_u {i} {np.max(np.abs(U[:, deck[i]])):.17g}\n")
            out.write(f"final_u {i} {U[-1, deck[i]]:.17g}\n")
            out.write(f"peak_frame_force {i} {np.max(np.abs(Qs[:, i])):.17g}\n")
            for key, count in sorted(hyst[i].counts.items() if hyst[i] else []):
                out.write(f"qhyst_{key} {i} {count}\n")
        for j in range(nf - 1):
            on = Fs[:, j] > 0
            out.write(f"impacts {j} {int(np.sum(on[1:] & ~on[:-1]))}\n")
            out.write(f"peak_force {j} {np.max(Fs[:, j]):.17g}\n")
            out.write(f"peak_restrainer {j} {np.max(Rs[:, j]):.17g}\n")
        out.write(f"peak_abutment 0 {np.max(As[:, 0]):.17g}\npeak_abutment 1 {np.max(As[:, 1]):.17g}\n")
        for i, L in enumerate(links):  # restrainer j / abutment 0 (left), 1 (right): peak x = side d, final slack
            kind, idx = ("restrainer", deck.index(L.dofs[0])) if L.dofs[0] >= 0 else ("abutment", 0 if L.side < 0 else 1)
            out.write(f"peak_{kind}_x {idx} {np.max(Ds[:, i]):.17g}\n")
            out.write(f"final_{kind}_slack {idx} {L.s:.17g}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    pm = sub.add_parser("modes")
    pm.add_argument("--masses")
    pm.add_argument("--stiffnesses")
    pm.add_argument("--zeta", type=float, default=0.05)
    pm.add_argument("--rayleigh-modes", default="1,2")
    pm.add_argument("--input", help="a JSON file with masses, stiffnesses (and zeta, rayleigh_modes)")
    pr = sub.add_parser("response")
    pr.add_argument("--input", required=True)
    pr.add_argument("--method", choices=["lsim", "modal", "both"], default="both")
    pr.add_argument("--substeps", type=int, default=1)
    pr.add_argument("--series")
    sub.add_parser("selftest")
    for name, what in (("system", "systems of shear buildings, linear or pounding"),
                       ("isolation", "a linear base-isolated building"),
                       ("smooth", "a building on a friction-pendulum or Bouc-Wen isolator"),
                       ("row", "a row of n buildings pounding their neighbours (or: row selftest)"),
                       ("bridge", "a chain of elastic frames with linear joints, restrainers and abutments (elastic or yielding)")):
        p = sub.add_parser(name, help=what)
        p.add_argument("input")
        p.add_argument("output", nargs="?" if name == "row" else None)
    a = ap.parse_args()
    if a.cmd == "row":
        if a.input == "selftest":
            return row_selftest()
        row_main(a.input, a.output)
        return 0
    if a.cmd == "system":
        cfg = json.load(open(a.input))
        with open(a.output, "w") as out:
            (system_linear if cfg["mode"] == "linear" else system_nonlinear)(cfg, out)
        return 0
    if a.cmd == "isolation":
        isolation_main(a.input, a.output)
        return 0
    if a.cmd == "bridge":
        bridge_main(a.input, a.output)
        return 0
    if a.cmd == "smooth":
        smooth_main(a.input, a.output)
        return 0
    if a.cmd == "selftest":
        return selftest()
    if a.cmd == "modes":
        if a.input:
            b = json.load(sys.stdin if a.input == "-" else open(a.input))
            one = lambda c: modes_json(np.array(c["masses"], float), np.array(c["stiffnesses"], float),
                                       c.get("zeta", a.zeta), tuple(c.get("rayleigh_modes", [1, 2])))
            json.dump([one(c) for c in b] if isinstance(b, list) else one(b), sys.stdout, indent=1, default=float)
            print()
            return 0
        else:
            m, k = numbers(a.masses), numbers(a.stiffnesses)
            zeta, pair = a.zeta, tuple(int(x) for x in a.rayleigh_modes.split(","))
        json.dump(modes_json(np.array(m), np.array(k), zeta, pair), sys.stdout, indent=1, default=float)
    else:
        b = json.load(sys.stdin if a.input == "-" else open(a.input))
        json.dump(response(b, a.method, a.substeps, a.series), sys.stdout, indent=1, default=float)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
