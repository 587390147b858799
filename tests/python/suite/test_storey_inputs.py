"""pounding.analyze_storeys with the inputs an engineer has: per-storey masses, stiffnesses, strengths and heights
(buildings that are not uniform), and the contact stiffness `pounding simulate` takes without --kh. Bits against
`pounding simulate --json` with the same lists."""
import json
import os
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, write_at2

G = 9.80665
NOT_CLAIMED = os.environ.get("POUNDING_BITS_NOT_CLAIMED", "")
REC = pounding.Record(pounding.testing.builtin_motion(0.005, 20.0) / G, 0.005, name="builtin-sweep")


def _simulate(path, *extra):
    args = [cli(), "simulate", "--record", str(path), "--storeys1", "3", "--storeys2", "4",
            "--storey-mass1", "2e5,2e5,1.5e5", "--storey-stiffness1", "3e8,2.5e8,2e8", "--storey-height1", "4.5,3.2,3.2",
            "--storey-yield1", "9e5,7e5,5e5", "--storey-mass2", "2.5e5", "--storey-stiffness2", "2.2e8",
            "--gap", "0.01", "--contact", "hertzdamp", "--e", "0.65", "--dt", "0.0025", "--json", *extra]
    run = subprocess.run(args, capture_output=True, text=True)
    assert run.returncode in (0, 3), run.stderr  # 3: a coarse contact (the stiff default kh at this step), same bits
    return json.loads(run.stdout)


def _buildings(n=1):
    return dict(floor_mass1=np.tile([2e5, 2e5, 1.5e5], (n, 1)), storey_stiffness1=np.tile([3e8, 2.5e8, 2e8], (n, 1)),
                storey_yield1=np.tile([9e5, 7e5, 5e5], (n, 1)), alpha1=np.full(n, 0.05),
                floor_mass2=np.full(n, 2.5e5), storey_stiffness2=np.full(n, 2.2e8), yield_drift2=np.full(n, 0.02 / 6),
                alpha2=np.full(n, 0.05), gap=np.full(n, 0.01))


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
@pytest.mark.parametrize("kh", [2e9, None])
def test_per_storey_lists_same_bits_as_simulate(tmp_path, kh):
    """[pair, storey] arrays and per-storey heights give simulate's per-storey lists bit for bit; without kh both take
    the equivalent-sphere stiffness of the floor masses each element joins (simulate's default)."""
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    rec = pounding.read_record(str(path))
    j = _simulate(path, *(["--kh", f"{kh:g}"] if kh else []))
    r = pounding.analyze_storeys(_buildings(), rec, storeys=(3, 4), storey_height=[[4.5, 3.2, 3.2], 3.2],
                                 contact="hertzdamp", kh=kh, e=0.65, substeps=2)
    for key in ("peak_u1", "peak_drift1", "peak_u2", "peak_drift2"):
        assert r[key][0].tolist() == j[key], key
    assert r["element_labels"] == [lv["label"] for lv in j["levels"]]
    assert sum(lv["impacts"] for lv in j["levels"]) > 0
    for e, lv in enumerate(j["levels"]):
        assert r["impact_count"][0, e] == lv["impacts"] and r["peak_force"][0, e] == lv["peak_force"]


def test_uniform_rows_are_the_numbers():
    """A [pair, storey] array of equal values is the one-value-per-pair input bit for bit; another row differs."""
    n = 3
    one = dict(floor_mass1=np.full(n, 2e5), storey_stiffness1=np.full(n, 3e8), floor_mass2=np.full(n, 2.5e5),
               period2=np.full(n, 0.6), gap=np.full(n, 0.02))
    rows = dict(one, floor_mass1=np.full((n, 3), 2e5), storey_stiffness1=np.full((n, 3), 3e8))
    a = pounding.analyze_storeys(one, REC, storeys=(3, 4), contact="hertzdamp", kh=2e9, e=0.65)
    b = pounding.analyze_storeys(rows, REC, storeys=(3, 4), contact="hertzdamp", kh=2e9, e=0.65)
    assert np.array_equal(a["peak_u1"], b["peak_u1"]) and np.array_equal(a["peak_force"], b["peak_force"])
    rows["floor_mass1"] = np.array([[2e5] * 3, [2e5, 2e5, 1e5], [2e5] * 3])
    c = pounding.analyze_storeys(rows, REC, storeys=(3, 4), contact="hertzdamp", kh=2e9, e=0.65)
    assert np.array_equal(c["peak_u1"][[0, 2]], a["peak_u1"][[0, 2]]) and not np.array_equal(c["peak_u1"][1], a["peak_u1"][1])


def test_per_storey_errors():
    b = _buildings()
    b["floor_mass1"] = np.array([[2e5, 2e5]])
    with pytest.raises(ValueError, match=r"floor_mass1.*\(1, 3\)"):
        pounding.analyze_storeys(b, REC, storeys=(3, 4), contact="hertzdamp", kh=2e9, e=0.65)
    b = _buildings()
    b["storey_stiffness1"] = np.array([[3e8, -1.0, 2e8]])
    with pytest.raises(ValueError, match=r"storey_stiffness1 \(lane 0, storey 2\) = -1 is out of range"):
        pounding.analyze_storeys(b, REC, storeys=(3, 4), contact="hertzdamp", kh=2e9, e=0.65)
    with pytest.raises(ValueError, match=r"storey_height\[0\]: 2 heights and building 1 has 3 storeys"):
        pounding.analyze_storeys(_buildings(), REC, storeys=(3, 4), storey_height=[[3.2, 3.2], 3.2],
                                 contact="hertzdamp", kh=2e9, e=0.65)
    with pytest.raises(ValueError, match="linear.*kh"):  # N/m laws have no equivalent-sphere default
        pounding.analyze_storeys(_buildings(), REC, storeys=(3, 4), contact="linear", e=0.65)


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_initial_state_same_bits_as_simulate(tmp_path):
    """initial_u1 / initial_v1 ([pair, floor]) are simulate's --initial-u1 / --initial-v1: a free vibration after a
    record of zeros, every floor's final displacement bit for bit; at rest it stays at rest."""
    zeros = pounding.Record(np.zeros(401), 0.005, name="zeros")
    path = write_at2(tmp_path / "zeros.AT2", zeros.acc_g, zeros.dt)
    rec = pounding.read_record(str(path))
    args = [cli(), "simulate", "--record", str(path), "--storeys1", "2", "--storey-mass1", "2e5,1.5e5",
            "--storey-stiffness1", "2e8,1.5e8", "--initial-u1", "0.02,0.05", "--initial-v1", "0,0.1", "--storeys2", "1",
            "--storey-mass2", "1e5", "--storey-stiffness2", "1e8", "--elastic", "--contact", "none", "--gap", "1",
            "--dt", "0.0025", "--duration", "3", "--json"]
    j = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    b = dict(floor_mass1=[[2e5, 1.5e5]], storey_stiffness1=[[2e8, 1.5e8]], initial_u1=[[0.02, 0.05]],
             initial_v1=[[0.0, 0.1]], floor_mass2=[1e5], storey_stiffness2=[1e8], gap=[1.0])
    r = pounding.analyze_storeys(b, rec, storeys=(2, 1), substeps=2, duration=3.0)
    assert r["final_u1"][0].tolist() == j["final_u1"] and r["peak_u1"][0].tolist() == j["peak_u1"]
    assert r["peak_u1"][0, 1] >= 0.05 and r["final_u2"][0, 0] == 0.0


@pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
def test_lead_rubber_dashpot_same_bits_as_simulate(tmp_path):
    """isolation zeta_eff on a lead-rubber bearing is simulate's --bearing-zeta1 (the rubber's dashpot on k2); without
    it the bearing has none, as before."""
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    rec = pounding.read_record(str(path))
    lrb = ["--isolation1", "lead-rubber", "--base-mass1", "3e5", "--bearing-k1-1", "1.2e8", "--bearing-k2-1", "1.2e7",
           "--bearing-qd1", "6e5"]
    b = dict(floor_mass1=[3e5], storey_stiffness1=[9.80665e7], floor_mass2=[3e5], storey_stiffness2=[9.80665e7],
             gap=[0.5])
    for zeta in (0.05, None):
        args = [cli(), "simulate", "--record", str(path), "--storeys1", "3", "--storey-mass1", "3e5",
                "--storey-stiffness1", "9.80665e7", "--storeys2", "5", "--storey-mass2", "3e5", "--storey-stiffness2",
                "9.80665e7", "--elastic", "--contact", "none", "--gap", "0.5", "--dt", "0.0025", "--json", *lrb,
                *(["--bearing-zeta1", str(zeta)] if zeta else [])]
        j = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
        iso = dict(bearing="lead-rubber", base_mass=3e5, k1=1.2e8, k2=1.2e7, qd=6e5, **({"zeta_eff": zeta} if zeta else {}))
        r = pounding.analyze_storeys(b, rec, storeys=(3, 5), substeps=2, isolation=[iso, None])
        assert r["peak_bearing_u1"][0] == j["peak_bearing_u1"] and r["peak_u1"][0].tolist() == j["peak_u1"]
        assert (j["buildings"][0]["isolation"]["bearing_c"] > 0) == bool(zeta)
