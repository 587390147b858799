"""pounding.analyze_storeys with isolated bases, moat walls and rows (issue 28's last item): bit for bit against
`pounding simulate --isolation1 ... --json` and `simulate --buildings 3 --json`; bad isolation input raises
ValueError with the CLI's wording for the same mistake (one check, sampling::validate_isolation)."""
import json
import os
import re
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, write_at2

G = 9.80665
NOT_CLAIMED = os.environ.get("POUNDING_BITS_NOT_CLAIMED", "")
bits = pytest.mark.skipif(bool(NOT_CLAIMED), reason=f"not applicable: {NOT_CLAIMED}")
REC = pounding.Record(pounding.testing.builtin_motion(0.005, 20.0) / G, 0.005, name="builtin-sweep")
PAIR = ["--storeys1", "3", "--storeys2", "5", "--storey-mass1", "3e5", "--storey-stiffness1", "9.81e7",
        "--storey-mass2", "3e5", "--storey-stiffness2", "2.5e8", "--contact", "hertzdamp", "--kh", "2e9", "--e", "0.65",
        "--dt", "0.0025"]
BUILDINGS = dict(floor_mass1=[3e5], storey_stiffness1=[9.81e7], yield_drift1=[0.02 / 6], alpha1=[0.05],
                 floor_mass2=[3e5], storey_stiffness2=[2.5e8], yield_drift2=[0.02 / 6], alpha2=[0.05])
KW = dict(contact="hertzdamp", kh=2e9, e=0.65, substeps=2)


def simulate(tmp_path, *args):
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    out = subprocess.run([cli(), "simulate", "--record", str(path), *args, "--json"], capture_output=True, text=True,
                         check=True).stdout
    return json.loads(out), pounding.read_record(str(path))


def same_bits(r, j, buildings):
    for b in range(1, buildings + 1):
        for key in (f"peak_u{b}", f"peak_drift{b}", f"final_u{b}"):
            assert r[key][0].tolist() == j[key], key
        assert (r[f"peak_acc{b}"][0] / G).tolist() == j[f"peak_abs_acc{b}_g"]
    assert r["element_labels"] == [lv["label"] for lv in j["levels"]]
    for e, lv in enumerate(j["levels"]):
        assert r["impact_count"][0, e] == lv["impacts"], lv["label"]
        assert r["peak_force"][0, e] == lv["peak_force"] and r["peak_closing"][0, e] == lv["peak_closing"]


def same_base(r, j, b=1, moat=True):
    for key in ("peak_bearing_u", "final_bearing_u", "peak_bearing_force") + (("moat_impacts", "moat_peak_force")
                                                                              if moat else ()):
        assert r[f"{key}{b}"][0] == j[f"{key}{b}"], key
    if not moat:  # no moat: not computed (simulate prints 0)
        assert r[f"moat_impacts{b}"][0] == -1 and np.isnan(r[f"moat_peak_force{b}"][0])


@bits
def test_linear_bearing_and_moat_same_bits_as_simulate(tmp_path):
    j, rec = simulate(tmp_path, *PAIR, "--isolation1", "linear", "--base-mass1", "3e5", "--bearing-keff1", "1.2e7",
                      "--bearing-zeta1", "0.1", "--moat-gap1", "0.03", "--gap", "0.05")
    iso = [dict(bearing="linear", base_mass=3e5, k_eff=1.2e7, zeta_eff=0.1), None]
    r = pounding.analyze_storeys(dict(BUILDINGS, gap=[0.05]), rec, storeys=(3, 5), isolation=iso,
                                 moat=[dict(gap=0.03), None], **KW)
    same_bits(r, j, 2)
    same_base(r, j)
    assert j["moat_impacts1"] > 0 and r["peak_u1"].shape == (1, 3)  # the moat is hit; the base is not a floor
    assert np.isnan(r["peak_bearing_u2"][0]) and r["moat_impacts2"][0] == -1
    # per-pair arrays: the moat gap of lane 1 is another run; lane 0 keeps its bits
    two = {k: v * 2 for k, v in BUILDINGS.items()}
    r2 = pounding.analyze_storeys(dict(two, gap=[0.05, 0.05]), rec, storeys=(3, 5), isolation=iso,
                                  moat=[dict(gap=[0.03, 0.5]), None], threads=2, batch=1, **KW)
    assert r2["peak_bearing_u1"][0] == r["peak_bearing_u1"][0] and r2["moat_impacts1"][1] == 0


@bits
@pytest.mark.parametrize("bearing,cli_opts,keys", [
    ("lead-rubber", ["--bearing-k1-1", "1.2e8", "--bearing-k2-1", "1.2e7", "--bearing-qd1", "6e5"],
     dict(k1=1.2e8, k2=1.2e7, qd=6e5)),
    ("friction-pendulum", ["--bearing-radius1", "2", "--bearing-mu-slow1", "0.05", "--bearing-mu-fast1", "0.1",
                           "--bearing-rate1", "20", "--bearing-uy1", "5e-4"],
     dict(radius=2, mu_slow=0.05, mu_fast=0.1, rate=20, u_y=5e-4)),
    ("bouc-wen", ["--bearing-k1-1", "1.2e8", "--bearing-k2-1", "1.2e7", "--bearing-qd1", "6e5", "--bearing-eta1", "2",
                  "--bearing-beta1", "0.9", "--bearing-gamma1", "0.1"],
     dict(k1=1.2e8, k2=1.2e7, qd=6e5, eta=2, beta=0.9, gamma=0.1)),
])
def test_bearings_same_bits_as_simulate(tmp_path, bearing, cli_opts, keys):
    j, rec = simulate(tmp_path, *PAIR, "--isolation1", bearing, "--base-mass1", "3e5", *cli_opts, "--gap", "0.05")
    r = pounding.analyze_storeys(dict(BUILDINGS, gap=[0.05]), rec, storeys=(3, 5),
                                 isolation=[dict(bearing=bearing, base_mass=3e5, **keys), None], **KW)
    same_bits(r, j, 2)
    same_base(r, j, moat=False)
    assert j["peak_bearing_u1"] > 0.01  # the bearing works


@bits
def test_row_of_three_same_bits_as_simulate(tmp_path):
    j, rec = simulate(tmp_path, *PAIR, "--buildings", "3", "--storeys3", "4", "--storey-mass3", "2e5",
                      "--storey-stiffness3", "1.5e8", "--gap", "0.02")
    b = dict(BUILDINGS, floor_mass3=[2e5], storey_stiffness3=[1.5e8], yield_drift3=[0.02 / 6], alpha3=[0.05],
             gap=[0.02])
    r = pounding.analyze_storeys(b, rec, storeys=(3, 5, 4), **KW)
    same_bits(r, j, 3)
    assert r["peak_u3"].shape == (1, 4) and sum(lv["impacts"] for lv in j["levels"]) > 0


def cli_error(tmp_path, *args):
    path = write_at2(tmp_path / "sweep.AT2", REC.acc_g, REC.dt)
    p = subprocess.run([cli(), "simulate", "--record", str(path), *PAIR, "--gap", "0.05", *args], capture_output=True,
                       text=True)
    assert p.returncode == 2 and p.stdout == "", p.stderr
    return re.search(r"ERROR: (.*)", p.stderr).group(1)


@pytest.mark.parametrize("cli_args,iso,moat,names", [
    (["--isolation1", "rubber"], dict(bearing="rubber"), None, {"--isolation1": "isolation[0]['bearing']"}),
    (["--isolation1", "linear", "--bearing-keff1", "1e7", "--base-mass1", "-1"],
     dict(bearing="linear", k_eff=1e7, base_mass=-1.0), None, {"--base-mass1": "isolation[0]['base_mass']"}),
    (["--moat-gap2", "0.1"], None, dict(gap=0.1), {"--isolation2": "isolation[1]['bearing']"}),
    (["--isolation1", "linear", "--bearing-keff1", "1e7", "--bearing-k1-1", "1e8"],
     dict(bearing="linear", k_eff=1e7, k1=1e8),
     None, {"--bearing-k1/k2/qd": "isolation[0] keys k1/k2/qd", "--isolation1": "isolation[0]['bearing']",
            "--bearing-k1-1": "isolation[0]['k1']", "--bearing-keff1": "isolation[0]['k_eff']",
            "--bearing-zeta1": "isolation[0]['zeta_eff']"}),
])
def test_bad_isolation_has_the_cli_wording(tmp_path, cli_args, iso, moat, names):
    want = cli_error(tmp_path, *cli_args)
    for option, name in names.items():
        want = want.replace(option, name)
    isolation = [iso, None] if moat is None else [None, None]
    moats = [None, moat] if moat is not None else None
    b = dict(BUILDINGS, gap=[0.05])
    with pytest.raises(ValueError) as err:
        pounding.analyze_storeys(b, REC, storeys=(3, 5), isolation=isolation, moat=moats, **KW)
    assert str(err.value) == want  # what, where, how to fix: the CLI's words, Python's names


def test_isolation_beyond_building_two_refused():
    b = dict(BUILDINGS, floor_mass3=[2e5], storey_stiffness3=[1.5e8], gap=[0.05])
    with pytest.raises(ValueError, match="buildings 1 and 2 only"):
        pounding.analyze_storeys(b, REC, storeys=(3, 5, 4), isolation=[None, None, dict(bearing="linear", k_eff=1e7)])


@bits
def test_modal_damping_of_an_isolated_building_same_bits_as_simulate(tmp_path):
    # the superstructure's fixed-base modal C acting relative to the base (physics::isolated_damping_matrix)
    j, rec = simulate(tmp_path, *PAIR, "--isolation1", "linear", "--base-mass1", "3e5", "--bearing-keff1", "1.2e7",
                      "--modal-zeta", "0.02,0.05,0.03", "--gap", "0.05")
    r = pounding.analyze_storeys(dict(BUILDINGS, gap=[0.05]), rec, storeys=(3, 5), modal_zeta=[0.02, 0.05, 0.03],
                                 isolation=[dict(bearing="linear", base_mass=3e5, k_eff=1.2e7), None], **KW)
    same_bits(r, j, 2)
    same_base(r, j, moat=False)
