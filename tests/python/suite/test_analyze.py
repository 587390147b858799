"""pounding.analyze and pounding.simulate (issue 28, item 3): the kernel on many pairs, threaded, interruptible.

Bits: the same pair through `pounding simulate --json` (the CLI) and through analyze() must agree exactly (the JSON
numbers are shortest round-trip). Physics: a linear pair without contact against scipy.signal.lsim, which is exact
for acceleration linear between samples, as the Nigam-Jennings stepper is.
"""
import json
import math
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import pounding
from conftest import cli, need, write_at2

G = 9.80665
NOT_CLAIMED = os.environ.get("POUNDING_BITS_NOT_CLAIMED", "")


def record(tmp_path):
    t = 0.005 * np.arange(2401)
    acc = 0.35 * np.sin(2 * math.pi * 1.1 * t) * np.exp(-0.15 * t) + 0.1 * np.sin(2 * math.pi * 3.7 * t)
    return write_at2(tmp_path / "rec.AT2", acc, 0.005)


PAIRS = [  # m1 k1 fy1 m2 k2 fy2 alpha gap zeta contact kh e stepper substeps
    (1e6, 4e7, 1.2e6, 2e6, 3e7, 2e6, 0.05, 0.02, 0.05, "hertzdamp", 1e9, 0.65, "central-difference", 2),
    (5e5, 8e7, math.inf, 1.5e6, 2e7, math.inf, 0.0, 0.01, 0.03, "linear", 5e8, 1.0, "central-difference", 4),
    (8e5, 2e7, 4e5, 8e5, 6e7, 9e5, 0.1, 0.03, 0.05, "hertz", 2e9, 1.0, "newmark", 1),
]


def cli_run(rec, p):
    m1, k1, fy1, m2, k2, fy2, alpha, gap, zeta, law, kh, e, stepper, sub = p
    args = [cli(), "simulate", "--record", str(rec), "--m1", repr(m1), "--k1", repr(k1), "--m2", repr(m2),
            "--k2", repr(k2), "--alpha", repr(alpha), "--gap", repr(gap), "--zeta", repr(zeta), "--contact", law,
            "--kh", repr(kh), "--e", repr(e), "--stepper", stepper, "--dt", repr(0.005 / sub), "--json"]
    args += ["--elastic"] if math.isinf(fy1) else ["--fy1", repr(fy1), "--fy2", repr(fy2)]
    out = subprocess.run(args, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def pair_dict(p):
    m1, k1, fy1, m2, k2, fy2, alpha, gap, zeta = p[:9]
    c = lambda k, m: 2.0 * zeta * math.sqrt(k * m)  # as simulate's make_structure computes it
    return dict(m1=[m1], k1=[k1], c1=[c(k1, m1)], fy1=[fy1], alpha1=[alpha if fy1 < math.inf else 0.0],
                m2=[m2], k2=[k2], c2=[c(k2, m2)], fy2=[fy2], alpha2=[alpha if fy2 < math.inf else 0.0], gap=[gap])


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_same_bits_as_the_cli(tmp_path):
    rec_path = record(tmp_path)
    rec = pounding.read_record(str(rec_path))
    # the three pairs in one call, in batches of 1 on 2 threads: each lane is its own
    pairs = {k: np.concatenate([pair_dict(p)[k] for p in PAIRS]) for k in pair_dict(PAIRS[0])}
    for i, p in enumerate(PAIRS):
        law, kh, e, stepper, sub = p[9:]
        one = {k: v[i:i + 1] for k, v in pairs.items()}
        r = pounding.analyze(one, rec, contact=law, kh=kh, e=e, stepper=stepper, substeps=sub, energy=True,
                             batch=1, threads=2)
        j = cli_run(rec_path, p)
        level = j["levels"][0]
        want = {"peak_u1": j["peak_u1"][0], "peak_u2": j["peak_u2"][0], "final_u1": j["final_u1"][0],
                "final_u2": j["final_u2"][0], "impact_count": j["impact_count"], "peak_force": j["peak_force"],
                "peak_penetration": j["peak_penetration"], "peak_closing": j["peak_closing"],
                "t_peak_closing": level["t_peak_closing"], "contact_energy": level["contact_energy"],
                "contact_time": level["contact_time"], "h_omega_contact": j["h_omega_contact"],
                "e_input": j["energy_input_J"], "e_hysteretic": j["energy_hysteretic_J"],
                "e_viscous": j["energy_viscous_J"], "e_kinetic": j["energy_kinetic_J"]}
        for key, value in want.items():
            assert r[key][0] == value, f"pair {i} {key}: {r[key][0]!r} (Python) != {value!r} (CLI)"
        assert r["t_first_impact"][0] == j["t_first_impact"] or math.isnan(r["t_first_impact"][0])
        assert r["peak_acc1"][0] / G == j["peak_abs_acc1_g"][0]
        assert pounding.Status(r["status"][0]).name == j["status"].replace("-", "_")
        assert j["impact_count"] > 0  # the pairs do pound: the contact part is compared too


def test_batches_and_threads_do_not_change_bits(tmp_path):
    rec = pounding.read_record(str(record(tmp_path)))
    pairs = pounding.testing.benchmark_batch(37)
    ref = pounding.run_batch(pairs, rec.acc, rec.dt, substeps=2)
    for batch, threads in ((1, 2), (5, 1), (16, 2), (64, 0)):
        r = pounding.analyze(pairs, rec, contact="hertzdamp", substeps=2, batch=batch, threads=threads)
        for key in ref:
            assert np.array_equal(r[key], ref[key], equal_nan=True), (key, batch, threads)


def test_linear_pair_matches_scipy_lsim(tmp_path):
    signal = need("scipy.signal")
    rec = pounding.read_record(str(record(tmp_path)))
    rng = np.random.default_rng(7)
    n = 6
    T1, T2 = rng.uniform(0.3, 2.0, n), rng.uniform(0.3, 2.0, n)
    z1, z2 = rng.uniform(0.01, 0.1, n), rng.uniform(0.01, 0.1, n)
    m1, m2 = rng.uniform(1e5, 1e7, n), rng.uniform(1e5, 1e7, n)
    k1, k2 = 4 * math.pi ** 2 * m1 / T1 ** 2, 4 * math.pi ** 2 * m2 / T2 ** 2
    pairs = dict(m1=m1, k1=k1, c1=2 * z1 * np.sqrt(k1 * m1), m2=m2, k2=k2, c2=2 * z2 * np.sqrt(k2 * m2),
                 gap=np.full(n, 0.05))
    r = pounding.analyze(pairs, rec, stepper="nigam-jennings")
    t = rec.dt * np.arange(rec.npts)
    for i in range(n):
        u = []
        for T, z in ((T1[i], z1[i]), (T2[i], z2[i])):
            w = 2 * math.pi / T
            sys = signal.lti([[0, 1], [-w * w, -2 * z * w]], [[0], [-1]], [[1, 0]], [[0]])
            u.append(signal.lsim(sys, rec.acc, t)[1])
        scale = np.abs(u[0]).max()
        assert abs(r["peak_u1"][i] - np.abs(u[0]).max()) <= 1e-9 * scale
        assert abs(r["peak_u2"][i] - np.abs(u[1]).max()) <= 1e-9 * np.abs(u[1]).max()
        assert abs(r["peak_closing"][i] - (u[0] - u[1]).max()) <= 1e-9 * scale
    assert np.all(r["status"] == pounding.Status.ok)


def test_not_computed_is_nan(tmp_path):
    rec = pounding.read_record(str(record(tmp_path)))
    pairs = pounding.testing.benchmark_batch(4)
    r = pounding.analyze(pairs, rec, contact="hertzdamp")
    for key in ("e_input", "e_viscous", "e_hysteretic"):
        assert np.isnan(r[key]).all(), key  # energy=False: not tracked (it was 0 before issue 28)
    for key in ("e_kinetic", "e_strain"):  # of the final state: always computed
        assert np.isfinite(r[key]).all() and (r[key] > 0).any(), key
    r = pounding.analyze(pairs, rec, contact="hertzdamp", energy=True)
    assert np.isfinite(r["e_input"]).all() and (r["e_input"] > 0).all()
    r = pounding.analyze(pairs, rec)  # contact none: no contact quantities
    assert np.isnan(r["peak_force"]).all() and (r["impact_count"] == -1).all()
    assert np.isfinite(r["peak_closing"]).all()


def test_status_enum_and_docstring():
    assert {s.name: int(s) for s in pounding.Status} == {"ok": 0, "diverged": 1, "non_finite": 2, "coarse": 3}
    assert "pounding.Status" in pounding.run_batch.__doc__ and "0 ok / 1 diverged / 2 non-finite," not in \
        pounding.run_batch.__doc__


def test_bad_input_is_a_value_error_naming_the_pair(tmp_path):
    rec = pounding.read_record(str(record(tmp_path)))
    pairs = pounding.testing.benchmark_batch(300)
    pairs["k2"] = pairs["k2"].copy()
    pairs["k2"][257] = -1.0
    with pytest.raises(ValueError, match=r"k2 \(lane 257\)"):  # checked before any work, numbered as given
        pounding.analyze(pairs, rec, contact="hertzdamp", batch=256)
    with pytest.raises(ValueError, match="stereomechanical"):
        pounding.analyze(pairs, rec, contact="glue")
    bare = {k: v for k, v in pounding.testing.benchmark_batch(300).items() if k not in ("kc", "e")}
    with pytest.raises(ValueError, match="needs the contact stiffness, kh"):  # never a silent default
        pounding.analyze(bare, rec, contact="hertzdamp", e=0.65)
    with pytest.raises(ValueError, match="needs the coefficient of restitution"):
        pounding.analyze(bare, rec, contact="hertzdamp", kh=1e9)
    assert pounding.analyze(bare, rec, contact="hertz", kh=1e9)["impact_count"].shape == (300,)  # e not needed
    structured = np.zeros(3, dtype=[(k, float) for k in ("m1", "k1", "c1", "m2", "k2", "c2", "gap")])
    for k in ("m1", "m2"):
        structured[k] = 1e6
    for k in ("k1", "k2"):
        structured[k] = 4e7
    r = pounding.analyze(structured, rec)
    assert r["peak_u1"].shape == (3,)


def test_ctrl_c_stops_a_long_call(tmp_path):
    rec = pounding.read_record(str(record(tmp_path)))
    pairs = pounding.testing.benchmark_batch(20000)
    # 400 s (the record, then free vibration) x 2 substeps: 3.2e9 pair-steps, seconds even on an idle machine; the
    # interrupt comes at 0.2 s and must end the call within a few batches (64 pairs, ~40 ms each)
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        pounding.analyze(pairs, rec, contact="hertzdamp", substeps=2, duration=400.0, batch=64, threads=2)
    assert time.monotonic() - start < 3.0


def test_simulate_series(tmp_path):
    rec = pounding.read_record(str(record(tmp_path)))
    p = {k: v[0] for k, v in pair_dict(PAIRS[0]).items()}
    s = pounding.simulate(p, rec, contact="hertzdamp", kh=1e9, e=0.65, substeps=2)
    r = pounding.analyze({k: [v] for k, v in p.items()}, rec, contact="hertzdamp", kh=1e9, e=0.65, substeps=2)
    assert s.summary["peak_u1"] == r["peak_u1"][0]
    assert np.abs(s.series["u1"]).max() == r["peak_u1"][0]
    assert np.max(s.series["u1"] - s.series["u2"]) == r["peak_closing"][0]
    assert len(s.series["t"]) >= 2 * (rec.npts - 1)


def test_collide_same_as_the_cli():
    for args in ({}, {"law": "hertzdamp", "damping": "calibrated", "e": 0.5, "v0": 0.8, "m2": 3e6},
                 {"law": "kelvin", "kh": 5e8, "stepper": "central-difference"}):
        r = pounding.collide(**args)
        opt = {"damping": "--damping-law"}
        cmd = [cli(), "collide", "--json"] + [x for k, v in args.items() for x in (opt.get(k, "--" + k), str(v))]
        out = subprocess.run(cmd, capture_output=True, text=True)
        j = json.loads(out.stdout)
        assert r["e_effective"] == j["e_effective"] and r["peak_force"] == j["peak_force_N"]
        assert r["peak_penetration"] == j["peak_penetration_m"] and r["duration"] == j["contact_duration_s"]
        assert r["energy_lost"] == j["energy_lost_J"] and r["h_omega_contact"] == j["h_omega_contact"]
    assert pounding.collide(damping="calibrated")["e_effective"] == pytest.approx(0.65, abs=1e-3)
    with pytest.raises(ValueError, match="--v0"):
        pounding.collide(v0=-1.0)
