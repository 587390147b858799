# Sourced by tests/cli/study_*.sh (shear buildings, rows): the common set-up ($tmp, cmp) and the invariance checks
# every study of a system must pass, given $bin, $src and $study:
#   r0.h5 (one process), r1.h5 (mpirun -np 1), r2.h5 (mpirun -np 2) bit-identical; narrow.h5 (batch = 1) and
#   full.h5 (skip_untouched = false) equal to r0.h5 but for the settings they change. Leaves them in $tmp.
# bad_run <want> <file>: `pounding run FILE` in $tmp (FILE relative to it) must exit 2 with exactly one ERROR line
# matching "ERROR: .*<want>" and write no results (needs the script's fail "<what>").
# simulate_both <name> [options]: the script's sim [options] with contact (--contact hertzdamp --e 0.5) into
# $tmp/<name>-sim.json and without (--contact none) into $tmp/<name>-free.json, beside the study $tmp/<name>.h5 (read by
# tests/lib/study_simulate.py load).
# expect_error <name> <pattern> <study text>: the same for a study given as text, counting failures in $fails (the
# script sets fails=0 and exits non-zero at the end when it is not 0), printing "ok" or "FAIL" per case.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmp() { /usr/bin/python3 "$src/tests/cli/compare_results.py" "$@"; }

# with_analysis <key = value> <study> <out>: the study with the key in its [analysis] (a new one before [contact])
with_analysis() {
  if grep -q '^\[analysis\]' "$2"; then sed "s/^\[analysis\]/[analysis]\n$1/" "$2" > "$3"
  else sed "s/^\[contact\]/[analysis]\n$1\n\n[contact]/" "$2" > "$3"; fi
}

study_invariance() {
  "$bin" run "$study" --out "$tmp/r0.h5" --quiet > /dev/null 2>&1
  timeout 120 mpirun -np 1 "$bin" run "$study" --out "$tmp/r1.h5" --quiet > /dev/null 2>&1
  timeout 120 mpirun -np 2 "$bin" run "$study" --out "$tmp/r2.h5" --quiet > /dev/null 2>&1
  cmp "$tmp/r0.h5" "$tmp/r1.h5"
  cmp "$tmp/r0.h5" "$tmp/r2.h5"
  with_analysis 'batch = 1' "$study" "$tmp/narrow.toml"
  "$bin" run "$tmp/narrow.toml" --out "$tmp/narrow.h5" --quiet > /dev/null 2>&1
  cmp "$tmp/r0.h5" "$tmp/narrow.h5" --ignore=study_text,batch,output
  with_analysis 'skip_untouched = false' "$study" "$tmp/full.toml"
  "$bin" run "$tmp/full.toml" --out "$tmp/full.h5" --quiet > /dev/null 2>&1
  cmp "$tmp/r0.h5" "$tmp/full.h5" --ignore=study_text,skip_untouched,output,scene_reason
}

bad_run() {
  local want=$1 file=$2
  set +e; (cd "$tmp" && "$bin" run "$file" --out bad.h5 > bad.out 2> bad.err); local rc=$?; set -e
  [ $rc -eq 2 ] || fail "$file: exit $rc, want 2: $(cat "$tmp/bad.err")"
  [ ! -e "$tmp/bad.h5" ] || fail "$file: wrote results"
  grep -q "ERROR: .*$want" "$tmp/bad.err" || fail "$file: the error does not name $want: $(cat "$tmp/bad.err")"
  [ "$(grep -c ERROR "$tmp/bad.err")" -eq 1 ] || fail "$file: more than one ERROR line: $(cat "$tmp/bad.err")"
}

simulate_both() {
  local name=$1; shift
  sim "$@" --contact hertzdamp --e 0.5 > "$tmp/$name-sim.json"
  sim "$@" --contact none > "$tmp/$name-free.json"
}

expect_error() {
  local name=$1 pattern=$2
  printf '%s\n' "$3" > "$tmp/$name.toml"
  local rc=0
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" --quiet > "$tmp/$name.out" 2>&1 || rc=$?
  if [ $rc -ne 2 ] || [ "$(grep -c "ERROR:" "$tmp/$name.out")" -ne 1 ] || ! grep -q -- "$pattern" "$tmp/$name.out" \
     || [ -e "$tmp/$name.h5" ] || [ -e "$tmp/$name.h5.ckpt" ]; then
    echo "FAIL $name (rc $rc):"; cat "$tmp/$name.out"; fails=$((fails+1))
  else
    echo "ok   $name: $(grep ERROR "$tmp/$name.out")"
  fi
}

# The IDA's final brackets of a fragility study of systems (pairs of shear buildings, rows): up to 3 bisected
# (model, gap) of record 1 in FILE ($1), each checked at both ends with the caller's `sim FACTOR OUT.json` (simulate
# on record 1 scaled by FACTOR): the largest closing over the contact levels stays at or below the gap at scale_lo
# and passes it at scale_hi. Fails the script (set -e) on the first bracket that does not hold.
check_ida_brackets() {
  local py=${py:-/usr/bin/python3} m flo fhi gap
  "$py" - "$1" > "$tmp/brackets.txt" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
lo, hi = f["ida/scale_lo"][0], f["ida/scale_hi"][0]
gaps = f["ida/gaps"][()]
d = f["models/code_gap"][()]
n = 0
for m in range(lo.shape[0]):
    for g in range(lo.shape[1]):
        if np.isfinite(hi[m, g]) and 0 < lo[m, g] < hi[m, g] and n < 3 and m == 0:
            print(m, repr(float(lo[m, g])), repr(float(hi[m, g])), repr(float(gaps[g] * d[m])))
            n += 1
assert n > 0, "no bisected bracket"
PY
  while read -r m flo fhi gap; do
    sim "$flo" "$tmp/lo.json"; sim "$fhi" "$tmp/hi.json"
    "$py" - "$tmp/lo.json" "$tmp/hi.json" "$gap" <<'PY'
import sys, json
lo, hi, gap = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), float(sys.argv[3])
D = lambda j: max(l["peak_closing"] for l in j["levels"])
assert lo["status"] == "ok" and hi["status"] == "ok"
assert D(lo) <= gap < D(hi), (D(lo), gap, D(hi))
print(f"ok   IDA bracket: simulate D = {D(lo):.5f} m at scale_lo, {D(hi):.5f} m at scale_hi, gap {gap:.5f} m")
PY
  done < "$tmp/brackets.txt"
}
