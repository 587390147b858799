#!/usr/bin/env bash
# Issue 27.1: the report `pounding run` prints after the results shows the separation bootstrap's progress and
# honours a stop. Before issue 27 the report ignored SIGINT/SIGTERM (the handler only raised a flag nobody read in
# the report), so a stop there waited for every replicate. A pair study with [report] bootstrap = 100000 spends
# seconds in the report's bootstrap (the lognormal refit draws every analysis):
#  - "progress: report: separation bootstrap" lines on stderr;
#  - SIGINT there ends the run within 5 s with exit 130 and "interrupted during the report", the results file
#    complete (the report can be written from it later), no temporary left.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
sed -e 's/^output = .*//' -e 's/^bootstrap = 2000/bootstrap = 100000/' -e 's/^synthetic_only = true/synthetic_only = true\nlimit = 8/' \
  "$src/studies/example-pair.toml" > "$tmp/s.toml"
grep -q '^bootstrap = 100000' "$tmp/s.toml" || { echo "FAIL: could not derive the study from studies/example-pair.toml"; exit 1; }
"$bin" run "$tmp/s.toml" --out "$tmp/s.h5" > "$tmp/out" 2> "$tmp/err" &
pid=$!
seen=0
for _ in $(seq 1 600); do
  grep -q "^progress: report: separation bootstrap" "$tmp/err" && { seen=1; break; }
  kill -0 "$pid" 2> /dev/null || break
  sleep 0.1
done
if [ $seen -eq 0 ]; then
  fail "no 'progress: report: separation bootstrap' line within 60 s"; cat "$tmp/err"; kill -9 "$pid" 2> /dev/null || true
else
  ok "the report's bootstrap shows progress ($(grep -m1 '^progress: report' "$tmp/err"))"
  t0=$(date +%s.%N)
  kill -INT "$pid"; rc=0; wait "$pid" || rc=$?
  took=$(echo "$(date +%s.%N) - $t0" | bc)
  if [ "$rc" -eq 130 ] && [ "$(echo "$took < 5" | bc)" -eq 1 ] && [ -s "$tmp/s.h5" ] \
     && grep -q "interrupted during the report (report: separation bootstrap): the results file $tmp/s.h5 is complete" "$tmp/err"; then
    ok "exit 130 ${took} s after SIGINT in the report's bootstrap; results file kept"
  else
    fail "exit $rc ${took} s after SIGINT in the report's bootstrap (want 130 within 5 s, the results kept)"; tail -5 "$tmp/err"
  fi
  ls "$tmp"/*.tmp[0-9]* > /dev/null 2>&1 && fail "a temporary was left"
  [ -e "$tmp/s.h5.ckpt" ] && fail "the checkpoint was left beside complete results"
fi
[ $fails -eq 0 ] && echo "all report-stop checks passed" || { echo "$fails failure(s)"; exit 1; }
