// The stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1). See sampler.hpp.
#include "pounding/sampling/sampler.hpp"

#include "pounding/sampling/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/policies/policy.hpp>
#include <boost/random/taus88.hpp>
#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

namespace {

constexpr double standard_gravity = 9.80665;  // m/s^2: fy = Cy m g

// Boost.Math's default policy promotes double to long double inside the special functions, which is 6x
// slower and makes results depend on the platform's long double; evaluate in double throughout.
using DoublePolicy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
using Normal = boost::math::normal_distribution<double, DoublePolicy>;

// The per-sample engine: boost::random::taus88, L'Ecuyer's maximally equidistributed combined Tausworthe
// generator (Math. Comp. 65, 1996; GSL's "taus2"), period ~2^88. A sample needs only 8 uniforms, so what
// matters is independence between streams -- carried by the SplitMix64 key -- and a cheap start: its 88-bit
// state is set from three 32-bit words of the key in a few ns, where mt19937_64 spends ~0.6 us initialising
// and twisting 312 words (that alone is ~20 ms for 30,976 models).
using Engine = boost::random::taus88;

Engine make_engine(std::uint64_t key) {
  const std::uint64_t key2 = splitmix64(key);
  // Each component uses the top 31, 29, 28 bits of its word (the remainder is shifted out); Boost bumps a
  // word whose used bits are all zero (probability ~2^-28), which keeps every component on its full cycle.
  std::uint32_t words[3] = {static_cast<std::uint32_t>(key), static_cast<std::uint32_t>(key >> 32),
                            static_cast<std::uint32_t>(key2 >> 32)};
  std::uint32_t* first = words;
  Engine g;
  g.seed(first, words + 3);
  return g;
}

// A uniform variate in the open interval (0, 1) from two 32-bit outputs: j = 27 top bits of the first
// and 26 of the second, u = (j + 1/2) 2^-53. Never 0 or 1, so quantiles stay finite; identical on every machine.
inline double uniform01(Engine& g) {
  const std::uint32_t a = g() >> 5, b = g() >> 6;
  return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b) + 0.5) * 0x1p-53;
}

std::string fmt_num(double x) { return fmt::format("{:.6g}", x); }

void need(bool ok, const std::string& key, double value, const std::string& range, const WhereFn& where) {
  if (!ok || !std::isfinite(value))
    throw InputError(fmt::format("{} = {} is out of range", key, fmt_num(value)), where(key),
                     fmt::format("give {} in {}", key, range));
}

// The settings only [structures] has (both buildings share them).
void validate_shared(const StructureModel& m, const WhereFn& where) {
  if (m.samples_per_pair < 1 || m.samples_per_pair > (std::int64_t{1} << 40))
    throw InputError(fmt::format("samples_per_pair = {} is out of range", m.samples_per_pair),
                     where("samples_per_pair"), "give samples_per_pair in [1, 2^40]");
  need(m.code_gap_coefficient > 0 && m.code_gap_coefficient <= 1, "code_gap_coefficient", m.code_gap_coefficient,
       "(0, 1]", where);
  need(m.contact_density > 0 && m.contact_density <= 1e5, "contact_density", m.contact_density,
       "(0, 1e5] kg/m^3", where);
  need(m.contact_youngs_modulus > 0 && m.contact_youngs_modulus <= 1e13, "contact_youngs_modulus",
       m.contact_youngs_modulus, "(0, 1e13] Pa", where);
  need(m.contact_poisson >= 0 && m.contact_poisson < 0.5, "contact_poisson", m.contact_poisson, "[0, 0.5)", where);
  need(m.kh >= 0 && m.kh <= 1e20, "kh", m.kh, "[0, 1e20] N/m^1.5 (0: equivalent spheres)", where);
}

// equal_heights: heights from the rule and grid (or fixed) periods in both buildings, and a common height for
// every period pair.
void check_equal_heights(const StructureModel& m, const std::string& where) {
  if (!m.equal_heights) return;
  const std::array<BuildingModel, 2> b{m.building(0), m.building(1)};
  for (int i = 0; i < 2; ++i) {
    if (!b[i].height_from_rule())
      throw InputError(fmt::format("equal_heights = true needs heights from the period-height rule, but building{} "
                                   "has height = {}",
                                   i + 1, b[i].height.describe("m")),
                       where,
                       fmt::format("remove height from [structures.building{}], or set equal_heights = false", i + 1));
    if (b[i].period.random())
      throw InputError(fmt::format("equal_heights = true needs grid or fixed periods, but building{} has period = {}",
                                   i + 1, b[i].period.describe("s")),
                       where,
                       fmt::format("give building{} a period grid or a fixed period, or set equal_heights = false",
                                   i + 1));
  }
  for (double T1 : b[0].periods)
    for (double T2 : b[1].periods) {
      const HeightInterval a = checked_rule_heights(b[0], T1, where), c = checked_rule_heights(b[1], T2, where);
      if (!(std::max(a.lo, c.lo) <= std::min(a.hi, c.hi)))
        throw InputError(fmt::format("equal_heights: no height suits both T1 = {} s (building 1: [{}, {}] m) and "
                                     "T2 = {} s (building 2: [{}, {}] m)",
                                     fmt_num(T1), fmt_num(a.lo), fmt_num(a.hi), fmt_num(T2), fmt_num(c.lo),
                                     fmt_num(c.hi)),
                         where, "drop one of these periods from its grid, widen the height limits, or set "
                                "equal_heights = false");
    }
}

void validate_impl(const StructureModel& m, const WhereFn& where) {
  validate_shared(m, where);
  validate_building(m.default_building(), where);
  for (int i = 0; i < 2; ++i)
    if (m.buildings[i].resolved)
      validate_building(m.buildings[i], [&](std::string_view key) {
        return fmt::format("{} (building{}.{})", where(key), i + 1, key);
      });
  for (std::size_t i = 0; i < m.more.size(); ++i)
    validate_building(m.more[i], [&](std::string_view key) {
      return fmt::format("{} (building{}.{})", where(key), i + 3, key);
    });
  check_equal_heights(m, where("equal_heights"));
}

}  // namespace


std::vector<double> StructureModel::default_periods() { return make_period_grid(1.00, 1.50, 0.05); }

BuildingModel StructureModel::default_building() const {
  BuildingModel b;
  b.resolved = true;
  b.periods = periods;
  b.zeta = Distribution::fixed(zeta);
  b.aspect_ratios = aspect_ratios;
  b.rho_mean = rho_mean, b.rho_cov = rho_cov;
  b.mbar_mean = mbar_mean, b.mbar_cov = mbar_cov, b.mbar_min = mbar_min, b.mbar_max = mbar_max;
  b.hysteresis = hysteresis;
  b.drift = drift, b.ductility = ductility, b.alpha = alpha;
  b.height_min = height_min, b.height_max = height_max;
  b.ct_lower = ct_lower, b.ct_upper = ct_upper, b.height_exponent = height_exponent;
  b.kind = kind, b.profile = profile, b.code.storey_height = storey_height;
  b.modal_damping = modal_damping, b.modal_zeta = modal_zeta;
  b.rayleigh_i = rayleigh_i, b.rayleigh_j = rayleigh_j;
  return b;
}

bool StructureModel::heights_specified() const {
  return buildings[0].height.given() && buildings[1].height.given();
}

HeightInterval height_interval(const StructureModel& model, double T, const std::string& where) {
  return checked_rule_heights(model.default_building(), T, where);
}

void validate(const StructureModel& model, const std::string& where) {
  validate_impl(model, [&](std::string_view key) { return fmt::format("{}.{}", where, key); });
}

LognormalParams lognormal_from_mean_cov(double mean, double cov) {
  LognormalParams p;
  p.sigma = std::sqrt(std::log1p(cov * cov));
  p.mu = std::log(mean) - 0.5 * p.sigma * p.sigma;
  return p;
}

// ---------------------------------------------------------------- parsing

namespace {

// Both buildings from the [structures] defaults and their own tables (absent tables: the defaults).
void resolve_buildings(StructureModel& m, const std::array<const toml::table*, 2>& tables, const std::string& file,
                       const WhereFn& where, bool rule_explicit) {
  BuildingModel defaults = m.default_building();
  defaults.rule_explicit = rule_explicit;
  for (int i = 0; i < 2; ++i)
    m.buildings[i] = parse_building(tables[i], file, fmt::format("structures.building{}", i + 1), defaults, where);
  check_equal_heights(m, where("equal_heights"));
  // shear buildings of different storey heights: floors meet floors within [contact] level_tolerance and the
  // neighbour's columns elsewhere (model::shear_buildings, docs/floor-contact.md)
}

// A row (docs/architecture.md §2.7.1): buildings = n and the tables [structures.buildingK] for K = 3..n (null when
// absent); a table beyond n is refused.
std::vector<const toml::table*> read_row_tables(config::TableReader& r, const toml::table& table, const std::string& file) {
  const long count = r.integer("buildings");
  for (const auto& [key, node] : table) {
    const std::string_view k = key.str();
    if (k.size() <= 8 || k.substr(0, 8) != "building" || k.find_first_not_of("0123456789", 8) != std::string_view::npos)
      continue;
    const long K = std::stol(std::string(k.substr(8)));
    if (K >= 1 && K <= count) continue;
    throw InputError(fmt::format("[structures.{}] is given but the row has buildings = {}", k, count),
                     config::location(file, node.source()) + " [structures." + std::string(k) + "]",
                     K >= 1 ? fmt::format("set [structures] buildings = {} (or more), or remove the table", K)
                            : std::string("number the buildings from 1, left to right"));
  }
  std::vector<const toml::table*> row_tables;
  for (long K = 3; K <= count; ++K)
    row_tables.push_back(r.table(fmt::format("building{}", K), "buildingK"));
  return row_tables;
}

// A row's buildings 3..n (tables may be null: the defaults) and what a row needs: one period slot each beyond
// building 2, one structural model throughout, no common height (storey heights may differ: floors then meet columns).
void resolve_row(StructureModel& m, const std::vector<const toml::table*>& tables, const std::string& file,
                 const WhereFn& where, bool rule_explicit) {
  if (tables.empty()) return;
  BuildingModel defaults = m.default_building();
  defaults.rule_explicit = rule_explicit;
  const std::size_t n = tables.size() + 2;
  // a building's own table, or [structures] for what it does not give
  auto at = [&](std::size_t b, std::string_view key) {
    const toml::table* t = b < 2 ? nullptr : tables[b - 2];
    if (t && t->get(key))
      return config::location(file, t->get(key)->source()) + fmt::format(" [structures.building{}].{}", b + 1, key);
    if (t) return config::location(file, t->source()) + fmt::format(" [structures.building{}]", b + 1);
    return fmt::format("{} (the default of [structures.building{}])", where(key), b + 1);
  };
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const std::size_t b = k + 2;
    m.more.push_back(parse_building(tables[k], file, fmt::format("structures.building{}", b + 1), defaults, where));
    const BuildingModel& x = m.more.back();
    if (x.slots() != 1)
      throw InputError(fmt::format("building{} of the row has a grid of {} periods; the period grid spans buildings 1 "
                                   "and 2 only",
                                   b + 1, x.slots()),
                       at(b, "periods"),
                       fmt::format("give [structures.building{}] period = <s> (fixed) or a distribution, e.g. period "
                                   "= {{lognormal = {{median = 1.0, cov = 0.2}}}}",
                                   b + 1));
  }
  if (m.equal_heights)
    throw InputError(fmt::format("equal_heights = true is for a pair, and the row has {} buildings", n),
                     where("equal_heights"), "set equal_heights = false, or buildings = 2");
  // SDOF and shear buildings mix freely: a run of SDOFs meets its shear neighbours at one of their floors
  // (study/system_block.cpp mixed_row_levels)
}

// [structures] rayleigh_modes and damping = "modal" damp the shear buildings; an SDOF building keeps its zeta (the
// rule's one storey, model::rayleigh_modes_for; a one-storey building's only mode takes zeta; parse_building drops the
// inherited keys), so each is refused only where no building has storeys to damp.
void check_shared_damping(const StructureModel& m, const WhereFn& where) {
  if (m.any_shear()) return;
  if (!(m.rayleigh_i == 1 && m.rayleigh_j == 2))
    throw InputError("rayleigh_modes is given and every building is an SDOF", where("rayleigh_modes"),
                     "add model = \"shear\" to [structures] or to a building's table, or remove rayleigh_modes");
  if (m.modal_damping)
    throw InputError("damping = \"modal\" is given and every building is an SDOF", where("damping"),
                     "add model = \"shear\" to [structures] or to a building's table, or remove damping and modal_zeta");
}

}  // namespace

StructureModel parse_structure_model(const toml::table& table, const std::string& file) {
  StructureModel m;
  config::TableReader r(&table, file, "structures");
  std::string periods_where;  // set when the grid keys make the periods: later errors point at them
  auto where = [&](std::string_view key) {
    return key == "periods" && !periods_where.empty() ? periods_where : r.where(key);
  };
  if (table.get("seed"))
    throw InputError("seed is not a [structures] setting", r.where("seed"),
                     "move seed = <integer> to the top of the study file, before any [table]");

  // Values are only read here; validate_impl checks their ranges (non-finite values included).
  auto number = [&](const char* key, double& out) {
    if (const toml::node* n = r.get(key)) out = config::number(*n, key, r.where(key));
  };
  for (auto [key, out] :
       {std::pair{"rho_mean", &m.rho_mean}, {"rho_cov", &m.rho_cov}, {"mbar_mean", &m.mbar_mean},
        {"mbar_cov", &m.mbar_cov}, {"mbar_min", &m.mbar_min}, {"mbar_max", &m.mbar_max}, {"zeta", &m.zeta},
        {"drift", &m.drift}, {"ductility", &m.ductility}, {"alpha", &m.alpha}, {"height_min", &m.height_min},
        {"height_max", &m.height_max}, {"ct_lower", &m.ct_lower}, {"ct_upper", &m.ct_upper},
        {"height_exponent", &m.height_exponent}, {"code_gap_coefficient", &m.code_gap_coefficient},
        {"contact_density", &m.contact_density}, {"contact_youngs_modulus", &m.contact_youngs_modulus},
        {"contact_poisson", &m.contact_poisson}, {"kh", &m.kh}})
    number(key, *out);
  bool rule_explicit = false;
  for (const char* key : {"ct_lower", "ct_upper", "height_exponent"}) rule_explicit |= r.get(key) != nullptr;
  m.equal_heights = r.boolean("equal_heights");
  {
    BuildingModel shared;
    read_shear_defaults(r, shared);
    m.kind = shared.kind, m.profile = shared.profile;
    m.modal_damping = shared.modal_damping, m.modal_zeta = shared.modal_zeta;
    m.rayleigh_i = shared.rayleigh_i, m.rayleigh_j = shared.rayleigh_j;
    if (r.get("storey_height"))
      m.storey_height = r.number("storey_height", 0.0);
    BuildingModel d = m.default_building();
    if (!d.shear())  // modes and modal damping for the shear buildings only (check_shared_damping)
      d.rayleigh_i = 1, d.rayleigh_j = 2, d.modal_damping = false, d.modal_zeta.clear();
    check_shear_keys(d, [&](std::string_view key) { return r.where(key); });
  }
  const std::array<const toml::table*, 2> buildings{r.table("building1"), r.table("building2")};
  const std::vector<const toml::table*> row_tables = read_row_tables(r, table, file);
  if (const toml::node* n = r.get("aspect_ratios")) m.aspect_ratios = config::numbers(*n, "aspect_ratios", r.where("aspect_ratios"));
  if (const toml::node* n = r.get("samples_per_pair"))
    m.samples_per_pair = config::integer(*n, "samples_per_pair", r.where("samples_per_pair"));
  if (const auto h = read_hysteresis(r.get("hysteresis"), r.where("hysteresis"))) m.hysteresis = *h;
  const toml::node* periods = r.get("periods");
  if (periods) m.periods = config::numbers(*periods, "periods", r.where("periods"));
  std::optional<double> pmin, pmax, pstep;
  for (auto [key, out] : {std::pair{"period_min", &pmin}, {"period_max", &pmax}, {"period_step", &pstep}})
    if (const toml::node* n = r.get(key)) *out = config::number(*n, key, r.where(key));
  r.finish("periods, period_min, period_max, period_step, samples_per_pair, aspect_ratios, rho_mean, rho_cov, "
           "mbar_mean, mbar_cov, mbar_min, mbar_max, zeta, hysteresis, drift, ductility, alpha, height_min, "
           "height_max, ct_lower, ct_upper, height_exponent, code_gap_coefficient, contact_density, "
           "contact_youngs_modulus, contact_poisson, kh, equal_heights, model, storey_height, stiffness_profile, "
           "damping, modal_zeta, rayleigh_modes, buildings, building1, building2, ... (tables "
           "[structures.building1], [structures.building2], ... [structures.building<buildings>])");

  if (periods && (pmin || pmax || pstep))
    throw InputError("both periods and period_min/period_max/period_step are given", r.where("periods"),
                     "give either the list periods = [..] or the grid period_min, period_max, period_step");
  if (pmin || pmax || pstep) {
    periods_where = r.where(pmax ? "period_max" : pmin ? "period_min" : "period_step");
    m.periods = make_period_grid(pmin.value_or(1.00), pmax.value_or(1.50), pstep.value_or(0.05), periods_where);
  }
  validate_shared(m, where);
  validate_building(m.default_building(), where);
  resolve_buildings(m, buildings, file, where, rule_explicit);
  resolve_row(m, row_tables, file, where, rule_explicit);
  check_shared_damping(m, where);
  return m;
}

std::uint64_t parse_study_seed(const toml::table& root, const std::string& file) {
  const toml::node* n = root.get("seed");
  if (!n)
    throw InputError("the study has no seed", config::location(file, root.source()),
                     "add a top-level line seed = <integer >= 0> before any [table]");
  return config::seed(*n, "seed", fmt::format("{} seed", config::location(file, n->source())));
}

// ---------------------------------------------------------------- streams

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, const SampleId& id) {
  // Each step is a bijection of the running value for fixed input, so for a given (seed, stream, i1, i2)
  // distinct sample indices give distinct engine seeds; the chain makes every input bit avalanche.
  const std::uint64_t pair = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(id.i1)) << 32) |
                             static_cast<std::uint32_t>(id.i2);
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ stream);
  h = splitmix64(h ^ pair);
  return splitmix64(h ^ static_cast<std::uint64_t>(id.sample));
}

// ---------------------------------------------------------------- sampler

StructureSampler::StructureSampler(StructureModel model, std::uint64_t seed, std::uint64_t stream)
    : model_(std::move(model)), seed_(seed), stream_(stream) {
  validate(model_);
  for (int b = 0; b < 2; ++b) side_[b] = make_side(model_.building(b));
  for (const BuildingModel& b : model_.more) more_.push_back(make_side(b));
}

StructureSampler::Side StructureSampler::make_side(BuildingModel b) {
  Side s;
  if (b.height_from_rule() && !b.period.random())
    for (double T : b.periods) s.heights.push_back(checked_rule_heights(b, T, "[structures].periods"));
  const LognormalParams rho = lognormal_from_mean_cov(b.rho_mean, b.rho_cov);
  s.rho_mu = rho.mu, s.rho_sigma = rho.sigma;
  const LognormalParams mb = lognormal_from_mean_cov(b.mbar_mean, b.mbar_cov);
  s.mbar_mu = mb.mu, s.mbar_sigma = mb.sigma;
  s.mbar = Truncated::lognormal_mu_sigma(mb.mu, mb.sigma, b.mbar_min, b.mbar_max);
  // Each drawn key truncated to its valid range; T also to the periods the rule admits when it gives h.
  const HeightInterval pr = b.height_from_rule() ? b.rule_periods() : HeightInterval{min_period, max_period};
  s.period = Truncated(b.period, std::max(pr.lo, min_period), std::min(pr.hi, max_period));
  s.height = Truncated(b.height, min_height, max_height);
  s.mass = Truncated(b.mass, min_mass, max_mass);
  s.zeta = Truncated(b.zeta, 0.0, max_zeta);
  s.cy = Truncated(b.yield_coefficient, min_cy, max_cy);
  s.model = std::move(b);
  return s;
}

SampledStructure StructureSampler::draw_structure(const Side& side, const Uniforms& u, std::size_t slot,
                                                  const double* h_equal) const {
  const BuildingModel& b = side.model;
  const Normal nd;
  SampledStructure s;
  s.T = b.period.random() ? side.period.sample(u.T) : b.periods[slot];
  if (h_equal) {
    s.h = *h_equal;
  } else if (b.height.given()) {
    s.h = side.height.sample(u.h);
  } else {
    HeightInterval iv = b.period.random() ? b.rule_heights(s.T) : side.heights[slot];
    iv.hi = std::max(iv.lo, iv.hi);  // a drawn T at the edge of the rule's range: rounding only
    s.h = iv.lo + (iv.hi - iv.lo) * u.h;  // uniform on [lo, hi] (section 3.1)
  }
  if (b.mass_index_model()) {
    const std::size_t na = b.aspect_ratios.size();
    s.aspect = b.aspect_ratios[std::min(na - 1, static_cast<std::size_t>(u.aspect * static_cast<double>(na)))];
    s.r = s.h / s.aspect;
    s.rho = std::exp(side.rho_mu + side.rho_sigma * quantile(nd, u.rho));
    s.mbar = side.mbar.sample(u.mbar);  // the truncated lognormal, exact (Truncated, building.cpp)
    s.m = s.mbar * s.rho * s.r * s.r * s.h;  // eq. (7)
  } else {
    s.aspect = s.r = s.rho = s.mbar = std::numeric_limits<double>::quiet_NaN();
    s.m = side.mass.sample(u.mbar);
  }
  if (b.shear() && !b.floor_mass.empty()) {
    // the floors' mass is the building's (the mass drawn above, unused by the floors, was reported beside floors
    // carrying another): floor_mass on each of the sample's storeys, or the per-floor values' sum
    const double n = b.storeys_at(s.h);
    s.m = b.floor_mass.size() == 1 ? n * b.floor_mass[0] : std::accumulate(b.floor_mass.begin(), b.floor_mass.end(), 0.0);
  }
  s.zeta = b.zeta.random() ? side.zeta.sample(u.zeta) : b.zeta.median();
  Structure st = Structure::from_period(s.m, s.T, s.zeta);  // eqs (8), (9)
  s.k = st.k;
  s.c = st.c;
  if (b.hysteresis == Hysteresis::elastic) {
    s.fy = std::numeric_limits<double>::infinity();
    s.alpha = 0.0;
  } else {
    s.fy = b.yield_coefficient.given() ? side.cy.sample(u.cy) * s.m * standard_gravity
                                       : s.k * (b.drift * s.h / b.ductility);  // ductility 6 at 2 % drift (2.1)
    s.alpha = b.alpha;
    if (b.shear() && !b.storey_yield.empty()) s.fy = b.storey_yield[0];  // the base storey's: the building's strength
  }
  return s;
}

SampledPair StructureSampler::sample(const SampleId& id) const {
  const auto n1 = static_cast<std::int32_t>(model_.slots(0)), n2 = static_cast<std::int32_t>(model_.slots(1));
  if (id.i1 < 0 || id.i1 >= n1 || id.i2 < 0 || id.i2 >= n2 || id.sample < 0)
    throw std::out_of_range(fmt::format("sample identity ({}, {}, {}) outside {} x {} period slots", id.i1, id.i2,
                                        id.sample, n1, n2));
  if (model_.bridge) {  // the bridge's frames: two uniforms per frame from its own stream (sampling/bridge.hpp)
    Engine gb = make_engine(stream_seed(seed_, bridge_stream ^ (stream_ << 48), id));
    std::vector<double> u(2 * model_.bridge->frames());
    for (double& x : u) x = uniform01(gb);
    return bridge_pair(*model_.bridge, id, u);
  }
  Engine g = make_engine(stream_seed(seed_, stream_, id));
  // The paper's 8 uniforms first (building 1 then 2: h, aspect, rho, mbar), then per building T, zeta, Cy:
  // always all 14, so a stream never depends on which keys a study sets.
  std::array<Uniforms, 2> u;
  for (Uniforms& x : u) x.h = uniform01(g), x.aspect = uniform01(g), x.rho = uniform01(g), x.mbar = uniform01(g);
  for (Uniforms& x : u) x.T = uniform01(g), x.zeta = uniform01(g), x.cy = uniform01(g);
  const auto i1 = static_cast<std::size_t>(id.i1), i2 = static_cast<std::size_t>(id.i2);
  double h_equal = 0;
  if (model_.equal_heights) {  // one height on the intersection of both rule intervals, building 1's uniform
    const HeightInterval &a = side_[0].heights[i1], &c = side_[1].heights[i2];
    const double lo = std::max(a.lo, c.lo), hi = std::max(lo, std::min(a.hi, c.hi));
    h_equal = lo + (hi - lo) * u[0].h;
  }
  SampledPair p;
  p.id = id;
  p.s1 = draw_structure(side_[0], u[0], i1, model_.equal_heights ? &h_equal : nullptr);
  p.s2 = draw_structure(side_[1], u[1], i2, model_.equal_heights ? &h_equal : nullptr);
  p.d = model_.code_gap_coefficient * (p.s1.h + p.s2.h);  // eq. (5)
  p.kh = model_.kh > 0 ? model_.kh
                       : hertz_stiffness_spheres(p.s1.m, p.s2.m, model_.contact_density, model_.contact_youngs_modulus,
                                                 model_.contact_poisson);
  // a row's buildings 3..n: each from its own stream at this identity (the same 7 uniforms in the same order as a
  // building of the pair), its one period slot; the row's d is the largest joint's code separation
  for (std::size_t k = 0; k < more_.size(); ++k) {
    Engine gk = make_engine(stream_seed(seed_, row_stream(k + 2) ^ (stream_ << 48), id));
    Uniforms x;
    x.h = uniform01(gk), x.aspect = uniform01(gk), x.rho = uniform01(gk), x.mbar = uniform01(gk);
    x.T = uniform01(gk), x.zeta = uniform01(gk), x.cy = uniform01(gk);
    p.more.push_back(draw_structure(more_[k], x, 0, nullptr));
  }
  for (std::size_t b = 1; b + 1 < p.buildings(); ++b)
    p.d = std::max(p.d, model_.code_gap_coefficient * (p.structure(b).h + p.structure(b + 1).h));
  return p;
}

void StructureSampler::sample_block(std::int32_t i1, std::int32_t i2, std::int64_t first,
                                    std::span<SampledPair> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = sample(SampleId{i1, i2, first + static_cast<std::int64_t>(j)});
}

std::int64_t StructureSampler::global_index(const SampleId& id) const {
  const auto n2 = static_cast<std::int64_t>(model_.slots(1));
  return (id.i1 * n2 + id.i2) * model_.samples_per_pair + id.sample;
}

SampleId StructureSampler::identity(std::int64_t global_index) const {
  return model_.pair_id(global_index / model_.samples_per_pair, global_index % model_.samples_per_pair);
}

PairParams SampledPair::pair_params(double gap_ratio, double e) const {
  PairParams p;
  p.s1 = s1.structure();
  p.s2 = s2.structure();
  p.gap = gap_ratio * d;
  p.kc = kh;
  p.e = e;
  return p;
}

SampledPair sample_pair(const StructureModel& model, std::uint64_t seed, std::uint64_t stream, const SampleId& id) {
  return StructureSampler(model, seed, stream).sample(id);
}

}  // namespace pounding
