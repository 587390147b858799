#!/usr/bin/env bash
# docs/study-reference.md is `pounding study-reference` (generated from src/config/study_keys.cpp, the list
# the study parsers check keys and ranges against): fails while the committed file differs. Regenerate with
#   build/pounding study-reference -o docs/study-reference.md
set -euo pipefail
pounding=$1
src=$2
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$pounding" study-reference > "$out"
if ! diff -u "$src/docs/study-reference.md" "$out"; then
  echo "FAIL: docs/study-reference.md differs from \`pounding study-reference\` (diff above);"
  echo "      regenerate it: build/pounding study-reference -o docs/study-reference.md"
  exit 1
fi
# -o writes the same text
"$pounding" study-reference -o "$out.md"
trap 'rm -f "$out" "$out.md"' EXIT
cmp "$out" "$out.md"
echo "docs/study-reference.md matches the generator ($(grep -c '^| `' "$out") keys)"
# --help texts point to the reference and README, never to source files (issue 23 item 10: `records select
# --help` said "see src/cli/commands/records_select.cpp")
bad=0
for cmd in "" run report simulate collide bench sample accuracy study-reference records "records select" "records im" modes; do
  # shellcheck disable=SC2086
  help=$("$pounding" $cmd --help 2>&1 || true)
  if grep -nE '(src|include)/[A-Za-z0-9_/]+\.(cpp|hpp)' <<<"$help"; then
    echo "FAIL: \`pounding $cmd --help\` points to a source file"
    bad=1
  fi
done
"$pounding" run --help | grep 'docs/study-reference.md' > /dev/null || { echo "FAIL: run --help does not name docs/study-reference.md"; bad=1; }
exit $bad
