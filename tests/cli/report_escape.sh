#!/usr/bin/env bash
# User strings cannot forge or shift the report (issue 44 item 9): a pair study whose title holds newlines, a
# forged "Separation for this pair" heading with a table row advising 0.001 m, and <script>, on a record file whose
# name holds a '|', run beside the same study with a plain title. The Markdown report has one separation heading and
# its table equals the plain study's, no forged row, no raw HTML tag, and Table 2 as many cells in every row as in its
# header; the HTML's answer box equals the plain study's, with no <script> anywhere and the record named as given.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
py=${POUNDING_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$bin" records synth --M 6.9 --R 15 --vs30 300 --F 1 --seed 3 --pga 0.4 -o "$tmp/EQ|A.AT2" > /dev/null
"$bin" records synth --M 6.5 --R 20 --vs30 400 --F 1 --seed 4 --pga 0.3 -o "$tmp/EQ-B.AT2" > /dev/null
study() {  # <file> <title line>: a small pair (heights given: the answer in metres)
  cat > "$1" <<EOF
$2
seed = 7
scene = "probability"

[records]
files = ["EQ|A.AT2", "EQ-B.AT2"]

[structures]
samples_per_pair = 20

[structures.building1]
period = {lognormal = {median = 0.9, cov = 0.15}}
height = 28.0
mass = 3.1e6

[structures.building2]
period = {lognormal = {median = 1.3, cov = 0.15}}
height = 42.0
mass = 4.7e6

[gaps]
ratios = [0.25, 0.5, 1.0]

[report]
targets = [10, 5]
bootstrap = 200
EOF
}
study "$tmp/plain.toml" 'title = "plain"'
study "$tmp/forged.toml" \
  'title = "plain\n\n## Separation for this pair, in metres\n\n| P(at least one impact) | separation m | 95 % interval m | advice m (upper end) |\n|---|---|---|---|\n| 10% | 0.001 | [0.001, 0.001] | **0.001** |\n<script>alert(1)</script>"'
for s in plain forged; do
  (cd "$tmp" && "$bin" run "$s.toml" --out "$s.h5" --quiet > "$s.md" 2> "$s.err") || { cat "$tmp/$s.err"; fail "$s: run"; }
  "$bin" report "$tmp/$s.h5" --html "$tmp/$s.html" --no-figures > /dev/null 2> "$tmp/$s.html.err" ||
    { cat "$tmp/$s.html.err"; fail "$s: report --html"; }
done

"$py" - "$tmp" <<'PY'
import html.parser, re, sys
tmp = sys.argv[1]
def read(name):
    return open(f"{tmp}/{name}", encoding="utf-8").read()
def section(md, heading):  # the lines after `heading` up to the next heading
    lines = md.splitlines()
    at = lines.index(heading)
    out = []
    for line in lines[at + 1:]:
        if line.startswith("#"):
            break
        out.append(line)
    return out
def pipes(row):  # unescaped '|' of a Markdown table row
    return len(re.findall(r"(?<!\\)(?:\\\\)*\|", row))
plain, forged = read("plain.md"), read("forged.md")
errors = []
sep = "## Separation for this pair, in metres"
n = sum(line.startswith("## Separation for this pair") for line in forged.splitlines())
if n != 1:
    errors.append(f"the forged report has {n} 'Separation for this pair' headings (the title made one)")
elif section(forged, sep) != section(plain, sep):
    errors.append("the forged report's separation table differs from the plain study's")
for line in forged.splitlines():
    if "0.001 | [0.001, 0.001]" in line and line.startswith("|"):
        errors.append(f"the forged table row is a row of the report: {line}")
    if re.search(r"(?<!\\)<[A-Za-z/!?]", line):
        errors.append(f"a raw HTML tag in the Markdown: {line[:120]}")
if not forged.startswith("# Pounding study: plain  ## Separation for this pair, in metres  "):
    errors.append("the title is not one heading line: " + forged.splitlines()[0][:120])
# Table 2: the record with '|' in its name keeps the columns in place
for name, md in (("plain", plain), ("forged", forged)):
    table = [l for l in section(md, "## Probability of at least one impact per record (Table 2)") if l.startswith("|")]
    if len(table) != 4 or any(pipes(row) != pipes(table[0]) for row in table):
        errors.append(f"{name}: Table 2's rows do not have the header's columns: {table}")
    if not any(row.startswith("| EQ\\|A |") for row in table):
        errors.append(f"{name}: Table 2 does not name the record EQ|A (escaped as EQ\\|A): {table}")

class Page(html.parser.HTMLParser):  # the answer box's text and every table's rows of cells
    def __init__(self):
        super().__init__()
        self.depth, self.answer, self.tables, self.tags, self.cell = 0, [], [], [], None
    def handle_starttag(self, tag, attrs):
        self.tags.append(tag.lower())
        if tag == "section" and ("class", "answer") in attrs:
            self.depth = 1
        elif tag == "section" and self.depth:
            self.depth += 1
        if tag == "table":
            self.tables.append([])
        if tag == "tr":
            self.tables[-1].append([])
        if tag in ("td", "th"):
            self.cell = ""
    def handle_endtag(self, tag):
        if tag == "section" and self.depth:
            self.depth -= 1
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self.cell.strip())
            self.cell = None
    def handle_data(self, data):
        if self.depth:
            self.answer.append(data)
        if self.cell is not None:
            self.cell += data
pages = {}
for name in ("plain", "forged"):
    p = Page()
    p.feed(read(f"{name}.html"))
    pages[name] = p
    if "script" in p.tags:
        errors.append(f"{name}.html has a <script> element")
    t2 = [t for t in p.tables if t and t[0][:3] == ["record", "synthetic", "PGA g"]]
    if len(t2) != 1 or any(len(row) != len(t2[0][0]) for row in t2[0]) or ["EQ|A"] != [r[0] for r in t2[0] if "|" in r[0]]:
        errors.append(f"{name}.html: Table 2 is not one table with the record EQ|A in its own cell: {t2}")
if "".join(pages["forged"].answer) != "".join(pages["plain"].answer):
    errors.append("the forged HTML's answer differs from the plain study's:\n  " + "".join(pages["forged"].answer)[:600])
if "0.001" in "".join(pages["forged"].answer):
    errors.append("the forged 0.001 m is in the HTML's answer")
if "&lt;script&gt;alert(1)&lt;/script&gt;" not in read("forged.html"):
    errors.append("the title's <script> is not shown as text in the HTML")
for e in errors:
    print("FAIL:", e)
if errors:
    sys.exit(1)
print("ok: the forged title and the record name EQ|A change neither the answer nor the tables (Markdown and HTML)")
PY
