#!/usr/bin/env bash
# `pounding motions`: the coherency it uses, printed (--coherency-table), with the user's Harichandran-Vanmarcke
# parameters and Der Kiureghian's (1996) site-response phase (../shared/research/systems-and-bridges.md section 6):
#  - the table at 1,5 Hz x 50,100,200 m holds T6.1's Event 24 values (--hv-* given) and Event 20's (defaults), T6.2's
#    Luco-Wong values, and with sites T6.4's complex gamma and theta_s; every row recomputed by
#    tools/reference_spatial.py (numpy, none of our code) to 1e-9;
#  - the README.md of a written folder carries the same table; the default HV parameters write the same bytes as
#    --hv-a 0.736 ... given explicitly (the defaults are Event 20);
#  - 100 realisations on two sites (2.5 Hz/0.6 at support 1, 1 Hz/0.4 at support 2): the phase of the estimated
#    cross-spectrum after the wave-passage shift matches theta_s within 4 standard errors; the same check without
#    --site fails (the check can fail);
#  - bad HV and site options: exit 2, one " ERROR:" line naming the option and its range, nothing written.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

bad() {  # <text the error must hold> <args...>
  local want=$1; shift
  set +e
  "$bin" motions "$@" > "$tmp/bad.out" 2> "$tmp/bad.err"
  local rc=$?
  set -e
  [ "$rc" = 2 ] || fail "motions $* exited $rc, want 2: $(cat "$tmp/bad.err")"
  [ "$(grep -c '^ ERROR: ' "$tmp/bad.err")" = 1 ] || fail "motions $*: not one ERROR line: $(cat "$tmp/bad.err")"
  grep -qF -- "$want" "$tmp/bad.err" || fail "motions $*: the error does not say '$want': $(cat "$tmp/bad.err")"
  [ ! -s "$tmp/bad.out" ] || fail "motions $*: wrote to stdout"
  [ ! -e "$tmp/never" ] || fail "motions $*: wrote the folder"
  echo "refused: $(cat "$tmp/bad.err")"
}
hv=(--coherency harichandran-vanmarcke --soil D --out "$tmp/never")
bad "--hv-a = 1.5 is out of range" "${hv[@]}" --hv-a 1.5
bad "[0.001, 1]" "${hv[@]}" --hv-a 0
bad "--hv-alpha" "${hv[@]}" --hv-alpha -0.1
bad "--hv-k = 0 is out of range" "${hv[@]}" --hv-k 0
bad "[1, 1000000] m" "${hv[@]}" --hv-k 2e6
bad "--hv-f0" "${hv[@]}" --hv-f0 0
bad "--hv-b" "${hv[@]}" --hv-b 50
bad "--hv-k applies to coherency harichandran-vanmarcke only" --loss high --soil D --hv-k 19700 --out "$tmp/never"
bad "--site-damping" --loss high --soil D --site-frequency 2.5,1 --out "$tmp/never"
bad "3 values of --site-frequency for 2 supports" --loss high --soil D --site-frequency 2.5,1,3 --site-damping 0.5 \
  --out "$tmp/never"
bad "--site-frequency = 0.01 is out of range" --loss high --soil D --site-frequency 0.01,1 --site-damping 0.5 \
  --out "$tmp/never"
bad "--site-damping = 5 is out of range" --loss high --soil D --site-frequency 2,1 --site-damping 5 --out "$tmp/never"
bad "--coherency-frequencies" --loss high --soil D --coherency-table --coherency-frequencies 0,1
bad "--coherency-distances" --loss high --soil D --coherency-table --coherency-distances -5
bad "--out" --loss high --soil D

# ---- the table: known values ----
has() {  # <file> <row regex>
  grep -Eq -- "$2" "$1" || { cat "$1"; fail "$1 holds no row matching '$2'"; }
}
at=(--coherency-table --coherency-frequencies 1,5 --coherency-distances 50,100,200)
"$bin" motions --coherency harichandran-vanmarcke --soil D "${at[@]}" --hv-a 0.626 --hv-alpha 0.022 --hv-k 19700 \
  --hv-f0 2.02 --hv-b 3.47 > "$tmp/ev24.txt"
has "$tmp/ev24.txt" '^ +1 +50 +0\.9434744706 '
has "$tmp/ev24.txt" '^ +1 +200 +0\.8019762650 '
has "$tmp/ev24.txt" '^ +5 +100 +0\.6263098936 '
has "$tmp/ev24.txt" '^ +5 +200 +0\.4673460234 '
has "$tmp/ev24.txt" 'k = 19700 m'
[ "$(grep -Ec '^ +[0-9]' "$tmp/ev24.txt")" = 6 ] || fail "want 6 rows: $(cat "$tmp/ev24.txt")"
"$bin" motions --coherency harichandran-vanmarcke --soil D "${at[@]}" > "$tmp/ev20.txt"
has "$tmp/ev20.txt" '^ +1 +50 +0\.9511976853 +-0\.6283185307 '
has "$tmp/ev20.txt" '^ +5 +200 +0\.3525109158 '
# T6.4: support 2 (downstream, stiff: w_g = 5 pi, 0.6) against support 1 (soft: 2 pi, 0.4), Luco-Wong 2.5e-4 s/m
"$bin" motions --coherency luco-wong --soil D --positions 0,50 --site-frequency 1,2.5 --site-damping 0.4,0.6 \
  "${at[@]}" > "$tmp/dk.txt"
has "$tmp/dk.txt" '^ +5 +200 +0\.0848049725 '
has "$tmp/dk.txt" '^ +2 +1 +1 +50 +0\.9938504834 +-0\.6283185307 +0\.8244292455 +0\.9748002034 +0\.1936578087$'
has "$tmp/dk.txt" '^ +2 +1 +5 +50 +0\.8570898111 +-3\.1415926536 +0\.3597798082 +-0\.8022140950 +-0\.3017540224$'
"$bin" motions --coherency luco-wong --soil D --positions 0,100 --site-frequency 1,2.5 --site-damping 0.4,0.6 \
  --coherency-table --coherency-frequencies 1,5 > "$tmp/dk100.txt"
has "$tmp/dk100.txt" '^ +2 +1 +1 +100 .* +0\.8859122461 +-0\.4086677129$'
has "$tmp/dk100.txt" '^ +2 +1 +5 +100 .* +0\.5050905991 +0\.1899905785$'
grep -q 'theta_s' "$tmp/ev20.txt" && fail "a table without sites shows theta_s"

# ---- README.md carries the table; explicit Event 20 parameters = the defaults, byte for byte ----
base=(--coherency harichandran-vanmarcke --soil C --supports 3 --realisations 2 --duration 10 --strong 4 --seed 5
      --quiet)
"$bin" motions "${base[@]}" --out "$tmp/d1" > /dev/null
"$bin" motions "${base[@]}" --hv-a 0.736 --hv-alpha 0.147 --hv-k 5210 --hv-f0 1.09 --hv-b 2.78 --out "$tmp/d2" > /dev/null
"$bin" motions "${base[@]}" --hv-k 19700 --out "$tmp/d3" > /dev/null
for f in "$tmp"/d1/*.AT2; do
  cmp -s "$f" "$tmp/d2/$(basename "$f")" || fail "explicit Event 20 parameters changed $(basename "$f")"
done
cmp -s "$tmp/d1/r001_s02.AT2" "$tmp/d3/r001_s02.AT2" && fail "--hv-k 19700 did not change the motions"
grep -q 'abs_gamma' "$tmp/d1/README.md" || fail "README.md has no coherency table"
has "$tmp/d1/README.md" '^ +2 +200 +0\.'  # the supports' separations 100 and 200 m
"$bin" motions "${base[@]}" --site-frequency 2.5,1,1 --site-damping 0.6,0.4,0.4 --out "$tmp/d4" > /dev/null
cmp -s "$tmp/d1/r001_s01.AT2" "$tmp/d4/r001_s01.AT2" || fail "site response changed support 1 (L_11 = 1)"
cmp -s "$tmp/d1/r001_s02.AT2" "$tmp/d4/r001_s02.AT2" && fail "site response did not change support 2"
grep -q 'theta_s_rad' "$tmp/d4/README.md" || fail "README.md has no site-response table"

# ---- against the independent reference ----
"$py" -c 'import numpy, scipy' 2>/dev/null ||
  skip_or_fail "needs $py with numpy and scipy (Debian: python3-numpy python3-scipy; tools/setup.sh installs them)"
ref=$src/tools/reference_spatial.py
"$py" "$ref" selftest
"$py" "$ref" table "$tmp/ev24.txt" --model harichandran-vanmarcke --hv 0.626,0.022,19700,2.02,3.47
"$py" "$ref" table "$tmp/ev20.txt" --model harichandran-vanmarcke
"$py" "$ref" table "$tmp/dk.txt" --model luco-wong --positions 0,50 --site 1,0.4:2.5,0.6
if "$py" "$ref" table "$tmp/ev24.txt" --model harichandran-vanmarcke > "$tmp/wrong.txt"; then
  cat "$tmp/wrong.txt"; fail "the Event 24 table passed as Event 20: the check cannot tell them apart"
fi
"$bin" motions --supports 3 --spacing 100 --soil D --coherency harichandran-vanmarcke --hv-k 19700 \
  --site-frequency 2.5,1,5 --site-damping 0.6,0.4,0.3 --coherency-table --coherency-frequencies 0.5,1,2,5,10 > "$tmp/t3.txt"
"$py" "$ref" table "$tmp/t3.txt" --model harichandran-vanmarcke --hv 0.736,0.147,19700,1.09,2.78 --positions 0,100,200 \
  --site 2.5,0.6:1,0.4:5,0.3
# generated motions on two sites: the phase between the supports is theta_s
gen=(--supports 2 --spacing 100 --velocity 500 --coherency luco-wong --soil D --iterations 0 --realisations 100
     --seed 3 --quiet)
"$bin" motions "${gen[@]}" --site-frequency 2.5,1 --site-damping 0.6,0.4 --out "$tmp/site" > /dev/null
"$py" "$ref" check "$tmp/site" --model luco-wong --site 2.5,0.6:1,0.4 ||
  fail "estimated coherency or site phase differs from the model (above)"
"$bin" motions "${gen[@]}" --out "$tmp/nosite" > /dev/null
if "$py" "$ref" check "$tmp/nosite" --model luco-wong --site 2.5,0.6:1,0.4 > "$tmp/wrong.txt"; then
  cat "$tmp/wrong.txt"; fail "motions without site response passed the site-phase check: it cannot fail"
fi

# ---- a study's [records.motions] takes the same keys: its realisations are the command's ----
"$py" -c 'import h5py' 2>/dev/null || skip_or_fail "needs $py with h5py (Debian: python3-h5py)"
keys='positions = [0.0, 100.0]
coherency = "harichandran-vanmarcke"
hv_k = 19700.0
hv_b = 3.47
site_frequency = [2.5, 1.0]
site_damping = [0.6, 0.4]
soil = "D"
duration = 10.0
rise = 1.0
strong = 5.0
iterations = 2
realisations = 2
seed = 5'
printf 'title = "two spans on two sites"\nseed = 26\nscene = "impacts"\n\n[records]\n\n[records.motions]\n%s\n\n%s\n' "$keys" \
  '[gaps]
ratios = [1.0, 4.0]
[bridge]
[[bridge.frame]]
mass = 1895413.0
period = 1.0204
[[bridge.frame]]
mass = 1895413.0
period = 0.8
support = 2
[[bridge.joint]]
gap = 0.01
[contact]
law = "hertzdamp"
stiffness = 2.0e9
e = 0.6' > "$tmp/site.toml"
(cd "$tmp" && "$bin" run site.toml --out site.h5 --quiet > run.out 2>&1) || fail "the study does not run: $(cat "$tmp/run.out")"
"$bin" motions --positions 0,100 --coherency harichandran-vanmarcke --hv-k 19700 --hv-b 3.47 --site-frequency 2.5,1 \
  --site-damping 0.6,0.4 --soil D --duration 10 --rise 1 --strong 5 --iterations 2 --realisations 2 --seed 5 --quiet \
  --out "$tmp/study-m" > /dev/null
sed -e '/^\[records.motions\]$/,/^seed = 5$/d' -e 's|^\[records\]$|[records]\ndirectory = "study-m"\nsupports = 2|' \
  "$tmp/site.toml" > "$tmp/files.toml"
(cd "$tmp" && "$bin" run files.toml --out files.h5 --quiet > run.out 2>&1) || fail "the file study does not run: $(cat "$tmp/run.out")"
"$py" - "$tmp/site.h5" "$tmp/study-m/MANIFEST.tsv" "$tmp/files.h5" <<'PY'
import csv, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
# the joint closes by the two supports' motions: the study's = the same study on the command's files, to their rounding
Dg, Df = f["uncoupled/peak_closing"][()], h5py.File(sys.argv[3], "r")["uncoupled/peak_closing"][()]
rel = np.abs(Dg - Df).max() / np.abs(Df).max()
assert rel < 1e-6 and (Dg > 0).all(), ("closings differ beyond the AT2 rounding", Dg, Df)
m = f["settings/records.motions"].attrs
assert m["hv_k"] == 19700.0 and m["hv_b"] == 3.47 and m["hv_a"] == 0.736, dict(m)
assert list(m["site_frequency"]) == [2.5, 1.0] and list(m["site_damping"]) == [0.6, 0.4], dict(m)
assert "site response (Der Kiureghian 1996)" in m["generator"] and "k = 19700 m" in m["generator"], m["generator"]
# the study's record r is the command's realisation r (support 1's PGA, to the manifest's 6 digits)
rows = list(csv.DictReader(open(sys.argv[2]), delimiter="\t"))
want = [float(r["pga_g"]) for r in rows if int(r["support"]) == 1]
got = f["records/pga_g"][()]
assert np.allclose(got, want, rtol=1e-5), (got, want)
print("study: /settings/records.motions holds hv_* and site_*; closings", np.round(Dg[:, 0], 4),
      "m = the command's files' (relative %.1e)" % rel)
PY
sed 's/^hv_k = 19700.0/hv_k = 0.5/' "$tmp/site.toml" > "$tmp/bad-hv.toml"
set +e
(cd "$tmp" && "$bin" run bad-hv.toml --out bad-hv.h5 > bad.out 2> bad.err)
rc=$?
set -e
[ "$rc" = 2 ] || fail "hv_k = 0.5 in a study: exit $rc, want 2"
[ "$(grep -c '^ ERROR: ' "$tmp/bad.err")" = 1 ] || fail "hv_k = 0.5: not one ERROR line: $(cat "$tmp/bad.err")"
grep -q 'bad-hv.toml:[0-9]* \[records.motions\].hv_k, give a value in \[1, 1000000\] m' "$tmp/bad.err" ||
  fail "hv_k = 0.5: $(cat "$tmp/bad.err")"
[ ! -e "$tmp/bad-hv.h5" ] || fail "hv_k = 0.5: wrote results"
echo "refused: $(cat "$tmp/bad.err")"
echo "motions_coherency: ok"
