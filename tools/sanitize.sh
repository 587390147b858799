#!/usr/bin/env bash
# The sanitizer run (README, "Sanitizers"): AddressSanitizer + UndefinedBehaviorSanitizer on every target
# (RelWithDebInfo) in build-asan/, then ctest there. Any sanitizer report fails its test (UBSan halts, ASan
# aborts, LeakSanitizer fails the process; tests/sanitize/lsan.supp names only Open MPI's libraries).
#   tools/sanitize.sh                 the whole suite (the identical-bits comparisons report themselves not
#                                     applicable there, with the reason: they hold for the Release build)
#   tools/sanitize.sh -R REGEX ...    any ctest arguments instead, e.g. one test family
# Prints the date, the commit and ctest's summary line at the end (what README's "Sanitizers" quotes).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build-asan -DPOUNDING_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPOUNDING_BUILD_BENCH=OFF \
  "${launcher[@]}" > /dev/null
start=$(date +%s)
cmake --build build-asan -j "$(nproc)"
built=$(date +%s)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rc=0
(cd build-asan && ctest --output-on-failure -j "$(nproc)" -O sanitize.log "$@") || rc=$?
end=$(date +%s)
echo "sanitize.sh: $(date -u +%Y-%m-%d) at $(git rev-parse --short HEAD), build $((built - start)) s, tests" \
     "$((end - built)) s: $(grep -E 'tests passed' build-asan/sanitize.log || echo 'no ctest summary')"
exit "$rc"
