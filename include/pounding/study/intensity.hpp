#pragma once
// The study's intensity, hazard and target-spectrum sections (issue 14): what turns a study of records "as they
// are" into a multiple-stripe (or IDA) fragility study with a site hazard.
//
//   [intensity]  measure = "PGA" | "PGV" | "Sa" | "Sa_avg"        (motion/intensity.hpp)
//                period = <s> | "pair"     Sa: the period; "pair": the geometric mean of the two buildings' median
//                                          periods (a grid's median element, a distribution's median)
//                periods = [..] | {min, max, count}   Sa_avg: the periods of the geometric mean (count log-spaced)
//                damping = 0.05
//                levels = [0.1, 0.2, ...]  the stripes' IM levels (g for PGA, Sa, Sa_avg; m/s for PGV), increasing
//                max_scale = 10            a record whose factor to a level exceeds this is dropped from that stripe
//                method = "msa" | "ida"    multiple stripes (Baker 2015 MLE) or incremental dynamic analysis
//                tolerance = 0.01          ida, yielding structures: bisection on the scale factor until the
//                                          bracket of the IM at first contact is within this relative width
//   [hazard]     curve = "hazard.csv" (IM, annual rate of exceedance; relative to the study) | k0 = .., k = ..
//                years = 50;  target = 2.0 (% in `years`: the risk-targeted separation);  source = "..." (cited)
//
// Every value is checked here, so a bad level, a hazard table that does not decrease or a missing file is an
// InputError naming file:line and key before any work starts.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "pounding/core/enum_names.hpp"
#include "pounding/motion/intensity.hpp"

namespace pounding {

struct StructureModel;

enum class FragilityMethod : std::uint8_t { msa, ida };
inline constexpr EnumName<FragilityMethod> fragility_method_names[] = {{FragilityMethod::msa, "msa"},
                                                                       {FragilityMethod::ida, "ida"}};
constexpr const auto& enum_names(FragilityMethod) { return fragility_method_names; }

struct IntensitySpec {
  bool enabled = false;
  IntensityMeasure im;            // periods resolved ("pair" -> one period)
  bool period_pair = false;       // period = "pair"
  std::vector<double> levels;     // the stripes (IM units), strictly increasing
  double max_scale = 10.0;
  FragilityMethod method = FragilityMethod::msa;
  double tolerance = 0.01;
  bool bisection = false;         // ida on yielding buildings: hunt and bisection per (record, model, gap); set by
                                  // parse_study (linear pairs take the exact capacities of one run instead)
  std::string levels_where;       // "file:line [intensity].levels", for the checks made after the records load
  std::size_t stripes() const { return enabled && method == FragilityMethod::msa ? levels.size() : 0; }
};

struct HazardSpec {
  bool enabled = false;
  std::string curve;              // the CSV's path ("" for a power law)
  std::vector<double> im, rate;   // the table (IM units, 1/year); a power law: empty
  double k0 = 0, k = 0;           // power law lambda(x) = k0 x^-k
  double years = 50.0;
  double target = 2.0;            // % in `years`
  std::string source;
};

// The stripes of a multiple-stripe study: the IM of each record as loaded and its factor to each level.
struct StripePlan {
  std::size_t stripes = 0, records = 0;
  std::vector<double> im;              // [records], IM units
  std::vector<double> scale;           // [stripes x records]: level / im
  std::vector<std::uint8_t> dropped;   // [stripes x records]: 1 when the factor exceeds max_scale (not analysed)
  std::size_t dropped_count(std::size_t stripe) const;
};
// The IM of every record (motion/intensity.hpp) and the factors; no stripes without [intensity] (or for ida).
StripePlan plan_stripes(const IntensitySpec& spec, std::span<const double> im);
// Before any work: a multiple-stripe fit needs at least two stripes that some record reaches within max_scale.
// Throws InputError naming [intensity] levels, the records' IM range and the way out (levels in the IM's units,
// a larger max_scale) otherwise -- found before the first unit, not after the work.
void check_stripes_reachable(const IntensitySpec& spec, const StripePlan& plan);

// The bisection IDA's hunt (study/run.cpp): the scale factors at which a record of intensity `im` is analysed
// before bisecting, ascending: each level's factor below max_scale, then max_scale itself when a level lies beyond
// it. Capacities are censored at the last of them: at the top level, or at im max_scale when that is lower.
std::vector<double> ida_hunt_factors(const IntensitySpec& spec, double im);

// Parse the sections (null table: absent). `structures` resolves period = "pair".
IntensitySpec parse_intensity(const toml::table* t, const std::string& path, const StructureModel& structures);
HazardSpec parse_hazard(const toml::table* t, const std::string& path, const IntensitySpec& intensity);
// A hazard CSV: rows "im, rate" (a header line and # comments allowed); IM strictly increasing, rate strictly
// decreasing and positive; errors name file:line.
void read_hazard_csv(const std::string& file, std::vector<double>& im, std::vector<double>& rate);
// The median period of building b (0, 1): a distribution's median, a grid's median element.
double median_period(const StructureModel& structures, int b);

}  // namespace pounding
