#pragma once
// The plain fields of each Study section, listed once (issue 46 step 8, docs/runner-design.md section 6): the
// section's reader (src/study/study_sections.cpp, config::read_fields) reads each through config::TableReader with the
// default and range of its key in src/config/study_keys.cpp, and visit_settings (settings.hpp, store_fields) stores
// each by the key's store rule. A list is a generic lambda calling v(key, &Study::member) per field; the member is a double, int, bool,
// std::string or std::vector<double>. A field whose default is computed, whose value is a name among choices, or
// whose reading depends on other keys stays with its section's reader and its own line in visit_settings.
#include "pounding/motion/selection.hpp"
#include "pounding/study/intensity.hpp"
#include "pounding/study/study.hpp"

namespace pounding::study_fields {

inline constexpr auto records = [](auto&& v) {
  v("scale", &Study::scale);
  v("limit", &Study::record_limit);
  v("synthetic_only", &Study::synthetic_only);
};

inline constexpr auto gaps = [](auto&& v) {
  v("curve_step", &Study::curve_step);
};

inline constexpr auto contact = [](auto&& v) {
  v("e", &Study::e);
  v("level_tolerance", &Study::level_tolerance);
};

inline constexpr auto analysis = [](auto&& v) {
  v("substeps", &Study::substeps);
  v("threads", &Study::threads);
  v("free_vibration", &Study::free_vibration);
  v("displacement_limit", &Study::displacement_limit);
  v("skip_untouched", &Study::skip_untouched);
  v("scale_elastic", &Study::scale_elastic);
  v("max_excluded_fraction", &Study::max_excluded_fraction);
};

inline constexpr auto report = [](auto&& v) {
  v("targets", &Study::targets);
  v("confidence", &Study::confidence);
  v("bootstrap", &Study::bootstrap);
  v("compare_with", &Study::compare_with);
  v("html", &Study::html);
};

inline constexpr auto outputs = [](auto&& v) {
  v("forces", &Study::want_forces);
  v("amplification", &Study::want_amplification);
};

// Sections kept in structs of their own (their initialisers stay: the command line makes them too).
inline constexpr auto hazard = [](auto&& v) {
  v("years", &HazardSpec::years);
  v("target", &HazardSpec::target);
  v("source", &HazardSpec::source);
};

inline constexpr auto target_spectrum = [](auto&& v) {
  v("points", &SelectionOptions::points);
  v("damping", &SelectionOptions::damping);
  v("min_scale", &SelectionOptions::min_scale);
  v("max_scale", &SelectionOptions::max_scale);
};

}  // namespace pounding::study_fields
