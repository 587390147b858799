#pragma once
// Where the tests find their data, and what they do when some of it is absent.
//
// The real PEER records are not in the repository; they live in ../shared/records/real beside the clone
// (POUNDING_TEST_REAL_RECORDS_DIR, set by CMake for the tests only). A test that needs them starts with
// POUNDING_REQUIRE_REAL_RECORDS(): without the folder it is reported by ctest as skipped with the reason
// -- or, when the environment says CI (CI=true, as .ci/run has ../shared), it fails: a silent skip there
// would hide a broken path. The same rule for anything else a test needs from outside (SciPy):
// POUNDING_SKIP_OR_FAIL(reason).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#ifndef POUNDING_TEST_DATA_DIR
#error "POUNDING_TEST_DATA_DIR (tests/data) is set by CMakeLists.txt for the test targets"
#endif
#ifndef POUNDING_TEST_REAL_RECORDS_DIR
#error "POUNDING_TEST_REAL_RECORDS_DIR (../shared/records/real) is set by CMakeLists.txt for the test targets"
#endif
#ifndef POUNDING_TEST_SOURCE_DIR
#error "POUNDING_TEST_SOURCE_DIR is set by CMakeLists.txt for the test targets"
#endif

namespace pounding::testdata {

// The source tree (studies/, tools/), the tests' own data (tests/data) and the real records.
inline std::string source_dir() { return POUNDING_TEST_SOURCE_DIR; }
inline std::string data_dir() { return POUNDING_TEST_DATA_DIR; }
inline std::string real_records_dir() { return POUNDING_TEST_REAL_RECORDS_DIR; }

// CI=true (GitHub, GitLab and .ci/run's callers set it): missing data is a failure, not a skip.
inline bool in_ci() {
  const char* c = std::getenv("CI");
  if (!c) return false;
  const std::string v = c;
  return !v.empty() && v != "0" && v != "false" && v != "no";
}

// The folder counts as present when it holds its MANIFEST.tsv; a file missing from a present folder is then
// an ordinary read error (a failure), never a skip.
inline bool real_records_present() {
  return std::filesystem::is_regular_file(std::filesystem::path(real_records_dir()) / "MANIFEST.tsv");
}

inline std::string real_records_reason() {
  return "needs the real records in ../shared/records/real; see README (looked for " + real_records_dir() +
         "/MANIFEST.tsv)";
}

}  // namespace pounding::testdata

// Skip the current test with `reason`, or fail it under CI. Only in a TEST body (GTEST_SKIP returns from it).
#define POUNDING_SKIP_OR_FAIL(reason)                                              \
  do {                                                                             \
    if (::pounding::testdata::in_ci()) GTEST_FAIL() << "CI: " << (reason);         \
    GTEST_SKIP() << (reason);                                                      \
  } while (0)

#define POUNDING_REQUIRE_REAL_RECORDS()                                                   \
  do {                                                                                    \
    if (!::pounding::testdata::real_records_present())                                    \
      POUNDING_SKIP_OR_FAIL(::pounding::testdata::real_records_reason());                 \
  } while (0)
