#pragma once
// A fragility study's analysis and report (issue 14): from the stripes' uncoupled peak closings (or, method "ida",
// the capacities) to fragility curves per gap, the site's annual rate and 50-year probability of pounding, and the
// risk-targeted separation (analysis/stripes.hpp does the statistics; this module reads and writes results).
//
//   /fragility  gaps [G] (ratios of d; gaps_m for a pair study), theta, beta and their bootstrap intervals,
//               status and note per gap, observed_n / observed_z / fitted [G, S] at the levels; attributes: method,
//               confidence, replicates, units of theta
//   /hazard     the curve used (im, rate), annual_rate, probability (in `years`) and intervals per gap, tail_share,
//               the rate-versus-separation curve (curve_gap, curve_rate, curve_probability), and the risk-targeted
//               separation as attributes (target_gap, target_gap_lo/hi, in metres too for a pair study)
#include <string>

#include "pounding/core/progress.hpp"
#include "pounding/results/results.hpp"

namespace pounding {

// Adds /fragility (and /hazard with a [hazard] section) to the results of a fragility study; nothing otherwise.
// `pounding run` calls it through RunOptions::analyse before the file is written; the report calls it for a file
// that lacks the groups. `hook` (may be null): progress of the bootstrap and jackknife loops and a stop flag
// (core/progress.hpp); a raised stop ends the analysis within a replicate by throwing Cancelled.
void analyse_fragility(results::Results& r, const WorkHook* hook = nullptr);
bool is_fragility_study(const results::Results& r);

std::string fragility_markdown(const results::Results& r);
std::string fragility_csv(const results::Results& r);

}  // namespace pounding
