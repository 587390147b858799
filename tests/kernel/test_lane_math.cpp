// issue 25 §1, architecture.md §2.4.6: lane::exp and lane::expm1 give the same bits for T = double and for
// T = simd::V, lane by lane, on 2e5 arguments over the whole range (and the edge cases: 0, -0, tiny, the
// denormal range, overflow, +-inf, NaN), and the error of exp against a long-double reference is at most 1 ulp
// and expm1 at most 2 ulp (measured 0.957 and 1.721 ulp: printed by the test). Compiled with the kernel's architecture flag.
#ifndef POUNDING_BITS_NOT_CLAIMED
#error "POUNDING_BITS_NOT_CLAIMED (empty, or why this build makes no identical-bits claim) is set by CMakeLists.txt"
#endif
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "pounding/kernel/lane.hpp"

namespace lane = pounding::lane;
using V = pounding::simd::V;
constexpr int W = pounding::simd::W;

namespace {

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

std::vector<double> arguments() {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> x = {0.0, -0.0, 1e-300, -1e-300, 4.9e-324, -4.9e-324, 1e-17, -1e-17, 1e-9, -1e-9,
                           0.34657359027997264, -0.34657359027997264, 0.3465735902799727, 0.5, -0.5, 1.0, -1.0,
                           std::log(2.0), 700.0, 709.782712893384, 709.7827128933841, 709.79, 710.0, 711.0, 1e300,
                           -700.0, -708.3964185322641, -708.4, -720.0, -744.44, -745.1332191019411,
                           -745.1332191019412, -745.14, -746.0, -1e300, inf, -inf, nan};
  std::mt19937_64 g(25071);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 100000; ++i) x.push_back(-750.0 + 1462.0 * u(g));  // the whole range and past both ends
  for (int i = 0; i < 50000; ++i) x.push_back((u(g) - 0.5) * 2.0);       // where the laws live (|x| < 1)
  for (int i = 0; i < 50000; ++i) x.push_back((u(g) < 0.5 ? -1 : 1) * std::pow(10.0, -20.0 + 22.0 * u(g)));
  while (x.size() % W) x.push_back(0.25);
  return x;
}

template <class F> std::vector<double> at_double(const std::vector<double>& x, F f) {
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = f(x[i]);
  return y;
}
template <class F> std::vector<double> at_simd(const std::vector<double>& x, F f) {
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); i += W) {
    const V v(x.data() + i, pounding::simd::stdx::element_aligned);
    f(v).copy_to(y.data() + i, pounding::simd::stdx::element_aligned);
  }
  return y;
}

// |y - exact| in units of the last place of the exact value (long double reference, 64-bit mantissa)
double ulps(double y, long double exact) {
  if (std::isnan(y) || std::isnan(static_cast<double>(exact))) return std::isnan(y) == std::isnan(static_cast<double>(exact)) ? 0 : 1e9;
  if (std::isinf(y) || std::isinf(static_cast<double>(exact))) return y == static_cast<double>(exact) ? 0 : 1e9;
  const double e = static_cast<double>(exact);
  const double ulp = std::nextafter(std::abs(e), std::numeric_limits<double>::infinity()) - std::abs(e);
  return static_cast<double>(std::abs(static_cast<long double>(y) - exact) / ulp);
}

}  // namespace

TEST(LaneMath, ExpIsBitEqualAtBothLaneTypes) {
  if (*POUNDING_BITS_NOT_CLAIMED) GTEST_SKIP() << "no identical-bits claim in this build: " << POUNDING_BITS_NOT_CLAIMED;
  const auto x = arguments();
  const auto a = at_double(x, [](double v) { return lane::exp(v); });
  const auto b = at_simd(x, [](const V& v) { return lane::exp(v); });
  const auto c = at_double(x, [](double v) { return lane::expm1(v); });
  const auto d = at_simd(x, [](const V& v) { return lane::expm1(v); });
  int differ = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool same = (bits(a[i]) == bits(b[i]) || (std::isnan(a[i]) && std::isnan(b[i]))) &&
                      (bits(c[i]) == bits(d[i]) || (std::isnan(c[i]) && std::isnan(d[i])));
    if (!same && ++differ < 5) ADD_FAILURE() << "x = " << x[i] << ": exp " << a[i] << " vs " << b[i] << ", expm1 " << c[i] << " vs " << d[i];
  }
  EXPECT_EQ(differ, 0);
}

TEST(LaneMath, ExpWithinOneUlpExpm1WithinTwo) {
  const auto x = arguments();
  double worst = 0.0, worst_m1 = 0.0, at = 0.0, at_m1 = 0.0;
  for (double v : x) {
    const double e = ulps(lane::exp(v), std::exp(static_cast<long double>(v)));
    const double m = ulps(lane::expm1(v), std::expm1(static_cast<long double>(v)));
    if (e > worst) worst = e, at = v;
    if (m > worst_m1) worst_m1 = m, at_m1 = v;
  }
  std::printf("lane::exp max error %.3f ulp (at %.17g), lane::expm1 %.3f ulp (at %.17g) over %zu arguments\n", worst,
              at, worst_m1, at_m1, x.size());
  EXPECT_LE(worst, 1.0);
  EXPECT_LE(worst_m1, 2.0);
}

TEST(LaneMath, ExpEdgeCases) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(lane::exp(0.0), 1.0);
  EXPECT_EQ(lane::exp(-0.0), 1.0);
  EXPECT_EQ(lane::exp(1e-300), 1.0);
  EXPECT_EQ(lane::exp(710.0), inf);
  EXPECT_EQ(lane::exp(inf), inf);
  EXPECT_EQ(lane::exp(-inf), 0.0);
  EXPECT_EQ(lane::exp(-746.0), 0.0);
  EXPECT_EQ(lane::exp(-745.0), std::exp(-745.0));  // a denormal: 4.94e-324 (one ulp of zero)
  EXPECT_EQ(lane::exp(-740.0), std::exp(-740.0));
  EXPECT_TRUE(std::isfinite(lane::exp(709.78)));
  EXPECT_TRUE(std::isnan(lane::exp(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(lane::expm1(1e-300), 1e-300);
  EXPECT_TRUE(std::signbit(lane::expm1(-0.0)));
  EXPECT_EQ(lane::expm1(-inf), -1.0);
  EXPECT_EQ(lane::expm1(inf), inf);
  EXPECT_TRUE(std::isnan(lane::expm1(std::numeric_limits<double>::quiet_NaN())));
}
