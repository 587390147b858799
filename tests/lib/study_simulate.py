"""The "study equals simulate" comparison of the cli tests that run a one-record, one-model study of shear buildings
beside pounding simulate --json (cli.study_steppers, cli.study_modal, cli.rayleigh_modes, cli.study_rows_mixed):
imported by their Python here-documents run with PYTHONPATH=$src/tests/lib.

  load(tmp, name)  the study tmp/name.h5 and simulate's tmp/name-sim.json (with contact) and tmp/name-free.json
                   (--contact none), and the study's gap index of ratio 0.5: (f, s, u, g)
  pair_checks(f, s, u, g, buildings=2, coupled_floors=False)
                   (what, study's number, simulate's) for the coupled run at the gap (impact count, peak force, first
                   impact, each building's peak u -- building 1's with its base when isolated) and the uncoupled run
                   (peak closing; every floor's peak u, drift and absolute acceleration of each building), with
                   coupled_floors the coupled run's floors too. An isolated building 1 (peak_bearing_u1 in the JSON):
                   the study's floors start with the base, simulate gives the base apart.
  assert_equal(checks)  every pair equal to the bit, else an AssertionError listing the ones that are not
"""
import json

import h5py

FIELDS = (("peak_u_floors", "peak_u"), ("peak_drift", "peak_drift"), ("peak_acc_floors", "peak_abs_acc"))


def load(tmp, name):
    f = h5py.File(f"{tmp}/{name}.h5", "r")
    s, u = (json.load(open(f"{tmp}/{name}-{run}.json")) for run in ("sim", "free"))
    return f, s, u, list(f["impacts/gap_ratios"][()]).index(0.5)


def floor_checks(run, mine, j, field, key, b, base):
    theirs = j[f"{key}{b}_g" if key == "peak_abs_acc" else f"{key}{b}"]
    if base:
        mine, theirs = (mine, [j["peak_bearing_u1"]] + theirs) if key == "peak_u" else (mine[1:], theirs)
    return [(f"{run} {field}{b}[{i}]", a, c) for i, (a, c) in enumerate(zip(mine, theirs, strict=True))]


def pair_checks(f, s, u, g, buildings=2, coupled_floors=False):
    iso = "peak_bearing_u1" in u
    at = lambda name: f[name][()].ravel()[g]
    out = [("impact_count", at("impacts/impact_count"), s["impact_count"]),
           ("peak_force", at("impacts/peak_force"), s["peak_force"]),
           ("t_first_impact", at("impacts/t_first_impact"), s["t_first_impact"]),
           ("uncoupled peak_closing", f["uncoupled/peak_closing"][()].ravel()[0], u["peak_closing"])]
    for b in range(1, buildings + 1):
        base = iso and b == 1
        out.append((f"peak_u{b}", at(f"impacts/peak_u{b}"),
                    max(s[f"peak_u{b}"] + ([s["peak_bearing_u1"]] if base else []))))
        for field, key in FIELDS:
            out += floor_checks("uncoupled", list(f[f"uncoupled/{field}{b}"][()].ravel()), u, field, key, b, base)
            if coupled_floors:
                out += floor_checks("impacts", list(f[f"impacts/{field}{b}"][0, 0, g]), s, field, key, b, base)
    return out


def assert_equal(checks):
    bad = [(n, a, c) for n, a, c in checks if not (a == c)]
    assert not bad, bad
