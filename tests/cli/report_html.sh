#!/usr/bin/env bash
# The HTML report (issue 29): `pounding report R.h5 --html R.html` for the shipped studies that run in seconds (made
# small), each checked by tests/cli/report_html_check.py against the Markdown report and the HDF5 file (the numbers
# equal, the answer first, every table, the figures inline, nothing loaded from elsewhere); the comparison report of
# two files; [report] html = true in a run; the figures left out, with the reason, when Python is missing, when the
# plotting module fails and when it runs past its time; bad input: one ERROR line, exit 2, no file left.
# Needs Debian's python3 with h5py and numpy (the checker) and matplotlib (the figures): skipped without, a failure
# under CI=true. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/html_studies.sh"
fail() { echo "FAIL: $*"; exit 1; }
check="$py $src/tests/cli/report_html_check.py"

# every shipped study (the fixture's reduced runs): its HTML against its Markdown and HDF5, every figure drawn (the
# reduction must not cost a figure: html_studies.py figures fails on any left out), the machine named
for name in $html_names; do
  n=$("$py" "$src/tests/cli/html_studies.py" figures "$studies/$name.html") || fail "$name: $n"
  $check "$studies/$name.h5" "$studies/$name.report.md" "$studies/$name.html" --figures "$n"
  "$py" - "$studies/$name.h5" "$studies/$name.html" "$studies/$name.report.md" <<'PY' || fail "$name: the machine"
import html, os, sys, h5py
a = h5py.File(sys.argv[1], "r").attrs
want = (os.uname().nodename, os.cpu_count())
got = (a["host"].decode() if isinstance(a["host"], bytes) else a["host"], int(a["cpu_cores"]))
assert got == want, f"the results name {got}, this machine is {want}"
line = f"host '{got[0]}'"
assert line in html.unescape(open(sys.argv[2]).read()), "the HTML provenance does not name the machine"
assert f"- machine: {line}" in open(sys.argv[3]).read(), "the Markdown does not name the machine"
PY
done
echo "checked the HTML of: $html_names"
# a file written before the machine was stored: read, and the report says the machine is not recorded
cp "$studies/quick.h5" "$tmp/old.h5"
"$py" -c 'import sys, h5py; f = h5py.File(sys.argv[1], "r+"); [f.attrs.__delitem__(k) for k in ("host", "cpu_model", "cpu_cores")]' "$tmp/old.h5"
"$bin" report "$tmp/old.h5" > "$tmp/old.md"
grep -q '^- machine: not recorded' "$tmp/old.md" || fail "a file without the machine: no 'not recorded'"
# the accuracy statement's hints name the study keys beside the options (quick-impacts: lankarani-nikravesh, impacts)
for want in '[contact] damping_law = &quot;calibrated&quot; in the study (--damping-law calibrated on the command line)' \
            '<code>[analysis] substeps = N</code>'; do
  grep -qF "$want" "$studies/quick-impacts.html" || fail "the accuracy statement lacks: $want"
done
# the figures as the HTML report draws them pass the figure-layout checks (tests/cli/plot_layout.py, as cli.plot_layout
# checks the tools' PNGs): a pair study (x-axis near the data, advice labels beside their points) and a risk study
stripes=$("$py" -c 'import sys, h5py; l = h5py.File(sys.argv[1])["fragility/levels"][()]; print(f"{l.min()!r},{l.max()!r}")' "$studies/fragility-pair.h5")
mkdir -p "$tmp/layout-pair" "$tmp/layout-risk"
"$py" "$src/tests/cli/plot_layout.py" --pair-report "$studies/example-pair.csv" -- "$src/tools/pounding_plots.py" figures \
  "$studies/example-pair.h5" --dir "$tmp/layout-pair" --report-csv "$studies/example-pair.csv"
"$py" "$src/tests/cli/plot_layout.py" --stripes "$stripes" -- "$src/tools/pounding_plots.py" figures \
  "$studies/fragility-pair.h5" --dir "$tmp/layout-risk"

# the report printed by the run and `pounding report` agree (the HTML quotes the latter)
cmp -s <(grep -v '^- results:' "$studies/quick.md") <(grep -v '^- results:' "$studies/quick.report.md") ||
  fail "the run's report and \`pounding report\` differ for quick"

# two files side by side: polarity "both" against as recorded
sed -e 's/^polarity = .*//' -e 's/^\[records\]/[records]\npolarity = "recorded"/' "$studies/studies/example-pair.toml" \
  > "$tmp/recorded.toml"
"$bin" run "$tmp/recorded.toml" --out "$tmp/recorded.h5" --quiet > /dev/null
"$bin" report "$tmp/recorded.h5" > "$tmp/recorded.report.md"
"$bin" report "$studies/example-pair.h5" "$tmp/recorded.h5" --html "$tmp/compare.html" --no-figures
$check "$studies/example-pair.h5" "$studies/example-pair.report.md" "$tmp/compare.html" --compare "$tmp/recorded.h5" \
  "$tmp/recorded.report.md"
grep -q 'id="s2-answer"' "$tmp/compare.html" || fail "the comparison has no second answer block"

# figures left out, with the reason; every table still there
POUNDING_PYTHON=/nonexistent/python3 "$bin" report "$studies/quick.h5" --html "$tmp/nopy.html"
$check "$studies/quick.h5" "$studies/quick.report.md" "$tmp/nopy.html" --left-out "no Python interpreter at '/nonexistent/python3'"
printf 'import sys\nsys.exit("plots: matplotlib is broken here")\n' > "$tmp/broken.py"
POUNDING_PLOTS=$tmp/broken.py "$bin" report "$studies/quick.h5" --html "$tmp/broken.html"
$check "$studies/quick.h5" "$studies/quick.report.md" "$tmp/broken.html" --left-out "matplotlib is broken here"
printf 'import time\ntime.sleep(60)\n' > "$tmp/slow.py"
start=$(date +%s)
POUNDING_PLOTS=$tmp/slow.py POUNDING_FIGURE_TIMEOUT=1 "$bin" report "$studies/quick.h5" --html "$tmp/slow.html"
[ $(($(date +%s) - start)) -lt 20 ] || fail "the figure time limit did not stop the plotting module"
$check "$studies/quick.h5" "$studies/quick.report.md" "$tmp/slow.html" --left-out "did not finish within 1 s"
"$bin" report "$studies/quick.h5" --html "$tmp/asked.html" --no-figures
$check "$studies/quick.h5" "$studies/quick.report.md" "$tmp/asked.html" --left-out "on request"

# [report] html = true: written next to the results at the end of the run; its path is checked before any work
sed 's/^\[report\]/[report]\nhtml = true/' "$studies/studies/quick.toml" > "$studies/studies/quick-html.toml"
grep -q '^html = true' "$studies/studies/quick-html.toml" || fail "studies/quick.toml has no [report] section any more"
mkdir -p "$tmp/run" "$tmp/run/quick-html.html"
if "$bin" run "$studies/studies/quick-html.toml" --out "$tmp/run/quick-html.h5" --quiet > /dev/null 2> "$tmp/dir.err"; then
  fail "[report] html = true into a path that is a directory was accepted"
fi
grep -q 'ERROR: .*quick-html.html.*\[report\] html = true' "$tmp/dir.err" || fail "no clear error: $(cat "$tmp/dir.err")"
[ ! -e "$tmp/run/quick-html.h5" ] || fail "the run wrote results although its HTML path was refused"
rmdir "$tmp/run/quick-html.html"
"$bin" run "$studies/studies/quick-html.toml" --out "$tmp/run/quick-html.h5" --quiet > "$tmp/run/quick-html.md" 2> "$tmp/run.err"
[ -s "$tmp/run/quick-html.html" ] || fail "[report] html = true wrote no $tmp/run/quick-html.html: $(cat "$tmp/run.err")"
"$bin" report "$tmp/run/quick-html.h5" > "$tmp/run/quick-html.report.md"
$check "$tmp/run/quick-html.h5" "$tmp/run/quick-html.report.md" "$tmp/run/quick-html.html" --figures 2
ls "$tmp/run" | grep -q '\.tmp' && fail "a temporary file was left in $tmp/run: $(ls "$tmp/run")"

# bad input: one ERROR line, exit 2, nothing written
expect_error() {  # <what it must say> <command...>
  local want=$1; shift
  set +e; "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"; local rc=$?; set -e
  [ "$rc" = 2 ] || fail "exit $rc (not 2) from: $* ($(cat "$tmp/bad.err"))"
  [ "$(grep -c 'ERROR' "$tmp/bad.err")" = 1 ] && grep -q "$want" "$tmp/bad.err" ||
    fail "not one clear error saying '$want' from: $*: $(cat "$tmp/bad.err")"
}
expect_error "cannot open HDF5 file" "$bin" report "$src/README.md" --html "$tmp/bad1.html"
[ ! -e "$tmp/bad1.html" ] || fail "a report of a bad input left $tmp/bad1.html"
expect_error "does not exist" "$bin" report "$studies/quick.h5" --html "$tmp/no/such/folder.html"
# a folder given as the page: the fix names --html and an .html file, not --out results.h5
expect_error "e.g. --html $tmp/report.html" "$bin" report "$studies/quick.h5" --html "$tmp/"
mkdir "$tmp/adir"
expect_error "adir" "$bin" report "$studies/quick.h5" --html "$tmp/adir"
expect_error "2 results files" "$bin" report "$studies/quick.h5" "$studies/example-pair.h5"
set +e; "$bin" report "$studies/quick.h5" --html "$tmp/x.html" --csv > /dev/null 2> "$tmp/bad.err"; rc=$?; set -e
[ "$rc" = 2 ] && grep -q "^ ERROR: --.* and --.* of pounding report cannot be given together, command line, give one of them" "$tmp/bad.err" ||
  fail "--html with --csv: exit $rc, $(cat "$tmp/bad.err")"
# README shows the first screen of studies/example-pair.toml's report (a small PNG in docs/img)
img=$src/docs/img/report-example-pair.png
grep -q '](docs/img/report-example-pair.png)' "$src/README.md" || fail "README does not show docs/img/report-example-pair.png"
[ "$(head -c 4 "$img" | od -An -tx1 | tr -d ' \n')" = "89504e47" ] && [ "$(wc -c < "$img")" -lt 200000 ] ||
  fail "$img is not a PNG under 200 kB"
echo "report_html: ok ($(echo $html_names | wc -w) studies (the machine named; the hints name the study keys), the comparison, figures left out 4 ways, [report] html, bad input)"
