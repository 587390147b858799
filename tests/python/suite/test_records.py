"""pounding.read_record, spectrum and design_spectrum: the engine's readers and formulas (issue 28, item 2)."""
import math
import os
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, need, write_at2

G = 9.80665


def sine(npts=801, dt=0.01, amp=0.2, f=1.3):
    return amp * np.sin(2 * math.pi * f * dt * np.arange(npts))


def test_formats_and_units(tmp_path):
    acc = sine()
    at2 = write_at2(tmp_path / "a.AT2", acc, 0.01)
    rec = pounding.read_record(str(at2))
    parsed = np.array([float(v) for line in at2.read_text().splitlines()[4:] for v in line.split()])
    assert rec.dt == 0.01 and rec.npts == len(acc)
    assert np.array_equal(rec.acc, parsed * G)  # m/s^2 inside
    assert rec.acc_g == pytest.approx(parsed, rel=1e-15)
    assert rec.meta["format"].startswith("PEER")
    two = tmp_path / "two.txt"
    two.write_text("".join(f"{i * 0.01:.2f} {v * 980.665:.6f}\n" for i, v in enumerate(acc)))
    r2 = pounding.read_record(str(two), units="cm/s2")
    assert r2.acc_g == pytest.approx(acc, abs=1e-8)
    one = tmp_path / "one.txt"
    one.write_text("\n".join(f"{v:.8f}" for v in acc))
    r1 = pounding.read_record(str(one), dt=0.01)
    assert r1.dt == 0.01 and r1.acc_g == pytest.approx(acc, abs=1e-8)
    assert rec.measures()["pga"] == pytest.approx(np.abs(parsed).max() * G)


def test_errors_are_the_clis(tmp_path):
    bad = tmp_path / "bad.AT2"
    write_at2(bad, sine(), 0.01)
    text = bad.read_text().replace(f"NPTS=  801", "NPTS=  900")
    bad.write_text(text)
    with pytest.raises(ValueError) as e:
        pounding.read_record(str(bad))
    out = subprocess.run([cli(), "records", "show", str(bad)], capture_output=True, text=True)
    assert out.returncode == 2
    assert f" ERROR: {e.value}" in out.stderr
    with pytest.raises(ValueError, match="cm/s2"):
        pounding.read_record(str(bad), units="furlongs")
    with pytest.raises(ValueError, match="not found"):
        pounding.read_record(str(tmp_path / "missing.AT2"))


def test_spectrum_against_scipy_lsim():
    signal = need("scipy.signal")
    rec = pounding.Record(sine(npts=1501, dt=0.005, f=2.0), 0.005, name="sine")
    periods = [0.2, 0.5, 1.0, 3.0]
    sp = pounding.spectrum(rec, periods, zeta=0.05)
    for T, sd in zip(periods, sp["sd"]):
        # as the engine samples the peak: steps of at most T/40 (ag linear in between) and one period of free
        # vibration after the record (it ends at ag = 0: sin(2 pi 2 Hz 7.5 s))
        sub = max(1, math.ceil(40 * rec.dt / T - 1e-9))
        h = rec.dt / sub
        t_rec = rec.dt * np.arange(rec.npts)
        t = np.arange(0, round((rec.duration + T) / h) + 1) * h
        ag = np.interp(t, t_rec, rec.acc, right=0.0)
        w = 2 * math.pi / T
        sys = signal.lti([[0, 1], [-w * w, -2 * 0.05 * w]], [[0], [-1]], [[1, 0]], [[0]])
        _, y, _ = signal.lsim(sys, ag, t)
        assert sd == pytest.approx(np.abs(y).max(), rel=1e-6), T
    assert sp["sa_g"] == pytest.approx(sp["psa"] / G, rel=1e-15)
    with pytest.raises(ValueError, match="periods"):
        pounding.spectrum(rec, [0.5, -1.0])


def test_design_spectra_closed_forms():
    sds, sd1, tl = 1.0, 0.6, 8.0
    t0, ts = 0.2 * sd1 / sds, sd1 / sds
    T = np.array([0.0, 0.06, 0.3, 1.0, 10.0])
    want = [0.4 * sds, sds * (0.4 + 0.6 * 0.06 / t0), sds, sd1 / 1.0, sd1 * tl / 100.0]
    assert pounding.design_spectrum("asce7-16", T, sds=sds, sd1=sd1, tl=tl) == pytest.approx(want, rel=1e-12)
    mcer = pounding.design_spectrum("asce7-16", T, mcer=True, sds=sds, sd1=sd1, tl=tl)
    assert mcer == pytest.approx(1.5 * np.array(want), rel=1e-12)
    # EN 1998-1 type 1, ground C: S 1.15, TB 0.2, TC 0.6, TD 2.0 (table 3.2); agR 0.25 g, 5 % (eta = 1)
    ec8 = pounding.design_spectrum("ec8", [0.4, 1.0, 3.0], ground="C", agr=0.25)
    assert ec8 == pytest.approx([2.5 * 0.25 * 1.15, 2.5 * 0.25 * 1.15 * 0.6, 2.5 * 0.25 * 1.15 * 0.6 * 2.0 / 9],
                                rel=1e-12)
    assert "ASCE 7-16" in pounding.design_spectrum_text("asce7-16", sds=sds, sd1=sd1)
    with pytest.raises(ValueError, match="SDS"):
        pounding.design_spectrum("asce7-16", T, sds=-1.0, sd1=0.6)
    with pytest.raises(ValueError, match="unknown code"):
        pounding.design_spectrum("ubc97", T)


def test_ctrl_c_stops_a_long_spectrum():
    """Ctrl-C reaches the oscillators: 200 short periods of a 10^6-sample record (about 20 s of work on the 2-core VM)
    raise KeyboardInterrupt within a second of SIGINT, not after the last period."""
    import signal
    import threading
    import time
    rec = pounding.Record(0.3 * np.sin(np.arange(1_000_000) * 0.05), 0.01, name="long")
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        pounding.spectrum(rec, np.full(200, 0.01))
    took = time.monotonic() - t0
    timer.join()
    assert took < 2.5, f"KeyboardInterrupt {took:.2f} s after the call (SIGINT at 0.5 s)"
