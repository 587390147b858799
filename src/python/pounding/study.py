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
        return self.section("Code separation rules")

    @property
    def separation_advice(self):
        return self.section("Separation advice")

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

    def frame(self, group):
        """The 1-D datasets of a group of equal length as one DataFrame (e.g. "hazard", "fragility")."""
        import pandas as pd
        a = {k: v for k, v in self.arrays(group).items() if getattr(v, "ndim", 0) == 1}
        if not a:
            raise KeyError(f"/{group} holds no 1-D datasets")
        n = max(len(v) for v in a.values())
        return pd.DataFrame({k: v for k, v in a.items() if len(v) == n})


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
