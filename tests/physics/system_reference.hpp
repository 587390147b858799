#pragma once
// The SciPy reference of the system tests (tools/reference_systems.py, none of our code), shared by
// test_system_scipy.cpp, test_floor_column.cpp and test_row.cpp: the interpreter, whether it has numpy and scipy, a
// run of `reference_systems.py system` and its parsed output, and a stick's body in its JSON.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <span>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include "pounding/motion/records.hpp"
#include "pounding/physics/system_batch.hpp"
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

// The first `seconds` of El Centro 1940 NS (PEER, dt 0.02 s; ../shared/records/real), m/s^2; dt set from the file.
inline std::vector<double> el_centro(double seconds, double& dt) {
  const Record r = read_record(testdata::real_records_dir() + "/ImperialValley_1940_ElCentro_NS_Peknold1559pts.AT2");
  dt = r.dt;
  const auto n = static_cast<std::size_t>(std::lround(seconds / dt)) + 1;
  return {r.acc.begin(), r.acc.begin() + static_cast<long>(std::min(n, r.acc.size()))};
}

// A stick with Rayleigh a0, a1, or with classical modal damping ratios.
inline Stick stick(std::vector<double> m, std::vector<double> k, double a0 = 0.0, double a1 = 0.0) {
  Stick s;
  s.m = std::move(m), s.k = std::move(k), s.a0 = a0, s.a1 = a1;
  return s;
}
inline Stick modal_stick(std::vector<double> m, std::vector<double> k, std::vector<double> zeta) {
  Stick s;
  s.m = std::move(m), s.k = std::move(k), s.modal_zeta = std::move(zeta);
  return s;
}

// The observed order of convergence between two errors one halving apart.
inline double order(double e_coarse, double e_fine) { return std::log2(e_coarse / e_fine); }

// The engine's results of one lane of `S` (the sticks filled in body order, every element with gap, kc, e) at
// `substeps` with `stepper`.
inline physics::SystemResult run_engine(const model::System& S, const std::vector<Stick>& sticks,
                                        const std::vector<double>& ag, double dt, int substeps, double gap, double kc,
                                        double e, std::span<const ContactModel> groups,
                                        Stepper stepper = Stepper::central_difference) {
  physics::SystemBatch B;
  B.resize(S, 1);
  for (std::size_t b = 0; b < sticks.size(); ++b) fill_stick(B, static_cast<int>(b), 0, sticks[b]);
  for (std::size_t k = 0; k < S.contacts().size(); ++k) B.gap[k] = gap, B.kc[k] = kc, B.e[k] = e;
  KernelSettings ks;
  ks.substeps = substeps, ks.stepper = stepper;
  physics::SystemResult r;
  physics::run_system(B, groups, GroundMotion{dt, ag, 0.0}, ks, r);
  return r;
}

// The 3- vs 5-storey pair (Rayleigh-damped elastic storeys) pounding with Hertzdamp at its three common levels under
// 8 s of El Centro, and its solve_ivp reference with event-located onsets at dt/10 .. dt/80 (test_system_scipy.cpp,
// test_system_steppers.cpp).
struct PoundingPairCase {
  double dt = 0;
  std::vector<double> ag;
  std::vector<int> grids{10, 20, 40, 80};
  double gap = 0.01, kc = 1.0e10, e = 0.65;
  std::vector<Stick> sticks;
  model::System S;
  Reference R;
};
inline PoundingPairCase pounding_pair_case() {
  PoundingPairCase c;
  c.ag = el_centro(8.0, c.dt);
  c.sticks = {stick({3.0e5, 3.0e5, 2.5e5}, {4.0e8, 3.6e8, 3.0e8}, 0.7, 0.0015),
              stick({2.5e5, 2.5e5, 2.5e5, 2.2e5, 2.0e5}, {2.6e8, 2.5e8, 2.3e8, 2.0e8, 1.6e8}, 0.4, 0.003)};
  c.S = shear_row({3, 5}, true);
  std::string contacts;
  for (int k = 1; k <= 3; ++k)
    contacts += fmt::format(R"({}{{"left": [0, {}], "right": [1, {}], "gap": {}, "kc": {}, "n": 1.5, "e": {}, "v0_min": 0.001}})",
                            k > 1 ? ", " : "", k, k, c.gap, c.kc, c.e);
  c.R = run_reference(fmt::format(
      R"({{"mode": "nonlinear", "dt": {:.17g}, "ag": [{:.17g}], "duration": {:.17g}, "substeps": [{}], "bodies": [{}, {}], "contacts": [{}]}})",
      c.dt, fmt::join(c.ag, ", "), c.dt * static_cast<double>(c.ag.size() - 1), fmt::join(c.grids, ", "),
      body_json(c.sticks[0]), body_json(c.sticks[1]), contacts));
  return c;
}

}  // namespace pounding::test
