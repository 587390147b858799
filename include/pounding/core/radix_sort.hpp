#pragma once
// An LSD radix sort of doubles (layer 0). Ascending in the IEEE-754 total order restricted to non-NaN values:
// -inf < negative numbers < -0.0 < +0.0 < positive numbers (denormals in their place) < +inf, i.e. std::sort's order
// with -0.0 placed before +0.0 (std::sort leaves equal values, which -0.0 and +0.0 are for operator<, in no
// particular order). NaN has no place in that order: the caller removes it (separation::prepare sorts demands with
// the excluded analyses, NaN, left out).
//
// Why: `pounding report` on 10^8 per-model analyses spent most of its time in std::sort of the per-record demands
// (13.6 s of 45 s wall on the 2-core VM); six counting passes of 11 bits over 64-bit keys are linear in n.
#include <cstdint>
#include <span>
#include <vector>

namespace pounding {

// The unsigned key whose order is the doubles' order above: the sign bit flipped for +, every bit for -.
inline std::uint64_t radix_key(std::uint64_t bits) {
  return bits >> 63 ? ~bits : bits | (std::uint64_t{1} << 63);
}
inline std::uint64_t radix_unkey(std::uint64_t key) {
  return key >> 63 ? key & ~(std::uint64_t{1} << 63) : ~key;
}

// Sorts v (no NaN) ascending; `scratch` is resized to v.size() and reused between calls.
void radix_sort(std::span<double> v, std::vector<std::uint64_t>& scratch);
void radix_sort(std::span<double> v);

}  // namespace pounding
