// Results files from before /settings: the report's settings read back from the echoed study text.
#include "legacy_v1.hpp"

#include "pounding/study/study.hpp"

namespace pounding::legacy_v1 {

ReportSettings report_settings_from_text(const results::Results& r) {
  const Study s = parse_study(r.header.study_text, r.header.study_path);
  ReportSettings set;
  set.gap_ratios = s.gap_ratios;
  set.targets = s.targets;
  set.code_gap_coefficient = s.structures.code_gap_coefficient;
  set.fit_min = s.fit_min, set.fit_max = s.fit_max;
  set.seed = s.seed;
  set.compare_with = s.compare_with;
  set.confidence = s.confidence, set.bootstrap = s.bootstrap;
  set.curve_max = s.curve_max, set.curve_step = s.curve_step;
  return set;
}

}  // namespace pounding::legacy_v1
