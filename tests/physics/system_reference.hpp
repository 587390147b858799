#pragma once
// The SciPy reference of the system tests (tools/reference_systems.py, none of our code), shared by
// test_system_scipy.cpp, test_floor_column.cpp and test_row.cpp: the interpreter, whether it has numpy and scipy, a
// run of `reference_systems.py system` and its parsed output, and a stick's body in its JSON.
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include "system_test_support.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

namespace pounding::test {

inline std::string python() {
  const char* p = std::getenv("POUNDING_PYTHON");
  return p && *p ? p : "/usr/bin/python3";
}
inline bool have_scipy() { return std::system((python() + " -c 'import numpy, scipy' 2>/dev/null").c_str()) == 0; }

// `reference_systems.py system`'s output: (grid substeps, body, floor) -> peak |u| and final u; element -> impacts
// (continuous onsets); (grid, element) -> peak force.
struct Reference {
  std::map<std::tuple<int, int, int>, double> peak_u, final_u;
  std::map<int, int> impacts;
  std::map<std::pair<int, int>, double> peak_force;
};

inline Reference run_reference(const std::string& json) {
  testdata::TempDir tmp("system-scipy");
  const std::string in = tmp.file("in.json"), out = tmp.file("out.txt");
  std::ofstream(in) << json;
  const std::string cmd = python() + " " + testdata::source_dir() + "/tools/reference_systems.py system " + in + " " + out;
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  Reference R;
  std::ifstream f(out);
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    int a = 0, b = 0, c = 0;
    double v = 0;
    if (key == "peak_u" || key == "final_u") {
      s >> a >> b >> c >> v;
      (key == "peak_u" ? R.peak_u : R.final_u)[{a, b, c}] = v;
    } else if (key == "impacts") {
      s >> a >> b;
      R.impacts[a] = b;
    } else if (key == "peak_force") {
      s >> a >> b >> v;
      R.peak_force[{a, b}] = v;
    }
  }
  return R;
}

// A stick as the reference's body: masses, stiffnesses and Rayleigh a0, a1, or modal_zeta (classical damping).
inline std::string body_json(const Stick& s) {
  if (!s.modal_zeta.empty())
    return fmt::format(R"({{"m": [{:.17g}], "k": [{:.17g}], "modal_zeta": [{:.17g}]}})", fmt::join(s.m, ", "),
                       fmt::join(s.k, ", "), fmt::join(s.modal_zeta, ", "));
  return fmt::format(R"({{"m": [{:.17g}], "k": [{:.17g}], "a0": {:.17g}, "a1": {:.17g}}})", fmt::join(s.m, ", "),
                     fmt::join(s.k, ", "), s.a0, s.a1);
}

}  // namespace pounding::test
