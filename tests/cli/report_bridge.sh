#!/usr/bin/env bash
# Bridge reports (issue 45 item 3), on studies/bridge-joint.toml with 6 generated realisations and targets 10, 5, 1 %:
#  1. the joint-gap advice of a target 6 records do not resolve (floor(t N) = 0: every target here) is marked "not
#     resolved by 6 records" with the lognormal's upper end, as the building report does (one rule, resolved_by), in
#     the Markdown and the CSV's separation rows;
#  2. generated motions ([records.motions]) are labelled generated, never real: the overview's count, the per-record
#     table and the HTML records table;
#  3. every Markdown table row has its header's number of cells (a joint label "joint 1 (segment 1|segment 2)" is
#     escaped; unescaped it split the cell) and so does every HTML table row;
#  4. studies/four-frame-bridge.toml in a clone without ../shared/records/real stops with one error naming the
#     folder the real records go in and the README that describes them (exit 2).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/clone/studies"
sed -e 's/^realisations = 20/realisations = 6/' -e 's/^targets = \[10, 5\]/targets = [10, 5, 1]/' -e '/^output = /d' \
  "$src/studies/bridge-joint.toml" > "$tmp/bj.toml"
grep -q '^realisations = 6' "$tmp/bj.toml" && grep -q '^targets = \[10, 5, 1\]' "$tmp/bj.toml"
"$bin" run "$tmp/bj.toml" --out "$tmp/bj.h5" --quiet > "$tmp/run.md" 2> "$tmp/run.log" || { cat "$tmp/run.log"; exit 1; }
"$bin" report "$tmp/bj.h5" > "$tmp/report.md"
"$bin" report "$tmp/bj.h5" --csv > "$tmp/report.csv"
"$bin" report "$tmp/bj.h5" --html "$tmp/report.html"
"$py" - "$tmp" <<'PY'
import csv, re, sys
from html.parser import HTMLParser
tmp = sys.argv[1]
for name in ("run.md", "report.md"):
    md = open(f"{tmp}/{name}").read()
    # 1. the advice: every target unresolved by 6 records
    sec = md[md.index("## Joint gap advice"):]
    sec = sec[:sec.find("\n## ", 1)]
    rows = [l for l in sec.splitlines() if re.match(r"\| \d+% \|", l)]
    assert len(rows) == 3, rows
    for l in rows:
        assert "not resolved by 6 records; lognormal: **" in l, (name, l)
    # 2. generated, not real
    assert "- 6 records (6 generated, 0 synthetic stand-ins, 0 real)" in md, (name, [l for l in md.splitlines() if "records (" in l])
    per = md[md.index("## Probability of at least one impact per record"):]
    assert re.search(r"\| r001 \| generated \|", per), name
    # 3. every table row has its header's cells (a '|' inside a cell is escaped as \|)
    cells = lambda l: len(re.split(r"(?<!\\)\|", l.strip())) - 2
    table = None
    for l in md.splitlines():
        if l.startswith("|"):
            if table is None:
                table = cells(l)
            assert cells(l) == table, (name, table, l)
        else:
            table = None
    assert "(segment 1\\|segment 2)" in md, name
notes = [r["name"] for r in csv.DictReader(open(f"{tmp}/report.csv")) if r["table"] == "separation"]
assert notes == ["not resolved by 6 records"] * 3, notes
assert sum(r["table"] == "separation_lognormal" for r in csv.DictReader(open(f"{tmp}/report.csv"))) == 3

class Tables(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tables, self.row, self.cell = [], None, None
    def handle_starttag(self, tag, attrs):
        if tag == "table": self.tables.append([])
        elif tag == "tr": self.row = []
        elif tag in ("td", "th"): self.cell = ""
    def handle_endtag(self, tag):
        if tag in ("td", "th"): self.row.append(self.cell); self.cell = None
        elif tag == "tr": self.tables[-1].append(self.row)
    def handle_data(self, data):
        if self.cell is not None: self.cell += data
t = Tables()
t.feed(open(f"{tmp}/report.html").read())
assert t.tables
for rows in t.tables:
    assert all(len(r) == len(rows[0]) for r in rows), rows
    head = rows[0]
    if "synthetic" in head:  # the records table
        col = head.index("synthetic")
        assert {r[col] for r in rows[1:]} == {"generated"}, {r[col] for r in rows[1:]}
assert any("joint 1 (segment 1|segment 2)" in c for rows in t.tables for r in rows for c in r)
print("report_bridge: unresolved advice marked, generated motions labelled, tables aligned (md and html)")
PY
# 4. the paper's bridge on a clone without the real records: one error saying where they go
cp "$src/studies/four-frame-bridge.toml" "$tmp/clone/studies/"
set +e
(cd "$tmp/clone" && "$bin" run studies/four-frame-bridge.toml --out ff.h5 --quiet) > "$tmp/ff.out" 2>&1
rc=$?
set -e
cat "$tmp/ff.out"
[ "$rc" = 2 ] || { echo "FAIL: exit $rc, not 2"; exit 1; }
[ "$(grep -c 'ERROR' "$tmp/ff.out")" = 1 ] || { echo "FAIL: not one ERROR line"; exit 1; }
grep -q "6 of the study's 6 record files are missing from the real records" "$tmp/ff.out"
grep -q "expected in $tmp/shared/records/real" "$tmp/ff.out"
grep -q "../shared/records/README.md" "$tmp/ff.out"
[ ! -e "$tmp/clone/ff.h5" ] || { echo "FAIL: a results file was written"; exit 1; }
echo "1 passed, 0 failed"
