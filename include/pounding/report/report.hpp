#pragma once
// Reports from a study's results (results/results.hpp): the paper's Tables 2 and 3, the T1 x T2 matrix, the
// cubic fit (eq. 10), separation recommendations and code rules side by side. Markdown or CSV. The report's
// settings come from the results' /settings; only files written before /settings existed go through the
// study text (src/report/legacy_v1.cpp).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "pounding/core/progress.hpp"
#include "pounding/results/results.hpp"

namespace pounding {

// What the report needs from the study: [gaps], [report], the seed, and of [structures] the code gap coefficient
// and whether the buildings' heights are given (a pair study: answers in metres) or come from the period-height
// rule (a grid study: answers in ratios of the code gap d).
struct ReportSettings {
  std::vector<double> gap_ratios, targets;  // gap_ratios: the axis (metres when `metres`)
  bool metres = false;   // [gaps] metres: the axis, curve and fit range are metres, every model's gap the same
  double existing = NAN;  // [gaps] existing (m): the as-built gap; NaN when not given
  double code_gap_coefficient = 0.005;  // d = coefficient (h1 + h2) (Standard 2800: 0.005)
  double fit_min = 0.1, fit_max = 1.0, curve_max = 1.5, curve_step = 0.005;
  double confidence = 0.95;
  int bootstrap = 2000;       // replicates of the two-stage bootstrap (analysis/separation.hpp)
  std::string compare_with;   // "stochastic-pounding": the published Table 3 and eq. 10 beside ours
  std::uint64_t seed = 0;     // the study's seed (the bootstrap's stream derives from it)
  bool pair = false;          // [structures] heights_specified
  // a bridge study (settings section "bridge"): its description and reference joint gap d (m)
  bool bridge = false;
  std::string bridge_text;
  double bridge_d = 0.0;
};
ReportSettings report_settings(const results::Results& r);

// The machine that ran the study, from the results' host, cpu_model and cpu_cores ("host 'h', CPU, n CPUs"), or
// "not recorded ..." for a file written before they were stored. The reports' "- machine:" line and provenance.
std::string run_machine(const results::Header& h);

// Probability (fraction) that the uncoupled peak closing exceeds ratio x d, over all ok (record, model)s.
struct Curve {
  std::vector<double> x, p;  // p in [0, 1]
  std::int64_t n = 0;        // ok samples
};
Curve probability_curve(const results::Results& r, double step, double xmax, int record = -1);

// `hook` (may be null): progress of the long loops (the separation bootstrap, a fragility study's fit when the
// file lacks it) and a stop flag (Cancelled, core/progress.hpp).
// `bootstrap_s` (may be null): the seconds spent ranking the demands and in the separation bootstrap are added to it.
std::string report_markdown(const results::Results& r, const WorkHook* hook = nullptr, double* bootstrap_s = nullptr);
std::string report_csv(const results::Results& r, const WorkHook* hook = nullptr, double* bootstrap_s = nullptr);

// Both texts of one file as report_markdown() and report_csv() give them (the same bytes), from ONE pass: the
// separation bootstrap runs once for both (the CSV's call covers every target and gap the Markdown asks for), a
// fragility file without its fit is analysed once. The HTML report takes this. `bootstraps`: the bootstraps that ran.
struct ReportTexts {
  std::string markdown, csv;  // csv: "" unless asked for
  int bootstraps = 0;
  double bootstrap_s = 0;  // seconds ranking the demands and in the bootstrap
};
ReportTexts report_texts(const results::Results& r, bool with_csv, const WorkHook* hook = nullptr);

}  // namespace pounding
