#pragma once
// Reports from a study's results (results/results.hpp): the paper's Tables 2 and 3, the T1 x T2 matrix, the
// cubic fit (eq. 10), separation recommendations and code rules side by side. Markdown or CSV. The report's
// settings come from the results' /settings; only files written before /settings existed go through the
// study text (src/report/legacy_v1.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "pounding/results/results.hpp"

namespace pounding {

// What the report needs from the study: [gaps], [report] and the code gap coefficient of [structures].
struct ReportSettings {
  std::vector<double> gap_ratios, targets;
  double code_gap_coefficient = 0.005;  // d = coefficient (h1 + h2) (Standard 2800: 0.005)
  double h1 = 40, h2 = 40, fit_min = 0.1, fit_max = 1.0, curve_max = 1.5, curve_step = 0.005;
};
ReportSettings report_settings(const results::Results& r);

// Probability (fraction) that the uncoupled peak closing exceeds ratio x d, over all ok (record, model)s.
struct Curve {
  std::vector<double> x, p;  // p in [0, 1]
  std::int64_t n = 0;        // ok samples
};
Curve probability_curve(const results::Results& r, double step, double xmax, int record = -1);

std::string report_markdown(const results::Results& r);
std::string report_csv(const results::Results& r);

}  // namespace pounding
