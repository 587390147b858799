# Sourced by the tests that require the ctest fixture "html_studies" (cli.report_html, cli.report_html_browser,
# cli.plot_layout) after they set $bin and $src: their shared preamble. The fixture (tests/cli/html_studies.sh, ctest
# cli.html_studies) ran every shipped study once, made small, into <build>/html-studies (see it for how each is
# reduced). Sets
#   $py        the Python with matplotlib, h5py, numpy (skip_or_fail without)
#   $studies   the fixture's folder: <name>.h5, .md, .report.md, .csv, .html, studies/<name>.toml
#   $html_names  the studies it ran; a study it skipped (../shared/records/real missing) is named with its reason,
#              and fails the test under CI=true (skip_or_fail when it ran none)
#   $tmp       a temporary folder, removed at exit
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
export MPLBACKEND=Agg
studies=$(cd "$(dirname "$bin")" && pwd)/html-studies
[ -f "$studies/ready" ] ||
  { echo "FAIL: $studies/ready is missing: run the fixture (ctest -R 'cli.html_studies|$(basename "$0" .sh)')"; exit 1; }
if grep -q '^none' "$studies/studies.tsv"; then skip_or_fail "$(cut -f3 "$studies/studies.tsv")"; fi
html_names=$(awk -F '\t' '$1 == "ok" { printf "%s ", $2 }' "$studies/studies.tsv")
while IFS=$'\t' read -r state name why; do
  [ "$state" = skip ] || continue
  if in_ci; then echo "FAIL (CI=$CI, so not skipped): studies/$name.toml: $why"; exit 1; fi
  echo "skip studies/$name.toml: $why"
done < "$studies/studies.tsv"
[ -n "$html_names" ] || skip_or_fail "the fixture ran no study ($(cut -f2,3 "$studies/studies.tsv" | tr '\n' ' '))"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
