#pragma once
// Selecting and amplitude-scaling records to a code design spectrum (issue 14 part 4). Research note
// /work/shared/research/fragility-and-codes.md 3.4 (the code rules) and 3.5 (the algorithm, worked numbers):
//   1. each candidate's 5 %-damped (options.damping) Sa at `points` log-spaced periods in [t_lo, t_hi];
//   2. its least-squares factor in log space (PEER ground-motion database tool, 2010), equal weights:
//        ln f = mean_j ln(S_T(T_j) / S_r(T_j)),   MSE = mean_j [ln S_T(T_j) - ln(f S_r(T_j))]^2;
//   3. eligible: min_scale <= f <= max_scale; the eligible are taken in order of MSE (ties by candidate index)
//      until `count` are chosen, passing over (Selection::refused says which and why, library.hpp says how a
//      recording is identified):
//        - a second copy of a recording already chosen (same event, station and axis: two digitisations);
//        - with components = one, the other component of a station already chosen (the better match is kept);
//        - a record of an event that already has max_per_event records chosen;
//      fewer than `count` left is an InputError saying which limit or rule to relax;
//   4. one suite factor F >= 1 on all so the code's condition holds for the arithmetic mean m(T) = mean_i f_i S_i:
//        F = max(1, max_T alpha S_T(T) / m(T)),
//      alpha = 0.9 (ASCE 7-16 16.2.3, EC8 3.2.3.1.2) or 1.0 (ASCE 7-10 16.1.3.1); EC8 also needs the mean PGA
//      (the zero-period value) >= S_T(0) = ag S, so F = max(F, S_T(0) / mean_i f_i PGA_i). "none": F = 1.
// The range [t_lo, t_hi] is the caller's: 0.2 T to 2 T for ASCE 7-16 and EC8 (T1), 0.2 T to 1.5 T for ASCE 7-10.
// The engine analyses one horizontal component: ASCE 7-16 compares maximum-direction (RotD100) spectra with
// the MCER target, so component spectra scaled to that target give conservative (larger) factors; the
// Selection's warnings say so.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/motion/records.hpp"

namespace pounding {

// Components of one station: one (default: one motion per station, the better-matching component; ASCE 7-16
// 16.2.2 and FEMA P-695 treat a station's two components as ONE record, so two of them in a one-direction
// analysis would count one ground motion twice) or both.
enum class ComponentRule : std::uint8_t { one, both };
inline constexpr EnumName<ComponentRule> component_rule_names[] = {{ComponentRule::one, "one"},
                                                                   {ComponentRule::both, "both"}};
constexpr const auto& enum_names(ComponentRule) { return component_rule_names; }
ComponentRule parse_component_rule(const std::string& name);  // InputError (where "--components") otherwise

// The limits validate() enforces, the same for `records select` and a study's [target_spectrum]: the match
// periods lie in the spectra's domain (spectrum.hpp's default grid runs 0.01-10 s; design spectra are defined
// to TL <= 20 s), points at most 1000 (30 is the PEER tool's practice; more buys nothing but time).
inline constexpr double selection_period_min = 0.01, selection_period_max = 20.0;  // s
inline constexpr int selection_points_max = 1000;
inline constexpr double selection_scale_min = 1e-3, selection_scale_max = 1e3;
inline constexpr double selection_damping_max = 0.5;
// FEMA P-695 (2009) Appendix A: the far-field set takes at most two records from any one earthquake "to avoid
// event bias"; ASCE 7-16 16.2.2 asks for motions from events consistent with the hazard, and records of one
// event share its source, path and magnitude, so their responses are not independent samples.
inline constexpr std::size_t default_max_per_event = 2;

enum class ScalingRule : std::uint8_t { asce7_16, asce7_10, ec8, none };
inline constexpr EnumName<ScalingRule> scaling_rule_names[] = {{ScalingRule::asce7_16, "ASCE 7-16"},
                                                               {ScalingRule::asce7_10, "ASCE 7-10"},
                                                               {ScalingRule::ec8, "EC8"},
                                                               {ScalingRule::none, "none"}};
constexpr const auto& enum_names(ScalingRule) { return scaling_rule_names; }  // to_string(ScalingRule)
// "ASCE 7-16", "ASCE 7-10", "EC8", "none"; InputError (where "--rule") listing them otherwise.
ScalingRule parse_scaling_rule(const std::string& name);
// The fraction of the target the mean must reach: 0.9, 1.0, 0.9; 0 for none (no condition).
double rule_fraction(ScalingRule rule);

struct SelectionOptions {
  std::size_t count = 11;    // N records to choose
  double t_lo = 0, t_hi = 0; // s, the period range (the caller computes it from the period(s)); 0 < t_lo < t_hi
  int points = 30;           // log-spaced periods in [t_lo, t_hi] for matching and for the code check, >= 2
  double min_scale = 0.25, max_scale = 4.0;  // a candidate whose least-squares factor is outside is not eligible
  ScalingRule rule = ScalingRule::asce7_16;
  double damping = 0.05;     // of the record spectra, [0, selection_damping_max]
  std::size_t max_per_event = default_max_per_event;  // records of one event at most; 0: no limit
  ComponentRule components = ComponentRule::one;
  bool mcer_target = false;  // the target is ASCE 7's MCER spectrum (1.5 x design): what ASCE 7-16 16.2 scales to
};
void validate(const SelectionOptions& options);  // InputError naming the option

struct SelectionCandidate {
  std::string id;
  const Record* record;  // not owned; must outlive select_records. Its identity: identity_of (library.hpp)
};

struct RefusedCandidate {
  std::size_t candidate;  // index into the candidates
  std::string reason;     // "the same recording as X (event, station, component 180 ~ NS)", ...
};

struct Selection {
  std::vector<std::size_t> chosen;          // indices into the candidates, best match (smallest MSE) first
  std::vector<double> individual_scale;     // f_i, the log-space least-squares factor of each chosen record
  std::vector<double> mse;                  // its misfit (mean squared log error over the periods)
  std::vector<RecordIdentity> identity;     // its event, station, component (library.hpp; unknown: from empty)
  double suite_factor = 1;                  // F >= 1 applied to all so the code's condition holds
  std::vector<double> scale;                // f_i F, the factors the records are used with
  std::vector<double> periods, target;      // the check periods (s) and the target Sa (g)
  std::vector<double> mean;                 // arithmetic mean of the scaled spectra at the periods (g)
  std::vector<std::vector<double>> spectra; // each chosen record's spectrum at the periods, unscaled (g)
  double min_ratio = 0;                     // min over the periods of mean/target (EC8: and pga_ratio)
  double pga_ratio = 0;                     // EC8: mean scaled PGA / target.sa(0); 0 for the other rules
  std::string rule_text;                    // the code condition in words
  bool meets = false;                       // the condition holds after scaling (within 1e-9); "none": true
  std::vector<std::string> warnings;        // final scale outside the limits, too few records, RotD100, ...
  std::size_t eligible = 0;                 // candidates with a factor within the limits
  std::vector<RefusedCandidate> refused;    // eligible candidates passed over by the recording/event rules, in
                                            // rank order (only those ranked above the last chosen record)
  std::size_t unidentified = 0;             // candidates without event/station (never refused as duplicates)
};

// Throws InputError for invalid options, a null or empty record, a target that is not > 0 over the range
// (or, EC8, has no value at T = 0), and fewer than options.count eligible candidates.
Selection select_records(std::span<const SelectionCandidate> candidates, const DesignSpectrum& target,
                         const SelectionOptions& options);

// The pure-number building blocks (research note 3.5).
struct LogFit {
  double scale, mse;
};
// Equal weights. InputError unless the spans have the same non-zero length and every value is > 0.
LogFit log_least_squares_scale(std::span<const double> target, std::span<const double> record);
// F = max(1, max_T fraction S_T(T) / m(T)), m the arithmetic mean of the scaled spectra at each period.
// InputError for an empty suite or a spectrum whose length differs from the target's.
double suite_factor(std::span<const double> target, std::span<const std::vector<double>> scaled_spectra,
                    double fraction);
// `points` periods log-spaced from t_lo to t_hi inclusive.
std::vector<double> log_spaced(double t_lo, double t_hi, int points);
// Step 3's rules: walks `ranked` (eligible candidate indices, best first) and returns the first options.count
// that are distinct recordings within max_per_event and the components rule; fills s.refused and s.unidentified.
// InputError when fewer than options.count remain.
std::vector<std::size_t> apply_recording_rules(Selection& s, std::span<const SelectionCandidate> candidates,
                                               const std::vector<std::size_t>& ranked, const SelectionOptions& options);

}  // namespace pounding
