#!/usr/bin/env bash
# Set up (missing Debian packages, build) and run every test. Tests that need what a fresh clone does not
# have (the real records in ../shared/records/real) are reported as skipped, with the reason listed at the
# end; under CI=true (.ci/run) they fail instead.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/tools/setup.sh"
cd "$here/build"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rc=0
ctest --output-on-failure -j "$(nproc)" "$@" || rc=$?
# ctest names skipped tests but not why: the reason is the line after GoogleTest's "...: Skipped" or the
# "SKIPPED: ..." line of a shell test (tests/lib/needs_real_records.sh).
log=Testing/Temporary/LastTest.log
if [ -f "$log" ]; then
  awk '/^[0-9]+\/[0-9]+ Test: / { name = $3; next }
       after { why[name] = $0; after = 0; next }
       /: Skipped$/ { after = 1; next }
       /^SKIP(PED)?: / { sub(/^SKIP(PED)?: /, ""); why[name] = $0 }
       END { for (n in why) print "  " n ": " why[n] }' "$log" | sort > skipped.txt
  if [ -s skipped.txt ]; then
    echo "Skipped tests and why:"
    cat skipped.txt
  fi
fi
exit "$rc"
