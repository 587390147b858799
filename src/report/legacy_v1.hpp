#pragma once
// Results files written before /settings existed: the report's settings from the echoed study text. The
// only place outside study/ that parses a study.
#include "pounding/report/report.hpp"

namespace pounding::legacy_v1 {

ReportSettings report_settings_from_text(const results::Results& r);

}  // namespace pounding::legacy_v1
