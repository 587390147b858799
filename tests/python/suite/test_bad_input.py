"""Bad input to the Python module raises a short ValueError naming the argument, never a crash (issue 44 item 4).

pairs['m1'] = 'abc' (or [{}]) crashed pounding.run_batch and _core.analyze with a segfault (exit 139): m1 sizes the
batch and its conversion was not checked; the same value in k1 gave a ValueError. Each call runs in a child
process, so a crash fails its case instead of ending the suite; the child prints the exception's type and text.
"""
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import pounding

CHILD = textwrap.dedent("""
    import sys
    import numpy as np
    import pounding
    from pounding import _core

    def pairs(**bad):
        d = {k: np.full(2, v) for k, v in dict(m1=1e6, k1=4e7, c1=1e5, m2=2e6, k2=3e7, c2=2e5, gap=0.02,
                                                    kc=1e9, e=0.65).items()}
        d.update(bad)
        return d

    ag = 0.5 * np.sin(np.arange(200) * 0.05)
    try:
        {call}
    except Exception as e:  # noqa: BLE001
        print(type(e).__name__ + ": " + str(e))
    else:
        print("no error")
""")

BAD = {"'abc'": "'abc'", "[{}]": "[{}]", "None": "None", "np.zeros((2, 2))": "shape (2, 2)",
       "['x'] * 100000": "['x', 'x'"}


def child(call):
    """The output of `call` in a child process: 'Type: message' or 'no error'; a crash fails the test."""
    run = subprocess.run([sys.executable, "-c", CHILD.replace("{call}", call)], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, f"{call}: the process ended with {run.returncode} (a crash)\n{run.stderr[-2000:]}"
    return run.stdout.strip()


@pytest.mark.parametrize("value", list(BAD))
@pytest.mark.parametrize("column", ["m1", "k1"])
@pytest.mark.parametrize("entry", ["pounding.run_batch(pairs({column}={value}), ag, 0.01)",
                                   "_core.analyze(pairs({column}={value}), ag, 0.01, 'central-difference', 'hertzdamp', "
                                   "'lankarani-nikravesh', 1.5, 1, False, 0.0, 10.0, 256, 1)",
                                   "pounding.analyze(pairs({column}={value}), (ag / 9.80665, 0.01), "
                                   "contact='hertzdamp')"])
def test_a_column_that_is_not_numbers_names_itself(entry, column, value):
    out = child(entry.format(column=column, value=value))
    assert out.startswith(("ValueError: ", "TypeError: ")), out
    assert f"pairs['{column}']" in out, out
    assert BAD[value] in out, out  # what was given
    assert len(out) < 200, out     # short: never the whole array


def test_a_bad_ground_motion_names_itself():
    out = child("pounding.run_batch(pairs(), 'abc', 0.01)")
    assert out.startswith("ValueError: ag: ") and "'abc'" in out, out
    out = child("pounding.run_batch(pairs(), np.zeros((300, 2)), 0.01)")
    assert out.startswith("ValueError: ag: ") and "shape (300, 2)" in out and len(out) < 200, out


def test_good_columns_still_run():
    assert child("pounding.run_batch(pairs(), ag, 0.01)") == "no error"
    assert child("pounding.run_batch(pairs(m1=[1e6, 2e6], k1=(4e7, 5e7)), ag, 0.01)") == "no error"


def test_a_column_of_the_wrong_length_says_how_many():
    out = child("pounding.run_batch(pairs(k1=np.ones(3)), ag, 0.01)")
    assert out.startswith("ValueError: pairs['k1']: 2 values") and "got 3" in out, out


def test_design_spectrum_parameter_that_is_not_a_number():
    with pytest.raises(ValueError, match=r"design_spectrum: sds: a number is needed, got str 'high'"):
        pounding.design_spectrum("asce7-16", [0.5, 1.0], sds="high", sd1=0.6)


def test_hazard_curve_that_is_not_numbers():
    from pounding import _core
    with pytest.raises(ValueError, match=r"curve k: a number is needed, got str 'x'"):
        _core.analysis.rate(0.5, 0.4, (1e-4, "x"), 50.0)
    with pytest.raises(ValueError, match=r"curve: \(k0, k\) of a power law .* got str 'abc'"):
        _core.analysis.rate(0.5, 0.4, "abc", 50.0)


# issue 44 item 10: arguments out of range named with their range and the fix; unknown keywords refused
G = 9.80665


def pair_dict():
    import numpy as np
    return {k: np.full(2, v) for k, v in dict(m1=1e6, k1=4e7, c1=1e5, m2=2e6, k2=3e7, c2=2e5, gap=0.02).items()}


def motion():
    import numpy as np
    return (0.3 * np.sin(np.arange(300) * 0.05), 0.01)


def test_design_spectrum_refuses_an_unknown_keyword():
    with pytest.raises(TypeError, match=r"unknown parameter 'TL' \(did you mean 'tl'\?\); it takes sds, sd1, tl, ss, s1, "
                                        r"site_class"):
        pounding.design_spectrum("asce7-16", [0.5, 1.0], sds=1.0, sd1=0.6, TL=4)
    with pytest.raises(TypeError, match=r"design_spectrum\(\"ec8\"\): unknown parameter 'sds'; it takes type, ground"):
        pounding.design_spectrum_text("ec8", agr=0.3, sds=1.0)
    assert "TL = 4 s" in pounding.design_spectrum_text("asce7-16", sds=1.0, sd1=0.6, tl=4)


@pytest.mark.parametrize("kw, want", [
    (dict(threads=-3), r"threads = -3 is outside \[0, 1024\], threads, give the worker threads, 1 to 1024, or 0 for "
                       r"every core"),
    (dict(displacement_limit=float("nan")), r"displacement_limit = nan is outside \(0, inf\) m, displacement_limit, give"),
    (dict(displacement_limit=-1.0), r"displacement_limit = -1 is outside \(0, inf\) m"),
    (dict(duration=float("nan")), r"duration = nan is outside \[0, inf\) s, duration, give the analysis length in s, or "
                                  r"0 for the record's own length"),
    (dict(duration=-2.0), r"duration = -2 is outside \[0, inf\) s"),
])
def test_run_settings_out_of_range_name_the_argument(kw, want):
    with pytest.raises(ValueError, match=want):
        pounding.analyze(pair_dict(), motion(), **kw)
    with pytest.raises(ValueError, match=want):
        pounding.analyze_storeys({"floor_mass1": [1e5, 1e5], "floor_mass2": [1e5, 1e5], "period1": [0.5, 0.5],
                                  "period2": [0.8, 0.8], "gap": [0.05, 0.05]}, motion(), storeys=(2, 3), **kw)
    if "threads" not in kw:
        with pytest.raises(ValueError, match=want):
            pounding.simulate({k: v[0] for k, v in pair_dict().items()}, motion(), **kw)


def test_storeys_must_be_whole_numbers():
    b = {"floor_mass1": [1e5], "floor_mass2": [1e5], "period1": [0.5], "period2": [0.8], "gap": [0.05]}
    for bad in ((2.5, 3), ("2", 3), (True, 3)):
        with pytest.raises(ValueError, match=r"storeys: .* is not a whole number of storeys; give one integer per "
                                             r"building, 1 or more, e.g. storeys=\(3, 5\)"):
            pounding.analyze_storeys(b, motion(), storeys=bad)
    assert pounding.analyze_storeys(b, motion(), storeys=(2.0, 3))["status"][0] == 0


@pytest.mark.parametrize("key, value, want", [
    ("floor_mass1", 1e-30, r"floor_mass1 \(lane 0\) = 1e-30 is out of range, floor_mass1, give a value in \[1e-3, 1e9\] kg "
                           r"\(as floor_mass in a study's \[structures.buildingK\]\)"),
    ("floor_mass2", 1e300, r"floor_mass2 \(lane 0\) = 1e\+300 is out of range"),
    ("period1", 1e9, r"period1 \(lane 0\) = 1000000000 is out of range, period1, give a value in \[0.02, 20\]"),
    ("zeta2", 0.9, r"zeta2 \(lane 0\) = 0.9 is out of range, zeta2, give a value in \[0, 0.5\]"),
    ("yield_coefficient1", 50.0, r"yield_coefficient1 \(lane 0\) = 50 is out of range"),
])
def test_storey_numbers_take_the_study_keys_ranges(key, value, want):
    """Issue 44 item 11: the ranges of a study's floor_mass, period, zeta, yield_coefficient (config::study_key), as
    `pounding simulate --storey-massK` etc.; they were (0, 1e12) kg, (0, 100) s, [0, 1), (0, 10)."""
    b = {"floor_mass1": [1e5], "floor_mass2": [1e5], "period1": [0.5], "period2": [0.8], "gap": [0.05]}
    b[key] = [value]
    with pytest.raises(ValueError, match=want):
        pounding.analyze_storeys(b, motion(), storeys=(2, 3))
    with pytest.raises(ValueError, match=r"storey_height: every storey height in \[0.01, 10\] m \(as storey_height in a "
                                         r"study\), not 50"):
        pounding.analyze_storeys({"floor_mass1": [1e5], "floor_mass2": [1e5], "period1": [0.5], "period2": [0.8],
                                  "gap": [0.05]}, motion(), storeys=(2, 3), storey_height=50.0)


def test_an_empty_record_is_refused():
    for acc in ([], [0.1]):
        with pytest.raises(ValueError, match=r"Record: acc_g holds [01] value\(s\), Record\(acc_g=\), give at least 2 "
                                             r"accelerations"):
            pounding.Record(acc, 0.01)


def test_ranges_are_printed_as_numbers_not_fixed_point():
    """Messages print a range as 1e+16 or inf, not %f's '(0.000000, 10000000000000000.000000)'; Record's dt and repr too."""
    b = {"floor_mass1": [1e5], "floor_mass2": [1e5], "period1": [0.5], "period2": [0.8], "gap": [0.05],
         "yield_drift1": [2.0]}
    with pytest.raises(ValueError, match=r"yield_drift1 \(lane 0\) = 2 is out of range, yield_drift1, give a value in "
                                         r"\(0, 1\)") as e:
        pounding.analyze_storeys(b, motion(), storeys=(2, 3))
    assert "000000" not in str(e.value)
    with pytest.raises(ValueError, match=r"Record: dt = 5 s is outside \[1e-4, 0.1\] s"):
        pounding.Record([0.0, 0.1], 5.0)
    assert repr(pounding.Record([0.0, 0.1, -0.2], 0.01, name="x")) == "<pounding.Record x: 3 points, dt 0.01 s, PGA 0.2 g>"


def test_a_batch_larger_than_memory_is_refused_before_any_copy():
    """10^9 pairs (views that cost nothing until copied) were copied column by column until the process was killed:
    the size is checked first, naming the memory needed and available and the largest part that fits."""
    n = 10**9
    pairs = {k: np.broadcast_to(np.float64(v), (n,)) for k, v in
             dict(m1=1e5, m2=1e5, k1=4e6, k2=4e6, c1=1e4, c2=1e4, gap=0.05).items()}
    for call in (lambda: pounding.analyze(pairs, (np.zeros(100), 0.01)),
                 lambda: pounding._core.check_batch_memory(n)):
        with pytest.raises(ValueError, match=r"pairs: 1000000000 pairs need about .* of memory .* is available; give "
                                             r"the pairs in parts of at most \d+ and join the results"):
            call()
    pounding._core.check_batch_memory(1000)  # a small batch passes
