#pragma once
// Integer mixing for reproducible random streams (OpenMC's idea: a stream is derived from the seed and the
// sample's identity, never from rank or order of work). Integer-only on purpose: no floating point here, so
// nothing depends on -ffp-contract (architecture.md, P2). The engines that consume these keys live with
// their users: taus88 in sampler.cpp, mt19937_64 in synthetic.cpp (P14 wants both behind one module later).
#include <cstdint>

namespace pounding {

// SplitMix64 (Steele, Lea, Flood 2014; Vigna's splitmix64.c): the finaliser applied to x + 0x9e3779b97f4a7c15.
// Used as a bijective 64-bit mix: the sampler's per-sample keys (stream_seed) and the suite's per-entry
// seeds (derive_seed).
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace pounding
