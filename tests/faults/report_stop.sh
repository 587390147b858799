#!/usr/bin/env bash
# Issue 27.1: the report `pounding run` prints shows the separation bootstrap's progress and honours a stop.
# Before issue 27 the report ignored SIGINT/SIGTERM (the handler only raised a flag nobody read in the report), so
# a stop there waited for every replicate. The report is rendered before the results are written (issue 27.2: its
# time is in them), so a stop there is a stop in the analysis phase. A pair study with [report] bootstrap = 100000
# spends seconds in the report's bootstrap (the lognormal refit draws every analysis):
#  - "progress: report: separation bootstrap" lines on stderr;
#  - SIGINT there ends the run within 5 s with exit 130 and "interrupted during the analysis (report: separation
#    bootstrap)", the checkpoint holding every unit, no results file, no temporary;
#  - --resume then computes no unit and writes the results and the report (the full 100,000 replicates again).
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
  if [ "$rc" -eq 130 ] && [ "$(echo "$took < 5" | bc)" -eq 1 ] && [ ! -e "$tmp/s.h5" ] && [ -s "$tmp/s.h5.ckpt" ] \
     && grep -qE "interrupted during the analysis \(report: separation bootstrap\): all [0-9]+ units are checkpointed in $tmp/s.h5.ckpt" "$tmp/err"; then
    ok "exit 130 ${took} s after SIGINT in the report's bootstrap; checkpoint kept, no results file"
  else
    fail "exit $rc ${took} s after SIGINT in the report's bootstrap (want 130 within 5 s, the checkpoint kept, no results)"; tail -5 "$tmp/err"
  fi
  ls "$tmp"/*.tmp[0-9]* > /dev/null 2>&1 && fail "a temporary was left"
  rc=0; "$bin" run "$tmp/s.toml" --out "$tmp/s.h5" --resume --quiet > "$tmp/out2" 2> "$tmp/err2" || rc=$?
  if [ $rc -eq 0 ] && [ -s "$tmp/s.h5" ] && grep -q "^## Separation for this pair" "$tmp/out2" && ! grep -q "^progress: units" "$tmp/err2"; then
    ok "--resume wrote the results and the report"
  else
    fail "--resume after the stop: exit $rc"; tail -5 "$tmp/err2"
  fi
fi
[ $fails -eq 0 ] && echo "all report-stop checks passed" || { echo "$fails failure(s)"; exit 1; }
