#!/usr/bin/env bash
# The bits guard of a refactoring step (docs/runner-design.md section 1): every shipped study, run small by
# tests/cli/html_studies.sh, with an old and a new `pounding` program, must give the same results and reports.
#   results files: tests/cli/compare_results.py (every dataset and attribute bit for bit, provenance aside);
#   `pounding report` Markdown and CSV and the run's own report (the .md the run prints): line for line, once the
#   provenance that differs run to run is dropped (the date, wall time and phase seconds). Both run in one folder.
# Usage: tools/compare_builds.sh OLD_PROGRAM NEW_PROGRAM [DIR]    (DIR: a new temporary folder when not given)
# Exit 0 when every study that ran under both agrees, 1 with the differences listed, 2 on bad usage.
# Example, old build kept aside:  cp build/pounding /tmp/pounding-old; <change>; ninja -C build pounding;
#                                 tools/compare_builds.sh /tmp/pounding-old build/pounding
set -euo pipefail
if [ $# -lt 2 ] || [ ! -x "$1" ] || [ ! -x "$2" ]; then
  echo "usage: tools/compare_builds.sh OLD_PROGRAM NEW_PROGRAM [DIR] (both programs must exist and be executable)" >&2
  exit 2
fi
old=$(readlink -f "$1"); new=$(readlink -f "$2")
src=$(cd "$(dirname "$0")/.." && pwd)
dir=${3:-$(mktemp -d /tmp/compare-builds.XXXXXX)}
mkdir -p "$dir"
py=${POUNDING_PYTHON:-/usr/bin/python3}
# both run in the same folder ($dir/run, then moved), so the paths the files record are the same
rm -rf "$dir/old" "$dir/new" "$dir/run"
bash "$src/tests/cli/html_studies.sh" "$old" "$src" "$dir/run" > "$dir/old.log" && mv "$dir/run" "$dir/old"
bash "$src/tests/cli/html_studies.sh" "$new" "$src" "$dir/run" > "$dir/new.log" && mv "$dir/run" "$dir/new"
# provenance that differs run to run: the date, the wall time and per-phase seconds
volatile='written 20[0-9-]+T|wall time|^timing|^  [a-z ]+ +[0-9.]+ s$|[0-9.]+ s of units|^# provenance|^provenance,'
same() {  # same FILE_A FILE_B: equal once provenance is dropped and the folders named alike
  diff <(grep -Ev "$volatile" "$1") <(grep -Ev "$volatile" "$2")
}
failed=0; compared=0
while IFS=$'\t' read -r state name why; do
  [ "$state" = ok ] || { echo "skipped: $name ${why:-}"; continue; }
  grep -q "^ok	$name\$" "$dir/new/studies.tsv" || { echo "DIFF $name: ran with the old program only"; failed=1; continue; }
  compared=$((compared + 1))
  "$py" "$src/tests/cli/compare_results.py" "$dir/old/$name.h5" "$dir/new/$name.h5" > "$dir/$name.diff" 2>&1 ||
    { echo "DIFF $name: results file"; sed 's/^/  /' "$dir/$name.diff" | head -20; failed=1; }
  for ext in report.md csv md; do
    if ! same "$dir/old/$name.$ext" "$dir/new/$name.$ext" > "$dir/$name.$ext.diff"; then
      echo "DIFF $name: $([ $ext = md ] && echo "the run's report" || echo "pounding report ($ext)")"
      head -10 "$dir/$name.$ext.diff"; failed=1
    fi
  done
done < "$dir/old/studies.tsv"
echo "compare_builds: $compared studies compared in $dir: $([ $failed = 0 ] && echo identical || echo DIFFERENT)"
exit $failed
