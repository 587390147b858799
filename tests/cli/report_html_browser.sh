#!/usr/bin/env bash
# The HTML report in a real browser (issue 29): the reports of a pair, a risk and a grid study (made small,
# tests/lib/html_studies.sh; each Chromium start costs seconds of waiting) and a comparison report, opened in headless Chromium by tests/cli/report_html_browser.py:
# no console message, no request leaves the file (Chromium's net log), every figure has a non-empty bounding box,
# the answer block is in the first screen (1280 x 800); the first screen (PNG) and the print (PDF) of each are
# written to <build>/report-html/. A planted report (an image from the network, a console error, a figure of no
# size, the answer pushed below the first screen) must fail every check.
# Needs Debian's chromium (tools/setup.sh installs it) and python3 with matplotlib, h5py, numpy: skipped with the
# reason without them, a failure under CI=true. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"
. "$src/tests/lib/html_studies.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import matplotlib, h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with matplotlib, h5py and numpy (Debian: python3-matplotlib python3-h5py python3-numpy; tools/setup.sh installs them)"
chromium=${POUNDING_CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$chromium" ] || skip_or_fail "needs Debian's chromium (apt-get install chromium; tools/setup.sh installs it)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
out=$(cd "$(dirname "$bin")" && pwd)/report-html
export MPLBACKEND=Agg

html_studies example-pair fragility-pair quick  # a pair, a risk and a grid study (cli.report_html has them all)
reports=()
for name in $html_names; do
  "$bin" report "$tmp/$name.h5" --html "$tmp/$name.html"
  reports+=("$tmp/$name.html")
done
"$bin" report "$tmp/example-pair.h5" "$tmp/fragility-pair.h5" --html "$tmp/compare.html"
reports+=("$tmp/compare.html")
set +e
"$py" "$src/tests/cli/report_html_browser.py" "$chromium" "$out" "${reports[@]}"
rc=$?
set -e
[ "$rc" = 77 ] && skip_or_fail "chromium cannot run headless here (above)"
[ "$rc" = 0 ] || { echo "FAIL: the reports above"; exit 1; }

# the negative control: each defect planted must be found
"$py" - "$tmp/example-pair.html" "$tmp/planted.html" <<'PY'
import sys
s = open(sys.argv[1]).read()
s = s.replace('<section class="answer"', '<div style="height:900px"></div><section class="answer"', 1)
s = s.replace("</body>", '<img src="http://198.51.100.7/x.png" alt=""><script>console.error("planted")</script>'
              '<figure id="empty"><svg viewBox="0 0 1 1" style="display:none"></svg></figure></body>', 1)
open(sys.argv[2], "w").write(s)
PY
set +e
"$py" "$src/tests/cli/report_html_browser.py" "$chromium" "$tmp/planted-out" "$tmp/planted.html" > "$tmp/planted.log"
rc=$?
set -e
for want in "console: CONSOLE" "198.51.100.7" "figure empty has an empty bounding box" "not within the first screen"; do
  grep -q "$want" "$tmp/planted.log" || { cat "$tmp/planted.log"; echo "FAIL: the planted defect '$want' was not found"; exit 1; }
done
[ "$rc" = 1 ] || { echo "FAIL: the planted report passed (exit $rc)"; exit 1; }
echo "report_html_browser: ok (${#reports[@]} reports; screenshots and PDFs in $out)"
