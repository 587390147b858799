#!/usr/bin/env bash
# ctest fixture "html_studies" (FIXTURES_SETUP of cli.html_studies; cli.report_html, cli.report_html_browser and
# cli.plot_layout require it): EVERY shipped study (studies/*.toml with a [records] section; a [structures] fragment
# has none), run once, made small, for all three tests. A study dropped in studies/ is picked up (a glob). Each is
# reduced from the shipped file, keeping every section and key (so the same report sections and figures appear):
#   samples_per_pair = 2 (the models per period pair: the period grid itself is kept, so is the T1 x T2 map);
#   [report] bootstrap = 100 replicates; output removed;
#   [records] limit = 3 (the first 3 records) unless the study selects records (select keeps its count: the
#   selection is what its figure shows), sets a limit already, or reads multi-support realisations from a directory
#   (supports: the 3 realisations generated here by `pounding motions`); [records.motions] realisations = 3;
#   paths to ../../shared/records/real made absolute.
# The stripes, gap ratios, periods and durations are kept. The check that the reduction kept the study's form:
# tests/cli/html_studies.py compares the shipped and the reduced file's tables and keys (only [records] limit may
# be added), and no figure of the reduced report is left out (cli.report_html).
# Out: DIR/<name>.h5, .md (the run's report), .report.md (`pounding report`), .csv, .html (with figures), .toml,
# and DIR/studies.tsv: "ok<TAB>name" or "skip<TAB>name<TAB>why" (a study reading ../shared/records/real without it;
# the tests skip it with the reason, and fail under CI=true). DIR/ready is written last.
# Needs python3 with matplotlib, h5py, numpy for the figures (without them: DIR/studies.tsv says why; the tests skip).
# Args: <pounding binary> <source dir> [DIR, default <binary dir>/html-studies]
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd); out=${3:-$(cd "$(dirname "$bin")" && pwd)/html-studies}
rm -rf "$out"; mkdir -p "$out/studies"
ln -s "$src/records" "$out/records"
cp "$src/studies/"*.csv "$out/studies/"
real=${POUNDING_REAL_RECORDS:-$(cd "$src/.." && pwd)/shared/records/real}
py=${POUNDING_PYTHON:-/usr/bin/python3}
export MPLBACKEND=Agg
: > "$out/studies.tsv"
if ! "$py" -c 'import matplotlib, h5py, numpy' 2>/dev/null; then
  printf 'none\t-\tneeds %s with matplotlib, h5py and numpy (Debian: python3-matplotlib python3-h5py python3-numpy; tools/setup.sh installs them)\n' "$py" > "$out/studies.tsv"
  touch "$out/ready"; exit 0
fi
for study in "$src"/studies/*.toml; do
  name=$(basename "$study" .toml)
  grep -q '^\[records\]' "$study" || continue  # a [structures] fragment, not a study
  if grep -q '^[^#]*shared/records/real' "$study" && [ ! -f "$real/MANIFEST.tsv" ]; then
    printf 'skip\t%s\tneeds the real records in %s (see README)\n' "$name" "$real" >> "$out/studies.tsv"; continue
  fi
  limit='s/^\[records\]$/[records]\nlimit = 3/'
  if grep -q -E '^(select|limit) *=' "$study" || { grep -q '^directory = ' "$study" && grep -q '^supports = ' "$study"; }; then
    limit=''
  fi
  sed -e 's/^samples_per_pair = [0-9_]*/samples_per_pair = 2/' -e 's/^bootstrap = [0-9_]*/bootstrap = 100/' \
      -e '/^output = /d' -e 's/^realisations = [0-9_]*/realisations = 3/' -e "s|^directory = \"../../shared/records/real\"|directory = \"$real\"|" \
      -e "s|\"../../shared/records/real/|\"$real/|g" ${limit:+-e "$limit"} "$study" > "$out/studies/$name.toml"
  if grep -q '^directory = ' "$study" && grep -q '^supports = ' "$study"; then  # a bridge reading support motions
    dir=$(sed -n 's/^directory = "\(.*\)"/\1/p' "$study")
    n_sup=$(sed -n 's/^supports = \([0-9]*\)/\1/p' "$study")
    mkdir -p "$(dirname "$out/studies/$dir")"
    "$bin" motions --supports "$n_sup" --spacing 100 --velocity 500 --loss high --soil D --spectrum nzs1170.5 --z 0.5 \
      --r 1.4 --realisations 3 --seed 1 --quiet --out "$out/studies/$dir" > /dev/null
  fi
  "$py" "$src/tests/cli/html_studies.py" same-form "$study" "$out/studies/$name.toml"
  h5=$out/$name.h5
  "$bin" run "$out/studies/$name.toml" --out "$h5" --quiet > "$out/$name.md" 2> "$out/$name.log" ||
    { cat "$out/$name.log"; echo "FAIL: studies/$name.toml (small) did not run"; exit 1; }
  "$bin" report "$h5" > "$out/$name.report.md"
  "$bin" report "$h5" --csv > "$out/$name.csv"
  "$bin" report "$h5" --html "$out/$name.html" 2> "$out/$name.html.log" ||
    { cat "$out/$name.html.log"; echo "FAIL: report --html of studies/$name.toml (small)"; exit 1; }
  printf 'ok\t%s\n' "$name" >> "$out/studies.tsv"
done
touch "$out/ready"
echo "html_studies: $(grep -c '^ok' "$out/studies.tsv") studies run small in $out ($(grep -c '^skip' "$out/studies.tsv" || true) skipped)"
