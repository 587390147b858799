#!/usr/bin/env bash
# One header for every `pounding simulate` summary (src/report/summary.cpp run_header): the pair and a multi-storey
# system print the same record / stepper / contact-law lines, and the system's copy carries the damping law's
# stiffness factor too (before issue 27's clean-up the system summary had its own copy without the
# contact_stiffness_factor line that the pair prints for damping law three-spring, k_eq = 1.5 k).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
header() { sed -n '/^record: /,/^e_target: /p' "$1"; }
"$bin" simulate --damping-law three-spring --gap 0.02 --dt 0.001 > "$tmp/pair.txt"
"$bin" simulate --damping-law three-spring --gap 0.02 --dt 0.001 --storeys1 2 --storeys2 3 > "$tmp/system.txt"
grep -qx "contact_stiffness_factor: 1.5" "$tmp/pair.txt" || fail "the pair summary lacks contact_stiffness_factor: 1.5"
grep -qx "contact_stiffness_factor: 1.5" "$tmp/system.txt" || fail "the system summary lacks contact_stiffness_factor: 1.5"
[ "$(header "$tmp/pair.txt" | wc -l)" -ge 10 ] || fail "the pair summary's header is short: $(header "$tmp/pair.txt")"
diff <(header "$tmp/pair.txt") <(header "$tmp/system.txt") || fail "the pair's and the system's header lines differ"
# a law without a stiffness factor prints none
"$bin" simulate --gap 0.02 --dt 0.001 --storeys1 2 --storeys2 3 > "$tmp/ln.txt"
! grep -q "contact_stiffness_factor" "$tmp/ln.txt" || fail "lankarani-nikravesh printed a stiffness factor"
echo "ok: one header for the pair and the system summaries, contact_stiffness_factor for three-spring in both"
