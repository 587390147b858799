#pragma once
// The stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1): realistic pairs of
// SDOF structures drawn reproducibly, one independent random stream per sample identity.
//
// Parameters of one structure (SI units: m, s, kg, N, kg/m^3):
//   T       fundamental period, a point of the period grid (default 1.00, 1.05, ..., 1.50 s)
//   h       effective height, uniform on [max(h_min, (T/ct_upper)^(1/x)), min(h_max, (T/ct_lower)^(1/x))],
//           i.e. the period-height rule ct_lower h^x <= T <= ct_upper h^x (eq. 6; 0.05, 0.08, x = 0.75)
//           intersected with the height limits (30-50 m)
//   aspect  h/r, one of the aspect ratios (1, 2, 3) with equal probability
//   r       foundation radius r = h / aspect
//   rho     soil mass density, lognormal (mean 1800, CoV 6.8 %); drawn per structure, independently (the
//           paper states no correlation between the two sites)
//   mbar    mass index m / (rho r^2 h) (eq. 7), lognormal (mean 0.6, CoV 20 %) truncated to [0.4, 0.8]
//   m       mbar rho r^2 h
//   k       4 pi^2 m / T^2 (eq. 8);  c = 2 zeta sqrt(k m) (eq. 9, zeta = 0.05)
//   fy, alpha  bilinear kinematic hardening: u_y = drift h / ductility (2 % drift, ductility 6), fy = k u_y,
//           alpha = 0.05 (section 2.1)
// Per pair:
//   d       code separation (Standard 2800, eq. 5): d = 0.005 (h1 + h2); study gaps are ratios of d
//   kh      Hertz contact stiffness: equivalent concrete spheres of masses m1, m2 (muthukumar eqs 11-13),
//           or a value given directly by the study
//
// NOT sampled: the soil shear-wave velocity V_s (175-375 m/s in the paper, section 3.1). A fixed-base SDOF
// does not use it (no soil-structure interaction), and sampling what no model uses would only shift the
// streams. rho enters only through the mass m = mbar rho r^2 h.
//
// The mean and CoV of mbar are those of the parent lognormal before truncation; the truncated
// distribution is sampled exactly by inverse CDF (see sampler.cpp).
//
// Random numbers: 8 uniforms per pair in a fixed order (structure 1 then 2; each h, aspect, rho, mbar), each
// from 53 bits of two engine outputs, mapped by inverse CDF (Boost.Math normal quantile in double precision);
// no std:: distributions (their algorithms are implementation-defined).
//
// Reproducibility (OpenMC's idea): a sample's identity is (i1, i2, sample) -- period indices of structures 1
// and 2 into the grid and the sample index within that period pair. Its engine (boost::random::taus88, a
// combined Tausworthe generator) is seeded only from (study seed, stream, identity) through a SplitMix64 mix
// (stream_seed; the 64-bit key and splitmix64(key) give the engine's three 32-bit seed words), so the same structures appear
// for every record and gap (common random numbers), at any rank count, batch width or order of work; and
// the first N samples of a pair do not depend on samples_per_pair.
//
// Where the seed lives: the top-level integer key `seed` of the study file (not in [structures]);
// `parse_study_seed` reads it. Streams: `structure_stream` (1) is the structure model's stream id.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "pounding/physics/batch.hpp"
#include "pounding/core/enum_names.hpp"
#include "pounding/core/random.hpp"  // splitmix64

namespace pounding {

enum class Hysteresis : std::uint8_t {
  bilinear,  // kinematic hardening with fy from drift/ductility and alpha (the paper's model)
  elastic,   // fy = +inf: linear elastic structures
};
inline constexpr EnumName<Hysteresis> hysteresis_names[] = {{Hysteresis::bilinear, "bilinear"},
                                                            {Hysteresis::elastic, "elastic"}};
constexpr const auto& enum_names(Hysteresis) { return hysteresis_names; }  // to_string(Hysteresis), enum_names.hpp

// All settings of the structure model; the defaults reproduce the paper. A study file's [structures]
// table sets any of them (key names in parse_structure_model).
struct StructureModel {
  std::vector<double> periods = default_periods();  // period grid (s), strictly increasing
  std::int64_t samples_per_pair = 256;               // paper: 256 x 121 pairs = 30,976 models
  std::vector<double> aspect_ratios{1.0, 2.0, 3.0};  // h/r values, equally likely
  double rho_mean = 1800.0, rho_cov = 0.068;         // soil density lognormal (kg/m^3)
  double mbar_mean = 0.6, mbar_cov = 0.20;           // parent lognormal of the mass index
  double mbar_min = 0.4, mbar_max = 0.8;             // truncation interval of the mass index
  double zeta = 0.05;                                // viscous damping ratio
  Hysteresis hysteresis = Hysteresis::bilinear;
  double drift = 0.02, ductility = 6.0;              // yield displacement u_y = drift h / ductility
  double alpha = 0.05;                               // post-yield stiffness ratio
  double height_min = 30.0, height_max = 50.0;       // height limits (m)
  double ct_lower = 0.05, ct_upper = 0.08;           // period-height rule ct_lower h^x <= T <= ct_upper h^x
  double height_exponent = 0.75;                     // x
  double code_gap_coefficient = 0.005;               // d = coefficient (h1 + h2)
  // Equivalent-sphere Hertz stiffness (muthukumar eqs 11-13): concrete of 4000 psi as in that paper,
  // E = 57000 sqrt(4000) psi = 24.86 GPa, nu = 0.15, density 2400 kg/m^3.
  double contact_density = 2400.0, contact_youngs_modulus = 24.86e9, contact_poisson = 0.15;
  double kh = 0.0;  // > 0: the Hertz stiffness (N/m^1.5) for every pair; 0: equivalent spheres

  // 1.00, 1.05, ..., 1.50 s (section 3).
  static std::vector<double> default_periods();
  std::int64_t period_pair_count() const { return static_cast<std::int64_t>(periods.size() * periods.size()); }
  std::int64_t model_count() const { return period_pair_count() * samples_per_pair; }
};

// lo + i step for i = 0..n-1 where n = round((hi - lo)/step) + 1; throws InputError (naming `where`) when
// (hi - lo)/step is not an integer to 1e-9 or the grid is empty.
std::vector<double> make_period_grid(double lo, double hi, double step, const std::string& where = "periods");

// Height interval for period T: [max(h_min, (T/ct_upper)^(1/x)), min(h_max, (T/ct_lower)^(1/x))].
struct HeightInterval {
  double lo = 0.0, hi = 0.0;
};
// Throws InputError naming T and both bounds when the interval is empty (lo > hi).
HeightInterval height_interval(const StructureModel& model, double T, const std::string& where = "[structures]");

// Checks every setting and the cross-conditions (grid increasing, intervals non-empty for every period,
// mbar_min < mbar_max, ...); throws InputError naming `where` and the allowed range.
void validate(const StructureModel& model, const std::string& where = "[structures]");

// Reads a study file's [structures] table (pass an empty table for all defaults). Keys:
//   periods = [..]  or  period_min, period_max, period_step;  samples_per_pair; aspect_ratios = [..];
//   rho_mean, rho_cov; mbar_mean, mbar_cov, mbar_min, mbar_max; zeta; hysteresis = "bilinear"|"elastic";
//   drift, ductility, alpha; height_min, height_max; ct_lower, ct_upper, height_exponent;
//   code_gap_coefficient; contact_density, contact_youngs_modulus, contact_poisson; kh.
// Unknown keys, wrong types and out-of-range values throw InputError naming file:line, the key and the
// allowed range. The seed is NOT in this table (see parse_study_seed).
StructureModel parse_structure_model(const toml::table& table, const std::string& file);

// The study's top-level `seed` (an integer in [0, 2^63 - 1]); required, errors name file:line.
std::uint64_t parse_study_seed(const toml::table& root, const std::string& file);

// Stream ids: one per consumer of random numbers, so they never share a stream.
inline constexpr std::uint64_t structure_stream = 1;

// Global identity of a sample: period indices of structure 1 (left) and 2 (right), sample index in the pair.
struct SampleId {
  std::int32_t i1 = 0, i2 = 0;
  std::int64_t sample = 0;
  friend bool operator==(const SampleId&, const SampleId&) = default;
};

// The engine seed of one sample: splitmix64 chained over seed, stream, (i1, i2) and sample.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, const SampleId& id);

struct SampledStructure {
  double T = 0, h = 0, aspect = 0, r = 0, rho = 0, mbar = 0;
  double m = 0, k = 0, c = 0, fy = 0, alpha = 0;
  Structure structure() const { return Structure{m, k, c, fy, alpha}; }
};

struct SampledPair {
  SampleId id;
  SampledStructure s1, s2;  // 1 = left, 2 = right
  double d = 0;             // code separation 0.005 (h1 + h2) (eq. 5)
  double kh = 0;            // Hertz contact stiffness (N/m^1.5)
  // The kernel's input: gap = gap_ratio d, kc = kh, restitution e, at rest.
  PairParams pair_params(double gap_ratio, double e) const;
};

// Draws pairs for one (model, seed, stream). Construction validates the model (InputError) and precomputes
// the distributions; sample() is const and thread-safe.
class StructureSampler {
 public:
  StructureSampler(StructureModel model, std::uint64_t seed, std::uint64_t stream = structure_stream);

  // Requires 0 <= i1, i2 < periods.size() and sample >= 0 (throws std::out_of_range otherwise).
  SampledPair sample(const SampleId& id) const;
  // Samples first, first + 1, ... of period pair (i1, i2) into out.
  void sample_block(std::int32_t i1, std::int32_t i2, std::int64_t first, std::span<SampledPair> out) const;

  // Global index (i1 n + i2) samples_per_pair + sample, and back; an ordering of work, not the seed.
  std::int64_t global_index(const SampleId& id) const;
  SampleId identity(std::int64_t global_index) const;

  const StructureModel& model() const { return model_; }
  std::uint64_t seed() const { return seed_; }
  std::uint64_t stream() const { return stream_; }
  const HeightInterval& heights(std::size_t period_index) const { return heights_[period_index]; }
  // Parameters of the lognormals: ln X ~ N(mu, sigma^2).
  double rho_mu() const { return rho_mu_; }
  double rho_sigma() const { return rho_sigma_; }
  double mbar_mu() const { return mbar_mu_; }
  double mbar_sigma() const { return mbar_sigma_; }

 private:
  template <class Gen>
  SampledStructure draw_structure(Gen& g, std::size_t period_index) const;

  StructureModel model_;
  std::uint64_t seed_, stream_;
  std::vector<HeightInterval> heights_;
  double rho_mu_, rho_sigma_, mbar_mu_, mbar_sigma_;
  double mbar_za_, mbar_zb_;          // standardised truncation bounds (ln a - mu)/sigma, (ln b - mu)/sigma
  double mbar_pa_, mbar_pb_;          // Phi(za), Phi(zb)  (lower tails)
  double mbar_qa_, mbar_qb_;          // 1 - Phi(za), 1 - Phi(zb)  (upper tails)
  bool mbar_upper_tail_;              // sample through the upper tail (za > 0) to keep precision
};

// One pair for (model, seed, stream, identity); builds a sampler each call (use StructureSampler in loops).
SampledPair sample_pair(const StructureModel& model, std::uint64_t seed, std::uint64_t stream, const SampleId& id);

// ln X ~ N(mu, sigma^2) with E[X] = mean, CoV[X] = cov: sigma^2 = ln(1 + cov^2), mu = ln(mean) - sigma^2 / 2.
struct LognormalParams {
  double mu = 0, sigma = 0;
};
LognormalParams lognormal_from_mean_cov(double mean, double cov);

}  // namespace pounding
