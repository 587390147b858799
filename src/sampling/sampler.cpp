// The stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1). See sampler.hpp.
#include "pounding/sampling/sampler.hpp"

#include <algorithm>
#include <cmath>
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

using WhereFn = std::function<std::string(std::string_view key)>;

void need(bool ok, const std::string& key, double value, const std::string& range, const WhereFn& where) {
  if (!ok || !std::isfinite(value))
    throw InputError(fmt::format("{} = {} is out of range", key, fmt_num(value)), where(key),
                     fmt::format("give {} in {}", key, range));
}

HeightInterval height_interval_impl(const StructureModel& m, double T, const std::string& where) {
  // eq. (6): ct_lower h^x <= T <= ct_upper h^x  <=>  (T/ct_upper)^(1/x) <= h <= (T/ct_lower)^(1/x)
  const double rule_lo = std::pow(T / m.ct_upper, 1.0 / m.height_exponent);
  const double rule_hi = std::pow(T / m.ct_lower, 1.0 / m.height_exponent);
  HeightInterval iv{std::max(m.height_min, rule_lo), std::min(m.height_max, rule_hi)};
  if (!(iv.lo <= iv.hi))
    throw InputError(
        fmt::format("no height satisfies T = {} s: lower bound max({}, (T/{})^(1/{})) = {} m exceeds upper bound "
                    "min({}, (T/{})^(1/{})) = {} m",
                    fmt_num(T), fmt_num(m.height_min), fmt_num(m.ct_upper), fmt_num(m.height_exponent),
                    fmt_num(iv.lo), fmt_num(m.height_max), fmt_num(m.ct_lower), fmt_num(m.height_exponent),
                    fmt_num(iv.hi)),
        where,
        "remove that period from the grid, or widen height_min/height_max or ct_lower/ct_upper");
  return iv;
}

void validate_impl(const StructureModel& m, const WhereFn& where) {
  if (m.periods.empty() || m.periods.size() > 1000)
    throw InputError(fmt::format("the period grid has {} points", m.periods.size()), where("periods"),
                     "give 1 to 1000 periods");
  for (std::size_t i = 0; i < m.periods.size(); ++i) {
    need(m.periods[i] > 0 && m.periods[i] <= 100, "periods", m.periods[i], "(0, 100] s", where);
    if (i > 0 && !(m.periods[i] > m.periods[i - 1]))
      throw InputError(fmt::format("periods are not strictly increasing at {} s", fmt_num(m.periods[i])),
                       where("periods"), "list each period once, in increasing order");
  }
  if (m.samples_per_pair < 1 || m.samples_per_pair > (std::int64_t{1} << 40))
    throw InputError(fmt::format("samples_per_pair = {} is out of range", m.samples_per_pair),
                     where("samples_per_pair"), "give samples_per_pair in [1, 2^40]");
  if (m.aspect_ratios.empty() || m.aspect_ratios.size() > 100)
    throw InputError(fmt::format("aspect_ratios has {} values", m.aspect_ratios.size()), where("aspect_ratios"),
                     "give 1 to 100 aspect ratios h/r");
  for (double a : m.aspect_ratios) need(a > 0 && a <= 100, "aspect_ratios", a, "(0, 100]", where);
  need(m.rho_mean > 0 && m.rho_mean <= 1e5, "rho_mean", m.rho_mean, "(0, 1e5] kg/m^3", where);
  need(m.rho_cov >= 0 && m.rho_cov <= 2, "rho_cov", m.rho_cov, "[0, 2]", where);
  need(m.mbar_mean > 0 && m.mbar_mean <= 100, "mbar_mean", m.mbar_mean, "(0, 100]", where);
  need(m.mbar_cov > 0 && m.mbar_cov <= 2, "mbar_cov", m.mbar_cov, "(0, 2]", where);
  need(m.mbar_min > 0 && m.mbar_min <= 100, "mbar_min", m.mbar_min, "(0, 100]", where);
  need(m.mbar_max > m.mbar_min && m.mbar_max <= 1000, "mbar_max", m.mbar_max,
       fmt::format("(mbar_min = {}, 1000]", fmt_num(m.mbar_min)), where);
  need(m.zeta >= 0 && m.zeta < 1, "zeta", m.zeta, "[0, 1)", where);
  need(m.drift > 0 && m.drift <= 1, "drift", m.drift, "(0, 1]", where);
  need(m.ductility >= 1 && m.ductility <= 100, "ductility", m.ductility, "[1, 100]", where);
  need(m.alpha >= 0 && m.alpha < 1, "alpha", m.alpha, "[0, 1)", where);
  need(m.height_min > 0 && m.height_min <= 1000, "height_min", m.height_min, "(0, 1000] m", where);
  need(m.height_max >= m.height_min && m.height_max <= 1000, "height_max", m.height_max,
       fmt::format("[height_min = {}, 1000] m", fmt_num(m.height_min)), where);
  need(m.ct_lower > 0 && m.ct_lower <= 10, "ct_lower", m.ct_lower, "(0, 10]", where);
  need(m.ct_upper > m.ct_lower && m.ct_upper <= 10, "ct_upper", m.ct_upper,
       fmt::format("(ct_lower = {}, 10]", fmt_num(m.ct_lower)), where);
  need(m.height_exponent > 0 && m.height_exponent <= 2, "height_exponent", m.height_exponent, "(0, 2]", where);
  need(m.code_gap_coefficient > 0 && m.code_gap_coefficient <= 1, "code_gap_coefficient", m.code_gap_coefficient,
       "(0, 1]", where);
  need(m.contact_density > 0 && m.contact_density <= 1e5, "contact_density", m.contact_density,
       "(0, 1e5] kg/m^3", where);
  need(m.contact_youngs_modulus > 0 && m.contact_youngs_modulus <= 1e13, "contact_youngs_modulus",
       m.contact_youngs_modulus, "(0, 1e13] Pa", where);
  need(m.contact_poisson >= 0 && m.contact_poisson < 0.5, "contact_poisson", m.contact_poisson, "[0, 0.5)", where);
  need(m.kh >= 0, "kh", m.kh, "[0, inf) N/m^1.5 (0: equivalent spheres)", where);
  for (double T : m.periods) height_interval_impl(m, T, where("periods"));
  // The truncation interval must carry probability, or the inverse CDF has nothing to invert.
  LognormalParams p = lognormal_from_mean_cov(m.mbar_mean, m.mbar_cov);
  Normal nd;
  double za = (std::log(m.mbar_min) - p.mu) / p.sigma, zb = (std::log(m.mbar_max) - p.mu) / p.sigma;
  double mass = za > 0 ? cdf(complement(nd, za)) - cdf(complement(nd, zb)) : cdf(nd, zb) - cdf(nd, za);
  if (!(mass > 1e-12))
    throw InputError(fmt::format("the lognormal(mean {}, CoV {}) has probability {} on [mbar_min, mbar_max] = "
                                 "[{}, {}]",
                                 fmt_num(m.mbar_mean), fmt_num(m.mbar_cov), mass, fmt_num(m.mbar_min),
                                 fmt_num(m.mbar_max)),
                     where("mbar_min"), "put the truncation interval where the distribution has mass");
}

}  // namespace


std::vector<double> StructureModel::default_periods() { return make_period_grid(1.00, 1.50, 0.05); }

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

HeightInterval height_interval(const StructureModel& model, double T, const std::string& where) {
  return height_interval_impl(model, T, where);
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
  number("rho_mean", m.rho_mean);
  number("rho_cov", m.rho_cov);
  number("mbar_mean", m.mbar_mean);
  number("mbar_cov", m.mbar_cov);
  number("mbar_min", m.mbar_min);
  number("mbar_max", m.mbar_max);
  number("zeta", m.zeta);
  number("drift", m.drift);
  number("ductility", m.ductility);
  number("alpha", m.alpha);
  number("height_min", m.height_min);
  number("height_max", m.height_max);
  number("ct_lower", m.ct_lower);
  number("ct_upper", m.ct_upper);
  number("height_exponent", m.height_exponent);
  number("code_gap_coefficient", m.code_gap_coefficient);
  number("contact_density", m.contact_density);
  number("contact_youngs_modulus", m.contact_youngs_modulus);
  number("contact_poisson", m.contact_poisson);
  number("kh", m.kh);
  if (const toml::node* n = r.get("aspect_ratios")) m.aspect_ratios = config::numbers(*n, "aspect_ratios", r.where("aspect_ratios"));
  if (const toml::node* n = r.get("samples_per_pair"))
    m.samples_per_pair = config::integer(*n, "samples_per_pair", r.where("samples_per_pair"));
  if (const toml::node* n = r.get("hysteresis")) {
    const std::string h = config::string(*n, "hysteresis", r.where("hysteresis"));
    const std::optional<Hysteresis> known = parse_enum(hysteresis_names, h);
    if (!known)
      throw InputError(fmt::format("hysteresis = \"{}\" is not a known model", h), r.where("hysteresis"),
                       "write hysteresis = " + enum_name_list(hysteresis_names, " or ", "\""));
    m.hysteresis = *known;
  }
  const toml::node* periods = r.get("periods");
  if (periods) m.periods = config::numbers(*periods, "periods", r.where("periods"));
  std::optional<double> pmin, pmax, pstep;
  for (auto [key, out] : {std::pair{"period_min", &pmin}, {"period_max", &pmax}, {"period_step", &pstep}})
    if (const toml::node* n = r.get(key)) *out = config::number(*n, key, r.where(key));
  r.finish("periods, period_min, period_max, period_step, samples_per_pair, aspect_ratios, rho_mean, rho_cov, "
           "mbar_mean, mbar_cov, mbar_min, mbar_max, zeta, hysteresis, drift, ductility, alpha, height_min, "
           "height_max, ct_lower, ct_upper, height_exponent, code_gap_coefficient, contact_density, "
           "contact_youngs_modulus, contact_poisson, kh");

  if (periods && (pmin || pmax || pstep))
    throw InputError("both periods and period_min/period_max/period_step are given", r.where("periods"),
                     "give either the list periods = [..] or the grid period_min, period_max, period_step");
  if (pmin || pmax || pstep) {
    periods_where = r.where(pmax ? "period_max" : pmin ? "period_min" : "period_step");
    m.periods = make_period_grid(pmin.value_or(1.00), pmax.value_or(1.50), pstep.value_or(0.05), periods_where);
  }
  validate_impl(m, where);
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
  for (double T : model_.periods) heights_.push_back(height_interval_impl(model_, T, "[structures].periods"));
  LognormalParams rho = lognormal_from_mean_cov(model_.rho_mean, model_.rho_cov);
  rho_mu_ = rho.mu;
  rho_sigma_ = rho.sigma;
  LognormalParams mb = lognormal_from_mean_cov(model_.mbar_mean, model_.mbar_cov);
  mbar_mu_ = mb.mu;
  mbar_sigma_ = mb.sigma;
  mbar_za_ = (std::log(model_.mbar_min) - mbar_mu_) / mbar_sigma_;
  mbar_zb_ = (std::log(model_.mbar_max) - mbar_mu_) / mbar_sigma_;
  Normal nd;
  mbar_pa_ = cdf(nd, mbar_za_);
  mbar_pb_ = cdf(nd, mbar_zb_);
  mbar_qa_ = cdf(complement(nd, mbar_za_));
  mbar_qb_ = cdf(complement(nd, mbar_zb_));
  mbar_upper_tail_ = mbar_za_ > 0;
}

template <class Gen>
SampledStructure StructureSampler::draw_structure(Gen& g, std::size_t pi) const {
  // Four uniforms per structure, always in this order: h, aspect ratio, rho, mbar.
  const double u_h = uniform01(g), u_a = uniform01(g), u_rho = uniform01(g), u_mbar = uniform01(g);
  const Normal nd;
  SampledStructure s;
  s.T = model_.periods[pi];
  const HeightInterval& iv = heights_[pi];
  s.h = iv.lo + (iv.hi - iv.lo) * u_h;  // uniform on [lo, hi] (section 3.1)
  const std::size_t na = model_.aspect_ratios.size();
  s.aspect = model_.aspect_ratios[std::min(na - 1, static_cast<std::size_t>(u_a * static_cast<double>(na)))];
  s.r = s.h / s.aspect;
  s.rho = std::exp(rho_mu_ + rho_sigma_ * quantile(nd, u_rho));
  // Truncated lognormal, exact: ln mbar = mu + sigma Z with Z standard normal restricted to [za, zb].
  // Its CDF is (Phi(z) - Phi(za)) / (Phi(zb) - Phi(za)); inverting at u gives
  // z = Phi^-1(Phi(za) + u (Phi(zb) - Phi(za))) -- every u in (0, 1) maps inside [za, zb], no rejection.
  // When za > 0 both bounds lie in the upper tail, where Phi ~ 1 loses digits, so the same map is applied
  // to the upper-tail probabilities: z = -Phi^-1(Q(za) - u (Q(za) - Q(zb))), Q = 1 - Phi.
  double z = mbar_upper_tail_ ? quantile(complement(nd, mbar_qa_ - u_mbar * (mbar_qa_ - mbar_qb_)))
                              : quantile(nd, mbar_pa_ + u_mbar * (mbar_pb_ - mbar_pa_));
  s.mbar = std::clamp(std::exp(mbar_mu_ + mbar_sigma_ * z), model_.mbar_min, model_.mbar_max);  // rounding only
  s.m = s.mbar * s.rho * s.r * s.r * s.h;  // eq. (7)
  Structure st = Structure::from_period(s.m, s.T, model_.zeta);  // eqs (8), (9)
  s.k = st.k;
  s.c = st.c;
  if (model_.hysteresis == Hysteresis::bilinear) {
    s.fy = s.k * (model_.drift * s.h / model_.ductility);  // ductility 6 at 2 % drift (section 2.1)
    s.alpha = model_.alpha;
  } else {
    s.fy = std::numeric_limits<double>::infinity();
    s.alpha = 0.0;
  }
  return s;
}

SampledPair StructureSampler::sample(const SampleId& id) const {
  const auto n = static_cast<std::int32_t>(model_.periods.size());
  if (id.i1 < 0 || id.i1 >= n || id.i2 < 0 || id.i2 >= n || id.sample < 0)
    throw std::out_of_range(fmt::format("sample identity ({}, {}, {}) outside a grid of {} periods", id.i1, id.i2,
                                        id.sample, n));
  Engine g = make_engine(stream_seed(seed_, stream_, id));
  SampledPair p;
  p.id = id;
  p.s1 = draw_structure(g, static_cast<std::size_t>(id.i1));
  p.s2 = draw_structure(g, static_cast<std::size_t>(id.i2));
  p.d = model_.code_gap_coefficient * (p.s1.h + p.s2.h);  // eq. (5)
  p.kh = model_.kh > 0 ? model_.kh
                       : hertz_stiffness_spheres(p.s1.m, p.s2.m, model_.contact_density, model_.contact_youngs_modulus,
                                                 model_.contact_poisson);
  return p;
}

void StructureSampler::sample_block(std::int32_t i1, std::int32_t i2, std::int64_t first,
                                    std::span<SampledPair> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = sample(SampleId{i1, i2, first + static_cast<std::int64_t>(j)});
}

std::int64_t StructureSampler::global_index(const SampleId& id) const {
  const auto n = static_cast<std::int64_t>(model_.periods.size());
  return (id.i1 * n + id.i2) * model_.samples_per_pair + id.sample;
}

SampleId StructureSampler::identity(std::int64_t global_index) const {
  const auto n = static_cast<std::int64_t>(model_.periods.size());
  const std::int64_t pair = global_index / model_.samples_per_pair;
  return SampleId{static_cast<std::int32_t>(pair / n), static_cast<std::int32_t>(pair % n),
                  global_index % model_.samples_per_pair};
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
