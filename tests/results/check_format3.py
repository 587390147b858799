#!/usr/bin/python3
"""Reads a format-3 results file written by tests/results/test_results.cpp (testdata::sample_system_results: a 3-
vs 5-storey pair, 2 records x 4 models x 2 gaps) with h5py, as a user's script would: format_version 3, /system's
columns (strings decode to str), the per-floor and per-element datasets with their shapes, units, descriptions and
axes, the NaN padding above model 1's 4-storey building 2, and the values' places. Exit 0 when all hold.
Usage: check_format3.py FILE.h5"""
import sys

import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
assert int(f.attrs["format_version"]) == 3, f.attrs["format_version"]
s = f["system"]
label = [x.decode() if isinstance(x, bytes) else x for x in s["element_label"][()]]
assert label == ["level 1", "level 2", "level 3"], label
assert [x.decode() for x in s["building_label"][()]] == ["building1", "building2"]
assert s["building_floors"][()].tolist() == [3, 5]
assert s["dof_floor"][()].tolist() == [1, 1, 2, 2, 3, 3, 4, 5]
assert s["spring_i"][()].tolist() == [-1, -1, 0, 1, 2, 3, 5, 6]
assert s["dof_height"].attrs["units"] == "m" and s["element_level_height"].attrs["units"] == "m"
assert [x.decode() for x in s["group_law"][()]] == ["hertzdamp"]
for name, d in s.items():
    assert d.attrs.get("units") and d.attrs.get("description"), f"/system/{name} lacks units or description"

R, M, G, E = 2, 4, 2, 3
expect = {
    "uncoupled/peak_u_floors1": ((R, M, 3), "m"), "uncoupled/peak_u_floors2": ((R, M, 5), "m"),
    "uncoupled/peak_drift1": ((R, M, 3), "m"), "uncoupled/peak_drift2": ((R, M, 5), "m"),
    "uncoupled/peak_acc_floors1": ((R, M, 3), "g"), "uncoupled/peak_acc_floors2": ((R, M, 5), "g"),
    "uncoupled/peak_closing_elements": ((R, M, E), "m"),
    "impacts/element_impact_count": ((R, M, G, E), "1"), "impacts/element_peak_force": ((R, M, G, E), "N"),
    "impacts/element_peak_penetration": ((R, M, G, E), "m"), "impacts/element_t_first_impact": ((R, M, G, E), "s"),
    "impacts/element_energy": ((R, M, G, E), "J"), "impacts/element_h_omega_contact": ((R, M, G, E), "1"),
}
for name, (shape, units) in expect.items():
    d = f[name]
    assert d.shape == shape, (name, d.shape)
    assert d.attrs["units"] == units, (name, d.attrs["units"])
    assert d.attrs["description"] and d.attrs["axes"].startswith("[records, models"), name
# the [R, M] fields keep format 2's names and shapes
assert f["uncoupled/peak_u1"].shape == (R, M) and f["impacts/peak_force"].shape == (R, M, G)
# values name their place: system_value(field, k) = 1000 field + 0.25 k, record-major flat index k
u2 = f["uncoupled/peak_u_floors2"][()]
assert np.isnan(u2[:, 1, 4]).all() and not np.isnan(u2[:, 1, :4]).any() and not np.isnan(u2[:, [0, 2, 3], :]).any()
base = u2[0, 0, 0]
assert u2[1, 2, 3] == base + 0.25 * ((1 * M + 2) * 5 + 3), u2[1, 2, 3]
count = f["impacts/element_impact_count"][()]
assert count.dtype == np.int32 and count[1, 3, 1, 2] == ((1 * M + 3) * G + 1) * E + 2
print(f"ok:   format 3 read by h5py: {len(s)} /system datasets, {len(expect)} per-floor and per-element datasets")
