// The hysteresis registry's driver traits (model/hysteresis/registry.hpp, architecture.md 2.5.2, D9) give the
// decisions and numbers study/run.cpp computed by value before the registry, bit for bit: elastic_at's
// `peak <= margin * fy / k` and the IDA bisection's `fy /= f`, on 1e5 random bilinear specs (elastic fy = inf,
// zero stiffness, peaks exactly at and one ulp around the yield displacement included). And the identity
// unscaled_equivalent stands for, R(f w; spec) = f R(w; spec'), through the model's own restoring force.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "pounding/model/hysteresis/registry.hpp"

namespace pounding {
namespace {

using model::BilinearKinematic;

static_assert(model::Hystereses::size == 7);  // bilinear, Bouc-Wen, friction pendulum (step 7), 4 bridge links (issue 26)
static_assert(model::Hysteresis<BilinearKinematic>);
static_assert(model::Hysteresis<model::BoucWen> && model::Hysteresis<model::FrictionPendulum>);

Structure random_spec(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Structure s;
  s.m = std::exp(std::log(1e3) + u(rng) * std::log(1e7));
  s.k = std::exp(std::log(1e2) + u(rng) * std::log(1e10));
  const double pick = u(rng);
  s.fy = pick < 0.05 ? std::numeric_limits<double>::infinity() : std::exp(std::log(1e1) + u(rng) * std::log(1e8));
  if (pick > 0.999) s.k = 0.0;  // fy / 0: inf (or nan with fy = inf): the old expression's own answer stands
  s.alpha = u(rng) < 0.2 ? 0.0 : 0.2 * u(rng);
  return s;
}

// study/run.cpp elastic_at before the registry (commit 0032648), per body
bool elastic_before(double fy, double k, double u, double margin) { return u <= margin * fy / k; }

TEST(HysteresisTraits, BilinearStaysElasticIsTheOldExpressionBitForBit) {
  std::mt19937_64 rng(20251126);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  constexpr double margin = 1.0 - 1e-9;  // study/run.cpp's
  int elastic = 0, yielded = 0;
  for (int n = 0; n < 100000; ++n) {
    const Structure s = random_spec(rng);
    const double uy = margin * s.fy / s.k;
    // a random peak, and peaks at, just below and just above the yield displacement
    for (double peak : {u(rng) * (std::isfinite(uy) ? uy : 1.0), uy, std::nextafter(uy, 0.0),
                        std::nextafter(uy, std::numeric_limits<double>::infinity())}) {
      const bool want = elastic_before(s.fy, s.k, peak, margin);
      ASSERT_EQ(BilinearKinematic::stays_elastic(s, peak, margin), want)
          << "k " << s.k << " fy " << s.fy << " peak " << peak;
      (want ? elastic : yielded) += 1;
    }
  }
  EXPECT_GT(elastic, 100000);  // both answers are exercised
  EXPECT_GT(yielded, 50000);
}

TEST(HysteresisTraits, BilinearUnscaledEquivalentIsTheOldDivisionBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 100000; ++n) {
    const Structure s = random_spec(rng);
    const double f = std::exp(std::log(1e-3) + u(rng) * std::log(1e6));
    Structure before = s;
    before.fy /= f;  // study/run.cpp's bisection before the registry: pp.s1.fy /= mid
    const std::optional<Structure> now = BilinearKinematic::unscaled_equivalent(s, f);
    ASSERT_TRUE(now.has_value());
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->fy), std::bit_cast<std::uint64_t>(before.fy)) << s.fy << " / " << f;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->k), std::bit_cast<std::uint64_t>(s.k));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->alpha), std::bit_cast<std::uint64_t>(s.alpha));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->m), std::bit_cast<std::uint64_t>(s.m));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(now->c), std::bit_cast<std::uint64_t>(s.c));
  }
}

// What the trait promises, through the model's restoring force on a cyclic path that yields: R(f w; s) and
// f R(w; s') agree to round-off at every step (the kernel-level identity is tests/study/test_ida_scaling.cpp).
TEST(HysteresisTraits, BilinearUnscaledEquivalentScalesTheRestoringForce) {
  const Structure s{1e6, 4e7, 0.0, 2e5, 0.05};  // yield displacement 5 mm
  for (double f : {0.3, 2.5}) {
    const Structure se = *BilinearKinematic::unscaled_equivalent(s, f);
    const auto p = BilinearKinematic::params(s), pe = BilinearKinematic::params(se);
    double fs = 0.0, fse = 0.0, w_old = 0.0, worst = 0.0, w_max = 0.0;
    for (int i = 1; i <= 4000; ++i) {
      const double w = 0.02 / f * std::sin(i * 0.005) * (1.0 + i / 2000.0);  // f w: growing cycles to ~8x yield
      fs = BilinearKinematic::restoring<double>(p, fs, f * (w - w_old), f * w);
      fse = BilinearKinematic::restoring<double>(pe, fse, w - w_old, w);
      worst = std::max(worst, std::abs(fs - f * fse) / (f * s.fy));
      w_max = std::max(w_max, std::abs(f * w));
      w_old = w;
    }
    EXPECT_LT(worst, 1e-12) << "f " << f;
    EXPECT_GT(w_max, 4.0 * s.fy / s.k) << "the path yields";
    EXPECT_FALSE(BilinearKinematic::stays_elastic(s, w_max, 1.0));
  }
}

}  // namespace
}  // namespace pounding
