# Sourced by the shell tests (tests/cli/*.sh, tests/faults/*.sh) after they set $src (the source dir).
#
#   skip_or_fail "<reason>"   exit 77 (ctest: SKIP_RETURN_CODE, reported as skipped with the reason) -- or,
#                             when CI is set (CI=true, as .ci/run has ../shared), exit 1: on CI a missing
#                             dependency is a broken set-up, not something to skip silently.
#   needs_real_records        sets $real to the real PEER records (../shared/records/real beside the clone, or
#                             $POUNDING_REAL_RECORDS from CMake) or skips/fails as above.
#   scaled_timeout <seconds>  prints <seconds> x $POUNDING_TIMEOUT_FACTOR (CMake sets the factor > 1 for the
#                             sanitizer build), rounded up, for `timeout "$(scaled_timeout 30)" ...`.

in_ci() {
  case "${CI:-}" in
    "" | 0 | false | no) return 1 ;;
    *) return 0 ;;
  esac
}

skip_or_fail() {
  if in_ci; then
    echo "FAIL (CI=$CI, so not skipped): $*" >&2
    exit 1
  fi
  echo "SKIPPED: $*"
  exit 77
}

needs_real_records() {
  real=${POUNDING_REAL_RECORDS:-${src:?set src before sourcing needs_real_records.sh}/../shared/records/real}
  [ -f "$real/MANIFEST.tsv" ] ||
    skip_or_fail "needs the real records in ../shared/records/real; see README (looked for $real/MANIFEST.tsv)"
}

scaled_timeout() {
  awk -v s="$1" -v f="${POUNDING_TIMEOUT_FACTOR:-1}" 'BEGIN { t = s * f; printf "%d\n", (t == int(t)) ? t : int(t) + 1 }'
}
