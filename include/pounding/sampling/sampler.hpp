#pragma once
// The stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1): realistic pairs of
// SDOF structures drawn reproducibly, one independent random stream per sample identity.
//
// Each building of a pair has its own model (building.hpp): [structures] gives the defaults of both, and the
// tables [structures.building1] (left) and [structures.building2] (right) override any per-building key and may
// give period, height, mass, zeta and yield_coefficient as a number or a distribution. Without building tables
// both buildings are the paper's model below, bit for bit as before.
//
// Parameters of one structure (SI units: m, s, kg, N, kg/m^3), defaults:
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
//           alpha = 0.05 (section 2.1); or fy = Cy m g for a building given yield_coefficient Cy
// A building given its period as a distribution has one period "slot" whose T is drawn per sample (truncated
// to the periods the height rule admits when h comes from the rule, then h uniform on the rule interval at T);
// a given height or mass replaces the rule or the mass-index model (aspect, r, rho, mbar are then NaN).
// equal_heights = true: one height for both, uniform on the intersection of their rule intervals.
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
// Random numbers: 14 uniforms per pair in a fixed order: first the paper's 8 (structure 1 then 2; each h, aspect,
// rho, mbar), then per structure (1 then 2) T, zeta, Cy -- all 14 always, used or not, so a stream never depends
// on which keys a study sets and the paper's studies keep their bits. A given height distribution uses its
// building's h uniform, a given mass its mbar uniform. Each uniform is 53 bits of two engine outputs, mapped by
// inverse CDF (Boost.Math normal quantile in double precision); no std:: distributions (their algorithms are
// implementation-defined).
//
// Reproducibility (OpenMC's idea): a sample's identity is (i1, i2, sample) -- period slots of structures 1
// and 2 in their own grids (n1 x n2 pairs) and the sample index within that period pair. Its engine (boost::random::taus88, a
// combined Tausworthe generator) is seeded only from (study seed, stream, identity) through a SplitMix64 mix
// (stream_seed; the 64-bit key and splitmix64(key) give the engine's three 32-bit seed words), so the same structures appear
// for every record and gap (common random numbers), at any rank count, batch width or order of work; and
// the first N samples of a pair do not depend on samples_per_pair.
//
// Where the seed lives: the top-level integer key `seed` of the study file (not in [structures]);
// `parse_study_seed` reads it. Streams: `structure_stream` (1) is the structure model's stream id.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <memory>
#include <vector>

#include <toml++/toml.h>

#include "pounding/physics/batch.hpp"
#include "pounding/core/enum_names.hpp"
#include "pounding/core/random.hpp"  // splitmix64
#include "pounding/sampling/building.hpp"

namespace pounding {

struct BridgeModel;  // sampling/bridge.hpp

// Global identity of a sample: slot indices of building 1 (left) and 2 (right) into their period grids, sample
// index in the pair.
struct SampleId {
  std::int32_t i1 = 0, i2 = 0;
  std::int64_t sample = 0;
  friend bool operator==(const SampleId&, const SampleId&) = default;
};

// All settings of the structure model; the defaults reproduce the paper. A study file's [structures]
// table sets any of them (key names in parse_structure_model); they are the defaults of both buildings, which
// [structures.building1] and [structures.building2] override (building.hpp). Sampling uses only the resolved
// buildings (building(b)); the fields below are the shared defaults.
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
  // One height for both buildings: uniform on the intersection of their rule intervals (building 1's uniform).
  bool equal_heights = false;
  // The buildings' structural model defaults (building.hpp): model, storey_height (0: 3.2 m), stiffness_profile.
  StructureKind kind = StructureKind::sdof;
  double storey_height = 0.0;
  model::StiffnessProfile profile = model::StiffnessProfile::uniform;
  bool modal_damping = false;         // damping = "modal" (building.hpp), the buildings' default
  std::vector<double> modal_zeta;     // modal_zeta, the buildings' default
  int rayleigh_i = 1, rayleigh_j = 2;  // rayleigh_modes, the buildings' default
  // Either building is a shear building (the study runs Systems, study/run.cpp).
  bool any_shear() const {
    bool any = building(0).shear() || building(1).shear();
    for (const BuildingModel& b : more) any = any || b.shear();
    return any;
  }
  // Index 0 = building 1 (left). parse_structure_model resolves both; a model built in code may leave them
  // unresolved, and building(b) then makes them from the fields above.
  std::array<BuildingModel, 2> buildings;
  // A row of n >= 3 buildings ([structures] buildings = n, docs/architecture.md §2.7.1; SB §4): buildings 3..n,
  // left to right after building 2, each resolved from [structures.buildingK] over the defaults. Each has ONE
  // period slot (a fixed period or a distribution: the period grid spans buildings 1 x 2) and is drawn per sample
  // from its own stream (row_stream). Empty: the pair (buildings = 2), bit for bit as before.
  std::vector<BuildingModel> more;
  // A bridge study ([bridge], sampling/bridge.hpp): every sample is the bridge (its frames in SampledPair::s1, s2,
  // more; d its reference joint gap), drawn by bridge_pair from the bridge's own stream; the fields above only shape
  // the sample identities (one period slot each, samples_per_pair = [bridge] samples). Null: buildings.
  std::shared_ptr<const BridgeModel> bridge;
  std::size_t building_count() const { return 2 + more.size(); }
  bool row() const { return !more.empty(); }
  // Building b (0 = building 1) of the row.
  BuildingModel row_building(std::size_t b) const { return b < 2 ? building(static_cast<int>(b)) : more[b - 2]; }

  // 1.00, 1.05, ..., 1.50 s (section 3).
  static std::vector<double> default_periods();
  // The building the shared fields make (no building table).
  BuildingModel default_building() const;
  // Building b (0 or 1), resolved.
  BuildingModel building(int b) const { return buildings[b].resolved ? buildings[b] : default_building(); }
  // Period slots of building b: its grid points, or 1 for a period distribution.
  std::size_t slots(int b) const { return (buildings[b].resolved ? buildings[b].periods : periods).size(); }
  // Both buildings have a given height (fixed or a distribution): a "pair study", answers in metres.
  bool heights_specified() const;
  std::int64_t period_pair_count() const { return static_cast<std::int64_t>(slots(0) * slots(1)); }
  std::int64_t model_count() const { return period_pair_count() * samples_per_pair; }
  // Period pair p = i1 n2 + i2 (n2 = slots(1)) as an identity.
  SampleId pair_id(std::int64_t pair, std::int64_t sample = 0) const {
    const auto n2 = static_cast<std::int64_t>(slots(1));
    return SampleId{static_cast<std::int32_t>(pair / n2), static_cast<std::int32_t>(pair % n2), sample};
  }
};

// Height interval of the shared defaults at period T; throws InputError naming T and both bounds when the
// interval is empty (lo > hi).
HeightInterval height_interval(const StructureModel& model, double T, const std::string& where = "[structures]");

// Checks every setting and the cross-conditions (grid increasing, intervals non-empty for every period,
// mbar_min < mbar_max, ...); throws InputError naming `where` and the allowed range.
void validate(const StructureModel& model, const std::string& where = "[structures]");

// Reads a study file's [structures] table (pass an empty table for all defaults). Keys:
//   periods = [..]  or  period_min, period_max, period_step;  samples_per_pair; aspect_ratios = [..];
//   rho_mean, rho_cov; mbar_mean, mbar_cov, mbar_min, mbar_max; zeta; hysteresis = "bilinear"|"elastic";
//   drift, ductility, alpha; height_min, height_max; ct_lower, ct_upper, height_exponent;
//   code_gap_coefficient; contact_density, contact_youngs_modulus, contact_poisson; kh; equal_heights (bool);
//   model = "sdof" | "shear", storey_height, stiffness_profile, damping, modal_zeta, rayleigh_modes (the buildings'
//   defaults, building.hpp);
//   and the sub-tables [structures.building1], [structures.building2] (keys in building.hpp), resolved into
//   StructureModel::buildings over these defaults; buildings = n (2..16) makes a row, whose [structures.buildingK]
//   K = 3..n resolve into StructureModel::more (each one period slot; SDOF and shear buildings may mix;
//   no equal_heights; a table beyond n is refused).
// Unknown keys, wrong types and out-of-range values throw InputError naming file:line, the key and the
// allowed range. The seed is NOT in this table (see parse_study_seed).
StructureModel parse_structure_model(const toml::table& table, const std::string& file);

// The study's top-level `seed` (an integer in [0, 2^63 - 1]); required, errors name file:line.
std::uint64_t parse_study_seed(const toml::table& root, const std::string& file);

// Stream ids: one per consumer of random numbers, so they never share a stream.
inline constexpr std::uint64_t structure_stream = 1;
// Building b (0-based, b >= 2) of a row: its own stream at the same sample identity (i1, i2, sample), so buildings
// 1 and 2 keep the pair's numbers and adding a building changes nobody else's.
inline constexpr std::uint64_t row_stream(std::size_t b) { return 0x526f770000ull + b; }

// The engine seed of one sample: splitmix64 chained over seed, stream, (i1, i2) and sample.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, const SampleId& id);

// aspect, r, rho and mbar are NaN when the mass is given (the mass-index model is not used).
struct SampledStructure {
  double T = 0, h = 0, aspect = 0, r = 0, rho = 0, mbar = 0;
  double m = 0, k = 0, c = 0, fy = 0, alpha = 0;
  double zeta = 0;  // viscous damping ratio: c = 2 zeta sqrt(k m)
  Structure structure() const { return Structure{m, k, c, fy, alpha}; }
};

struct SampledPair {
  SampleId id;
  SampledStructure s1, s2;  // 1 = left, 2 = right
  std::vector<SampledStructure> more;  // a row's buildings 3..n (StructureModel::more), left to right
  // code separation 0.005 (h1 + h2) (eq. 5); in a row the largest over its joints, 0.005 max_j (h_j + h_j+1), the
  // gap every joint gets (study gap = ratio d)
  double d = 0;
  double kh = 0;            // Hertz contact stiffness (N/m^1.5)
  // The kernel's input: gap = gap_ratio d, kc = kh, restitution e, at rest.
  PairParams pair_params(double gap_ratio, double e) const;
  // Building b (0 = building 1) of the pair or row.
  const SampledStructure& structure(std::size_t b) const { return b == 0 ? s1 : b == 1 ? s2 : more[b - 2]; }
  std::size_t buildings() const { return 2 + more.size(); }
};

// Draws pairs for one (model, seed, stream). Construction validates the model (InputError) and precomputes
// the distributions; sample() is const and thread-safe.
class StructureSampler {
 public:
  StructureSampler(StructureModel model, std::uint64_t seed, std::uint64_t stream = structure_stream);

  // Requires 0 <= i1 < slots(0), 0 <= i2 < slots(1) and sample >= 0 (throws std::out_of_range otherwise).
  SampledPair sample(const SampleId& id) const;
  // Samples first, first + 1, ... of period pair (i1, i2) into out.
  void sample_block(std::int32_t i1, std::int32_t i2, std::int64_t first, std::span<SampledPair> out) const;

  // Global index (i1 n2 + i2) samples_per_pair + sample, and back; an ordering of work, not the seed.
  std::int64_t global_index(const SampleId& id) const;
  SampleId identity(std::int64_t global_index) const;

  const StructureModel& model() const { return model_; }
  const BuildingModel& building(int b) const { return side_[b].model; }  // resolved, 0 = building 1
  std::uint64_t seed() const { return seed_; }
  std::uint64_t stream() const { return stream_; }
  // Rule interval of building b's grid slot (heights from the rule and grid periods; building 1 by default).
  const HeightInterval& heights(std::size_t period_index) const { return side_[0].heights[period_index]; }
  const HeightInterval& heights(int b, std::size_t slot) const { return side_[b].heights[slot]; }
  // Parameters of building 1's lognormals: ln X ~ N(mu, sigma^2).
  double rho_mu() const { return side_[0].rho_mu; }
  double rho_sigma() const { return side_[0].rho_sigma; }
  double mbar_mu() const { return side_[0].mbar_mu; }
  double mbar_sigma() const { return side_[0].mbar_sigma; }

 private:
  // One building's resolved model and its precomputed laws.
  struct Side {
    BuildingModel model;
    std::vector<HeightInterval> heights;  // per grid slot, when the height comes from the rule
    double rho_mu = 0, rho_sigma = 0, mbar_mu = 0, mbar_sigma = 0;
    Truncated mbar, period, height, mass, zeta, cy;
  };
  // One building's uniforms: the first four in the paper's order, then T, zeta, Cy (drawn even when unused).
  struct Uniforms {
    double h = 0, aspect = 0, rho = 0, mbar = 0, T = 0, zeta = 0, cy = 0;
  };
  static Side make_side(BuildingModel b);
  SampledStructure draw_structure(const Side& side, const Uniforms& u, std::size_t slot, const double* h_equal) const;

  StructureModel model_;
  std::uint64_t seed_, stream_;
  std::array<Side, 2> side_;
  std::vector<Side> more_;  // a row's buildings 3..n
};

// One pair for (model, seed, stream, identity); builds a sampler each call (use StructureSampler in loops).
SampledPair sample_pair(const StructureModel& model, std::uint64_t seed, std::uint64_t stream, const SampleId& id);

// ln X ~ N(mu, sigma^2) with E[X] = mean, CoV[X] = cov: sigma^2 = ln(1 + cov^2), mu = ln(mean) - sigma^2 / 2.
struct LognormalParams {
  double mu = 0, sigma = 0;
};
LognormalParams lognormal_from_mean_cov(double mean, double cov);

}  // namespace pounding
