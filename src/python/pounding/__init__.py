"""pounding: Monte Carlo seismic pounding of adjacent structures, from Python (issue 28).

Everything is the C++ engine (pounding._core, pybind11), reached with numpy arrays in and out:

    import pounding
    rec = pounding.read_record("RSN6_IMPVALL.I_I-ELC180.AT2")          # dt, acc (m/s^2), acc_g, meta
    sp = pounding.spectrum(rec, [0.5, 1.0, 2.0])                         # sd, psv, psa, sa_g
    r = pounding.analyze(pairs, rec, contact="hertzdamp", kh=..., e=0.65)   # dict of numpy arrays
    fit = pounding.fragility.fit(im, n, z)                               # Baker's MSA MLE
    lam = pounding.hazard.rate(fit.theta, fit.beta, (k0, k))

Units: SI inside (m, s, kg, N; ground acceleration in m/s^2 in the kernel), accelerations in g at the edges
(Record.acc_g, spectra's sa_g, design spectra). Bad input raises ValueError with the CLI's message; Ctrl-C
stops a long analyze() between batches (KeyboardInterrupt). docs/python.md walks through a study.
"""
import enum

import numpy as np

from . import _core
from ._core import Record, __version__, analysis, read_record, run_batch, testing  # noqa: F401

__all__ = ["Record", "Status", "analyze", "design_spectrum", "fragility", "hazard", "read_record", "run_batch",
           "collide", "simulate", "analyze_storeys", "spectrum", "PAIR_FIELDS", "Results", "Study"]

# The kernel's lane status (kernel/batch.hpp LaneStatus): 0 ok, 1 diverged, 2 non-finite, 3 coarse (ran to the end
# but the contact was under-resolved: h omega_c above the stepper's limit; peaks are returned, refine substeps).
Status = enum.IntEnum("Status", {name.replace("-", "_"): value for name, value in _core.status_names()})

# The fields of a pair (SI): masses kg, stiffnesses N/m, dashpots N s/m, yield forces N (inf: linear), post-yield
# ratios, at-rest gap m; kc contact stiffness (kh is accepted for it), e restitution, initial conditions.
PAIR_FIELDS = ("m1", "k1", "c1", "fy1", "alpha1", "m2", "k2", "c2", "fy2", "alpha2", "gap", "kc", "e",
               "u1_0", "v1_0", "u2_0", "v2_0")

# Filled where a run does not compute a value (the results files' fill values, results/schema.hpp).
_CONTACT_FIELDS = ("t_first_impact", "peak_force", "peak_penetration", "contact_energy", "contact_time",
                   "h_omega_contact")


def _given(value):
    """What a caller gave, short enough for an error message (an array's shape, never its values)."""
    if hasattr(value, "shape") and hasattr(value, "dtype"):
        return f"a {type(value).__name__} of shape {tuple(value.shape)} ({value.dtype})"
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001  (a repr that fails: say so, do not mask the caller's error)
        text = "(no repr)"
    return f"{type(value).__name__} {text if len(text) <= 40 else text[:37] + '...'}"


def _pairs_dict(pairs, kh, e, per_storey=()):
    """dict of arrays or numpy structured array -> dict of contiguous float64 arrays with the kernel's names; keys
    starting with a name in per_storey may also be 2-D, [pair, floor] (analyze_storeys' per-storey values)."""
    if isinstance(pairs, np.ndarray) and pairs.dtype.names:
        names = pairs.dtype.names
        d = {name: pairs[name] for name in names}
    elif hasattr(pairs, "to_dict") and hasattr(pairs, "columns"):  # a pandas DataFrame
        d = {name: pairs[name].to_numpy() for name in pairs.columns}
    else:
        d = dict(pairs)
    if "kh" in d:
        if "kc" in d:
            raise ValueError("pairs: give the contact stiffness as 'kh' or 'kc', not both")
        d["kc"] = d.pop("kh")
    width = None
    out = {}
    for value in d.values():  # the size first: copying 10^9 pairs' columns was an out-of-memory kill
        try:
            n = len(value)
        except TypeError:
            continue  # not a sequence: the loop below names it
        _core.check_batch_memory(n)
        break
    for key, value in d.items():
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"pairs['{key}']: numbers are needed, got {_given(value)}") from None
        if a.ndim == 2 and any(key.startswith(p) for p in per_storey):
            pass  # [pair, floor]: its shape is checked against the building's storeys by the engine
        elif a.ndim != 1:  # checked before ascontiguousarray, which makes a scalar 1-D
            raise ValueError(f"pairs['{key}']: a 1-D array (one value per pair) is needed, got {_given(value)}")
        out[key] = np.ascontiguousarray(a)
        width = len(a) if width is None else width
    for key, value in (("kc", kh), ("e", e)):
        if value is None:
            continue
        if key in out:
            raise ValueError(f"{'kh' if key == 'kc' else key}: given both in pairs and as an option")
        out[key] = np.broadcast_to(np.asarray(value, dtype=np.float64), (width or 0,)).copy()
    return out


def _require_law_numbers(contact, d, sphere_default=False):
    """A law that needs a stiffness or a restitution gets it from the caller, never from a silent default;
    sphere_default: a Hertz-family law (N/m^n) without kh takes the equivalent-sphere stiffness of the masses it
    joins, as `pounding simulate` without --kh (analyze_storeys)."""
    stiffness, restitution, unit = _core.contact_needs(contact)
    if stiffness and "kc" not in d and not (sphere_default and unit == "N/m^n"):
        raise ValueError(f"contact '{contact}' needs the contact stiffness, kh, give kh= ({unit}) or a 'kc' array")
    if restitution and "e" not in d:
        raise ValueError(f"contact '{contact}' needs the coefficient of restitution, e, give e= (0 < e <= 1) or an "
                         "'e' array")


def _motion(record):
    """A Record, or (acc_g, dt): -> (ag in m/s^2, dt)."""
    if isinstance(record, Record):
        return record.acc, record.dt
    try:
        acc_g, dt = record
    except (TypeError, ValueError):
        raise ValueError("record: a pounding.Record (read_record) or a tuple (acc_g, dt) is needed") from None
    rec = Record(np.asarray(acc_g, dtype=np.float64), float(dt))
    return rec.acc, rec.dt


def analyze(pairs, record, contact="none", stepper="central-difference", substeps=1, *, kh=None, e=None, n=1.5,
            damping="lankarani-nikravesh", energy=False, duration=0.0, displacement_limit=10.0, batch=256,
            threads=0):
    """Runs every pair through the record and returns a dict of per-pair numpy arrays.

    pairs: dict of equal-length arrays, numpy structured array or pandas DataFrame with the fields m1 k1 c1 fy1
      alpha1 m2 k2 c2 fy2 alpha2 gap (SI; fy = inf or absent: linear), kc or kh where the law needs a stiffness,
      e where it needs a restitution (or give kh=, e= here for every pair), optional u1_0 v1_0 u2_0 v2_0.
    record: a pounding.Record or (acc_g, dt).
    contact: none, linear, kelvin, hertz, hertzdamp, jankowski, stereomechanical; damping (hertzdamp's xibar law)
      and n (Hertz exponent) as the CLI's --damping-law and --n.
    stepper: central-difference, newmark, rk4, nigam-jennings; substeps per record step.
    Returns peak_u1, peak_u2, peak_closing, t_peak_closing (m, s), t_first_impact, impact_count, peak_force (N),
    peak_penetration, contact_energy, contact_time, peak_acc1/2 (m/s^2, absolute), final_*, the energy terms
    e_* (J; e_input, e_viscous, e_hysteretic are tracked only with energy=True, NaN otherwise), h_omega_contact,
    status (uint8, see pounding.Status). Contact fields are NaN
    (impact_count -1) with contact="none". Runs `threads` threads (0: every core) over batches of `batch` pairs
    with the GIL released; results do not depend on either. Every pair is checked before any work (ValueError
    naming the pair's lane).
    """
    ag, dt = _motion(record)
    d = _pairs_dict(pairs, kh, e)
    _require_law_numbers(contact, d)
    out = _core.analyze(d, ag, dt, stepper, contact, damping, n, substeps, energy, duration, displacement_limit,
                        batch, threads)
    if contact == "none":
        for key in _CONTACT_FIELDS:
            out[key][:] = np.nan
        out["impact_count"][:] = -1
        out["clamp_count"][:] = -1
    return out


def _rayleigh_modes(modes, counts, modal_zeta):
    """analyze_storeys' rayleigh_modes as one (i, j), i < j, per building, flat: (i1, j1, i2, j2, ...)."""
    pairs = [modes] * len(counts) if np.ndim(modes) == 1 else list(modes)
    if np.ndim(modes) not in (1, 2) or len(pairs) != len(counts) or any(len(p) != 2 for p in pairs):
        raise ValueError(f"rayleigh_modes: (i, j) for every building or one pair per building ({len(counts)}), "
                         f"not {modes!r}")
    flat = []
    for p in pairs:
        if any(float(x) != int(x) for x in p) or int(p[0]) == int(p[1]):
            raise ValueError(f"rayleigh_modes: {tuple(p)!r} is not two different whole mode numbers, e.g. (1, 3)")
        flat += sorted(int(x) for x in p)
    if modal_zeta and flat != [1, 2] * len(counts):
        raise ValueError("rayleigh_modes is given with modal_zeta (modal damping gives every mode its ratio): "
                         "give one of them")
    return flat


def _storey_count(value):
    """One building's storeys: a whole number (2.5 was taken as 2)."""
    try:
        count = int(value)
        whole = not isinstance(value, bool) and count == value
    except (TypeError, ValueError):
        whole = False
    if not whole:
        raise ValueError(f"storeys: {value!r} is not a whole number of storeys; give one integer per building, "
                         "1 or more, e.g. storeys=(3, 5)")
    return count


def analyze_storeys(buildings, record, storeys=(1, 1), storey_height=3.2, contact="none",
                    stepper="central-difference", substeps=1, *, kh=None, e=None, n=1.5,
                    damping="lankarani-nikravesh", contact_levels="common", level_tolerance=0.05,
                    stiffness_profile="uniform", energy=False, duration=0.0, displacement_limit=10.0, batch=64,
                    threads=0, modal_zeta=None, rayleigh_modes=(1, 2), isolation=None, moat=None, density=2400.0,
                    youngs=24.86e9, poisson=0.15):
    """A row of multi-storey shear buildings side by side (two or more), pounding floor to floor (the engine's
    system stepper, as `pounding simulate --storeys1 N --storeys2 M [--buildings K] [--isolation1 ...]` and the
    studies with model = "shear"); buildings 1 and 2 may stand on isolators inside moat walls. One topology per
    call (storeys, heights, bearings, moats); the numbers vary per pair.

    buildings: dict of per-pair arrays (SI) for b = 1 .. len(storeys): floor_mass{b} (kg, every floor),
      storey_stiffness{b} (N/m, every storey) -- these two and storey_yield{b} also as [pair, storey] arrays of one
      row per pair, one value per floor / storey from the bottom (a building that is not uniform) -- or period{b} (T1 in s -- of the fixed-base superstructure for an
      isolated building; stiffness_profile "uniform" or "shear" scaled to it), the storey strength as storey_yield{b}
      (N) or yield_drift{b} (theta_y) or yield_coefficient{b} (Cy) -- none: elastic --, alpha{b} (0), zeta{b} (0.05,
      Rayleigh on modes 1 and 2; the SDOF's ratio for one storey), initial_u{b}, initial_v{b} (m, m/s: the floors'
      initial displacement and velocity relative to the ground, every floor or [pair, floor]; default at rest --
      pull-back and free-vibration tests; an isolated base starts at rest); gap (m, between every two neighbours), kc (or
      kh=) and e where the law needs them; a Hertz-family law without kc / kh takes, per element, the
      equivalent-sphere stiffness of the two floor masses it joins (density, youngs, poisson), as `pounding
      simulate` without --kh; a linear or Kelvin law needs kc.
    storeys: one count per building, left to right (3 or more: a row, as simulate --buildings); storey_height: one
      height (m) for every building or one per building, each a number or a list of one height per storey (bottom
      first). One storey each is the SDOF pair of analyze(), bit for bit.
    modal_zeta: [z1, z2, ...] gives every multi-storey building classical modal damping instead of Rayleigh, the
      ratio of each mode from mode 1, the last repeating (as `pounding simulate --modal-zeta`); one storey keeps zeta.
      Not with isolation (as simulate).
    rayleigh_modes: (i, j), the two modes that get zeta exactly (Rayleigh; default (1, 2)), for every building, or
      one pair per building (as simulate --rayleigh-modesK i,j and the study key rayleigh_modes); a building with
      fewer than j storeys takes j' = min(j, n), i' = min(i, j' - 1) -- the highest two it has -- and one storey
      keeps the SDOF's zeta (as the studies' rule). Not with modal_zeta.
    isolation: None or one entry per building, None (fixed base) or a dict {"bearing": "linear" | "lead-rubber" |
      "friction-pendulum" | "bouc-wen", ...} with the study keys' names and ranges (study reference, section
      "isolation") and simulate's defaults: base_mass (kg; one floor's mass), linear: k_eff (N/m), zeta_eff (0.1);
      lead-rubber and bouc-wen: k1, k2 (N/m, k2 < k1), qd (N), lead-rubber also zeta_eff (0: the rubber's dashpot
      2 zeta_eff sqrt(k2 M_total)), bouc-wen also a (1), beta (0.5), gamma (0.5), eta (1);
      friction-pendulum: radius (m), mu_slow, mu_fast (mu_slow), rate (s/m, 0), u_y (2.5e-4 m). Buildings 1 and 2
      only, as simulate.
    moat: None or one entry per building, None or a dict {"gap": m (each side), "stiffness": N/m^n (default the
      equivalent-sphere Hertz stiffness of two base masses with density, youngs, poisson, as simulate), "law":
      "hertzdamp" (any force law), "e": restitution (default the pounding e)} -- an isolated building only.
    Every number of isolation/moat is a scalar (every pair) or an array of one value per pair. The inputs are
    checked by the check `pounding simulate` uses: a ValueError carries its wording with these names (e.g.
    "isolation[0]['base_mass'] = -1 is out of range").
    Returns per building peak_u{b}, peak_acc{b}, final_u{b} [pair, floor] (floors 1.., bottom first; an isolated
    base is not a floor), peak_drift{b}, peak_shear{b} [pair, storey]; for buildings 1 and 2 peak_bearing_u{b},
    final_bearing_u{b} (m, base relative to the ground), peak_bearing_force{b} (N), moat_impacts{b},
    moat_peak_force{b} (N) [pair] -- NaN (-1) for a fixed base / no moat; per contact element (element_labels:
    "level 1", ...; "1|2 level 1", "2|3 level 1", ... in a row; "building1 moat left", ...) peak_closing, t_peak_closing,
    t_first_impact, impact_count, peak_force, peak_penetration, contact_energy, contact_time, h_omega_contact [pair,
    element] (NaN / -1 for the pounding elements with contact="none"; a moat's are computed with its own law);
    status and e_* per pair (e_* NaN unless energy=True). Validation first: a ValueError names the pair's lane."""
    ag, dt = _motion(record)
    d = _pairs_dict(buildings, kh, e, per_storey=("floor_mass", "storey_stiffness", "storey_yield", "initial_u",
                                                   "initial_v"))
    _require_law_numbers(contact, d, sphere_default=True)
    counts = [_storey_count(s) for s in storeys]
    heights = ([[float(x) for x in np.atleast_1d(h)] for h in storey_height] if isinstance(storey_height, (list, tuple))
               or np.ndim(storey_height) >= 1 else [[float(storey_height)]] * len(counts))
    topology = _core._Topology(counts, heights, float(level_tolerance), contact_levels, stiffness_profile,
                               [float(z) for z in (modal_zeta or [])], _rayleigh_modes(rayleigh_modes, counts, modal_zeta))
    iso = list(isolation) if isolation is not None else [None] * len(counts)
    moats = list(moat) if moat is not None else [None] * len(counts)
    return _core.analyze_storeys(d, ag, dt, topology, stepper, contact, damping, n, substeps, energy, duration,
                                 displacement_limit, batch, threads, iso, moats,
                                 _core._MoatMaterial(float(density), float(youngs), float(poisson)))


class Simulation:
    """One pair's run: `summary` (the analyze() values of the pair, as scalars) and `series` (time series: t s,
    u1 u2 m, v1 v2 m/s, a1_abs a2_abs m/s^2, fs1 fs2 force N, ag m/s^2, one row per integration step)."""

    def __init__(self, summary, series):
        self.summary = summary
        self.series = series

    def to_frame(self):
        import pandas as pd
        return pd.DataFrame(self.series)

    def __repr__(self):
        s = self.summary
        return (f"<pounding.Simulation: {len(self.series['t'])} steps, peak closing {s['peak_closing']:.4g} m, "
                f"{s['impact_count']} impacts, status {Status(s['status']).name}>")


def simulate(pair, record, contact="none", stepper="central-difference", substeps=1, *, kh=None, e=None, n=1.5,
             damping="lankarani-nikravesh", energy=False, duration=0.0, displacement_limit=10.0):
    """One pair (a dict of scalars with analyze()'s fields) with its full time series: a Simulation."""
    d = _pairs_dict({key: np.atleast_1d(value) for key, value in dict(pair).items()}, kh, e)
    _require_law_numbers(contact, d)
    ag, dt = _motion(record)
    summary, series = _core.simulate(d, ag, dt, stepper, contact, damping, n, substeps, energy, duration,
                                     displacement_limit)
    scalars = {key: value[0].item() for key, value in summary.items()}
    if contact == "none":
        for key in _CONTACT_FIELDS:
            scalars[key] = float("nan")
    return Simulation(scalars, series)


def collide(law="hertzdamp", e=0.65, v0=1.0, m1=1.0e6, m2=1.0e6, kh=2.808e10, n=1.5, damping="lankarani-nikravesh",
            stepper="rk4", steps=20000):
    """`pounding collide`: mass m1 (kg) at v0 (m/s) hits m2 at rest through the contact law (kh in N/m^n, N/m for
    linear/Kelvin); a dict e_effective (the restitution the law delivered), peak_force (N), peak_penetration (m),
    duration (s), energy_lost (J), energy_lost_fraction (of 1/2 m1 v0^2), clamps, h_omega_contact, status,
    restitution_promise (what the law promises about e). Defaults and input checks are the CLI's."""
    return _core.collide(law, e, v0, m1, m2, kh, n, damping, stepper, steps)


def spectrum(record, periods, zeta=0.05):
    """Elastic response spectrum of a record (exact for acceleration linear between samples): a dict of arrays
    period (s), sd (m), psv (m/s), psa (m/s^2), sa_g (g)."""
    return _core.spectrum(record, np.asarray(periods, dtype=np.float64), zeta)


def design_spectrum(code, periods, mcer=False, **params):
    """Sa (g) of a code design spectrum at the periods (s), the engine's formulas (motion/design_spectrum.hpp):

      "asce7-16": sds, sd1 (g), tl=8 (s) -- or ss, s1 (mapped MCER, g), site_class ("A".."F", "D-default"), tl;
                  mcer=True gives the MCER spectrum, 1.5 x design (ASCE 7-16 16.2)
      "ec8":      type=1|2, ground "A".."E", agr (g), importance=1, damping_percent=5
      "2800":     a (0.2..0.35), soil "I".."IV", importance=1 (Iranian Standard 2800, 4th ed.)
      "nzs1170":  site "A".."E", z, r=1 (NZS 1170.5, N = 1)
      "table":    table_periods, table_sa (g), or file= a "period,sa" csv
    The parameters are range-checked (ValueError naming the parameter); design_spectrum_text() describes the
    spectrum in one line.
    """
    sa, _ = _core.design_spectrum(code, np.asarray(periods, dtype=np.float64), params, mcer)
    return sa


def design_spectrum_text(code, mcer=False, **params):
    """One line naming the code and every parameter (the engine's DesignSpectrum::describe())."""
    return _core.design_spectrum(code, np.array([1.0]), params, mcer)[1]


from . import fragility, hazard  # noqa: E402  (they use the names above)
from .study import Results, Study  # noqa: E402
