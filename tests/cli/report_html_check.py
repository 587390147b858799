#!/usr/bin/python3
"""Checks one HTML report (`pounding report R.h5 --html R.html`) against the Markdown report of the same file and
against the HDF5 file itself (issue 29: "the numbers in the HTML equal those in the Markdown and in the HDF5
file"). Reads the HTML with html.parser (no browser):
  - one self-contained page: a doctype, a Content-Security-Policy that forbids every load, no <script>, no
    src/href/url() that leaves the file, no @import;
  - the answer block comes before the figures, and every cell of its tables is a cell of the Markdown's tables;
  - every table of the Markdown is in the HTML, cell for cell (inline ** and ` removed), in the same order;
  - numbers recomputed from the HDF5 file with numpy (not the engine): Table 3's "hits / n" at each gap ratio; a
    pair study's separation at each target (the exact order statistic, millimetres); a fragility study's theta per
    gap and the risk-targeted separation; the records' ids in the provenance;
  - --figures N: N <figure> elements each holding an <svg> with a viewBox; --left-out WORD: no figure, and the
    "Figures left out" list names WORD.
Usage: report_html_check.py R.h5 R.md R.html [--figures N | --left-out WORD] [--compare R2.h5 R2.md]
Exit 1 listing every failure."""
import html.parser
import math
import re
import sys

import h5py
import numpy as np

args = sys.argv[1:]
h5_path, md_path, html_path = args[:3]
opts = args[3:]
failures = []


def fail(msg):
    failures.append(msg)


def plain(cell):
    return cell.replace("**", "").replace("`", "").strip()


def md_tables(text):
    """Every pipe table of the Markdown: a list of rows (cells, inline markup removed), rule rows dropped."""
    tables, cur = [], None
    for line in text.splitlines():
        if line.startswith("|"):
            cells = [plain(c.replace("\\|", "|")) for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
            if all(set(c) <= set("-: ") and c for c in cells):
                continue
            if cur is None:
                cur = []
                tables.append(cur)
            cur.append(cells)
        else:
            cur = None
    return tables


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tables, self.stack, self.cell, self.row = [], [], None, None
        self.order, self.scripts, self.external, self.csp = [], 0, [], ""
        self.figures, self.svg_in_figure, self.viewbox = 0, [], []
        self.doctype = False
        self.in_figure = False
        self.section = []
        self.table_section = []
        self.left_out = ""
        self.in_left_out = False

    def handle_decl(self, decl):
        self.doctype = self.doctype or decl.lower().startswith("doctype html")

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "script":
            self.scripts += 1
        if tag == "meta" and a.get("http-equiv", "").lower() == "content-security-policy":
            self.csp = a.get("content", "")
        for key in ("src", "href", "xlink:href", "action", "poster", "data"):
            v = a.get(key)
            if v is not None and not v.startswith("#") and not v.startswith("data:"):
                self.external.append(f"<{tag} {key}={v!r}>")
        if "style" in a and re.search(r"url\((?!['\"]?(#|data:))", a["style"]):
            self.external.append(f"<{tag} style={a['style']!r}>")
        if tag == "section" and "id" in a:
            self.order.append(a["id"])
            self.section.append(a["id"])
        elif tag == "section":
            self.section.append("")
        if tag == "figure":
            self.figures += 1
            self.in_figure = True
            self.svg_in_figure.append(False)
        if tag == "svg" and self.in_figure:
            self.svg_in_figure[-1] = True
            self.viewbox.append(a.get("viewbox", a.get("viewBox", "")))
        if tag == "table":
            self.tables.append([])
            self.table_section.append(next((s for s in reversed(self.section) if s), ""))
        if tag == "tr":
            self.row = []
            self.tables[-1].append(self.row)
        if tag in ("td", "th"):
            self.cell = ""
        if tag == "ul" and "left-out" in a.get("class", ""):
            self.in_left_out = True

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.cell is not None:
            self.row.append(" ".join(self.cell.split()))
            self.cell = None
        if tag == "figure":
            self.in_figure = False
        if tag == "section" and self.section:
            self.section.pop()
        if tag == "ul":
            self.in_left_out = False

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data
        if self.in_left_out:
            self.left_out += data


text = open(html_path, encoding="utf-8").read()
page = Page()
page.feed(text)
md = open(md_path, encoding="utf-8").read()

# --- one self-contained page -----------------------------------------------------------------------------------
if not page.doctype:
    fail("no <!DOCTYPE html>")
if "default-src 'none'" not in page.csp:
    fail(f"no Content-Security-Policy forbidding loads (got {page.csp!r})")
if page.scripts:
    fail(f"{page.scripts} <script> elements (the report needs none)")
if page.external:
    fail(f"references that leave the file: {page.external[:5]}")
for m in re.finditer(r"url\(([^)]*)\)|@import", text):
    target = (m.group(1) or "@import").strip("'\" ")
    if not (target.startswith("#") or target.startswith("data:")):
        fail(f"CSS loads {target!r}")
        break

# --- the answer first, then the figures ---------------------------------------------------------------------
compare = "--compare" in opts
answer_id = "s1-answer" if compare else "answer"
if answer_id not in page.order:
    fail(f"no section id={answer_id!r} (the answer block)")
elif not compare and ("figures" not in page.order or page.order.index("answer") > page.order.index("figures")):
    fail(f"the answer does not come before the figures: {page.order}")

md_list = md_tables(md)
md_cells = {c for t in md_list for row in t for c in row}
if compare:
    md2 = open(opts[opts.index("--compare") + 2], encoding="utf-8").read()
    md_list2 = md_tables(md2)
    md_cells |= {c for t in md_list2 for row in t for c in row}
answer_tables = [t for t, s in zip(page.tables, page.table_section) if s.endswith("answer")]
for t in answer_tables:
    for row in t:
        for c in row:
            if c not in md_cells:
                fail(f"answer cell {c!r} is not a cell of the Markdown's tables")
answer_text = text[text.find(f'id="{answer_id}"'):]
answer_text = answer_text[:answer_text.find("</section>")]

# --- every Markdown table, cell for cell, in order --------------------------------------------------------------
report_tables = [t for t, s in zip(page.tables, page.table_section) if s in ("report", "s1")]
if compare:
    report_tables_2 = [t for t, s in zip(page.tables, page.table_section) if s == "s2"]
at = 0
for i, t in enumerate(md_list):
    while at < len(report_tables) and report_tables[at] != t:
        at += 1
    if at == len(report_tables):
        fail(f"Markdown table {i + 1} (header {t[0][:4]}) is not in the HTML in order, cell for cell")
        break
    at += 1
if compare:
    for i, t in enumerate(md_list2):
        if t not in report_tables_2:
            fail(f"B's Markdown table {i + 1} (header {t[0][:4]}) is not in the HTML")
if not md_list:
    fail("the Markdown report has no table")


# --- numbers from the HDF5 file (numpy, not the engine) ----------------------------------------------------------
def find_table(tables, first_header):
    return next((t for t in tables if t and t[0] and t[0][0].startswith(first_header)), None)


f = h5py.File(h5_path, "r")
checked = []
if "uncoupled" in f and "fragility" not in f:
    pc = f["uncoupled/peak_closing"][()]
    R, M = pc.shape
    ok = f["uncoupled/status"][()].reshape(R, M) == 0
    d = f["models/code_gap"][()]
    metres = "gaps" in f and f["gaps"].attrs.get("unit", b"") in (b"m", "m")  # [gaps] metres: every model's gap x
    if metres:
        d = np.ones_like(d)
    t3 = find_table(report_tables, "gap m" if metres else "gap ratio")
    if t3 is None:
        fail(f"no Table 3 ({'gap m' if metres else 'gap ratio'} | models with impact) in the HTML")
    else:
        for row in t3[1:]:
            x = float(row[0])
            hits, n = int(np.sum((pc > x * d[None, :]) & ok)), int(ok.sum())
            if row[1] != f"{hits} / {n}":
                fail(f"Table 3 at {x}: HTML {row[1]!r}, HDF5 {hits} / {n}")
        checked.append(f"Table 3 ({len(t3) - 1} rows)")
    if "settings/gaps" in f and "existing" in f["settings/gaps"].attrs:  # [gaps] existing: its P in the answer
        e = float(f["settings/gaps"].attrs["existing"])
        hits, n = int(np.sum((pc > e) & ok)), int(ok.sum())
        if f"({hits} of {n} analyses" not in answer_text:
            fail(f"P(pounding) at the existing gap {e} m ({hits} of {n}, HDF5) is not in the answer block")
        checked.append(f"existing gap {e} m")
    sep = find_table(report_tables, "P(at least one impact)")
    if sep is not None:
        z = np.sort(pc[ok])[::-1]  # descending; with polarity both the rows are records x signs, same analyses
        n = z.size
        for row in sep[1:]:
            t = float(row[0].rstrip("%")) / 100
            k = int(math.floor(t * n + 1e-9))
            want = f"{z[k]:.3f}" if k < n else f"{0.0:.3f}"
            if row[1] != want:
                fail(f"separation at {row[0]}: HTML {row[1]} m, HDF5 order statistic {want} m (k = {k} of n = {n})")
            if row[1] not in answer_text:
                fail(f"separation {row[1]} m at {row[0]} is not in the answer block")
        checked.append(f"separation ({len(sep) - 1} targets)")
if "fragility" in f:
    g = f["fragility"]
    ft = find_table(report_tables, "gap")
    theta = g["theta"][()]
    if ft is None:
        fail("no fragility table in the HTML")
    else:
        for k, row in enumerate(ft[1:]):
            want = f"{theta[k]:.4g}" if np.isfinite(theta[k]) else "n/a"
            if row[1] != want:
                fail(f"theta of gap {row[0]}: HTML {row[1]}, HDF5 {want}")
        checked.append(f"theta ({len(ft) - 1} gaps)")
    if "hazard" in f and f["hazard"].attrs.get("target_status", b"") in (b"ok", "ok"):
        h = f["hazard"].attrs
        pair = "gaps_m" in g
        want = f"{h['target_gap_m']:.3f} m" if pair else f"{h['target_gap']:.3g} d"
        if want not in answer_text:
            fail(f"the risk-targeted separation {want} (HDF5 /hazard) is not in the answer block")
        checked.append(f"risk-targeted separation {want}")
ids = [x.decode() if isinstance(x, bytes) else str(x) for x in f["records/id"][()]]
prov = text[text.find('id="provenance"' if not compare else 'id="s1-provenance"'):]
missing = [i for i in dict.fromkeys(ids) if f"<td>{i}</td>" not in prov]
if missing:
    fail(f"records missing from the provenance: {missing[:5]}")
if f.attrs["study_text"] and not compare:
    st = f.attrs["study_text"]
    st = st.decode() if isinstance(st, bytes) else st
    first = next((line for line in st.splitlines() if line.strip()), "")
    if first and first not in html.unescape(text):
        fail(f"the study text is not in the provenance (line {first!r})")

# --- figures --------------------------------------------------------------------------------------------------------
if "--figures" in opts:
    want = int(opts[opts.index("--figures") + 1])
    if page.figures != want or not all(page.svg_in_figure):
        fail(f"{page.figures} figures ({sum(page.svg_in_figure)} with an <svg>), expected {want}")
    if any(not v for v in page.viewbox):
        fail("a figure's <svg> has no viewBox (it cannot scale)")
if "--left-out" in opts:
    word = opts[opts.index("--left-out") + 1]
    if page.figures:
        fail(f"{page.figures} figures drawn, expected none")
    if word not in page.left_out:
        fail(f"the 'Figures left out' list does not say {word!r}: {page.left_out.strip()[:200]!r}")

for m in failures:
    print(f"FAIL: {html_path}: {m}")
if not failures:
    print(f"ok {html_path}: {len(report_tables)} tables equal the Markdown's; from the HDF5: {', '.join(checked)}; "
          f"{page.figures} figures")
sys.exit(1 if failures else 0)
