#!/usr/bin/env bash
# When is an SDOF enough? (issue 25 §6, docs/sdof-vs-mdof.md): tools/compare_sdof_mdof.py on studies/quick-storeys.toml
# (shear buildings) and the same file with model = "sdof" (probability scene, synthetic records, seconds):
#  1. the samples are found identical (every /models and /records dataset) and said so;
#  2. Table 3 side by side has one row per gap ratio and 10 columns, and each side's "impacts / n" is the one
#     `pounding report` prints in its own Table 3 for that file (the report is the independent count);
#  3. the default gap ratio of the map is the report's 10 % advice x of the SDOF file; the T1 x T2 difference
#     matrix has one row per T1 of the grid, its cells are MDOF - SDOF of the per-pair counts;
#  4. refusals, exit 2 with one ERROR line, no figure written: other samples (samples_per_pair), other records
#     (limit), another seed, the files swapped (shear first), an SDOF file as the MDOF;
#  5. --figure writes the map and the curves (PNG and SVG).
# Needs /usr/bin/python3 with h5py, numpy and matplotlib: skipped (77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"  # skip_or_fail
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy, matplotlib' 2>/dev/null ||
  skip_or_fail "needs $py with h5py, numpy and matplotlib (Debian: python3-h5py python3-numpy python3-matplotlib)"
tool=$src/tools/compare_sdof_mdof.py
[ -f "$tool" ] || { echo "FAIL: $tool is missing"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
export MPLBACKEND=Agg
fail() { echo "FAIL: $*"; exit 1; }

# probability scene (one uncoupled run per model); substeps = 2 for both: the shear buildings' damped step bound
base() { sed -e 's/^scene = .*/scene = "probability"/' -e '/^output = /d' \
             -e 's/^\[contact\]/[analysis]\nsubsteps = 2\n\n[contact]/' "$src/studies/quick-storeys.toml"; }
base > "$tmp/mdof.toml"
base | sed 's/^model = "shear"/model = "sdof"/' > "$tmp/sdof.toml"
base | sed 's/^model = "shear"/model = "sdof"/; s/^samples_per_pair = 8/samples_per_pair = 7/' > "$tmp/fewer.toml"
base | sed 's/^model = "shear"/model = "sdof"/; s/^limit = 2/limit = 1/' > "$tmp/onerec.toml"
base | sed 's/^model = "shear"/model = "sdof"/; s/^seed = .*/seed = 1234/' > "$tmp/seed.toml"
grep -q '^model = "sdof"' "$tmp/sdof.toml" && grep -q '^samples_per_pair = 7' "$tmp/fewer.toml" &&
  grep -q '^limit = 1' "$tmp/onerec.toml" && grep -q '^seed = 1234' "$tmp/seed.toml" ||
  fail "studies/quick-storeys.toml changed: the test's edits no longer apply"
for s in mdof sdof fewer onerec seed; do
  "$bin" run "$tmp/$s.toml" --out "$tmp/$s.h5" --quiet > /dev/null 2> "$tmp/$s.log" || { cat "$tmp/$s.log"; exit 1; }
done

# 1-3
"$py" "$tool" "$tmp/sdof.h5" "$tmp/mdof.h5" --figure "$tmp/cmp" --format svg > "$tmp/out.md" 2> "$tmp/err" ||
  { cat "$tmp/err"; fail "the tool refused two files of the same samples"; }
"$bin" report "$tmp/sdof.h5" > "$tmp/sdof.md"
"$bin" report "$tmp/mdof.h5" > "$tmp/mdof.md"
"$py" - "$tmp/out.md" "$tmp/sdof.md" "$tmp/mdof.md" "$tmp/sdof.h5" "$tmp/mdof.h5" <<'PY'
import re, sys, h5py, numpy as np
out, sd, md = (open(p).read() for p in sys.argv[1:4])
bad = []
if not re.search(r"^- samples: identical -- 30 datasets of /models .* and \d+ of /records \(2 records\) compared exactly",
                 out, re.M):
    bad.append("no 'samples: identical' line naming 30 /models datasets and 2 records")

def section(text, head):
    i = text.index(head)
    rows = []
    for line in text[i:].splitlines()[1:]:
        if line.startswith("|") and not line.startswith("|---"):
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif rows and not line.startswith("|"):
            break
    return rows

t = section(out, "## Table 3 side by side")
head, rows = t[0], t[1:]
ratios = h5py.File(sys.argv[4], "r")["gaps/ratios"][()]
if len(head) != 10 or any(len(r) != 10 for r in rows) or len(rows) != len(ratios):
    bad.append(f"Table 3 side by side: {len(rows)} rows of {[len(r) for r in rows]} columns, want {len(ratios)} of 10")
rep = {}
for name, text in (("sdof", sd), ("mdof", md)):
    rep[name] = {r[0]: r[1] for r in section(text, "## Total probability of pounding (Table 3)")[1:]}
for r in rows:
    if r[1] != rep["sdof"].get(r[0]) or r[3] != rep["mdof"].get(r[0]):
        bad.append(f"gap {r[0]}: tool SDOF {r[1]} MDOF {r[3]}, report {rep['sdof'].get(r[0])} / {rep['mdof'].get(r[0])}")
    hs, ns = map(int, r[1].split(" / ")); hm, nm = map(int, r[3].split(" / "))
    if abs(float(r[5]) - (100 * hm / nm - 100 * hs / ns)) > 0.006:
        bad.append(f"gap {r[0]}: difference {r[5]} is not MDOF - SDOF")
if not any(float(r[5]) != 0 for r in rows):
    bad.append("no gap ratio differs between the models: the comparison shows nothing")

# the default ratio is the report's 10 % advice x of the SDOF file
adv = [r for r in section(sd, "## Separation advice in gap ratios")[1:] if r[0] == "10%"][0][1]
m = re.search(r"MDOF - SDOF by period pair at gap ratio x = ([0-9.]+) \(the SDOF study's 10 % advice point\)", out)
if not m or m.group(1) != adv:
    bad.append(f"map ratio {m.group(1) if m else None}, report's 10 % advice x {adv}")
x = float(adv)
mat = section(out, "## MDOF - SDOF by period pair")
S, M = h5py.File(sys.argv[4], "r"), h5py.File(sys.argv[5], "r")
p1, p2 = S["models/periods1"][()], S["models/periods2"][()]
if len(mat) != 1 + len(p1) or any(len(r) != 1 + len(p2) for r in mat):
    bad.append(f"difference matrix {len(mat) - 1} x {len(mat[0]) - 1}, want {len(p1)} x {len(p2)}")
d = S["models/code_gap"][()]
for a in range(len(p1)):
    for b in range(len(p2)):
        sel = (S["models/i1"][()] == a) & (S["models/i2"][()] == b)
        ps = 100 * np.mean(S["uncoupled/peak_closing"][()][:, sel] > x * d[sel])
        pm = 100 * np.mean(M["uncoupled/peak_closing"][()][:, sel] > x * d[sel])
        if abs(float(mat[1 + a][1 + b]) - (pm - ps)) > 0.051:
            bad.append(f"cell T1 {p1[a]} T2 {p2[b]}: {mat[1 + a][1 + b]}, want {pm - ps:+.1f}")
print("\n".join(bad) if bad else "tables ok")
sys.exit(1 if bad else 0)
PY
for f in cmp-map.png cmp-map.svg cmp-curves.png cmp-curves.svg; do
  [ -s "$tmp/$f" ] || fail "--figure did not write $f"
done

# 4. refusals
refuse() {  # refuse <what> <needle> <args...>
  local what=$1 needle=$2; shift 2
  rm -f "$tmp"/ref-*
  set +e; "$py" "$tool" "$@" --figure "$tmp/ref" > "$tmp/r.out" 2> "$tmp/r.err"; rc=$?; set -e
  [ "$rc" = 2 ] || { cat "$tmp/r.err"; fail "$what: exit $rc, want 2"; }
  [ "$(grep -c '^ ERROR: ' "$tmp/r.err")" = 1 ] || { cat "$tmp/r.err"; fail "$what: want one ERROR line"; }
  grep -q -- "$needle" "$tmp/r.err" || { cat "$tmp/r.err"; fail "$what: the error does not say '$needle'"; }
  [ ! -s "$tmp/r.out" ] && ! ls "$tmp"/ref-* > /dev/null 2>&1 || fail "$what: output written before the refusal"
  echo "refused ($what): $(cat "$tmp/r.err")"
}
refuse "other samples" "do not share their sampled structures" "$tmp/fewer.h5" "$tmp/mdof.h5"
refuse "other records" "do not share their records" "$tmp/onerec.h5" "$tmp/mdof.h5"
refuse "another seed" "the seeds differ" "$tmp/seed.h5" "$tmp/mdof.h5"
refuse "files swapped" "has shear buildings" "$tmp/mdof.h5" "$tmp/sdof.h5"
refuse "two SDOF files" "SDOF buildings only" "$tmp/sdof.h5" "$tmp/sdof.h5"
refuse "bad ratio" "--ratio" "$tmp/sdof.h5" "$tmp/mdof.h5" --ratio -1
refuse "missing file" "cannot read" "$tmp/nothere.h5" "$tmp/mdof.h5"
echo "compare_sdof_mdof: tables match the report, refusals hold"
