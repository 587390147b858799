#!/usr/bin/env bash
# The HTML report in a real browser (issue 29): the report of EVERY shipped study (made small by the ctest fixture
# html_studies, tests/cli/html_studies.sh) and a comparison report, opened in ONE headless Chromium by
# tests/cli/report_html_browser.py (the DevTools protocol on a pipe): no console message, no request leaves the
# file, every figure has a non-empty bounding box, the answer block is in the first screen (1280 x 800); the first
# screen (PNG) and the print (PDF) of each are written to <build>/report-html/. A planted report (an image from the
# network, a console error, a figure of no size, the answer pushed below the first screen) must fail every check.
# Needs Debian's chromium (tools/setup.sh installs it) and python3 with matplotlib, h5py, numpy: skipped with the
# reason without them, a failure under CI=true. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/html_studies.sh"
chromium=${POUNDING_CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$chromium" ] || skip_or_fail "needs Debian's chromium (apt-get install chromium; tools/setup.sh installs it)"
out=$(cd "$(dirname "$bin")" && pwd)/report-html

reports=()
for name in $html_names; do reports+=("$studies/$name.html"); done
"$bin" report "$studies/example-pair.h5" "$studies/fragility-pair.h5" --html "$tmp/compare.html"
reports+=("$tmp/compare.html")
"$py" - "$studies/example-pair.html" "$tmp/planted.html" <<'PY'
import sys
s = open(sys.argv[1]).read()
s = s.replace('<section class="answer"', '<div style="height:900px"></div><section class="answer"', 1)
s = s.replace("</body>", '<img src="http://198.51.100.7/x.png" alt=""><script>console.error("planted")</script>'
              '<figure id="empty"><svg viewBox="0 0 1 1" style="display:none"></svg></figure></body>', 1)
open(sys.argv[2], "w").write(s)
PY
set +e
"$py" "$src/tests/cli/report_html_browser.py" "$chromium" "$out" "${reports[@]}" "$tmp/planted.html" > "$tmp/browser.log"
rc=$?
set -e
cat "$tmp/browser.log"
[ "$rc" = 77 ] && skip_or_fail "chromium cannot run headless here (above)"
# every real report passed; the planted one failed on each defect planted (one Chromium for all: the planted page
# last, so that nothing it did can reach the others)
grep -v "planted.html" "$tmp/browser.log" | grep -q '^FAIL' && { echo "FAIL: the reports above"; exit 1; }
[ "$(grep -c '^ok ' "$tmp/browser.log")" = "${#reports[@]}" ] || { echo "FAIL: not every report was checked"; exit 1; }
for want in "console: CONSOLE error: planted" "a request left the file: http://198.51.100.7" \
            "figure empty has an empty bounding box" "not within the first screen"; do
  grep -q "planted.html: .*$want" "$tmp/browser.log" || { echo "FAIL: the planted defect '$want' was not found"; exit 1; }
done
[ "$rc" = 1 ] || { echo "FAIL: the planted report passed (exit $rc)"; exit 1; }
echo "report_html_browser: ok (${#reports[@]} reports in one Chromium, the planted one failed every check; screenshots and PDFs in $out)"
