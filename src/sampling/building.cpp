// One building's settings and distributions. See building.hpp.
#include "pounding/sampling/building.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/policies/policy.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/config/config.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

namespace {

// As in sampler.cpp: Boost.Math in double precision, no promotion to long double.
using DoublePolicy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
using Normal = boost::math::normal_distribution<double, DoublePolicy>;

std::string fmt_num(double x) { return fmt::format("{:.6g}", x); }

std::string with_unit(double x, std::string_view unit) {
  return unit.empty() ? fmt_num(x) : fmt::format("{} {}", fmt_num(x), unit);
}

void need(bool ok, std::string_view key, double value, const std::string& range, const WhereFn& where) {
  if (!ok || !std::isfinite(value))
    throw InputError(fmt::format("{} = {} is out of range", key, fmt_num(value)), where(key),
                     fmt::format("give {} in {}", key, range));
}

// The valid range of a distribution key: lo < x (or lo <= x when lo_closed) and x <= hi (x < hi when hi_open).
struct KeyRange {
  double lo, hi;
  bool lo_closed, hi_open;
  std::string_view text, unit;
  bool contains(double x) const {
    return std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_open ? x < hi : x <= hi);
  }
};
// The ranges a real building can have (building.hpp says why each end is where it is).
constexpr KeyRange period_range{min_period, max_period, true, false, "[0.02, 20] s", "s"};
constexpr KeyRange height_range{min_height, max_height, true, false, "[2, 1000] m", "m"};
constexpr KeyRange mass_range{min_mass, max_mass, true, false, "[1e3, 1e10] kg", "kg"};
constexpr KeyRange zeta_range{0, max_zeta, true, false, "[0, 0.5]", ""};
constexpr KeyRange cy_range{min_cy, max_cy, true, false, "[0.005, 5]", ""};

// Ranges of the parameters of d, then the probability the valid range keeps.
void check_distribution(const Distribution& d, std::string_view key, const KeyRange& r, const WhereFn& where) {
  using K = Distribution::Kind;
  const auto bad = [&](std::string_view what, double v, std::string_view range) {
    throw InputError(fmt::format("{}: {} = {} is out of range", key, what, fmt_num(v)), where(key),
                     fmt::format("give the {} of {} in {}", what, key, range));
  };
  if (d.kind == K::fixed) need(r.contains(d.value), key, d.value, std::string(r.text), where);
  if (d.kind == K::lognormal) {
    if (!r.contains(d.value) || !(d.value > 0)) bad("median", d.value, r.text);
    if (!(d.cov >= 0 && d.cov <= 2)) bad("cov", d.cov, "[0, 2]");
  }
  if (d.kind == K::uniform) {
    if (!r.contains(d.lo)) bad("min", d.lo, r.text);
    if (!r.contains(d.hi)) bad("max", d.hi, r.text);
    if (!(d.lo <= d.hi))
      throw InputError(fmt::format("{}: uniform min = {} exceeds max = {}", key, fmt_num(d.lo), fmt_num(d.hi)),
                       where(key), "give min <= max");
  }
  if (d.kind == K::lognormal && d.random()) {
    const double kept = Truncated(d, r.lo, r.hi).kept();
    if (!(kept >= 0.5))
      throw InputError(fmt::format("{} = {} keeps only {:.3g} % of its probability (at least 50 % needed) in the "
                                   "valid range {}",
                                   key,
                                   d.describe(r.unit), 100 * kept, r.text),
                       where(key), "move the median into the range or lower the cov");
  }
}

}  // namespace

// ---------------------------------------------------------------- Distribution

bool Distribution::random() const {
  return (kind == Kind::lognormal && cov > 0) || (kind == Kind::uniform && hi > lo);
}

double Distribution::sigma() const { return kind == Kind::lognormal ? std::sqrt(std::log1p(cov * cov)) : 0.0; }

double Distribution::quantile(double u) const {
  switch (kind) {
    case Kind::lognormal:
      return cov > 0 ? std::exp(std::log(value) + sigma() * boost::math::quantile(Normal(), u)) : value;
    case Kind::uniform:
      return lo + (hi - lo) * u;
    default:
      return value;
  }
}

double Distribution::cdf(double x) const {
  switch (kind) {
    case Kind::lognormal:
      if (!(x > 0)) return 0.0;
      if (!(cov > 0)) return x >= value ? 1.0 : 0.0;
      if (std::isinf(x)) return 1.0;
      return boost::math::cdf(Normal(), (std::log(x) - std::log(value)) / sigma());
    case Kind::uniform:
      if (!(hi > lo)) return x >= lo ? 1.0 : 0.0;
      return std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    default:
      return x >= value ? 1.0 : 0.0;
  }
}

double Distribution::median() const { return kind == Kind::uniform ? 0.5 * (lo + hi) : value; }

std::string Distribution::describe(std::string_view unit) const {
  switch (kind) {
    case Kind::none:
      return "not given";
    case Kind::lognormal:
      return fmt::format("lognormal(median {}, cov {})", with_unit(value, unit), fmt_num(cov));
    case Kind::uniform:
      return fmt::format("uniform({}, {})", with_unit(lo, unit), with_unit(hi, unit));
    default:
      return with_unit(value, unit);
  }
}

// ---------------------------------------------------------------- Truncated

Truncated::Truncated(const Distribution& d, double lo, double hi) : d_(d), lo_(lo), hi_(hi) {
  if (d.kind == Distribution::Kind::lognormal && d.cov > 0) {
    set_lognormal(std::log(d.value), d.sigma(), lo, hi);
  } else if (d.kind == Distribution::Kind::uniform && d.hi > d.lo) {
    lo_ = std::max(d.lo, lo), hi_ = std::min(d.hi, hi);
    kept_ = hi_ >= lo_ ? (hi_ - lo_) / (d.hi - d.lo) : 0.0;
  } else {
    const double v = d.median();
    kept_ = v >= lo && v <= hi ? 1.0 : 0.0;
  }
}

Truncated Truncated::lognormal_mu_sigma(double mu, double sigma, double lo, double hi) {
  Truncated t;
  t.set_lognormal(mu, sigma, lo, hi);
  return t;
}

void Truncated::set_lognormal(double mu, double sigma, double lo, double hi) {
  lognormal_ = true, mu_ = mu, sigma_ = sigma, lo_ = lo, hi_ = hi;
  const Normal nd;
  const double za = lo > 0 ? (std::log(lo) - mu) / sigma : -std::numeric_limits<double>::infinity();
  const double zb = std::isfinite(hi) ? (std::log(hi) - mu) / sigma : std::numeric_limits<double>::infinity();
  pa_ = std::isfinite(za) ? cdf(nd, za) : 0.0;
  pb_ = std::isfinite(zb) ? cdf(nd, zb) : 1.0;
  qa_ = std::isfinite(za) ? cdf(complement(nd, za)) : 1.0;
  qb_ = std::isfinite(zb) ? cdf(complement(nd, zb)) : 0.0;
  upper_tail_ = za > 0;
  kept_ = upper_tail_ ? qa_ - qb_ : pb_ - pa_;
}

double Truncated::sample(double u) const {
  if (!lognormal_) {
    if (d_.kind == Distribution::Kind::uniform && d_.hi > d_.lo) return lo_ + (hi_ - lo_) * u;
    return d_.median();
  }
  // ln X = mu + sigma Z with Z standard normal restricted to [za, zb]: z = Phi^-1(Phi(za) + u (Phi(zb) - Phi(za))),
  // or through the upper tail Q = 1 - Phi when za > 0 (Phi ~ 1 loses digits there).
  const Normal nd;
  const double z = upper_tail_ ? quantile(complement(nd, qa_ - u * (qa_ - qb_))) : quantile(nd, pa_ + u * (pb_ - pa_));
  return std::clamp(std::exp(mu_ + sigma_ * z), lo_, hi_);  // rounding only
}

// ---------------------------------------------------------------- grids and the rule

std::vector<double> make_period_grid(double lo, double hi, double step, const std::string& where) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && std::isfinite(step)) || !(step > 0) || !(hi >= lo) || !(lo > 0))
    throw InputError(fmt::format("period grid {}..{} step {} is not a grid", fmt_num(lo), fmt_num(hi), fmt_num(step)),
                     where, "give 0 < period_min <= period_max and period_step > 0");
  const double steps = (hi - lo) / step;
  const double n_steps = std::round(steps);
  if (std::abs(steps - n_steps) > 1e-9 * std::max(1.0, n_steps) || n_steps > 999)
    throw InputError(fmt::format("(period_max - period_min) / period_step = {} is not an integer <= 999",
                                 fmt::format("{:.12g}", steps)),
                     where, "choose period_max = period_min + n period_step");
  std::vector<double> grid(static_cast<std::size_t>(n_steps) + 1);
  // lo + i step, rounded to 1e-12 s so that 1.00 + 2 x 0.05 is the double nearest 1.1, as a user typing
  // the grid would get; never accumulated.
  for (std::size_t i = 0; i < grid.size(); ++i)
    grid[i] = std::round((lo + static_cast<double>(i) * step) * 1e12) / 1e12;
  return grid;
}

HeightInterval BuildingModel::rule_periods() const {
  return {ct_lower * std::pow(height_min, height_exponent), ct_upper * std::pow(height_max, height_exponent)};
}

HeightInterval BuildingModel::rule_heights(double T) const {
  // eq. (6): ct_lower h^x <= T <= ct_upper h^x  <=>  (T/ct_upper)^(1/x) <= h <= (T/ct_lower)^(1/x)
  const double rule_lo = std::pow(T / ct_upper, 1.0 / height_exponent);
  const double rule_hi = std::pow(T / ct_lower, 1.0 / height_exponent);
  return {std::max(height_min, rule_lo), std::min(height_max, rule_hi)};
}

HeightInterval checked_rule_heights(const BuildingModel& b, double T, const std::string& where) {
  const HeightInterval iv = b.rule_heights(T);
  if (!(iv.lo <= iv.hi))
    throw InputError(
        fmt::format("no height satisfies T = {} s: lower bound max({}, (T/{})^(1/{})) = {} m exceeds upper bound "
                    "min({}, (T/{})^(1/{})) = {} m",
                    fmt_num(T), fmt_num(b.height_min), fmt_num(b.ct_upper), fmt_num(b.height_exponent),
                    fmt_num(iv.lo), fmt_num(b.height_max), fmt_num(b.ct_lower), fmt_num(b.height_exponent),
                    fmt_num(iv.hi)),
        where, "remove that period from the grid, or widen height_min/height_max or ct_lower/ct_upper");
  return iv;
}

std::string BuildingModel::period_text() const {
  if (period.given()) return period.describe("s");
  return fmt::format("grid of {} period{} ({} s to {} s)", periods.size(), periods.size() == 1 ? "" : "s",
                     fmt_num(periods.empty() ? 0.0 : periods.front()), fmt_num(periods.empty() ? 0.0 : periods.back()));
}
std::string BuildingModel::height_text() const {
  return height.given() ? height.describe("m") : "period-height rule";
}
std::string BuildingModel::mass_text() const {
  // a shear building's floor_mass is its mass (the sampler's m): the mass key or model is not what the floors carry
  if (shear() && !floor_mass.empty())
    return mass.given() ? "the floors' (floor_mass; mass " + mass.describe("kg") + " not used)" : "the floors' (floor_mass)";
  return mass.given() ? mass.describe("kg") : "mass-index model";
}
std::string BuildingModel::zeta_text() const { return zeta.describe(""); }
std::string BuildingModel::damping_text() const {
  if (!modal_damping && rayleigh_default()) return "Rayleigh damping on modes 1 and 2";
  if (!modal_damping)
    return fmt::format("Rayleigh damping on modes {} and {} (a sample of n < {} storeys: modes min({}, j' - 1) and "
                       "j' = min({}, n); one storey: the SDOF's)",
                       rayleigh_i, rayleigh_j, rayleigh_j, rayleigh_i, rayleigh_j);
  if (modal_zeta.empty()) return "classical modal damping, every mode the building's zeta";
  std::string z;
  for (double x : modal_zeta) z += (z.empty() ? "" : ", ") + fmt::format("{:g}", x);
  return fmt::format("classical modal damping, zeta {} per mode from mode 1 (the last for the higher modes)", z);
}
std::string BuildingModel::yield_text() const {
  if (hysteresis == Hysteresis::elastic) return "elastic";
  if (yield_coefficient.given()) return "Cy " + yield_coefficient.describe("");
  return fmt::format("drift {} / ductility {}", fmt_num(drift), fmt_num(ductility));
}

// ---------------------------------------------------------------- validation

namespace {

void check_grid(const BuildingModel& b, const WhereFn& where) {
  const std::string_view key = b.period.given() ? "period" : "periods";
  if (b.periods.empty() || b.periods.size() > 1000)
    throw InputError(fmt::format("the period grid has {} points", b.periods.size()), where(key),
                     "give 1 to 1000 periods");
  for (std::size_t i = 0; i < b.periods.size(); ++i) {
    need(period_range.contains(b.periods[i]), key, b.periods[i], std::string(period_range.text), where);
    if (i > 0 && !(b.periods[i] > b.periods[i - 1]))
      throw InputError(fmt::format("periods are not strictly increasing at {} s", fmt_num(b.periods[i])),
                       where(key), "list each period once, in increasing order");
  }
}

void check_parameters(const BuildingModel& b, const WhereFn& where) {
  if (b.aspect_ratios.empty() || b.aspect_ratios.size() > 100)
    throw InputError(fmt::format("aspect_ratios has {} values", b.aspect_ratios.size()), where("aspect_ratios"),
                     "give 1 to 100 aspect ratios h/r");
  for (double a : b.aspect_ratios) need(a > 0 && a <= 100, "aspect_ratios", a, "(0, 100]", where);
  need(b.rho_mean > 0 && b.rho_mean <= 1e5, "rho_mean", b.rho_mean, "(0, 1e5] kg/m^3", where);
  need(b.rho_cov >= 0 && b.rho_cov <= 2, "rho_cov", b.rho_cov, "[0, 2]", where);
  need(b.mbar_mean > 0 && b.mbar_mean <= 100, "mbar_mean", b.mbar_mean, "(0, 100]", where);
  need(b.mbar_cov > 0 && b.mbar_cov <= 2, "mbar_cov", b.mbar_cov, "(0, 2]", where);
  need(b.mbar_min > 0 && b.mbar_min <= 100, "mbar_min", b.mbar_min, "(0, 100]", where);
  need(b.mbar_max > b.mbar_min && b.mbar_max <= 1000, "mbar_max", b.mbar_max,
       fmt::format("(mbar_min = {}, 1000]", fmt_num(b.mbar_min)), where);
  check_distribution(b.zeta, "zeta", zeta_range, where);
  need(b.drift > 0 && b.drift <= 1, "drift", b.drift, "(0, 1]", where);
  need(b.ductility >= 1 && b.ductility <= 100, "ductility", b.ductility, "[1, 100]", where);
  need(b.alpha >= 0 && b.alpha < 1, "alpha", b.alpha, "[0, 1)", where);
  need(height_range.contains(b.height_min), "height_min", b.height_min, std::string(height_range.text), where);
  need(b.height_max >= b.height_min && b.height_max <= max_height, "height_max", b.height_max,
       fmt::format("[height_min = {}, 1000] m", fmt_num(b.height_min)), where);
  need(b.ct_lower > 0 && b.ct_lower <= 10, "ct_lower", b.ct_lower, "(0, 10]", where);
  need(b.ct_upper > b.ct_lower && b.ct_upper <= 10, "ct_upper", b.ct_upper,
       fmt::format("(ct_lower = {}, 10]", fmt_num(b.ct_lower)), where);
  need(b.height_exponent > 0 && b.height_exponent <= 2, "height_exponent", b.height_exponent, "(0, 2]", where);
}

// A period distribution with heights from the rule: T is drawn from the periods the rule admits.
void check_period_truncation(const BuildingModel& b, const WhereFn& where) {
  const HeightInterval pr = b.rule_periods();
  const double hi = std::min(pr.hi, max_period);
  const double kept = pr.lo <= hi ? Truncated(b.period, pr.lo, hi).kept() : 0.0;
  if (!(kept >= 0.5))
    throw InputError(fmt::format("period = {} keeps only {:.3g} % of its probability (at least 50 % needed) in "
                                 "the periods the period-height rule admits, [{}, {}] s (ct_lower height_min^x, ct_upper height_max^x)",
                                 b.period.describe("s"), 100 * kept, fmt_num(pr.lo), fmt_num(hi)),
                     where("period"),
                     "centre the period distribution in that range, give a height, or widen height_min/height_max "
                     "or ct_lower/ct_upper");
}

// A given height against a rule the study asks for: every grid period, or the median of a distribution.
void check_given_height(const BuildingModel& b, const WhereFn& where) {
  const double h = b.height.median(), hx = std::pow(h, b.height_exponent);
  const std::vector<double> periods = b.period.random() ? std::vector<double>{b.period.median()} : b.periods;
  for (double T : periods)
    if (!(T >= b.ct_lower * hx && T <= b.ct_upper * hx))
      throw InputError(fmt::format("height {} m is outside the period-height rule at T = {} s: "
                                   "ct_lower h^x = {} s, ct_upper h^x = {} s",
                                   fmt_num(h), fmt_num(T), fmt_num(b.ct_lower * hx), fmt_num(b.ct_upper * hx)),
                       where("height"),
                       "give a height the rule admits, or drop ct_lower/ct_upper/height_exponent to take the "
                       "height as given");
}

void check_mass_index(const BuildingModel& b, const WhereFn& where) {
  // The truncation interval must carry probability, or the inverse CDF has nothing to invert.
  const double sigma = std::sqrt(std::log1p(b.mbar_cov * b.mbar_cov));
  const double mu = std::log(b.mbar_mean) - 0.5 * sigma * sigma;
  const double mass = Truncated::lognormal_mu_sigma(mu, sigma, b.mbar_min, b.mbar_max).kept();
  if (!(mass > 1e-12))
    throw InputError(fmt::format("the lognormal(mean {}, CoV {}) has probability {} on [mbar_min, mbar_max] = "
                                 "[{}, {}]",
                                 fmt_num(b.mbar_mean), fmt_num(b.mbar_cov), mass, fmt_num(b.mbar_min),
                                 fmt_num(b.mbar_max)),
                     where("mbar_min"), "put the truncation interval where the distribution has mass");
}

}  // namespace

void validate_building(const BuildingModel& b, const WhereFn& where) {
  check_grid(b, where);
  check_parameters(b, where);
  check_distribution(b.period, "period", period_range, where);
  check_distribution(b.height, "height", height_range, where);
  check_distribution(b.mass, "mass", mass_range, where);
  check_distribution(b.yield_coefficient, "yield_coefficient", cy_range, where);
  if (b.yield_coefficient.given() && b.hysteresis == Hysteresis::elastic)
    throw InputError("yield_coefficient is given for an elastic building", where("yield_coefficient"),
                     "remove yield_coefficient, or set hysteresis = \"bilinear\"");
  if (b.height_from_rule() && b.period.random()) check_period_truncation(b, where);
  if (b.height_from_rule() && !b.period.random())
    for (double T : b.periods) checked_rule_heights(b, T, where(b.period.given() ? "period" : "periods"));
  if (!b.height_from_rule() && b.rule_explicit) check_given_height(b, where);
  if (b.mass_index_model()) check_mass_index(b, where);
}

// ---------------------------------------------------------------- parsing

namespace {

double required_number(config::TableReader& r, std::string_view key) {
  const toml::node* n = r.get(key);
  if (!n) throw InputError(fmt::format("{} is missing", key), r.where(key), fmt::format("write {} = <number>", key));
  return config::number(*n, key, r.where(key));
}

}  // namespace

// The shear model's keys against the building's model: floor_mass and storey_stiffness need model = "shear", and a
// storey_height below 2 m (the 1/30-scale frames' 0.1 m) is a model's, not a real building's code storey.
void check_shear_keys(const BuildingModel& b, const WhereFn& where) {
  check_storey_heights(b, where);
  // A fixed height with storeys given must be storeys x storey_height where that product is the model's: a shear
  // building's roof level (its floors stand at k storey_height) or a storey_height given with both. It was used
  // silently beside the floors (its mass-index mass, its period-height rule): 30 m of 10 storeys of 3.2 m.
  const bool own_storey_height = b.code.storey_height > 0;
  if (b.height.kind == Distribution::Kind::fixed && !b.storey_heights.empty()) {  // the roof: their sum
    double roof = 0.0;
    for (double x : b.storey_heights) roof += x;
    if (std::abs(b.height.value - roof) > 1e-6 * roof)
      throw InputError(fmt::format("height = {:g} m disagrees with the sum of storey_height = [{:g}] m, {:g} m",
                                   b.height.value, fmt::join(b.storey_heights, ", "), roof),
                       where("height"),
                       fmt::format("give height = {:g} (the roof level), or storey heights that add up to {:g} m",
                                   roof, b.height.value));
  } else if (b.height.kind == Distribution::Kind::fixed && b.code.storeys > 0 && (b.shear() || own_storey_height)) {
    const double sh = b.storey_height(), product = b.code.storeys * sh, h = b.height.value;
    if (std::abs(h - product) > 1e-6 * product)
      throw InputError(fmt::format("height = {:g} m disagrees with storeys x storey_height = {} x {:g} m = {:g} m{}", h,
                                   b.code.storeys, sh, product, own_storey_height ? "" : " (the default storey height)"),
                       where("height"),
                       fmt::format("give height = {:g}, storey_height = {:.6g} (height / storeys) or storeys = {} -- "
                                   "the three must agree",
                                   product, h / b.code.storeys, std::max(1L, std::lround(h / sh))));
  }
  if (!b.shear()) {
    for (auto [key, v] : {std::pair{"floor_mass", &b.floor_mass}, {"storey_stiffness", &b.storey_stiffness},
                          {"storey_yield", &b.storey_yield}})
      if (!v->empty())
        throw InputError(fmt::format("{} is given for an SDOF building", key), where(key),
                         fmt::format("add model = \"shear\" to this table (or [structures]), or remove {}", key));
    for (auto [key, given] : {std::pair{"isolation", b.isolated}, {"moat", b.moat}, {"damping", b.modal_damping},
                              {"rayleigh_modes", !b.rayleigh_default()}})
      if (given)
        throw InputError(fmt::format("{} is given for an SDOF building", key), where(key),
                         fmt::format("add model = \"shear\" to this table (or [structures]), or remove {}", key));
    if (b.code.storey_height > 0 && b.code.storey_height < 2.0)
      throw InputError(fmt::format("storey_height = {:g} m is below 2 m for an SDOF building", b.code.storey_height),
                       where("storey_height"),
                       "give a storey height in [2, 10] m, or model = \"shear\" for a scale model's storeys (0, 10] m");
    return;
  }
  // an array of one value per floor / storey: as many as the storeys given
  for (auto [key, v] : {std::pair{"floor_mass", &b.floor_mass}, {"storey_stiffness", &b.storey_stiffness},
                        {"storey_yield", &b.storey_yield}}) {
    if (v->size() <= 1) continue;
    if (b.code.storeys <= 0)
      throw InputError(fmt::format("{} holds {} values (one per storey) and storeys is not given", key, v->size()),
                       where(key),
                       fmt::format("add storeys = {} to this table (a sampled building's storeys vary with its "
                                   "height), or give {} one number for every storey",
                                   v->size(), key));
    if (v->size() != static_cast<std::size_t>(b.code.storeys))
      throw InputError(fmt::format("{} holds {} values and the building has storeys = {}", key, v->size(),
                                   b.code.storeys),
                       where(key),
                       fmt::format("give {} one number (every storey) or {} numbers, one per storey from the bottom",
                                   key, b.code.storeys));
  }
}

namespace {
// A shear building's per-floor key: a number (every floor) or an array (one per floor, bottom first), each in the
// key's range (study_keys.cpp); empty when absent.
std::vector<double> per_storey(config::TableReader& r, std::string_view key) {
  const toml::node* n = r.get(key);
  if (!n) return {};
  if (n->is_array()) return r.numbers(key, {});
  return {r.number(key, 0.0)};
}

}  // namespace

namespace {

std::string bearing_list() { return enum_name_list(bearing_names, " or ", "\""); }
std::string_view bearing_name(physics::Bearing b) {
  for (const auto& n : bearing_names)
    if (n.value == b) return n.name;
  return "?";
}

// Which keys of an isolation table each bearing takes (bit 1 << Bearing) and requires: one row per key, so the
// "not a key of this bearing" and "missing" errors and the fix texts come from one place.
struct BearingKey {
  std::string_view key;
  unsigned takes, requires_;
};
constexpr unsigned bit(physics::Bearing b) { return 1u << static_cast<unsigned>(b); }
constexpr unsigned lin = bit(physics::Bearing::linear), lrb = bit(physics::Bearing::lead_rubber),
                   fps = bit(physics::Bearing::friction_pendulum), bw = bit(physics::Bearing::bouc_wen);
constexpr BearingKey bearing_keys[] = {
    {"k_eff", lin, lin},       {"zeta_eff", lin | lrb, 0},     {"k1", lrb | bw, lrb | bw}, {"k2", lrb | bw, lrb | bw},
    {"qd", lrb | bw, lrb | bw}, {"radius", fps, fps},    {"mu_slow", fps, fps},      {"mu_fast", fps, 0},
    {"rate", fps, 0},          {"u_y", fps, 0},          {"a", bw, 0},               {"beta", bw, 0},
    {"gamma", bw, 0},          {"eta", bw, 0}};

// "a friction-pendulum bearing takes radius, mu_slow (required), mu_fast, rate, u_y"
std::string bearing_fix(physics::Bearing b) {
  std::string out = fmt::format("a {} bearing takes", bearing_name(b));
  bool first = true;
  for (const BearingKey& k : bearing_keys)
    if (k.takes & bit(b)) {
      out += fmt::format("{} {}{}", first ? "" : ",", k.key, k.requires_ & bit(b) ? " (required)" : "");
      first = false;
    }
  return out;
}

// The keys a bearing does not take are refused, the ones it needs must be there (checked before any is read).
void check_bearing_keys(config::TableReader& q, physics::Bearing b) {
  for (const BearingKey& k : bearing_keys)  // another bearing's key first: it names the likely slip
    if (q.get(k.key) && !(k.takes & bit(b)))
      throw InputError(fmt::format("{} is not a key of a {} bearing", k.key, bearing_name(b)), q.where(k.key),
                       bearing_fix(b));
  for (const BearingKey& k : bearing_keys)
    if (!q.get(k.key) && (k.requires_ & bit(b)))
      throw InputError(fmt::format("the {} bearing has no {}", bearing_name(b), k.key), q.where(k.key),
                       bearing_fix(b));
}

// The smooth bearings' constants (model/hysteresis/smooth.hpp), ranges as pounding simulate's --bearing-* options.
void read_smooth_bearing(config::TableReader& q, physics::IsolationSpec& iso) {
  if (iso.bearing == physics::Bearing::friction_pendulum) {
    iso.radius = q.number("radius", 0.0), iso.mu_slow = q.number("mu_slow", 0.0);
    iso.mu_fast = q.number("mu_fast", iso.mu_slow), iso.rate = q.number("rate");
    iso.uy = q.number("u_y", iso.uy);
    if (iso.mu_fast != iso.mu_slow && !(iso.rate > 0))
      throw InputError(fmt::format("mu_fast = {:g} differs from mu_slow = {:g} but rate is 0, so mu(v) would stay "
                                   "mu_slow", iso.mu_fast, iso.mu_slow),
                       q.where("rate"), "give the rate a of mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|) "
                                        "(s/m, e.g. 20), or drop mu_fast");
  }
  if (iso.bearing == physics::Bearing::bouc_wen) {
    iso.bw_a = q.number("a", iso.bw_a), iso.bw_beta = q.number("beta", iso.bw_beta);
    iso.bw_gamma = q.number("gamma", iso.bw_gamma);
    iso.bw_eta = static_cast<int>(q.integer("eta", iso.bw_eta));
    if (!(std::abs(iso.bw_gamma) <= iso.bw_beta))
      throw InputError(fmt::format("gamma = {:g} is outside [-beta, beta] = [{:g}, {:g}]", iso.bw_gamma,
                                   -iso.bw_beta, iso.bw_beta),
                       q.where("gamma"),
                       "give |gamma| <= beta (the stable, passive Bouc-Wen class; beta is the |du| term's coefficient)");
  }
}

// isolation = {bearing, base_mass, and the bearing's keys (bearing_keys)} of a building table
void read_isolation(config::TableReader& r, const std::string& file, const std::string& name, BuildingModel& b) {
  const toml::table* t = r.table("isolation");
  if (!t) return;
  config::TableReader q(t, file, name + ".isolation");
  physics::IsolationSpec& iso = b.isolation;
  iso.bearing = q.choice("bearing", "linear", [](const std::string& v) {
    if (const auto x = parse_enum(bearing_names, v)) return *x;
    throw InputError(fmt::format("bearing = \"{}\" is not a bearing the study runs", v), "bearing",
                     "write bearing = " + bearing_list());
  });
  iso.base_mass = q.number("base_mass", 0.0);
  check_bearing_keys(q, iso.bearing);
  // zeta_eff: the linear bearing's ratio (default 0.1), a lead-rubber bearing's rubber dashpot (default none)
  iso.k_eff = q.number("k_eff", 0.0);
  iso.zeta_eff = q.number("zeta_eff", iso.bearing == physics::Bearing::linear ? physics::default_bearing_zeta : 0.0);
  iso.k1 = q.number("k1", 0.0), iso.k2 = q.number("k2", 0.0), iso.qd = q.number("qd", 0.0);
  if ((bit(iso.bearing) & (lrb | bw)) && !(iso.k2 < iso.k1))
    throw InputError(fmt::format("k2 = {:g} N/m is not below k1 = {:g} N/m", iso.k2, iso.k1), q.where("k2"),
                     "give the post-yield stiffness k2 below the elastic k1 (0 <= k2 < k1)");
  read_smooth_bearing(q, iso);
  std::string keys = "bearing, base_mass";
  for (const BearingKey& k : bearing_keys) keys += fmt::format(", {}", k.key);
  q.finish(keys);
  b.isolated = true;
}

// moat = {gap, law, stiffness, e} of a building table
void read_moat(config::TableReader& r, const std::string& file, const std::string& name, BuildingModel& b) {
  const toml::table* t = r.table("moat");
  if (!t) return;
  config::TableReader q(t, file, name + ".moat");
  if (!q.get("gap")) throw InputError("the moat has no gap", q.where("gap"), "give gap = <m> (the base's clearance to each wall)");
  b.moat_gap = q.number("gap", 0.0);
  b.moat_law = q.string("law", "");
  if (!b.moat_law.empty()) {
    const auto law = parse_enum(contact_law_table, b.moat_law);
    if (!law || *law == ContactLaw::none)
    {
      std::string names;
      for (const auto& n : contact_law_table)
        if (n.value != ContactLaw::none) names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ", n.name);
      throw InputError(fmt::format("law = \"{}\" is not a contact law for a moat wall", b.moat_law), q.where("law"),
                       "write law = one of " + names);
    }
    if (*law == ContactLaw::stereomechanical)
      throw InputError("the stereomechanical law runs one contact element (the SDOF pair), not moat walls",
                       q.where("law"), "choose a force law for the walls (hertzdamp, kelvin, ...)");
    if (contact::traits(*law).explicit_stiffness && !q.get("stiffness"))
      throw InputError(fmt::format("the moat's law '{}' needs a stiffness", b.moat_law), q.where("law"),
                       "give stiffness = <N/m> in the moat table");
  }
  b.moat_stiffness = q.number("stiffness", 0.0);
  b.moat_e = q.number("e", -1.0);
  q.finish("gap, law, stiffness, e");
  if (!b.isolated)
    throw InputError("a moat is given for a building without isolation", r.where("moat"),
                     "give the building an isolation table, or remove the moat (a moat surrounds an isolated base)");
  b.moat = true;
}

}  // namespace

void read_shear_defaults(config::TableReader& r, BuildingModel& b) {
  b.kind = r.choice("model", std::string(to_string(b.kind)), [](const std::string& name) {
    if (const auto k = parse_enum(structure_kind_names, name)) return *k;
    throw InputError(fmt::format("model = \"{}\" is not a structural model", name), "model",
                     "write model = " + enum_name_list(structure_kind_names, " or ", "\""));
  });
  b.profile = r.choice("stiffness_profile", std::string(to_string(b.profile)), [](const std::string& name) {
    if (const auto p = parse_enum(model::stiffness_profile_names, name)) return *p;
    throw InputError(fmt::format("stiffness_profile = \"{}\" is not a profile", name), "stiffness_profile",
                     "write stiffness_profile = " + enum_name_list(model::stiffness_profile_names, " or ", "\""));
  });
  b.modal_damping = r.choice("damping", std::string(b.modal_damping ? "modal" : "rayleigh"), [](const std::string& name) {
    if (name == "rayleigh" || name == "modal") return name == "modal";
    throw InputError(fmt::format("damping = \"{}\" is not a damping model", name), "damping",
                     "write damping = \"rayleigh\" (modes 1 and 2) or \"modal\" (classical modal damping)");
  });
  if (r.get("modal_zeta")) {
    b.modal_zeta = r.numbers("modal_zeta", {});
    if (!b.modal_damping)
      throw InputError("modal_zeta is given without damping = \"modal\"", r.where("modal_zeta"),
                       "add damping = \"modal\" to this table, or remove modal_zeta (Rayleigh takes zeta)");
  }
  if (r.get("rayleigh_modes")) {
    const std::vector<double> v = r.numbers("rayleigh_modes", {});  // each in [1, 200] (study_keys.cpp)
    if (v.size() != 2 || v[0] == v[1] || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]))
      throw InputError("rayleigh_modes is not two different mode numbers", r.where("rayleigh_modes"),
                       "write rayleigh_modes = [i, j], two different whole numbers in [1, 200], e.g. [1, 3]");
    if (b.modal_damping)
      throw InputError("rayleigh_modes is given with damping = \"modal\"", r.where("rayleigh_modes"),
                       "remove rayleigh_modes (modal damping gives every mode its ratio), or write damping = \"rayleigh\"");
    b.rayleigh_i = static_cast<int>(std::min(v[0], v[1])), b.rayleigh_j = static_cast<int>(std::max(v[0], v[1]));
  } else if (b.modal_damping) {
    b.rayleigh_i = 1, b.rayleigh_j = 2;  // inherited modes do not apply to a modally damped building
  }
}


std::string BuildingModel::isolation_text() const {
  if (!isolated) return "";
  const physics::IsolationSpec& i = isolation;
  const std::string base = i.base_mass > 0 ? fmt::format("base {:g} kg", i.base_mass) : "base one floor's mass";
  switch (i.bearing) {
    case physics::Bearing::linear:
      return fmt::format("{} bearing k_eff {:g} N/m, zeta_eff {:g}; {}", bearing_name(i.bearing), i.k_eff, i.zeta_eff,
                         base);
    case physics::Bearing::friction_pendulum:
      return fmt::format("{} bearing radius {:g} m, mu_slow {:g}, mu_fast {:g}, rate {:g} s/m, u_y {:g} m; {}",
                         bearing_name(i.bearing), i.radius, i.mu_slow, i.mu_fast, i.rate, i.uy, base);
    case physics::Bearing::bouc_wen:
      return fmt::format("{} bearing k1 {:g} N/m, k2 {:g} N/m, qd {:g} N, a {:g}, beta {:g}, gamma {:g}, eta {}; {}",
                         bearing_name(i.bearing), i.k1, i.k2, i.qd, i.bw_a, i.bw_beta, i.bw_gamma, i.bw_eta, base);
    default:  // zeta_eff only where given (the text of every earlier study otherwise)
      return fmt::format("{} bearing k1 {:g} N/m, k2 {:g} N/m, qd {:g} N{}; {}", bearing_name(i.bearing), i.k1, i.k2,
                         i.qd, i.zeta_eff > 0 ? fmt::format(", zeta_eff {:g} (on k2)", i.zeta_eff) : "", base);
  }
}

std::string BuildingModel::moat_text() const {
  if (!moat) return "";
  return fmt::format("walls {:g} m either side of the base; law {}; stiffness {}; e {}", moat_gap,
                     moat_law.empty() ? "[contact] law" : moat_law,
                     moat_stiffness > 0 ? fmt::format("{:g}", moat_stiffness) : "equivalent spheres of the base",
                     moat_e >= 0 ? fmt::format("{:g}", moat_e) : "[contact] e");
}

int BuildingModel::storeys_at(double h) const {
  if (code.storeys > 0) return static_cast<int>(code.storeys);
  return std::max(1, static_cast<int>(std::lround(h / storey_height())));
}

Distribution parse_distribution(const toml::node& n, std::string_view key, const std::string& file,
                                const std::string& name, const std::string& where) {
  const std::string fix = fmt::format("write {0} = <number>, "
                                      "{0} = {{lognormal = {{median = <number>, cov = <number>}}}} "
                                      "or {0} = {{uniform = {{min = <number>, max = <number>}}}}",
                                      key);
  if (n.is_number()) return Distribution::fixed(config::number(n, key, where));
  if (!n.is_table())
    throw InputError(fmt::format("{} must be a number or a distribution table, not {}", key, config::type_name(n)),
                     where, fix);
  const std::string sub = fmt::format("{}.{}", name, key);
  config::TableReader r(n.as_table(), file, sub);
  const toml::table* ln = r.table("lognormal");
  const toml::table* un = r.table("uniform");
  r.finish("lognormal, uniform");
  if (!ln == !un)
    throw InputError(fmt::format("{} names {} distribution", key, ln ? "more than one" : "no"), where, fix);
  config::TableReader q(ln ? ln : un, file, sub + (ln ? ".lognormal" : ".uniform"));
  const double a = required_number(q, ln ? "median" : "min"), b = required_number(q, ln ? "cov" : "max");
  q.finish(ln ? "median, cov" : "min, max");
  return ln ? Distribution::lognormal(a, b) : Distribution::uniform(a, b);
}

namespace {

// periods = [..] or period_min/period_max/period_step or period; the grid is only replaced when given.
void read_periods(config::TableReader& r, const std::string& file, const std::string& name, BuildingModel& b) {
  const toml::node* periods = r.get("periods");
  const toml::node* period = r.get("period");
  std::optional<double> pmin, pmax, pstep;
  for (auto [key, out] : {std::pair{"period_min", &pmin}, {"period_max", &pmax}, {"period_step", &pstep}})
    if (const toml::node* n = r.get(key)) *out = config::number(*n, key, r.where(key));
  if (period && (periods || pmin || pmax || pstep))
    throw InputError("both period and a period grid (periods or period_min/period_max/period_step) are given",
                     r.where("period"), "give either period = <number or distribution> or the grid, not both");
  if (periods && (pmin || pmax || pstep))
    throw InputError("both periods and period_min/period_max/period_step are given", r.where("periods"),
                     "give either the list periods = [..] or the grid period_min, period_max, period_step");
  if (periods) b.periods = config::numbers(*periods, "periods", r.where("periods")), b.period = {};
  if (pmin || pmax || pstep) {
    const std::string w = r.where(pmax ? "period_max" : pmin ? "period_min" : "period_step");
    b.periods = make_period_grid(pmin.value_or(1.00), pmax.value_or(1.50), pstep.value_or(0.05), w), b.period = {};
  }
  if (period) {
    b.period = parse_distribution(*period, "period", file, name, r.where("period"));
    b.periods = {b.period.median()};
  }
}

}  // namespace

std::optional<Hysteresis> read_hysteresis(const toml::node* n, const std::string& where) {
  if (!n) return std::nullopt;
  const std::string h = config::string(*n, "hysteresis", where);
  const std::optional<Hysteresis> known = parse_enum(hysteresis_names, h);
  if (!known)
    throw InputError(fmt::format("hysteresis = \"{}\" is not a known model", h), where,
                     "write hysteresis = " + enum_name_list(hysteresis_names, " or ", "\""));
  return known;
}

BuildingModel parse_building(const toml::table* t, const std::string& file, const std::string& name,
                             BuildingModel b, const WhereFn& fallback) {
  b.resolved = true;
  config::TableReader r(t, file, name);
  const auto where = [&](std::string_view key) {
    if (t && t->get(key)) return r.where(key);
    if (t && key == "periods")  // a grid made from period_min/period_max/period_step
      for (const char* k : {"period_max", "period_min", "period_step"})
        if (t->get(k)) return r.where(k);
    return fallback(key);
  };
  const auto number = [&](const char* key, double& out) {
    if (const toml::node* n = r.get(key)) out = config::number(*n, key, r.where(key));
  };
  for (auto [key, out] : {std::pair{"rho_mean", &b.rho_mean}, {"rho_cov", &b.rho_cov}, {"mbar_mean", &b.mbar_mean},
                          {"mbar_cov", &b.mbar_cov}, {"mbar_min", &b.mbar_min}, {"mbar_max", &b.mbar_max},
                          {"drift", &b.drift}, {"ductility", &b.ductility}, {"alpha", &b.alpha},
                          {"height_min", &b.height_min}, {"height_max", &b.height_max}, {"ct_lower", &b.ct_lower},
                          {"ct_upper", &b.ct_upper}, {"height_exponent", &b.height_exponent}})
    number(key, *out);
  for (const char* key : {"ct_lower", "ct_upper", "height_exponent"}) b.rule_explicit |= r.get(key) != nullptr;
  if (const toml::node* n = r.get("aspect_ratios"))
    b.aspect_ratios = config::numbers(*n, "aspect_ratios", r.where("aspect_ratios"));
  if (const auto h = read_hysteresis(r.get("hysteresis"), r.where("hysteresis"))) b.hysteresis = *h;
  read_periods(r, file, name, b);
  for (auto [key, out] : {std::pair{"height", &b.height}, {"mass", &b.mass}, {"zeta", &b.zeta},
                          {"yield_coefficient", &b.yield_coefficient}})
    if (const toml::node* n = r.get(key)) *out = parse_distribution(*n, key, file, name, r.where(key));
  if (b.yield_coefficient.given() && (r.get("drift") || r.get("ductility")))
    throw InputError("both yield_coefficient and drift/ductility are given", r.where("yield_coefficient"),
                     "give either yield_coefficient (fy = Cy m g) or drift and ductility (fy = k drift h / ductility)");
  const double shared_storey_height = b.code.storey_height;  // [structures] storey_height (0: not given)
  b.code = read_code_factors(t, file, name);
  for (const char* key : {"asce7_r", "asce7_cd", "asce7_ie", "ec8_q", "s2800_ru", "s2800_cd", "s2800_importance",
                          "storeys", "storey_height"})
    r.get(key);  // code_factor_keys: known here, read and checked by read_code_factors
  read_storey_heights(r, b);
  const bool own_storey_height = b.code.storey_height > 0;
  if (!own_storey_height) b.code.storey_height = shared_storey_height;
  read_shear_defaults(r, b);
  // [structures] rayleigh_modes of a row mixing SDOF and shear buildings: the SDOF's one mode keeps its zeta (the
  // rule j' = min(j, n), i' = min(i, j' - 1) at n = 1); its own table's rayleigh_modes is refused (check_shear_keys)
  if (!b.shear() && !(t && t->get("rayleigh_modes"))) b.rayleigh_i = 1, b.rayleigh_j = 2;
  // the same for [structures] damping = "modal" (and its modal_zeta): the shear buildings' damping; an SDOF keeps zeta
  if (!b.shear() && !(t && (t->get("damping") || t->get("modal_zeta")))) b.modal_damping = false, b.modal_zeta.clear();
  if (r.get("floor_mass")) b.floor_mass = per_storey(r, "floor_mass");
  if (r.get("storey_stiffness")) b.storey_stiffness = per_storey(r, "storey_stiffness");
  if (r.get("storey_yield")) {
    b.storey_yield = per_storey(r, "storey_yield");
    if (b.yield_coefficient.given() || r.get("drift") || r.get("ductility") || b.hysteresis == Hysteresis::elastic)
      throw InputError("storey_yield is given with another strength (yield_coefficient, drift/ductility or hysteresis "
                       "= \"elastic\")", r.where("storey_yield"),
                       "give one strength: storey_yield (N per storey), yield_coefficient or drift and ductility");
  }
  read_isolation(r, file, name, b);
  read_moat(r, file, name, b);
  r.finish(std::string("periods, period_min, period_max, period_step, period, height, mass, zeta, yield_coefficient, "
                       "alpha, hysteresis, aspect_ratios, rho_mean, rho_cov, mbar_mean, mbar_cov, mbar_min, mbar_max, "
                       "drift, ductility, height_min, height_max, ct_lower, ct_upper, height_exponent, model, "
                       "floor_mass, storey_stiffness, storey_yield, stiffness_profile, damping, modal_zeta, rayleigh_modes, isolation, moat, ") +
           code_factor_keys);
  check_shear_keys(b, [&](std::string_view key) {
    return key == "storey_height" && !own_storey_height ? fallback(key) : where(key);
  });
  validate_building(b, where);
  return b;
}

}  // namespace pounding
