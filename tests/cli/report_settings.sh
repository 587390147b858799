#!/usr/bin/env bash
# Results carry their settings (issue 11, C17): every key of the study file is stored at
# /settings/<section>/<key> with its value; `pounding report` prints the same Markdown after the study text
# attribute is deleted; a file without /settings (the older layout) still reports, from its study text.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/s.toml" <<'TOML'
title = "settings round trip"
seed = 5
scene = "impacts"
[records]
suite = "builtin"
synthetic_only = true
limit = 2
[structures]
samples_per_pair = 2
code_gap_coefficient = 0.008
zeta = 0.04
[gaps]
ratios = [0.2, 0.4, 0.8]
curve_step = 0.01
[contact]
e = 0.7
[analysis]
batch = 16
max_excluded_fraction = 0.5
[report]
targets = [20, 2]
fit_min = 0.2
confidence = 0.9
bootstrap = 300
TOML
"$bin" run "$tmp/s.toml" --out "$tmp/s.h5" --quiet > "$tmp/run.md" 2>/dev/null
"$bin" report "$tmp/s.h5" > "$tmp/a.md"
/usr/bin/python3 - "$tmp/s.toml" "$tmp/s.h5" <<'PY'
import sys, tomllib, h5py, numpy as np
study = tomllib.load(open(sys.argv[1], "rb"))
f = h5py.File(sys.argv[2], "r+")
checked = 0
for section, table in study.items():
    if not isinstance(table, dict):
        table, section = {section: table}, ""
    g = f["settings/" + section] if section else f["settings"]
    for key, want in table.items():
        assert key in g.attrs, f"/settings/{section}/{key} missing"
        got = g.attrs[key]
        got = got.decode() if isinstance(got, bytes) else got
        if isinstance(want, list):
            assert np.allclose(np.asarray(got, float), want), (section, key, got, want)
        elif isinstance(want, (int, float)) and not isinstance(want, bool):
            assert float(got) == float(want), (section, key, got, want)
        else:
            assert got == want, (section, key, got, want)
        checked += 1
del f.attrs["study_text"]
print(f"{checked} study keys found in /settings with their values")
PY
"$bin" report "$tmp/s.h5" > "$tmp/b.md"
diff <(grep -v '^- results:' "$tmp/a.md") <(grep -v '^- results:' "$tmp/b.md") || { echo "FAIL: the report changed without the study text"; exit 1; }
grep -q "d = 0.008 (h1 + h2)" "$tmp/b.md" && grep -q "300 replicates, 90 %" "$tmp/b.md" || { echo "FAIL: report settings not read from /settings"; exit 1; }
# the older layout: no /settings, the study text is read instead
"$bin" run "$tmp/s.toml" --out "$tmp/old.h5" --quiet > /dev/null 2>&1
/usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r+'); del f['settings']" "$tmp/old.h5"
"$bin" report "$tmp/old.h5" > "$tmp/c.md"
diff <(grep -v '^- results:' "$tmp/a.md") <(grep -v '^- results:' "$tmp/c.md") || { echo "FAIL: the older layout reports differently"; exit 1; }
echo "report identical from /settings, without study text, and from the older layout"

# /settings holds the batch the run used: the scene's default when the study gives none (impacts 64, probability 256,
# auto as the scene it resolves to: study.hpp default_batch), the study's own otherwise (16 above)
batch_of() {  # batch_of <scene> [analysis line]: the stored [analysis] batch of a run of the study above
  sed -e "s/^scene = .*/scene = \"$1\"/" -e "s/^batch = 16$/${2:-}/" "$tmp/s.toml" > "$tmp/d.toml"
  "$bin" run "$tmp/d.toml" --out "$tmp/d.h5" --quiet --force > /dev/null 2>&1 || { echo "FAIL: scene $1 did not run"; exit 1; }
  /usr/bin/python3 -c "import h5py, sys; print(int(h5py.File(sys.argv[1])['settings/analysis'].attrs['batch']))" "$tmp/d.h5"
}
for want in "impacts  64" "auto 64" "probability 256" "impacts 32 batch = 32" "probability 8 batch = 8"; do
  set -- $want; scene=$1 batch=$2; shift 2
  got=$(batch_of "$scene" "$*")
  [ "$got" = "$batch" ] || { echo "FAIL: scene $scene ${*:-without batch}: /settings says batch $got, want $batch"; exit 1; }
done
echo "/settings holds the batch used: impacts 64, auto (impacts) 64, probability 256 by default; a given batch as is"
