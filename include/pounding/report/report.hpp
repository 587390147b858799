#pragma once
// Reports from a results file: the paper's Tables 2 and 3, the T1 x T2 matrix, the cubic fit (eq. 10),
// separation recommendations and code rules side by side. Markdown or CSV.
#include <cstdint>
#include <string>
#include <vector>

namespace pounding {

struct Results {
  std::string path, title, scene, scene_reason, contact_law, damping_law, stepper, study_text, date, commit;
  std::string exclusion_warning;  // non-empty: too many excluded analyses (the run exited with code 3)
  double restitution = 0, wall_time = 0, zeta = 0.05;
  std::int64_t ranks = 1, seed = 0;
  // records
  std::vector<std::string> record_id, record_name, record_note;
  std::vector<std::uint8_t> record_synthetic;
  std::vector<double> record_pga_g, record_duration;
  // models
  std::vector<double> T1, T2, h1, h2, code_gap, periods;
  std::vector<std::int32_t> i1, i2;
  std::vector<std::int64_t> sample;
  // [records x models]
  std::vector<std::uint8_t> status;
  std::vector<double> peak_u1, peak_u2, peak_closing;
  // impacts scene: [records x models x gaps]
  bool impacts = false;
  std::vector<double> gap_ratios;
  std::vector<std::uint8_t> imp_status;
  std::vector<std::int32_t> impact_count;
  std::vector<double> peak_force, imp_peak_u1, imp_peak_u2;
  // report settings (from the study text)
  std::vector<double> study_gap_ratios, targets;
  double code_gap_coefficient = 0.005;  // d = coefficient (h1 + h2) (Standard 2800: 0.005)
  double h1_report = 40, h2_report = 40, fit_min = 0.1, fit_max = 1.0, curve_max = 1.5, curve_step = 0.005;
  std::size_t records() const { return record_id.size(); }
  std::size_t models() const { return T1.size(); }
};

Results load_results(const std::string& path);

// Probability (fraction) that the uncoupled peak closing exceeds ratio x d, over all ok (record, model)s.
struct Curve {
  std::vector<double> x, p;  // p in [0, 1]
  std::int64_t n = 0;        // ok samples
};
Curve probability_curve(const Results& r, double step, double xmax, int record = -1);

std::string report_markdown(const Results& r);
std::string report_csv(const Results& r);

}  // namespace pounding
