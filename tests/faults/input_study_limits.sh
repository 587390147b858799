#!/usr/bin/env bash
# Issue 10.4: study-level sanity limits are errors naming the key (exit 2, one " ERROR: " line, no output):
#   - [structures] samples_per_pair = 2^40: the memory the result arrays would need, not std::bad_alloc
#   - [analysis] max_excluded_fraction: a new key, default 0.001, accepted in [0, 1], refused outside
#   - a suite entry whose scale makes a PGA of 100 g (a synthetic stand-in): the PGA bound, naming the entry
#   - [records] scale = 1000 on the synthetic suite
# Only the embedded synthetic suite; nothing from ../shared. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }

study() {  # study <file> <[structures] lines> <[analysis] lines> [<[records] lines>]
  printf 'seed = 3\n[records]\n%s\n[structures]\nperiods = [1.0]\n%s\n[analysis]\n%s\n' \
    "${4:-suite = \"builtin\"
synthetic_only = true
limit = 1}" "$2" "$3" > "$1"
}
expect() {  # expect <label> <study> <patterns...>
  local label=$1 s=$2 rc=0
  shift 2
  "$bin" run "$s" --out "$tmp/o.h5" --quiet > "$tmp/out" 2> "$tmp/err" || rc=$?
  local bad=""
  [ "$rc" = 2 ] || bad+=" exit $rc (want 2);"
  grep -q '^ ERROR: ' "$tmp/err" || bad+=" no ' ERROR: ' line;"
  [ "$(wc -l < "$tmp/err")" = 1 ] || bad+=" $(wc -l < "$tmp/err") lines on stderr (want 1);"
  local p
  for p in "$@"; do grep -qF -- "$p" "$tmp/err" || bad+=" no '$p';"; done
  ! ls "$tmp"/o.h5* > /dev/null 2>&1 || bad+=" output left: $(ls "$tmp"/o.h5*);"
  if [ -n "$bad" ]; then fail "$label:$bad stderr: $(head -c 400 "$tmp/err")"; else ok "$label: $(head -c 200 "$tmp/err")"; fi
  rm -f "$tmp"/o.h5*
}
runs() {  # runs <label> <study>: exit 0 and a results file
  local rc=0
  "$bin" run "$2" --out "$tmp/o.h5" --quiet > "$tmp/out" 2> "$tmp/err" || rc=$?
  if [ "$rc" = 0 ] && [ -s "$tmp/o.h5" ]; then ok "$1: runs"; else fail "$1: exit $rc: $(head -c 300 "$tmp/err")"; fi
  rm -f "$tmp"/o.h5*
}

# --- samples_per_pair = 2^40 (the sampler's own upper bound): the memory, before any allocation ----------
study "$tmp/huge.toml" 'samples_per_pair = 1099511627776' ''
expect "samples_per_pair = 2^40" "$tmp/huge.toml" "samples_per_pair = 1099511627776 needs 25 TiB of result arrays" \
  "1 record x 1 period pairs" "25 bytes per model" "more than the 64 GiB limit" "huge.toml:8 [structures].samples_per_pair" \
  "give samples_per_pair <="
# the impacts scene: 49 bytes more per gap (45, and impacts/substeps of coarse = "refine")
study "$tmp/huge2.toml" 'samples_per_pair = 400000000' ''
sed -i '1a scene = "impacts"' "$tmp/huge2.toml"
expect "samples_per_pair = 4e8, impacts scene" "$tmp/huge2.toml" "319 bytes per model" "more than the 64 GiB limit"
study "$tmp/fine.toml" 'samples_per_pair = 2' ''
runs "samples_per_pair = 2" "$tmp/fine.toml"
# issue 24.7: below the 64 GiB limit but above the memory this machine has (POUNDING_TEST_MEMORY_AVAILABLE stands in
# for MemAvailable: 2 GiB): refused before any work, naming the size, the key and the way out, not std::bad_alloc
study "$tmp/mem.toml" 'samples_per_pair = 20000000' ''
export POUNDING_TEST_MEMORY_AVAILABLE=2147483648
expect "samples_per_pair = 2e7 on a 2 GiB machine" "$tmp/mem.toml" "samples_per_pair = 20000000 needs 477 MiB of result arrays" \
  "more than the 2 GiB of memory available on this machine (MemAvailable)" "mem.toml:8 [structures].samples_per_pair" \
  "give samples_per_pair <= "
# the other ranks on the node take their share (OMPI_COMM_WORLD_LOCAL_SIZE as the MPI launcher sets it)
study "$tmp/mem2.toml" 'samples_per_pair = 1000000' ''
OMPI_COMM_WORLD_LOCAL_SIZE=8 expect "8 ranks on the node" "$tmp/mem2.toml" "for rank 0 (MemAvailable less the other 7 ranks on this node)"
unset POUNDING_TEST_MEMORY_AVAILABLE

# --- [analysis] max_excluded_fraction ------------------------------------------------------------------
study "$tmp/mef.toml" 'samples_per_pair = 2' 'max_excluded_fraction = 0.05'
runs "max_excluded_fraction = 0.05" "$tmp/mef.toml"
study "$tmp/mef0.toml" 'samples_per_pair = 2' 'max_excluded_fraction = 0'
runs "max_excluded_fraction = 0" "$tmp/mef0.toml"
for v in 1.5 -0.1 nan '"a lot"'; do
  study "$tmp/mefbad.toml" 'samples_per_pair = 2' "max_excluded_fraction = $v"
  want="max_excluded_fraction = $v is out of range"
  [ "$v" = nan ] && want="max_excluded_fraction = nan is not a finite number"
  [ "$v" = '"a lot"' ] && want="max_excluded_fraction must be a number"
  expect "max_excluded_fraction = $v" "$tmp/mefbad.toml" "$want" "mefbad.toml:10 [analysis].max_excluded_fraction"
done

# --- PGA bound on suite records (synthetic stand-ins) ----------------------------------------------------
cat > "$tmp/suite.toml" <<'TOML'
[suite]
name = "one"
[[record]]
id = "EQ1"
M = 6.5
R_km = 20
vs30 = 300
F = 0
pga_g = 0.5
scale = 200
TOML
study "$tmp/suite_scale.toml" 'samples_per_pair = 2' '' "suite = \"suite.toml\""
expect "suite entry scale = 200" "$tmp/suite_scale.toml" "PGA 100 g is above the 5 g" "0.5 g in the file, times scale 200" \
  "scale of record EQ1 of" "too large"
study "$tmp/study_scale.toml" 'samples_per_pair = 2' '' 'suite = "builtin"
synthetic_only = true
limit = 1
scale = 1000'
expect "[records] scale = 1000 on the synthetic suite" "$tmp/study_scale.toml" "g is above the 5 g" "times scale 1000" \
  "[records] scale in"

if [ "$fails" -gt 0 ]; then
  echo "FAIL: $fails check(s) failed"
  exit 1
fi
echo "input_study_limits: ok"
