"""pounding.analyze_storeys: multi-storey shear buildings through the system stepper (issue 28: "the same call takes
multi-storey buildings"). Bits against `pounding simulate --storeys1/2 --json`; one storey each is analyze()'s pair."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, write_at2

G = 9.80665
NOT_CLAIMED = os.environ.get("POUNDING_BITS_NOT_CLAIMED", "")
REC = pounding.Record(pounding.testing.builtin_motion(0.005, 40.0) / G, 0.005, name="builtin-sweep")


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_same_bits_as_simulate_storeys(tmp_path):
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    rec = pounding.read_record(str(path))  # the CLI reads the same file: the same samples
    args = [cli(), "simulate", "--record", str(path), "--storeys1", "3", "--storeys2", "5", "--storey-mass1", "4e5", "--storey-stiffness1",
            "3e8", "--storey-mass2", "3e5", "--storey-stiffness2", "2.5e8", "--gap", "0.02", "--contact", "hertzdamp",
            "--kh", "2e9", "--e", "0.65", "--dt", "0.0025", "--json"]
    j = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    b = dict(floor_mass1=[4e5], storey_stiffness1=[3e8], yield_drift1=[0.02 / 6], alpha1=[0.05],
             floor_mass2=[3e5], storey_stiffness2=[2.5e8], yield_drift2=[0.02 / 6], alpha2=[0.05], gap=[0.02])
    r = pounding.analyze_storeys(b, rec, storeys=(3, 5), contact="hertzdamp", kh=2e9, e=0.65, substeps=2,
                                 energy=True, threads=2)
    for key in ("peak_u1", "peak_drift1", "final_u1", "peak_u2", "peak_drift2", "final_u2"):
        assert r[key][0].tolist() == j[key], key
    assert (r["peak_acc1"][0] / G).tolist() == j["peak_abs_acc1_g"]
    assert r["element_labels"] == [lv["label"] for lv in j["levels"]] == ["level 1", "level 2", "level 3"]
    for e, lv in enumerate(j["levels"]):
        assert r["impact_count"][0, e] == lv["impacts"] and r["peak_force"][0, e] == lv["peak_force"]
        assert r["peak_closing"][0, e] == lv["peak_closing"]
    assert r["e_input"][0] == j["energy_input_J"] and r["e_hysteretic"][0] == j["energy_hysteretic_J"]
    assert sum(lv["impacts"] for lv in j["levels"]) > 0


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_modal_damping_same_bits_as_simulate(tmp_path):
    """modal_zeta= (classical modal damping) gives pounding simulate --modal-zeta's numbers bit for bit, and not
    the Rayleigh run's."""
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    rec = pounding.read_record(str(path))
    args = [cli(), "simulate", "--record", str(path), "--storeys1", "3", "--storeys2", "5", "--storey-mass1", "4e5",
            "--storey-stiffness1", "3e8", "--storey-mass2", "3e5", "--storey-stiffness2", "2.5e8", "--gap", "0.02",
            "--contact", "hertzdamp", "--kh", "2e9", "--e", "0.65", "--dt", "0.0025", "--modal-zeta", "0.02,0.05",
            "--json"]
    j = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    assert [b["modal_damping"] for b in j["buildings"]] == [[0.02, 0.05, 0.05], [0.02, 0.05, 0.05, 0.05, 0.05]]
    b = dict(floor_mass1=[4e5], storey_stiffness1=[3e8], yield_drift1=[0.02 / 6], alpha1=[0.05],
             floor_mass2=[3e5], storey_stiffness2=[2.5e8], yield_drift2=[0.02 / 6], alpha2=[0.05], gap=[0.02])
    kw = dict(storeys=(3, 5), contact="hertzdamp", kh=2e9, e=0.65, substeps=2)
    r = pounding.analyze_storeys(b, rec, modal_zeta=[0.02, 0.05], **kw)
    for key in ("peak_u1", "peak_drift1", "final_u1", "peak_u2", "peak_drift2", "final_u2"):
        assert r[key][0].tolist() == j[key], key
    for e, lv in enumerate(j["levels"]):
        assert r["impact_count"][0, e] == lv["impacts"] and r["peak_force"][0, e] == lv["peak_force"]
    rayleigh = pounding.analyze_storeys(b, rec, **kw)
    assert rayleigh["peak_u2"][0].tolist() != r["peak_u2"][0].tolist()
    with pytest.raises(ValueError, match="modal_zeta"):
        pounding.analyze_storeys(b, rec, modal_zeta=[0.7], **kw)


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_rayleigh_modes_same_bits_as_simulate(tmp_path):
    """rayleigh_modes= gives pounding simulate --rayleigh-modesK i,j's numbers bit for bit: one pair per building, a
    4-storey building asked for (6, 3) taking the rule's modes 3 and 4 (j' = min(j, n), i' = min(i, j' - 1)), and one
    pair for every building; a one-storey building keeps its zeta (one pair for both = the SDOF's default with the
    other's); the default is (1, 2) and other modes differ."""
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    rec = pounding.read_record(str(path))

    def simulate(storeys1, *options):
        args = [cli(), "simulate", "--record", str(path), "--storeys1", str(storeys1), "--storeys2", "4",
                "--storey-mass1", "4e5", "--storey-stiffness1", "3e8", "--storey-mass2", "3e5", "--storey-stiffness2",
                "2.5e8", "--gap", "0.02", "--contact", "hertzdamp", "--kh", "2e9", "--e", "0.65", "--dt", "0.0025",
                "--json", *options]
        return json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)

    b = dict(floor_mass1=[4e5], storey_stiffness1=[3e8], yield_drift1=[0.02 / 6], alpha1=[0.05],
             floor_mass2=[3e5], storey_stiffness2=[2.5e8], yield_drift2=[0.02 / 6], alpha2=[0.05], gap=[0.02])
    kw = dict(contact="hertzdamp", kh=2e9, e=0.65, substeps=2)

    def same(r, j):
        for key in ("peak_u1", "peak_drift1", "final_u1", "peak_u2", "peak_drift2", "final_u2"):
            assert r[key][0].tolist() == j[key], key
        assert (r["peak_acc2"][0] / G).tolist() == j["peak_abs_acc2_g"]
        for e, lv in enumerate(j["levels"]):
            assert r["impact_count"][0, e] == lv["impacts"] and r["peak_force"][0, e] == lv["peak_force"]
            assert r["peak_closing"][0, e] == lv["peak_closing"]
        assert sum(lv["impacts"] for lv in j["levels"]) > 0

    j = simulate(3, "--rayleigh-modes1", "1,3", "--rayleigh-modes2", "3,4")
    assert [x["rayleigh_modes"] for x in j["buildings"]] == [[1, 3], [3, 4]]
    r = pounding.analyze_storeys(b, rec, storeys=(3, 4), rayleigh_modes=[(3, 1), (6, 3)], **kw)
    same(r, j)
    same(pounding.analyze_storeys(b, rec, storeys=(3, 4), rayleigh_modes=(1, 3), **kw),
         simulate(3, "--rayleigh-modes1", "1,3", "--rayleigh-modes2", "1,3"))
    one = pounding.analyze_storeys(b, rec, storeys=(1, 4), rayleigh_modes=(1, 3), **kw)  # the SDOF keeps its zeta
    own = pounding.analyze_storeys(b, rec, storeys=(1, 4), rayleigh_modes=[(1, 2), (1, 3)], **kw)
    for key in ("peak_u1", "peak_u2", "peak_force", "impact_count"):
        assert np.array_equal(one[key], own[key]), key
    default = pounding.analyze_storeys(b, rec, storeys=(3, 4), **kw)
    same(default, simulate(3))
    assert default["peak_u2"][0].tolist() != r["peak_u2"][0].tolist()
    for bad, match in (((2, 2), "two different"), ((1,), r"\(i, j\)"), ((1, 2.5), "whole"), ([(1, 2)], r"\(i, j\)")):
        with pytest.raises(ValueError, match=match):
            pounding.analyze_storeys(b, rec, storeys=(3, 4), rayleigh_modes=bad, **kw)
    with pytest.raises(ValueError, match="rayleigh_modes"):
        pounding.analyze_storeys(b, rec, storeys=(3, 4), rayleigh_modes=(0, 2), **kw)
    with pytest.raises(ValueError, match="modal_zeta"):
        pounding.analyze_storeys(b, rec, storeys=(3, 4), rayleigh_modes=(1, 3), modal_zeta=[0.05], **kw)


def test_one_storey_each_is_the_pair():
    pairs = pounding.testing.benchmark_batch(13)
    b = dict(floor_mass1=pairs["m1"], storey_stiffness1=pairs["k1"], storey_yield1=pairs["fy1"],
             alpha1=pairs["alpha1"], zeta1=pairs["c1"] / (2 * np.sqrt(pairs["k1"] * pairs["m1"])),
             floor_mass2=pairs["m2"], storey_stiffness2=pairs["k2"], storey_yield2=pairs["fy2"],
             alpha2=pairs["alpha2"], zeta2=pairs["c2"] / (2 * np.sqrt(pairs["k2"] * pairs["m2"])),
             gap=pairs["gap"], kc=pairs["kc"], e=pairs["e"])
    s = pounding.analyze_storeys(b, REC, contact="hertzdamp", batch=4)
    q = dict(pairs, c1=2 * b["zeta1"] * np.sqrt(pairs["k1"] * pairs["m1"]),
             c2=2 * b["zeta2"] * np.sqrt(pairs["k2"] * pairs["m2"]))
    r = pounding.analyze(q, REC, contact="hertzdamp")
    assert np.array_equal(s["peak_u1"][:, 0], r["peak_u1"]) and np.array_equal(s["peak_u2"][:, 0], r["peak_u2"])
    assert np.array_equal(s["peak_force"][:, 0], r["peak_force"])
    assert np.array_equal(s["impact_count"][:, 0], r["impact_count"])


def test_batches_threads_and_errors():
    n = 9
    rng = np.random.default_rng(1)
    b = dict(floor_mass1=rng.uniform(2e5, 4e5, n), period1=rng.uniform(0.4, 0.8, n), yield_coefficient1=np.full(n, 0.15),
             floor_mass2=rng.uniform(2e5, 4e5, n), period2=rng.uniform(0.5, 1.0, n), yield_coefficient2=np.full(n, 0.12),
             gap=np.full(n, 0.03))
    a = pounding.analyze_storeys(b, REC, storeys=(4, 6), contact="hertzdamp", kh=2e9, e=0.65, substeps=2, batch=1,
                                 threads=2)
    c = pounding.analyze_storeys(b, REC, storeys=(4, 6), contact="hertzdamp", kh=2e9, e=0.65, substeps=2, batch=64,
                                 threads=1)
    for key in ("peak_u1", "peak_u2", "peak_force", "impact_count", "status"):
        assert np.array_equal(a[key], c[key]), key
    assert a["peak_u1"].shape == (n, 4) and a["peak_drift2"].shape == (n, 6) and a["peak_force"].shape == (n, 4)
    none = pounding.analyze_storeys(b, REC, storeys=(4, 6))
    assert np.isnan(none["peak_force"]).all() and (none["impact_count"] == -1).all()
    bad = dict(b, floor_mass2=b["floor_mass2"].copy())
    bad["floor_mass2"][7] = -1.0
    with pytest.raises(ValueError, match=r"floor_mass2 \(lane 7\)"):
        pounding.analyze_storeys(bad, REC, storeys=(4, 6))
    with pytest.raises(ValueError, match="period1"):
        pounding.analyze_storeys({k: v for k, v in b.items() if k != "period1"}, REC, storeys=(4, 6))


def test_ctrl_c_stops_a_single_long_lane():
    """Ctrl-C reaches the steppers: one 10- against 15-storey pair at substeps=10000 (about 16 s of work on the 2-core
    VM) raises KeyboardInterrupt within a second of SIGINT, not at the lane's end."""
    import signal
    import threading
    import time
    b = {"floor_mass1": [1e5], "floor_mass2": [1e5], "period1": [1.0], "period2": [1.5], "gap": [0.05]}
    ag_g = 0.3 * np.sin(np.arange(4000) * 0.02)
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        pounding.analyze_storeys(b, (ag_g, 0.01), storeys=(10, 15), substeps=10000)
    took = time.monotonic() - t0
    timer.join()
    assert took < 3.0, f"KeyboardInterrupt {took:.2f} s after the call (SIGINT at 1 s)"
