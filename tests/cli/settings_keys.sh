#!/usr/bin/env bash
# Every key of every shipped study reaches its results file's /settings (issue 46, docs/runner-design.md section 6):
# the report reads only the results file, so a key parsed but not stored is a key the report cannot state.
# tests/cli/settings_keys.py holds the rules (a key under its name, a resolved alias, or stated in a resolved text)
# and is checked here on a planted loss first: a study whose /settings lost a key must fail it.
# Needs the ctest fixture html_studies (every shipped study run small once). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/html_studies.sh"
args=()
for name in $html_names; do args+=("$studies/studies/$name.toml" "$studies/$name.h5"); done
"$py" "$src/tests/cli/settings_keys.py" "${args[@]}"
# the check can fail: drop one stored key from a copy and one resolved text's value
cp "$studies/quick-storeys.h5" "$tmp/lost.h5"
"$py" - "$tmp/lost.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    del f["settings/contact"].attrs["e"]
PY
if "$py" "$src/tests/cli/settings_keys.py" "$studies/studies/quick-storeys.toml" "$tmp/lost.h5" > "$tmp/lost.out"; then
  echo "FAIL: a results file without /settings/contact e passed"; exit 1
fi
grep -q '\[contact\] e = 0.65 is not in' "$tmp/lost.out" || { cat "$tmp/lost.out"; echo "FAIL: the lost key is not named"; exit 1; }
if [ -f "$studies/four-frame-bridge.h5" ]; then
  cp "$studies/four-frame-bridge.h5" "$tmp/bridge.h5"
  "$py" - "$tmp/bridge.h5" <<'PY'
import re, sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    a = f["settings/bridge"].attrs
    a["description"] = re.sub(r" \(Caltrans[^)]*\)", "", str(a["description"]))
PY
  if "$py" "$src/tests/cli/settings_keys.py" "$studies/studies/four-frame-bridge.toml" "$tmp/bridge.h5" > "$tmp/b.out"; then
    echo "FAIL: a bridge description without the abutments' back-wall height passed"; exit 1
  fi
fi
echo "PASS: every key of $(echo $html_names | wc -w) shipped studies is in their /settings; a lost one fails"
