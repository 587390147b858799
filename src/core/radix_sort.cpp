// An LSD radix sort of doubles in std::sort's order (the bootstrap's and the histograms' sorts).
#include "pounding/core/radix_sort.hpp"

#include <array>
#include <cstring>

namespace pounding {

namespace {
constexpr int digit_bits = 11;
constexpr std::size_t buckets = std::size_t{1} << digit_bits;
constexpr int passes = (64 + digit_bits - 1) / digit_bits;  // 6: five of 11 bits and one of 9

// v's doubles are read and written as 64-bit keys through memcpy (no type punning through pointers).
std::uint64_t get(const unsigned char* base, std::size_t i) {
  std::uint64_t x;
  std::memcpy(&x, base + 8 * i, 8);
  return x;
}
void put(unsigned char* base, std::size_t i, std::uint64_t x) { std::memcpy(base + 8 * i, &x, 8); }

}  // namespace

void radix_sort(std::span<double> v, std::vector<std::uint64_t>& scratch) {
  static_assert(sizeof(double) == sizeof(std::uint64_t));
  const std::size_t n = v.size();
  if (n < 2) return;
  auto* a = reinterpret_cast<unsigned char*>(v.data());
  // the keys in place of the doubles (same width), every pass's histogram in one read
  std::vector<std::array<std::size_t, buckets>> count(passes);
  for (auto& c : count) c.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t key = radix_key(get(a, i));
    put(a, i, key);
    for (int p = 0; p < passes; ++p) ++count[p][(key >> (p * digit_bits)) & (buckets - 1)];
  }
  scratch.resize(n);
  unsigned char *src = a, *dst = reinterpret_cast<unsigned char*>(scratch.data());
  for (int p = 0; p < passes; ++p) {
    auto& c = count[p];
    const int shift = p * digit_bits;
    if (c[(get(src, 0) >> shift) & (buckets - 1)] == n) continue;  // one digit value for all: nothing moves
    std::size_t sum = 0;
    for (std::size_t b = 0; b < buckets; ++b) {  // bucket starts (stable: the input order within a bucket)
      const std::size_t k = c[b];
      c[b] = sum, sum += k;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t key = get(src, i);
      put(dst, c[(key >> shift) & (buckets - 1)]++, key);
    }
    std::swap(src, dst);
  }
  for (std::size_t i = 0; i < n; ++i) put(a, i, radix_unkey(get(src, i)));
}

void radix_sort(std::span<double> v) {
  std::vector<std::uint64_t> scratch;
  radix_sort(v, scratch);
}

}  // namespace pounding
