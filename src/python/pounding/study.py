"""Studies from Python: Study(path_or_toml_text).run() runs a study file in this process (one rank, no mpirun:
the engine's serial path; `pounding run` under mpirun is for clusters), writes the same results file as
`pounding run`, and Results(path) gives its tables as pandas DataFrames.

Results' tables are the C++ report's (report_markdown / report_csv on the HDF5 arrays, exactly what `pounding
report` prints): `csv_tables` from the CSV form (full precision: per_record = Table 2's counts, total = Table 3,
period_pair, separation, curve), `sections` every Markdown table under its heading (code rules, separation advice,
fragility and hazard tables of a fragility study, ...), and `arrays(group)` the raw HDF5 datasets (h5py).
"""
import io
import os

import numpy as np
import sys
import tempfile
import time

from . import _core

__all__ = ["Results", "Study"]


class Study:
    """A study file, or its TOML text (relative paths in it are then taken from `base_dir`, default the current
    directory). Bad studies raise ValueError with the CLI's message when run."""

    def __init__(self, path_or_text, base_dir=None):
        text = str(path_or_text)
        if "\n" not in text and os.path.exists(text):
            self.path, self.text = os.path.abspath(text), None
        elif "\n" in text or "=" in text:
            self.path, self.text = None, text
            self.base_dir = os.path.abspath(base_dir or os.getcwd())
        else:
            raise ValueError(f"study file not found, {text}, give the path of a study .toml or its text")

    def run(self, out=None, progress=True, resume=False, force=False, threads=None):
        """Runs the study (Ctrl-C stops it after the running units, keeping the checkpoint: KeyboardInterrupt, then
        resume=True). out: the results file (default: the study's `output`). progress: True prints a line to stderr
        every 2 s, a callable gets (phase, done, total, elapsed_s, final), False nothing. threads: worker threads
        (None: the study's [analysis] threads, whose default 0 means every CPU this process may use); the results
        do not depend on it. Returns Results."""
        if threads is None:
            threads = -1
        elif isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or not 0 <= threads <= 1024:
            raise ValueError(f"threads = {threads!r} is not a whole number in [0, 1024], Study.run(threads=), give "
                             "the worker threads, 0 for every CPU this process may use, or None for the study's "
                             "[analysis] threads")
        callback = _printer() if progress is True else (progress or None)
        info = (lambda line: print(line, file=sys.stderr)) if progress else None
        start = time.monotonic()
        if self.path:
            outcome = _core.run_study(self.path, out, resume, force, callback, info, int(threads))
        else:
            fd, path = tempfile.mkstemp(suffix=".toml", prefix=".pounding-study-", dir=self.base_dir)
            try:
                with os.fdopen(fd, "w") as f:
                    f.write(self.text)
                outcome = _core.run_study(path, out, resume, force, callback, info, int(threads))
            finally:
                os.unlink(path)
        results = Results(outcome["out"])
        results.report_text = outcome["report"]
        results.exit_code = outcome["code"]  # 3: done, but too many analyses excluded (the report says so)
        results.wall_s = time.monotonic() - start
        return results


def _printer():
    last = [0.0]

    def show(phase, done, total, elapsed, final):
        now = time.monotonic()
        if final or now - last[0] >= 2.0:
            last[0] = now
            print(f"progress: {phase} {done}/{total}, elapsed {elapsed:.1f} s", file=sys.stderr)
    return show


class Results:
    """A results file written by `pounding run` or Study.run()."""

    def __init__(self, path):
        if not os.path.isfile(path):
            raise ValueError(f"results file not found, {path}, give a file written by pounding run")
        self.path = path
        self.report_text = None
        self._sections = None
        self._csv = None

    @property
    def markdown(self):
        """The report, as `pounding report PATH` prints it."""
        return _core.report(self.path, False)

    @property
    def csv_tables(self):
        """The CSV report split by its `table` column: {name: DataFrame}, the empty columns of each dropped."""
        if self._csv is None:
            import pandas as pd
            frame = pd.read_csv(io.StringIO(_core.report(self.path, True)), keep_default_na=False,
                                na_values=[""], dtype={"record": str, "name": str})
            self._csv = {}
            for name, part in frame.groupby("table", sort=False):
                part = part.drop(columns="table").dropna(axis=1, how="all").reset_index(drop=True)
                for col in ("hits", "n"):  # counts (float in the mixed frame because other tables leave them empty)
                    if col in part and part[col].notna().all():
                        part[col] = part[col].astype("int64")
                self._csv[name] = part
        return self._csv

    @property
    def table2(self):
        """Table 2: probability of at least one impact per record (rows) and gap ratio (columns)."""
        t = self.csv_tables["per_record"]
        return t.pivot(index="record", columns=t.columns[1], values="probability").loc[t["record"].unique()]

    @property
    def table3(self):
        """Table 3: total probability of pounding per gap (hits, n, probability)."""
        return self.csv_tables["total"]

    @property
    def sections(self):
        """Every table of the Markdown report under its heading: {heading: DataFrame of strings}."""
        if self._sections is None:
            self._sections = markdown_tables(self.markdown)
        return self._sections

    def section(self, starts_with):
        """The first Markdown table whose heading starts with the text (e.g. "Code separation rules")."""
        for heading, table in self.sections.items():
            if heading.startswith(starts_with):
                return table
        raise KeyError(f"no table under a heading starting with {starts_with!r}; headings: {list(self.sections)}")

    @property
    def code_rules(self):
        """The code separation rules with the probability of pounding at each, from the CSV report's numbers (the
        same rows the Markdown table formats). Columns: rule (name), kind ("formula": the codes' formulas fed the
        mean record peaks, "design": the codes' own design displacements), hits, n, probability, wilson_lo,
        wilson_hi (Wilson 95 %), and for a pair study gap_m (the rule's separation), gap_ratio (in code gaps d),
        lo, hi (the two-stage bootstrap interval of the probability). A grid study's rules have a gap per model,
        so no gap column. Empty for a bridge study (no building code rules)."""
        import pandas as pd
        t = self.csv_tables
        if "code_rule" not in t:
            return pd.DataFrame(columns=["rule", "kind", "hits", "n", "probability", "wilson_lo", "wilson_hi"])
        parts = [t[k].assign(kind=kind) for k, kind in (("code_rule", "formula"), ("code_design", "design")) if k in t]
        rules = pd.concat(parts, ignore_index=True).rename(columns={"name": "rule"})
        if "rule_wilson" not in t:  # a grid study: lo, hi of its code_rule rows are the Wilson interval
            rules = rules.rename(columns={"lo": "wilson_lo", "hi": "wilson_hi"})
            return rules[["rule", "kind", "hits", "n", "probability", "wilson_lo", "wilson_hi"]]
        w = t["rule_wilson"].iloc[:len(rules)]  # then [gaps] existing's (its row: table "existing"), if any
        rules["wilson_lo"], rules["wilson_hi"] = w["lo"].to_numpy(), w["hi"].to_numpy()
        rules["hits"] = rules["hits"].astype("int64")
        return rules[["rule", "kind", "gap_m", "gap_ratio", "hits", "n", "probability", "lo", "hi", "wilson_lo",
                      "wilson_hi"]]

    @property
    def separation_advice(self):
        """The separation advice per target probability, from the CSV report's numbers (the rows the Markdown
        table formats), one row per target: target (a fraction), x (the separation in code gaps d; a bridge's in
        units of its reference gap; a study with [gaps] metres: in metres) and cubic_x (the root of the report's cubic fit, NaN outside its range). A grid
        or bridge study adds lo, hi (the two-stage bootstrap interval of x) and advice_x (its upper end); a pair
        study adds separation_m, lo_m, hi_m (the interval in metres), cubic_m, records_above (of `records`, the
        independent records), resolved (floor(t records) >= 1), lognormal_m, lognormal_lo_m, lognormal_hi_m (the
        parametric estimate) and advice_m: hi_m where resolved, else lognormal_hi_m, as the report advises."""
        import pandas as pd
        t = self.csv_tables
        sep = t["separation"]
        out = pd.DataFrame({"target": sep["probability"], "x": sep["gap_ratio"]})
        if "gap_m" not in sep:  # a grid (or bridge) study: the interval is in gap ratios
            out["lo"], out["hi"] = sep["lo"].to_numpy(), sep["hi"].to_numpy()
            out["advice_x"] = out["hi"]
            cubic = t.get("separation_cubic")
            out["cubic_x"] = cubic["gap_ratio"].to_numpy(dtype=float) if cubic is not None and "gap_ratio" in cubic \
                else np.nan
            return out
        out["separation_m"], out["lo_m"], out["hi_m"] = sep["gap_m"], sep["lo"], sep["hi"]
        cubic = t["separation_cubic"]
        out["cubic_x"] = cubic["gap_ratio"].to_numpy(dtype=float) if "gap_ratio" in cubic else np.nan
        out["cubic_m"] = cubic["gap_m"].to_numpy(dtype=float) if "gap_m" in cubic else np.nan
        out["records_above"], out["records"] = cubic["hits"].to_numpy(), cubic["n"].to_numpy()
        out["resolved"] = sep["name"].isna().to_numpy() if "name" in sep else True  # "not resolved by N records"
        ln = t["separation_lognormal"]
        out["lognormal_m"], out["lognormal_lo_m"], out["lognormal_hi_m"] = (ln[c].to_numpy(dtype=float)
                                                                           for c in ("gap_m", "lo", "hi"))
        out["advice_m"] = np.where(out["resolved"], out["hi_m"], out["lognormal_hi_m"])
        return out

    def period_pair(self, gap_ratio=None):
        """The period-pair map: probability with T1 as rows and T2 as columns at one gap (default: the first the
        CSV report lists)."""
        t = self.csv_tables["period_pair"]
        gcol = t.columns[0]
        g = t[gcol].iloc[0] if gap_ratio is None else gap_ratio
        part = t[np.isclose(t[gcol], g)]
        if part.empty:
            raise KeyError(f"no period-pair map at {gcol} {g}; maps at {sorted(t[gcol].unique())}")
        return part.pivot(index="T1", columns="T2", values="probability")

    @property
    def fragility(self):
        """A fragility study's fit per gap (/fragility): gap, gap_m, status, theta, beta and their bootstrap
        intervals, replicates_failed, note."""
        import pandas as pd
        a = self.arrays("fragility")
        cols = {k: a[k] for k in ("gaps", "gaps_m", "status", "theta", "theta_lo", "theta_hi", "beta", "beta_lo",
                                  "beta_hi", "replicates_failed", "note") if k in a}
        frame = pd.DataFrame(cols).rename(columns={"gaps": "gap"})
        for col in ("status", "note"):
            if col in frame:
                frame[col] = [v.decode() if isinstance(v, bytes) else v for v in frame[col]]
        return frame

    @property
    def hazard(self):
        """A fragility study's annual rate and probability per gap (/hazard) with their intervals."""
        import pandas as pd
        a = self.arrays("hazard")
        n = len(a["annual_rate"])
        frame = pd.DataFrame({k: v for k, v in a.items() if getattr(v, "ndim", 0) == 1 and len(v) == n
                              and not k.startswith("curve_")})
        frame.insert(0, "gap", self.arrays("fragility")["gaps"])
        return frame

    @property
    def hazard_curve(self):
        """The rate-versus-separation curve (/hazard curve_*)."""
        import pandas as pd
        a = self.arrays("hazard")
        return pd.DataFrame({k[len("curve_"):]: v for k, v in a.items() if k.startswith("curve_")})

    def groups(self):
        """The HDF5 groups and their datasets."""
        h5py = _h5py()
        out = {}
        with h5py.File(self.path, "r") as f:
            f.visititems(lambda name, obj: out.setdefault(name.rsplit("/", 1)[0] if "/" in name else "", [])
                         .append(name.rsplit("/", 1)[-1]) if isinstance(obj, h5py.Dataset) else None)
        return out

    def arrays(self, group):
        """The datasets of one HDF5 group (e.g. "uncoupled", "fragility", "hazard") as numpy arrays."""
        h5py = _h5py()
        with h5py.File(self.path, "r") as f:
            if group not in f:
                raise KeyError(f"no group /{group} in {self.path}; groups: {list(f.keys())}")
            return {k: v[()] for k, v in f[group].items() if isinstance(v, h5py.Dataset)}

    def histories(self):
        """The time histories a study stored ([outputs] histories; /histories/1, 2, ...), in order: a list of dicts,
        each with the analysis' attributes (record, record_row, model, i1, i2, sample, run, gap_ratio (none with
        [gaps] metres), gap_m, the peaks, ...) and its arrays: t (s), ag (m/s^2), u [dof, step] (m, relative to the support), a_abs [dof, step]
        (m/s^2), force [element, step] (N), dof_names, element_names. [] when the file holds none."""
        h5py = _h5py()
        out = []
        with h5py.File(self.path, "r") as f:
            if "histories" not in f:
                return out
            for name in sorted(f["histories"].keys(), key=int):
                g = f["histories"][name]
                h = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
                for k, v in g.items():
                    a = v[()]
                    if a.dtype.kind in "OS":
                        a = [x.decode() if isinstance(x, bytes) else str(x) for x in a]
                    h[k] = a
                h["n"] = int(name)
                out.append(h)
        return out

    def frame(self, group):
        """A group's datasets as one DataFrame. 1-D datasets of equal length (e.g. "hazard", "fragility", "models")
        become columns. A group of per-analysis arrays, record x model (e.g. "uncoupled"), becomes one row per
        analysis: columns record (its index), record_id (from /records/id), model (its index) and every dataset of
        that shape. Datasets of other shapes are left out: Results.arrays(group) has them all."""
        import numpy as np
        import pandas as pd
        arrays = self.arrays(group)
        a = {k: v for k, v in arrays.items() if getattr(v, "ndim", 0) == 1}
        if a:
            n = max(len(v) for v in a.values())
            return pd.DataFrame({k: v for k, v in a.items() if len(v) == n})
        two = {k: v for k, v in arrays.items() if getattr(v, "ndim", 0) == 2}
        if not two:
            shapes = {k: getattr(v, "shape", ()) for k, v in arrays.items()}
            raise KeyError(f"/{group} holds neither 1-D nor record x model datasets ({shapes}): "
                           f"use Results.arrays({group!r})")
        shape = max((v.shape for v in two.values()), key=lambda sh: sum(v.shape == sh for v in two.values()))
        r, m = np.meshgrid(np.arange(shape[0]), np.arange(shape[1]), indexing="ij")
        cols = {"record": r.ravel(), "model": m.ravel()}
        ids = self.arrays("records").get("id") if group != "records" else None
        if ids is not None and len(ids) == shape[0]:
            ids = np.array([x.decode() if isinstance(x, bytes) else str(x) for x in ids])
            cols = {"record": cols["record"], "record_id": ids[cols["record"]], "model": cols["model"]}
        for k, v in two.items():
            if v.shape == shape:
                cols[k] = v.ravel()
        return pd.DataFrame(cols)


def _h5py():
    try:
        import h5py
    except ImportError as e:
        raise ImportError("Results.arrays needs h5py (apt-get install python3-h5py)") from e
    return h5py


def markdown_tables(text):
    """{heading: DataFrame} of the pipe tables of a Markdown text (cells as strings)."""
    import pandas as pd
    tables, heading, rows = {}, "", []

    def flush():
        if len(rows) >= 2:
            name, k = heading, 2
            while name in tables:
                name, k = f"{heading} ({k})", k + 1
            tables[name] = pd.DataFrame(rows[1:], columns=rows[0])
        rows.clear()

    for line in text.splitlines():
        if line.startswith("#"):
            flush()
            heading = line.lstrip("#").strip()
        elif line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not all(set(c) <= set("-: ") for c in cells):
                rows.append(cells)
        else:
            flush()
    flush()
    return tables
