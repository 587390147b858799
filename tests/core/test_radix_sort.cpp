// The LSD radix sort of doubles (include/pounding/core/radix_sort.hpp) against std::sort with the total order it
// promises (-0.0 before +0.0, otherwise operator<), compared bit for bit: random doubles of every sign and scale,
// -0.0 and +0.0, +-inf, denormals, the largest and smallest normals, many duplicates, sorted and reversed inputs,
// sizes 0, 1, 2 and around the passes' skip (all keys sharing digits). A wrong key transform (the sign bit not
// flipped, or negatives not complemented) puts the negatives after the positives or in reverse order: these fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "pounding/core/radix_sort.hpp"

namespace {

using namespace pounding;

bool total_less(double a, double b) { return a < b || (a == b && std::signbit(a) && !std::signbit(b)); }

std::vector<std::uint64_t> bits(const std::vector<double>& v) {
  std::vector<std::uint64_t> out;
  for (double x : v) out.push_back(std::bit_cast<std::uint64_t>(x));
  return out;
}

void expect_sorted_like_std(std::vector<double> v) {
  std::vector<double> want = v;
  std::sort(want.begin(), want.end(), total_less);
  radix_sort(v);
  EXPECT_EQ(bits(v), bits(want)) << "n = " << v.size();
}

std::vector<double> special() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  using L = std::numeric_limits<double>;
  return {0.0, -0.0, inf, -inf, L::denorm_min(), -L::denorm_min(), 3 * L::denorm_min(), -7 * L::denorm_min(),
          L::min(), -L::min(), L::max(), -L::max(), 1.0, -1.0, 0.5, -0.5, std::nextafter(1.0, 2.0),
          std::nextafter(-1.0, -2.0), 1e-310, -1e-310};
}

TEST(RadixSort, KeysOrderLikeDoubles) {
  const std::vector<double> s = special();
  for (double a : s)
    for (double b : s) {
      const std::uint64_t ka = radix_key(std::bit_cast<std::uint64_t>(a)), kb = radix_key(std::bit_cast<std::uint64_t>(b));
      EXPECT_EQ(ka < kb, total_less(a, b)) << a << " vs " << b;
      EXPECT_EQ(radix_unkey(ka), std::bit_cast<std::uint64_t>(a));
    }
}

TEST(RadixSort, SmallAndSpecial) {
  expect_sorted_like_std({});
  expect_sorted_like_std({-0.0});
  expect_sorted_like_std({0.0, -0.0});
  expect_sorted_like_std({1.0, -1.0});
  expect_sorted_like_std(special());
  std::vector<double> rev = special();
  std::sort(rev.begin(), rev.end(), total_less);
  std::reverse(rev.begin(), rev.end());
  expect_sorted_like_std(rev);
}

TEST(RadixSort, RandomDoublesOfEverySignAndScale) {
  std::mt19937_64 g(20261127);
  for (std::size_t n : {3u, 100u, 2047u, 2048u, 2049u, 100000u}) {
    std::vector<double> v;
    const std::vector<double> s = special();
    std::uniform_int_distribution<int> pick(0, 9);
    for (std::size_t i = 0; i < n; ++i) {
      const int kind = pick(g);
      double x;
      if (kind == 0) x = s[g() % s.size()];                         // the special values, repeated
      else if (kind == 1) x = std::bit_cast<double>(g() & 0x800fffffffffffffULL);  // denormals of both signs
      else if (kind == 2 && !v.empty()) x = v[g() % v.size()];      // duplicates
      else {
        x = std::bit_cast<double>(g());                              // any bits: every exponent and sign
        if (std::isnan(x)) x = std::ldexp(static_cast<double>(g() % 1000), -500);
      }
      v.push_back(x);
    }
    expect_sorted_like_std(v);
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end(), total_less);
    expect_sorted_like_std(sorted);  // an already sorted input
  }
}

TEST(RadixSort, DemandsLikeTheReports) {
  // positive peak closings over code gaps on a narrow range (the high digits shared: passes skipped), with zeros
  std::mt19937_64 g(7);
  std::lognormal_distribution<double> z(-1.0, 0.8);
  std::vector<double> v(50000);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = i % 17 == 0 ? 0.0 : z(g);
  expect_sorted_like_std(v);
  std::vector<double> same(5000, 0.25);  // every digit shared: no pass moves anything
  expect_sorted_like_std(same);
  std::vector<std::uint64_t> scratch;  // a reused scratch buffer gives the same order
  std::vector<double> a = v, b = v;
  radix_sort(a, scratch);
  radix_sort(b, scratch);
  EXPECT_EQ(bits(a), bits(b));
}

}  // namespace
