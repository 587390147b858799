// Each building its own model (issue 13, part 1): the distributions of building.hpp, the [structures.building1/2]
// tables over the [structures] defaults, equal heights, truncated period draws and every validation error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <type_traits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "pounding/core/error.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/sampling/isolation_check.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/settings.hpp"

using namespace pounding;

namespace {

constexpr std::uint64_t kSeed = 20240917;

StructureModel parse(const std::string& text) {
  const toml::table root = toml::parse(std::string_view(text), std::string_view("s.toml"));
  const toml::table empty;
  const toml::table* t = root["structures"].as_table();
  return parse_structure_model(t ? *t : empty, "s.toml");
}

InputError parse_error(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("", "", "");
}

// The error names the key (in the message or the location) and a file:line location.
void expect_error(const std::string& text, const std::string& key, const std::string& in_message = "") {
  const InputError e = parse_error(text);
  const std::string all = std::string(e.what()) + " | " + e.where() + " | " + e.fix();
  EXPECT_NE(all.find(key), std::string::npos) << all;
  EXPECT_NE(e.where().find("s.toml:"), std::string::npos) << all;
  if (!in_message.empty()) {
    EXPECT_NE(all.find(in_message), std::string::npos) << all;
  }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_structure(const SampledStructure& a, const SampledStructure& b) {
  for (auto f : {&SampledStructure::T, &SampledStructure::h, &SampledStructure::aspect, &SampledStructure::r,
                 &SampledStructure::rho, &SampledStructure::mbar, &SampledStructure::m, &SampledStructure::k,
                 &SampledStructure::c, &SampledStructure::fy, &SampledStructure::alpha, &SampledStructure::zeta})
    EXPECT_TRUE(same_bits(a.*f, b.*f)) << a.*f << " vs " << b.*f;
}

void expect_same_pair(const SampledPair& a, const SampledPair& b) {
  EXPECT_EQ(a.id, b.id);
  expect_same_structure(a.s1, b.s1);
  expect_same_structure(a.s2, b.s2);
  EXPECT_TRUE(same_bits(a.d, b.d));
  EXPECT_TRUE(same_bits(a.kh, b.kh));
}

std::vector<SampledPair> draw(const StructureModel& m, int n, std::int32_t i1 = 0, std::int32_t i2 = 0) {
  const StructureSampler s(m, kSeed);
  std::vector<SampledPair> out(static_cast<std::size_t>(n));
  s.sample_block(i1, i2, 0, out);
  return out;
}

double median_of(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

// The two-building example of the issue: an 8-storey frame (T ~ 0.9 s, 28 m) beside a 12-storey one (1.3 s, 42 m).
const char* example = R"(
[structures]
samples_per_pair = 64
[structures.building1]
period = {lognormal = {median = 0.9, cov = 0.15}}
height = 28.0
mass = 4.2e6
zeta = 0.05
[structures.building2]
period = {lognormal = {median = 1.3, cov = 0.15}}
height = 42.0
mass = 6.3e6
zeta = 0.05
)";

}  // namespace

TEST(Distribution, QuantileCdfMedianDescribe) {
  const Distribution f = Distribution::fixed(1.5), ln = Distribution::lognormal(0.9, 0.15),
                     un = Distribution::uniform(0.8, 1.0), ln0 = Distribution::lognormal(0.9, 0.0);
  EXPECT_EQ(f.quantile(0.123), 1.5);
  EXPECT_FALSE(f.random());
  EXPECT_FALSE(ln0.random());
  EXPECT_EQ(ln0.quantile(0.99), 0.9);  // cov 0: fixed
  EXPECT_NEAR(ln.quantile(0.5), 0.9, 1e-15);
  EXPECT_NEAR(ln.sigma(), std::sqrt(std::log(1 + 0.15 * 0.15)), 1e-15);
  EXPECT_NEAR(ln.cdf(ln.quantile(0.3)), 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(un.quantile(0.25), 0.85);
  EXPECT_EQ(un.median(), 0.9);
  EXPECT_EQ(ln.describe("s"), "lognormal(median 0.9 s, cov 0.15)");
  EXPECT_EQ(un.describe("s"), "uniform(0.8 s, 1 s)");
  EXPECT_EQ(f.describe(""), "1.5");
}

TEST(Distribution, TruncatedStaysInsideAndKeepsTheRightMass) {
  const Distribution ln = Distribution::lognormal(1.0, 0.5);
  const Truncated t(ln, 0.8, 1.1);
  EXPECT_NEAR(t.kept(), ln.cdf(1.1) - ln.cdf(0.8), 1e-14);
  for (double u : {1e-12, 0.1, 0.5, 0.9, 1 - 1e-12}) {
    const double x = t.sample(u);
    EXPECT_GE(x, 0.8);
    EXPECT_LE(x, 1.1);
    // the inverse CDF of the truncated law
    EXPECT_NEAR((ln.cdf(x) - ln.cdf(0.8)) / t.kept(), u, 1e-9);
  }
  const Truncated upper(ln, 2.0, 3.0);  // both bounds in the upper tail
  EXPECT_NEAR(upper.kept(), ln.cdf(3.0) - ln.cdf(2.0), 1e-14);
  EXPECT_GE(upper.sample(0.01), 2.0);
  EXPECT_EQ(Truncated(Distribution::uniform(0.0, 4.0), 1.0, 2.0).kept(), 0.25);
}

TEST(Building, LognormalPeriodHasTheRightLawAndIsReproducible) {
  // A given height: T is truncated only to (0, 100] s, i.e. the plain lognormal.
  StructureModel m = parse(
      "[structures]\nsamples_per_pair = 1\n[structures.building1]\nperiod = {lognormal = {median = 0.9, cov = 0.15}}\n"
      "height = 28\n");
  constexpr int n = 20000;
  const auto a = draw(m, n), b = draw(m, n);
  std::vector<double> lnT;
  for (int i = 0; i < n; ++i) {
    lnT.push_back(std::log(a[static_cast<std::size_t>(i)].s1.T));
    expect_same_pair(a[static_cast<std::size_t>(i)], b[static_cast<std::size_t>(i)]);
  }
  const double sigma = std::sqrt(std::log(1 + 0.15 * 0.15));
  double mean = 0, var = 0;
  for (double x : lnT) mean += x / n;
  for (double x : lnT) var += (x - mean) * (x - mean) / (n - 1);
  // Sample median of a normal: standard error 1.2533 sigma / sqrt(n); sample std: sigma / sqrt(2 (n - 1)). 4 SE.
  EXPECT_NEAR(median_of(lnT), std::log(0.9), 4 * 1.2533 * sigma / std::sqrt(double(n)));
  EXPECT_NEAR(std::sqrt(var), sigma, 4 * sigma / std::sqrt(2.0 * (n - 1)));
  // building 2 keeps the paper's grid
  EXPECT_EQ(m.slots(0), 1u);
  EXPECT_EQ(m.slots(1), 11u);
  EXPECT_EQ(m.period_pair_count(), 11);
}

TEST(Building, UniformZetaStaysInItsBoundsWithTheRightMean) {
  StructureModel m = parse("[structures.building2]\nzeta = {uniform = {min = 0.02, max = 0.08}}\n");
  constexpr int n = 20000;
  const auto a = draw(m, n, 3, 4);
  double mean = 0;
  for (const auto& p : a) {
    EXPECT_GE(p.s2.zeta, 0.02);
    EXPECT_LE(p.s2.zeta, 0.08);
    EXPECT_EQ(p.s1.zeta, 0.05);
    EXPECT_NEAR(p.s2.c, 2 * p.s2.zeta * std::sqrt(p.s2.k * p.s2.m), 1e-9 * p.s2.c);
    mean += p.s2.zeta / n;
  }
  EXPECT_NEAR(mean, 0.05, 4 * (0.06 / std::sqrt(12.0)) / std::sqrt(double(n)));
}

TEST(Building, FixedPeriodHeightMassGiveOneModel) {
  StructureModel m = parse(
      "[structures.building1]\nperiod = 1.2\nheight = 35\nmass = 5e6\nyield_coefficient = 0.1\nalpha = 0.02\n");
  const auto a = draw(m, 50, 0, 5);
  for (const auto& p : a) {
    EXPECT_EQ(p.s1.T, 1.2);
    EXPECT_EQ(p.s1.h, 35.0);
    EXPECT_EQ(p.s1.m, 5e6);
    expect_same_structure(p.s1, a[0].s1);
    EXPECT_TRUE(std::isnan(p.s1.aspect) && std::isnan(p.s1.r) && std::isnan(p.s1.rho) && std::isnan(p.s1.mbar));
    EXPECT_EQ(p.s1.fy, 0.1 * 5e6 * 9.80665);
    EXPECT_EQ(p.s1.alpha, 0.02);
    EXPECT_FALSE(std::isnan(p.s2.mbar));  // building 2: the mass-index model
  }
  EXPECT_NE(a[0].s2.h, a[1].s2.h);
}

TEST(Building, DefaultsGiveTheSharedModelBitForBit) {
  const StructureModel shared;  // no building tables, unresolved
  const StructureModel parsed = parse("[structures]\n[structures.building1]\n[structures.building2]\n");
  // Restating [structures]'s values in a building table changes nothing either.
  const StructureModel restated = parse(
      "[structures]\nzeta = 0.04\ndrift = 0.015\n[structures.building1]\nzeta = 0.04\nperiods = [1.0, 1.1]\n"
      "[structures.building2]\ndrift = 0.015\nperiods = [1.0, 1.1]\n");
  const StructureModel plain = parse("[structures]\nzeta = 0.04\ndrift = 0.015\nperiods = [1.0, 1.1]\n");
  for (std::int32_t i1 : {0, 1})
    for (std::int32_t i2 : {0, 1}) {
      const auto a = draw(shared, 40, i1 * 7, i2 * 10), b = draw(parsed, 40, i1 * 7, i2 * 10);
      for (std::size_t j = 0; j < a.size(); ++j) expect_same_pair(a[j], b[j]);
      const auto c = draw(restated, 40, i1, i2), d = draw(plain, 40, i1, i2);
      for (std::size_t j = 0; j < c.size(); ++j) expect_same_pair(c[j], d[j]);
    }
}

TEST(Building, OverridesApplyOnlyToTheirBuilding) {
  const StructureModel base = parse("[structures]\nperiods = [1.0, 1.2]\n");
  const StructureModel over = parse(
      "[structures]\nperiods = [1.0, 1.2]\n[structures.building2]\nzeta = 0.1\nductility = 4\nalpha = 0.1\n"
      "aspect_ratios = [2]\n");
  const auto a = draw(base, 100, 1, 0), b = draw(over, 100, 1, 0);
  for (std::size_t j = 0; j < a.size(); ++j) {
    expect_same_structure(a[j].s1, b[j].s1);
    EXPECT_EQ(a[j].s2.h, b[j].s2.h);  // the same uniforms
    EXPECT_EQ(b[j].s2.zeta, 0.1);
    EXPECT_EQ(b[j].s2.alpha, 0.1);
    EXPECT_EQ(b[j].s2.aspect, 2.0);
    EXPECT_NEAR(b[j].s2.fy, b[j].s2.k * 0.02 * b[j].s2.h / 4, 1e-9 * b[j].s2.fy);
  }
  EXPECT_EQ(over.building(0).zeta.median(), 0.05);
  EXPECT_EQ(over.building(1).ductility, 4.0);
}

TEST(Building, EqualHeightsDrawOneHeightInsideBothRuleIntervals) {
  const StructureModel m = parse("[structures]\nequal_heights = true\nsamples_per_pair = 8\n");
  const StructureSampler s(m, kSeed);
  const auto& grid = m.building(0).periods;
  for (std::int32_t i1 = 0; i1 < 11; i1 += 2)
    for (std::int32_t i2 = 0; i2 < 11; i2 += 3)
      for (std::int64_t k = 0; k < 20; ++k) {
        const SampledPair p = s.sample({i1, i2, k});
        EXPECT_EQ(p.s1.h, p.s2.h);
        for (double T : {grid[static_cast<std::size_t>(i1)], grid[static_cast<std::size_t>(i2)]}) {
          const HeightInterval iv = height_interval(m, T);
          EXPECT_GE(p.s1.h, iv.lo);
          EXPECT_LE(p.s1.h, iv.hi);
        }
      }
}

TEST(Building, TruncatedPeriodStaysInTheRulesRange) {
  const StructureModel m = parse("[structures.building1]\nperiod = {lognormal = {median = 1.2, cov = 0.5}}\n");
  const HeightInterval range = m.building(0).rule_periods();  // [0.05 30^0.75, 0.08 50^0.75]
  EXPECT_NEAR(range.lo, 0.05 * std::pow(30.0, 0.75), 1e-12);
  const auto a = draw(m, 5000, 0, 2);
  double lo = 1e9, hi = 0;
  for (const auto& p : a) {
    EXPECT_GE(p.s1.T, range.lo);
    EXPECT_LE(p.s1.T, range.hi);
    const HeightInterval iv = m.building(0).rule_heights(p.s1.T);
    EXPECT_GE(p.s1.h, iv.lo * (1 - 1e-12));
    EXPECT_LE(p.s1.h, std::max(iv.lo, iv.hi) * (1 + 1e-12));
    lo = std::min(lo, p.s1.T), hi = std::max(hi, p.s1.T);
  }
  EXPECT_LT(lo, range.lo + 0.05);  // the draws fill the range
  EXPECT_GT(hi, range.hi - 0.05);
}

TEST(Building, TheTwoBuildingExampleParses) {
  const StructureModel m = parse(example);
  EXPECT_TRUE(m.heights_specified());
  EXPECT_EQ(m.period_pair_count(), 1);
  EXPECT_EQ(m.model_count(), 64);
  const BuildingModel b1 = m.building(0), b2 = m.building(1);
  EXPECT_EQ(b1.period.kind, Distribution::Kind::lognormal);
  EXPECT_EQ(b1.period.value, 0.9);
  EXPECT_EQ(b2.period.value, 1.3);
  EXPECT_EQ(b1.period_text(), "lognormal(median 0.9 s, cov 0.15)");
  EXPECT_EQ(b1.height_text(), "28 m");
  EXPECT_EQ(b2.mass_text(), "6.3e+06 kg");
  EXPECT_EQ(b1.yield_text(), "drift 0.02 / ductility 6");
  EXPECT_EQ(parse("").building(0).height_text(), "period-height rule");
  EXPECT_EQ(parse("").building(0).mass_text(), "mass-index model");
  const auto a = draw(m, 64);
  for (const auto& p : a) {
    EXPECT_EQ(p.s1.h, 28.0);
    EXPECT_EQ(p.s2.h, 42.0);
    EXPECT_EQ(p.s1.m, 4.2e6);
    EXPECT_EQ(p.s2.m, 6.3e6);
    EXPECT_EQ(p.d, 0.005 * (28.0 + 42.0));
    EXPECT_NEAR(p.s1.k, 4 * std::numbers::pi * std::numbers::pi * p.s1.m / (p.s1.T * p.s1.T), 1e-9 * p.s1.k);
  }
  EXPECT_NE(a[0].s1.T, a[1].s1.T);
  EXPECT_FALSE(parse("").heights_specified());
  EXPECT_FALSE(parse("[structures.building1]\nheight = 30\n").heights_specified());
}

TEST(BuildingErrors, ValuesOutOfRange) {
  const std::string b1 = "[structures.building1]\n";
  expect_error(b1 + "period = -1\nheight = 30\n", "period");
  expect_error(b1 + "period = 0\nheight = 30\n", "period");
  expect_error(b1 + "period = 150\nheight = 30\n", "period", "[0.02, 20] s");
  // issue 24.8: physically absurd values (each accepted before) are refused with the range a real building has
  expect_error(b1 + "period = 0.005\nheight = 30\n", "period", "[0.02, 20] s");
  expect_error(b1 + "mass = 1e-30\n", "mass", "[1e3, 1e10] kg");
  expect_error(b1 + "height = 1e-6\n", "height", "[2, 1000] m");
  expect_error(b1 + "yield_coefficient = 1e-12\n", "yield_coefficient", "[0.005, 5]");
  expect_error(b1 + "zeta = 0.999\n", "zeta", "[0, 0.5]");
  expect_error(b1 + "mass = {lognormal = {median = 1e-3, cov = 0.2}}\n", "mass", "[1e3, 1e10] kg");
  expect_error(b1 + "period = {lognormal = {median = 1.0, cov = -0.1}}\nheight = 30\n", "cov");
  expect_error(b1 + "period = {lognormal = {median = 1.0, cov = 2.5}}\nheight = 30\n", "cov");
  expect_error(b1 + "period = {uniform = {min = 1.2, max = 1.0}}\nheight = 30\n", "min", "exceeds max");
  expect_error(b1 + "mass = 0\n", "mass");
  expect_error(b1 + "mass = -5e6\n", "mass");
  expect_error(b1 + "height = 0\n", "height");
  expect_error(b1 + "height = 1500\n", "height", "[2, 1000] m");
  expect_error(b1 + "zeta = 1.0\n", "zeta", "[0, 0.5]");
  expect_error(b1 + "zeta = -0.01\n", "zeta");
  expect_error(b1 + "yield_coefficient = 0\n", "yield_coefficient", "[0.005, 5]");
  expect_error(b1 + "yield_coefficient = 6\n", "yield_coefficient");
  expect_error(b1 + "periods = [1.0, -1.0]\n", "periods");
  expect_error(b1 + "alpha = 1.5\n", "alpha");
}

TEST(BuildingErrors, KeysAndCombinations) {
  const std::string b1 = "[structures.building1]\n";
  expect_error(b1 + "floors = 8\n", "floors", "check the spelling");  // storeys is a key (code_factors.hpp)
  expect_error("[structures.building3]\nperiod = 1.0\n", "building3");
  expect_error(b1 + "period = 1.0\nperiods = [1.0, 1.1]\n", "period", "both period and a period grid");
  expect_error(b1 + "period = 1.0\nperiod_max = 1.4\n", "period", "both period and a period grid");
  expect_error(b1 + "yield_coefficient = 0.1\ndrift = 0.01\n", "yield_coefficient", "drift");
  expect_error(b1 + "hysteresis = \"elastic\"\nyield_coefficient = 0.1\n", "yield_coefficient", "elastic");
  expect_error(b1 + "period = \"fast\"\n", "period", "a string");
  expect_error(b1 + "period = {normal = {median = 1.0, cov = 0.1}}\n", "normal");
  expect_error(b1 + "period = {lognormal = {median = 1.0}}\n", "cov", "missing");
  expect_error(b1 + "period = {lognormal = {median = 1.0, cov = 0.1}, uniform = {min = 1, max = 2}}\n", "period",
               "more than one");
  expect_error(b1 + "period = {lognormal = {median = 1.0, cov = 0.1, mean = 1}}\n", "mean");
}

TEST(BuildingErrors, TheRuleAndEqualHeights) {
  // a period distribution mostly outside the periods the rule admits ([0.64, 1.50] s)
  expect_error("[structures.building1]\nperiod = {lognormal = {median = 3.0, cov = 0.1}}\n", "period", "50 %");
  // a fixed period outside the rule
  expect_error("[structures.building1]\nperiod = 2.5\n", "period", "no height satisfies T = 2.5 s");
  // a given height against a rule the building asks for explicitly
  expect_error("[structures.building1]\nheight = 100\nct_lower = 0.05\n", "height", "outside the period-height rule");
  expect_error("[structures]\nheight_exponent = 0.75\n[structures.building2]\nheight = 10\nperiod = 1.2\n", "height",
               "T = 1.2 s");
  // ... but without an explicit rule the given height is taken as it is
  EXPECT_NO_THROW(parse("[structures.building1]\nheight = 100\n"));
  expect_error("[structures]\nequal_heights = true\n[structures.building1]\nheight = 40\n", "equal_heights",
               "height from");
  expect_error("[structures]\nequal_heights = true\n[structures.building2]\nperiod = {uniform = {min = 1, max = 1.2}}\n",
               "equal_heights", "grid or fixed periods");
  // building 1 at 1.0 s capped at 40 m, building 2 at 1.5 s needs >= 49.8 m: no common height
  expect_error("[structures]\nequal_heights = true\n[structures.building1]\nperiods = [1.0]\nheight_max = 40\n"
               "[structures.building2]\nperiods = [1.5]\n",
               "equal_heights", "T1 = 1 s (building 1: [30, 40] m) and T2 = 1.5 s");
  expect_error("[structures]\nequal_heights = 1\n", "equal_heights");
}

TEST(Building, SettingsDescribeEachBuilding) {
  Study s;
  s.structures = parse(example);
  std::map<std::string, std::string> text;
  bool heights_specified = false;
  visit_settings(s, [&](const std::string& section, const std::string& key, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<V, std::string>) text[section + "/" + key] = value;
    if constexpr (std::is_same_v<V, bool>)
      if (section == "structures" && key == "heights_specified") heights_specified = value;
  });
  EXPECT_TRUE(heights_specified);
  EXPECT_EQ(text["structures.building1/period"], "lognormal(median 0.9 s, cov 0.15)");
  EXPECT_EQ(text["structures.building2/period"], "lognormal(median 1.3 s, cov 0.15)");
  EXPECT_EQ(text["structures.building1/height"], "28 m");
  EXPECT_EQ(text["structures.building1/mass"], "4.2e+06 kg");
  EXPECT_EQ(text["structures.building2/zeta"], "0.05");
  EXPECT_EQ(text["structures.building2/yield"], "drift 0.02 / ductility 6");
}

TEST(BuildingErrors, CodeFactors) {  // issue 23 item 5: the code design factors of a building table
  const std::string b1 = "[structures.building1]\n";
  expect_error(b1 + "asce7_r = 9\nasce7_cd = 5\n", "asce7_r", "[1, 8]");
  expect_error(b1 + "asce7_r = 8\n", "asce7_r", "both asce7_r and asce7_cd");
  expect_error(b1 + "asce7_cd = 5\n", "asce7_cd", "both asce7_r and asce7_cd");
  expect_error(b1 + "asce7_r = 8\nasce7_cd = 7\n", "asce7_cd", "[1, 6.5]");
  expect_error(b1 + "asce7_ie = 1.1\n", "asce7_ie", "1.0, 1.25 or 1.5");
  expect_error(b1 + "ec8_q = 0.5\n", "ec8_q", "[1, 8]");
  expect_error(b1 + "s2800_ru = 7.5\n", "s2800_ru", "both s2800_ru and s2800_cd");
  expect_error(b1 + "s2800_importance = 1.3\n", "s2800_importance", "0.8, 1.0, 1.2 or 1.4");
  expect_error(b1 + "storeys = 0\n", "storeys", "[1, 200]");
  expect_error(b1 + "storeys = 2.5\n", "storeys");
  expect_error(b1 + "storey_height = 12\n", "storey_height", "[0.01, 10] ([2, 10] for model = \"sdof\") m");
  const StructureModel m = parse(b1 + "asce7_r = 8\nasce7_cd = 5.5\nasce7_ie = 1.25\nec8_q = 3.9\nstoreys = 6\n"
                                      "[structures.building2]\ns2800_ru = 7.5\ns2800_cd = 5.5\ns2800_importance = 1.2\n"
                                      "storey_height = 3.5\n");
  const BuildingModel b1m = m.building(0), b2m = m.building(1);  // by value
  const CodeFactors& a = b1m.code;
  EXPECT_EQ(a.asce7_r, 8);
  EXPECT_EQ(a.asce7_cd, 5.5);
  EXPECT_EQ(a.asce7_ie, 1.25);
  EXPECT_EQ(a.ec8_q, 3.9);
  EXPECT_EQ(a.storeys, 6);
  EXPECT_EQ(a.s2800_ru, 0);  // not given
  const CodeFactors& b = b2m.code;
  EXPECT_EQ(b.s2800_ru, 7.5);
  EXPECT_EQ(b.s2800_cd, 5.5);
  EXPECT_EQ(b.s2800_importance, 1.2);
  EXPECT_EQ(b.storey_height, 3.5);
  EXPECT_EQ(b.asce7_r, 0);
}

// One default for a linear bearing's damping ratio: the study's isolation table without zeta_eff, simulate's
// --bearing-zeta and Python's isolation dicts (sampling::IsolationInput) all take physics::default_bearing_zeta, and
// the study reference says so. (The study reader took 0 while the other two took 0.1.)
TEST(Building, LinearBearingDampingHasOneDefault) {
  const StructureModel m = parse(
      "[structures]\nmodel = \"shear\"\n[structures.building1]\n"
      "isolation = {bearing = \"linear\", base_mass = 3.0e5, k_eff = 1.0e6}\n");
  ASSERT_TRUE(m.building(0).isolated);
  EXPECT_EQ(m.building(0).isolation.zeta_eff, physics::default_bearing_zeta);
  EXPECT_EQ(sampling::IsolationInput{}.zeta_eff, physics::default_bearing_zeta);
  const config::StudyKey* key = config::find_study_key("isolation", "zeta_eff");
  ASSERT_NE(key, nullptr);
  EXPECT_EQ(std::stod(std::string(key->def)), physics::default_bearing_zeta);
  const StructureModel given = parse(
      "[structures]\nmodel = \"shear\"\n[structures.building1]\n"
      "isolation = {bearing = \"linear\", base_mass = 3.0e5, k_eff = 1.0e6, zeta_eff = 0.0}\n");
  EXPECT_EQ(given.building(0).isolation.zeta_eff, 0.0);
}

// One limit on storeys: the study key's bounds are model::max_storeys (simulate and Python check that constant).
TEST(Building, StoreysHaveOneLimit) {
  const config::StudyKey* key = config::find_study_key("structures.buildingN", "storeys");
  ASSERT_NE(key, nullptr);
  EXPECT_EQ(key->hi, model::max_storeys);
  EXPECT_EQ(key->range, fmt::format("[1, {}]", model::max_storeys));
}
