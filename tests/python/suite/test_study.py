"""Study(...).run() in-process and Results (issue 28, item 5): the same results and tables as `pounding run`."""
import os
import re
import subprocess

import numpy as np
import pytest

import pounding
from conftest import cli, need

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = os.path.join(HERE, "..", "..", "..", "studies", "quick.toml")


def test_study_from_python_gives_the_clis_tables(tmp_path):
    need("pandas")
    h5py = need("h5py")
    py_out, cli_out = tmp_path / "py.h5", tmp_path / "cli.h5"
    res = pounding.Study(QUICK).run(out=str(py_out), progress=False)
    assert res.exit_code == 0 and py_out.exists()
    run = subprocess.run([cli(), "run", QUICK, "--out", str(cli_out), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    csv = subprocess.run([cli(), "report", str(cli_out), "--csv"], capture_output=True, text=True).stdout
    assert pounding._core.report(str(py_out), True) == csv  # every CSV table, to the digit
    md = subprocess.run([cli(), "report", str(cli_out)], capture_output=True, text=True).stdout
    cli_tables = pounding.study.markdown_tables(md)
    assert list(res.sections) == list(cli_tables)
    for heading, table in cli_tables.items():
        assert res.sections[heading].equals(table), heading
    with h5py.File(py_out) as a, h5py.File(cli_out) as b:
        for key in a["uncoupled"]:
            assert np.array_equal(a["uncoupled"][key][()], b["uncoupled"][key][()], equal_nan=True), key
    t3 = res.table3
    assert list(t3.columns) == ["gap_ratio", "hits", "n", "probability"] and t3["n"].dtype == np.int64
    assert (t3["probability"] == (t3["hits"] / t3["n"]).round(6)).all()
    assert res.table2.shape == (25, len(t3))
    assert res.code_rules["rule"].iloc[0] == "Standard 2800"
    m = res.period_pair(0.3)
    cp = res.csv_tables["period_pair"]
    assert m.shape == (11, 11) and m.loc[1.0, 1.05] == cp[(cp["gap_ratio"] == 0.3) & (cp["T1"] == 1.0)
                                                          & (cp["T2"] == 1.05)]["probability"].item()
    assert "uncoupled" in res.groups() and res.arrays("uncoupled")["peak_closing"].size > 0


def test_bad_study_text_is_a_value_error(tmp_path):
    text = open(QUICK).read().replace("[gaps]", "[gaps]\nbogus_key = 1", 1)
    with pytest.raises(ValueError, match="bogus_key"):
        pounding.Study(text, base_dir=str(tmp_path)).run(out=str(tmp_path / "x.h5"), progress=False)
    assert not (tmp_path / "x.h5").exists() and os.listdir(tmp_path) == []
    with pytest.raises(ValueError, match="not found"):
        pounding.Results(str(tmp_path / "missing.h5"))


def test_fragility_study_numbers_are_the_bindings(tmp_path):
    """A fragility study's /fragility and /hazard (written by the study's own analysis) against fragility.fit and
    hazard.rate on the file's observed stripes: the same C++ code, so the same bits."""
    need("h5py")
    studies = os.path.join(HERE, "..", "..", "..", "studies")
    text = open(os.path.join(studies, "fragility-pair.toml")).read()
    text = text.replace("samples_per_pair = 200", "samples_per_pair = 20").replace("bootstrap = 2000", "bootstrap = 50")
    (tmp_path / "frag.toml").write_text(text)
    (tmp_path / "example-hazard.csv").write_text(open(os.path.join(studies, "example-hazard.csv")).read())
    res = pounding.Study(str(tmp_path / "frag.toml")).run(out=str(tmp_path / "frag.h5"), progress=False)
    f, h = res.arrays("fragility"), res.arrays("hazard")
    ok = 0
    for g in range(len(f["gaps"])):
        fit = pounding.fragility.fit(f["levels"], f["observed_n"][g], f["observed_z"][g])
        stored = f["status"][g].decode() if isinstance(f["status"][g], bytes) else str(f["status"][g])
        if not fit.ok:
            assert np.isnan(f["theta"][g]), (g, fit.status, stored)
            continue
        ok += 1
        assert fit.theta == f["theta"][g] and fit.beta == f["beta"][g], g
        lam = pounding.hazard.rate(fit.theta, fit.beta, (h["im"], h["rate"]))
        assert lam["rate"] == h["annual_rate"][g], g
    assert ok >= 3
    assert any(k.startswith("Fragility per gap") for k in res.sections)
    fr, hz = res.fragility, res.hazard
    assert fr["theta"].tolist() == f["theta"].tolist() and (fr["status"] == "ok").sum() == ok
    assert hz["annual_rate"].tolist() == h["annual_rate"].tolist() and hz["gap"].tolist() == f["gaps"].tolist()
    assert len(res.hazard_curve) == len(h["curve_gap"]) and "rate" in res.hazard_curve


def test_ctrl_c_stops_a_study_and_resume_finishes_it(tmp_path):
    import signal
    out = tmp_path / "q.h5"
    calls = []

    def progress(phase, done, total, elapsed, final):
        calls.append(done)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C while the study runs

    with pytest.raises(KeyboardInterrupt, match="resume=True"):
        pounding.Study(QUICK).run(out=str(out), progress=progress)
    assert not out.exists() and (tmp_path / "q.h5.ckpt").exists()  # no results, the checkpoint kept
    res = pounding.Study(QUICK).run(out=str(out), progress=False, resume=True)
    assert res.exit_code == 0 and res.table3["n"].iloc[0] == 96800
    whole = pounding.Study(QUICK).run(out=str(tmp_path / "whole.h5"), progress=False)
    assert pounding._core.report(str(out), True) == pounding._core.report(str(whole.path), True)
    with pytest.raises(RuntimeError, match="callback failed"):
        pounding.Study(QUICK).run(out=str(tmp_path / "r.h5"), progress=lambda *a: 1 / 0)


def test_study_threads_give_the_same_bits(tmp_path):
    """Study.run(threads=2) writes the same results as threads=1 (each thread its own unit computer, results
    stored by unit id); the thread count is provenance in /timing, not a setting."""
    h5py = need("h5py")
    one, two = tmp_path / "t1.h5", tmp_path / "t2.h5"
    pounding.Study(QUICK).run(out=str(one), progress=False, threads=1)
    pounding.Study(QUICK).run(out=str(two), progress=False, threads=2)
    with h5py.File(one) as a, h5py.File(two) as b:
        assert a["timing"].attrs["threads"] == 1 and b["timing"].attrs["threads"] == 2
        for group in ("uncoupled", "models"):
            for key in a[group]:
                x, y = a[group][key][()], b[group][key][()]
                assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), (group, key)
    compare = os.path.join(HERE, "..", "..", "cli", "compare_results.py")
    run = subprocess.run(["/usr/bin/python3", compare, str(one), str(two)], capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


@pytest.mark.parametrize("bad", [-1, 1025, 1.5, "2", True])
def test_bad_threads_is_a_value_error(tmp_path, bad):
    with pytest.raises(ValueError, match=r"threads"):
        pounding.Study(QUICK).run(out=str(tmp_path / "x.h5"), progress=False, threads=bad)
    assert os.listdir(tmp_path) == []


def _small(tmp_path, name, samples, bootstrap=100):
    """A shipped study made small (tests/lib/html_studies.sh's reduction), its relative paths made absolute."""
    studies = os.path.join(HERE, "..", "..", "..", "studies")
    text = open(os.path.join(studies, name + ".toml")).read()
    text = re.sub(r"(?m)^samples_per_pair = [0-9_]*", f"samples_per_pair = {samples}", text)
    text = re.sub(r"(?m)^bootstrap = [0-9_]*", f"bootstrap = {bootstrap}", text)
    text = text.replace('"../records/', f'"{os.path.abspath(os.path.join(studies, "..", "records"))}/')
    (tmp_path / f"{name}.toml").write_text(text)
    return pounding.Study(str(tmp_path / f"{name}.toml")).run(out=str(tmp_path / f"{name}.h5"), progress=False,
                                                             threads=1)


def _cell(cell, *values, scale=1.0):
    """The numbers of a Markdown cell ("0.17%", "[0.09%, 0.30%]", "**0.416**", "6 of 25") equal the values as the
    report printed them: within half a unit of the cell's last digit (the CSV keeps 6 decimals, so a value may round
    either way at the cell's last digit)."""
    nums = re.findall(r"-?\d+(?:\.\d+)?", cell)
    assert len(nums) == len(values), (cell, values)
    for text, v in zip(nums, values):
        half = 0.5 * 10.0 ** -(len(text.split(".")[1]) if "." in text else 0)
        assert abs(float(text) - scale * v) <= half + 1e-9, (cell, values)
    return True


def test_grid_code_rules_and_advice_are_numbers(tmp_path):
    """Issue 28: Results.code_rules / separation_advice of a grid study (quick.toml, 2 samples per pair) are numeric
    DataFrames from the CSV report; they equal the Markdown tables' cells, and the code rules' probabilities equal
    numpy's count on the HDF5 arrays (each model's rule gap from /models and /uncoupled, the closing above it)."""
    need("pandas")
    h5py = need("h5py")
    res = _small(tmp_path, "quick", 2)
    rules, advice = res.code_rules, res.separation_advice
    assert rules["probability"].dtype == np.float64 and rules["hits"].dtype == np.int64
    assert list(rules["rule"][:4]) == ["Standard 2800", "ABS", "SRSS", "DDC"]
    md = res.section("Code separation rules")
    assert len(md) == len(rules)
    for (_, row), (_, cells) in zip(rules.iterrows(), md.iterrows()):
        assert cells["rule"] == row["rule"]
        assert _cell(cells["probability of pounding"], row["probability"], scale=100)
        assert _cell(cells["Wilson 95 %"], row["wilson_lo"], row["wilson_hi"], scale=100)
    md = res.section("Separation advice")
    assert len(md) == len(advice) == 3 and advice["x"].dtype == np.float64
    for (_, row), (_, cells) in zip(advice.iterrows(), md.iterrows()):
        assert cells["target"] == f"{100 * row['target']:g}%"
        assert _cell(cells["x"], row["x"]) and _cell(cells["cubic x"], row["cubic_x"])
        assert _cell(cells["95 % interval"], row["lo"], row["hi"])
        assert _cell(cells["advice x (upper end)"], row["advice_x"])
    # numpy on the file: per model, Standard 2800's gap is 0.005 (h1 + h2); ABS and SRSS take each building's mean
    # uncoupled peak over the model's records
    with h5py.File(res.path) as f:
        m, u = f["models"], f["uncoupled"]
        closing, ok = u["peak_closing"][()], u["status"][()] == 0
        assert ok.all()
        u1, u2 = u["peak_u1"][()].mean(axis=0), u["peak_u2"][()].mean(axis=0)
        gaps = {"Standard 2800": 0.005 * (m["h1"][()] + m["h2"][()]), "ABS": u1 + u2, "SRSS": np.hypot(u1, u2)}
    for name, gap in gaps.items():
        hits = int((closing > gap[None, :]).sum())
        row = rules[rules["rule"] == name].iloc[0]
        assert (row["hits"], row["n"]) == (hits, closing.size), name
        assert abs(row["probability"] - hits / closing.size) < 5e-7, name


def test_pair_code_rules_and_advice_are_numbers(tmp_path):
    """The same for a pair study (example-pair.toml, 4 models per record): rules in metres with the bootstrap and
    Wilson intervals, advice in metres with the records above, the cubic and the lognormal; numpy recomputes the
    rules' gaps (mean uncoupled peaks over every analysis, the median code gap) and their probabilities."""
    need("pandas")
    h5py = need("h5py")
    res = _small(tmp_path, "example-pair", 4)
    rules, advice = res.code_rules, res.separation_advice
    assert rules["gap_m"].dtype == np.float64 and rules["hits"].dtype == np.int64
    md = res.section("Code separation rules in metres")
    assert len(md) == len(rules) and rules["rule"].iloc[0].startswith("Standard 2800")
    for (_, row), (_, cells) in zip(rules.iterrows(), md.iterrows()):
        assert cells["rule"] == row["rule"] and _cell(cells["separation m"], row["gap_m"])
        assert _cell(cells["P(pounding)"], row["probability"], scale=100)
        assert _cell(cells["95 % interval"], row["lo"], row["hi"], scale=100)
        assert _cell(cells["Wilson 95 %"], row["wilson_lo"], row["wilson_hi"], scale=100)
    md = res.section("Separation for this pair")
    assert len(md) == len(advice) == 3
    for (_, row), (_, cells) in zip(advice.iterrows(), md.iterrows()):
        assert _cell(cells["separation m"], row["separation_m"])
        assert _cell(cells["95 % interval m"], row["lo_m"], row["hi_m"])
        assert _cell(cells["records above"], row["records_above"], row["records"])
        assert _cell(cells["in code gaps d"], row["x"])
        assert cells["cubic m"] == "outside fit range" if np.isnan(row["cubic_m"]) else _cell(cells["cubic m"],
                                                                                               row["cubic_m"])
        assert _cell(cells["lognormal m (parametric)"], row["lognormal_m"])
        assert _cell(cells["advice: at least m"].split("**")[1], row["advice_m"])
        assert ("not resolved" in cells["advice: at least m"]) == (not row["resolved"])
    assert not advice["resolved"].iloc[-1] and advice["advice_m"].iloc[-1] == advice["lognormal_hi_m"].iloc[-1]
    with h5py.File(res.path) as f:
        z, ok = f["uncoupled"]["peak_closing"][()], f["uncoupled"]["status"][()] == 0
        assert ok.all()
        u1, u2 = f["uncoupled"]["peak_u1"][()].mean(), f["uncoupled"]["peak_u2"][()].mean()
        d = np.median(f["models"]["code_gap"][()])
    for name, gap in {"ABS": u1 + u2, "SRSS": np.hypot(u1, u2), rules["rule"].iloc[0]: d}.items():
        row = rules[rules["rule"] == name].iloc[0]
        assert abs(row["gap_m"] - gap) < 5e-7, (name, row["gap_m"], gap)
        assert row["hits"] == int((z > gap).sum()) and row["n"] == z.size, name
        assert abs(row["probability"] - (z > gap).mean()) < 5e-7, name


def test_results_frame_of_per_analysis_arrays(tmp_path):
    """Results.frame("uncoupled") (record x model arrays) is one row per analysis, with the record's id."""
    need("pandas")
    need("h5py")
    res = pounding.Study(QUICK).run(out=str(tmp_path / "q.h5"), progress=False)
    r = pounding.study.Results(str(tmp_path / "q.h5"))
    df = r.frame("uncoupled")
    u = r.arrays("uncoupled")["peak_closing"]
    assert res.exit_code == 0 and len(df) == u.size == 25 * 3872
    assert list(df.columns[:3]) == ["record", "record_id", "model"]
    assert np.array_equal(df["peak_closing"].to_numpy(), u.ravel(), equal_nan=True)
    assert df["record_id"].iloc[0] == "EQ1" and df["record_id"].iloc[-1] == "EQ25" and df["model"].iloc[-1] == 3871
    assert r.frame("models").shape[0] == 3872  # 1-D datasets: as before


def test_histories_read_back_equal_the_study(tmp_path):
    """[outputs] histories from Python (issue 45 item 5): Results.histories() returns each stored analysis with its
    arrays, and its peaks are the study's per-model values for that analysis (the worst two by peak force)."""
    h5py = need("h5py")
    studies = os.path.join(HERE, "..", "..", "..", "studies")
    text = open(os.path.join(studies, "quick-impacts.toml")).read()
    text = text.replace("samples_per_pair = 4", "samples_per_pair = 1").replace(
        "synthetic_only = true", "synthetic_only = true\nlimit = 3")
    text += '\n[outputs]\nhistories = [{ worst = 2 }]\n'
    out = tmp_path / "h.h5"
    res = pounding.Study(text, base_dir=studies).run(out=str(out), progress=False)
    assert res.exit_code == 0
    hs = pounding.Results(str(out)).histories()
    assert [h["n"] for h in hs] == [1, 2] and all(h["run"] == "coupled" for h in hs)
    with h5py.File(out) as f:
        force = f["impacts"]["peak_force"][()]  # [record][model][gap]
        ratios = list(f["gaps"]["ratios"][()])
        largest = np.sort(np.nan_to_num(force, nan=-1.0).ravel())[::-1][:2]
        for h in hs:
            g = ratios.index(h["gap_ratio"])
            assert h["peak_force"] == force[h["record_row"], h["model"], g]  # bit for bit
            assert h["u"].shape[1] == h["t"].size == h["force"].shape[1]
            assert np.max(h["force"]) == h["peak_force"]  # an SDOF pair: its one element's largest force
        assert sorted([h["peak_force"] for h in hs], reverse=True) == list(largest)
