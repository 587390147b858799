#pragma once
// Selecting and amplitude-scaling records to a code design spectrum (issue 14 part 4). Research note
// /work/shared/research/fragility-and-codes.md 3.4 (the code rules) and 3.5 (the algorithm, worked numbers):
//   1. each candidate's 5 %-damped (options.damping) Sa at `points` log-spaced periods in [t_lo, t_hi];
//   2. its least-squares factor in log space (PEER ground-motion database tool, 2010), equal weights:
//        ln f = mean_j ln(S_T(T_j) / S_r(T_j)),   MSE = mean_j [ln S_T(T_j) - ln(f S_r(T_j))]^2;
//   3. eligible: min_scale <= f <= max_scale; the `count` eligible with the smallest MSE are chosen (ties by
//      candidate index); fewer eligible than `count` is an InputError saying which limit to relax;
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
#include "pounding/motion/records.hpp"

namespace pounding {

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
  double damping = 0.05;     // of the record spectra, [0, 1)
};
void validate(const SelectionOptions& options);  // InputError naming the option

struct SelectionCandidate {
  std::string id;
  const Record* record;  // not owned; must outlive select_records
};

struct Selection {
  std::vector<std::size_t> chosen;          // indices into the candidates, best match (smallest MSE) first
  std::vector<double> individual_scale;     // f_i, the log-space least-squares factor of each chosen record
  std::vector<double> mse;                  // its misfit (mean squared log error over the periods)
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

}  // namespace pounding
