#!/usr/bin/env bash
# `pounding sample`: output shape and header, reproducibility, --pair/--n selection, CSV = HDF5, and bad input
# (exit 2, one " ERROR:" line, no output file and no temporary left behind).
# Usage: bash sample_cli.sh <pounding binary> <source dir>
set -euo pipefail
bin=$1 src=$2
study=$src/studies/paper-structures.toml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# --- the paper's 30,976 models, twice: identical files
"$bin" sample "$study" --out "$tmp/a.csv" > "$tmp/stdout"
"$bin" sample "$study" --out "$tmp/b.csv" > /dev/null
cmp -s "$tmp/a.csv" "$tmp/b.csv" || fail "two runs with the same seed differ"
rows=$(grep -vc '^#' "$tmp/a.csv")
[ "$rows" -eq 30977 ] || fail "expected 30976 rows + header, got $rows"
grep -q '^# .*shear-wave velocity.*not sampled.*fixed-base SDOF' "$tmp/a.csv" || fail "header lacks the Vs note"
grep -q 'shear-wave velocity' "$tmp/stdout" || fail "stdout lacks the Vs note"
grep -q '^# seed: 20240917' "$tmp/a.csv" || fail "header lacks the seed"
header=$(awk '!/^#/ {print; exit}' "$tmp/a.csv")
[ "$header" = "i1,i2,sample,T1,T2,h1,h2,aspect1,aspect2,r1,r2,rho1,rho2,mbar1,mbar2,m1,m2,k1,k2,c1,c2,fy1,fy2,alpha1,alpha2,d,kh,zeta1,zeta2" ] \
  || fail "unexpected columns: $header"

# --- --pair and --n pick the same structures as the full dump (identity, not position, sets the stream)
"$bin" sample "$study" --pair 1.1,1.3 --n 5 --out "$tmp/p.csv" > /dev/null
grep -v '^#' "$tmp/p.csv" | tail -n +2 > "$tmp/p.rows"
[ "$(wc -l < "$tmp/p.rows")" -eq 5 ] || fail "--n 5 did not give 5 rows"
grep '^2,6,[0-4],' "$tmp/a.csv" > "$tmp/a.rows"
cmp -s "$tmp/p.rows" "$tmp/a.rows" || fail "--pair 1.1,1.3 --n 5 differs from the full dump's rows"
# more samples than the study's 256 extend, never change, the first 256
"$bin" sample "$study" --pair 1.1,1.3 --n 300 --out "$tmp/p300.csv" > /dev/null
grep -v '^#' "$tmp/p300.csv" | sed -n '2,257p' > "$tmp/p300.rows"
grep '^2,6,' "$tmp/a.csv" > "$tmp/a256.rows"
cmp -s "$tmp/p300.rows" "$tmp/a256.rows" || fail "--n 300 changed the first 256 samples"

# --- another seed gives other structures
"$bin" sample "$study" --seed 7 --pair 1.1,1.3 --n 5 --out "$tmp/s7.csv" > /dev/null
grep -v '^#' "$tmp/s7.csv" | tail -n +2 > "$tmp/s7.rows"
! cmp -s "$tmp/s7.rows" "$tmp/p.rows" || fail "--seed 7 gave the same structures"

# --- HDF5 holds the same numbers bit for bit
"$bin" sample "$study" --out "$tmp/a.h5" > /dev/null
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" - "$tmp/a.csv" "$tmp/a.h5" <<'PY'
import sys, h5py, numpy as np
lines = [l for l in open(sys.argv[1]) if not l.startswith("#")]
names = lines[0].strip().split(",")
csv = np.loadtxt(lines[1:], delimiter=",")
with h5py.File(sys.argv[2], "r") as f:
    g = f["samples"]
    for j, n in enumerate(names):
        col = g[n][:]
        assert np.array_equal(col.astype(float), csv[:, j]), n
    assert f.attrs["seed"] == 20240917
    assert "shear-wave" in f.attrs["not_sampled"]
    assert len(f["periods"][:]) == 11
print("csv == h5 for", len(names), "columns")
PY

# --- bad input: exit 2, " ERROR:", no file, no temporary
expect_error() {  # expect_error <pattern> <args...>
  local pattern=$1; shift
  local out=$tmp/bad.csv rc=0
  "$bin" sample "$@" > "$tmp/err.out" 2> "$tmp/err" || rc=$?
  [ "$rc" -eq 2 ] || fail "exit $rc (want 2) for: $*"
  grep -q "^ ERROR: .*$pattern" "$tmp/err" || { cat "$tmp/err" >&2; fail "no ' ERROR: ...$pattern' for: $*"; }
  [ ! -e "$out" ] && [ ! -e "$tmp/bad.h5" ] || fail "an output file was left for: $*"
  ! ls "$tmp"/bad.*.tmp* > /dev/null 2>&1 || fail "a temporary was left for: $*"
}
printf 'seed = 1\n[structures]\nzeta = 0.05\nrho_meen = 1800\n' > "$tmp/unknown.toml"
expect_error "unknown key 'rho_meen'.*unknown.toml:4" "$tmp/unknown.toml" --out "$tmp/bad.csv"
printf 'seed = 1\n[structures]\nperiods = [1.0, 1.6]\n' > "$tmp/empty.toml"
expect_error 'T = 1.6 s.*54.2884 m.*50 m.*empty.toml:3' "$tmp/empty.toml" --out "$tmp/bad.h5"
printf 'seed = 1\n[structures]\nmbar_cov = 3\n' > "$tmp/range.toml"
expect_error 'mbar_cov = 3 is out of range.*range.toml:3.*(0, 2\]' "$tmp/range.toml" --out "$tmp/bad.csv"
printf '[structures]\nzeta = 0.05\n' > "$tmp/noseed.toml"
expect_error 'no seed' "$tmp/noseed.toml" --out "$tmp/bad.csv"
printf 'seed = 1\n[structures\n' > "$tmp/syntax.toml"
expect_error 'syntax.toml:2' "$tmp/syntax.toml" --out "$tmp/bad.csv"
expect_error 'not on the study' "$study" --pair 1.12,1.3 --out "$tmp/bad.csv"
expect_error 'not a period' "$study" --pair 1.1,abc --out "$tmp/bad.csv"
expect_error 'no .csv or .h5' "$study" --out "$tmp/bad.txt"
expect_error 'missing.toml' "$tmp/missing.toml" --out "$tmp/bad.csv"
expect_error '--n = 0 is out of range' "$study" --n 0 --out "$tmp/bad.csv"
echo "sample_cli: ok"
