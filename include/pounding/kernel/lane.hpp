#pragma once
// Lane types of the kernel: T = double (one lane, the scalar steppers) or T = simd::V (a SIMD chunk,
// central difference). Laws, guard and observers are written once over T with these functions; each maps
// to the same operation for both types, so a lane's bits do not depend on the type it ran as
// (tests/kernel/test_lane_equivalence.cpp). max/min follow std::experimental's definition
// (a > b ? a : b, a < b ? a : b), which is also what the scalar kernel has always written out.
#include <cmath>
#include <experimental/simd>
#if defined(__AVX512F__) || defined(__FMA__)
#include <immintrin.h>
#endif

#ifndef POUNDING_HD
#define POUNDING_HD  // __host__ __device__ under a CUDA backend
#endif
#define POUNDING_INLINE [[gnu::always_inline]] inline POUNDING_HD

namespace pounding::simd {
namespace stdx = std::experimental;
using V = stdx::native_simd<double>;
using M = V::mask_type;
inline constexpr int W = static_cast<int>(V::size());
}  // namespace pounding::simd

namespace pounding::lane {

template <class T> struct Traits;
template <> struct Traits<double> {
  using mask = bool;
  static constexpr int width = 1;
};
template <> struct Traits<simd::V> {
  using mask = simd::M;
  static constexpr int width = simd::W;
};
template <class T> using mask_t = typename Traits<T>::mask;
template <class T> inline constexpr int width_v = Traits<T>::width;
template <class T> concept Lane = requires { typename Traits<T>::mask; };

POUNDING_INLINE double select(bool m, double a, double b) { return m ? a : b; }
POUNDING_INLINE simd::V select(const simd::M& m, const simd::V& a, const simd::V& b) {
  simd::V r = b;
  simd::stdx::where(m, r) = a;
  return r;
}
POUNDING_INLINE double max(double a, double b) { return a > b ? a : b; }
POUNDING_INLINE simd::V max(const simd::V& a, const simd::V& b) { return simd::stdx::max(a, b); }
POUNDING_INLINE double min(double a, double b) { return a < b ? a : b; }
POUNDING_INLINE simd::V min(const simd::V& a, const simd::V& b) { return simd::stdx::min(a, b); }
POUNDING_INLINE double sqrt(double a) { return std::sqrt(a); }
POUNDING_INLINE simd::V sqrt(const simd::V& a) { return simd::stdx::sqrt(a); }
POUNDING_INLINE double abs(double a) { return std::abs(a); }
POUNDING_INLINE simd::V abs(const simd::V& a) { return simd::stdx::abs(a); }
// a * b + c rounded once: pins the contraction where a sum of two products would let the compiler pick
// which product to fuse (its pick differs between lane types and inlining contexts)
POUNDING_INLINE double fma(double a, double b, double c) { return std::fma(a, b, c); }
// libstdc++ 12's stdx::fma is a per-element fallback (8 scalar fmas for a 512-bit chunk, measured 4.5 % on
// central difference + Jankowski); where the vector unit has FMA, one vector instruction gives the same bits.
POUNDING_INLINE simd::V fma(const simd::V& a, const simd::V& b, const simd::V& c) {
  alignas(64) double x[8], y[8], z[8];
  a.copy_to(x, simd::stdx::element_aligned), b.copy_to(y, simd::stdx::element_aligned);
  c.copy_to(z, simd::stdx::element_aligned);
#if defined(__AVX512F__)
  if constexpr (simd::W == 8) {
    _mm512_store_pd(x, _mm512_fmadd_pd(_mm512_load_pd(x), _mm512_load_pd(y), _mm512_load_pd(z)));
    return simd::V(x, simd::stdx::element_aligned);
  }
#endif
#if defined(__FMA__)
  if constexpr (simd::W == 4) {
    _mm256_store_pd(x, _mm256_fmadd_pd(_mm256_load_pd(x), _mm256_load_pd(y), _mm256_load_pd(z)));
    return simd::V(x, simd::stdx::element_aligned);
  }
#endif
  return simd::stdx::fma(a, b, c);  // no vector FMA unit: libstdc++'s exact per-element fallback
}
POUNDING_INLINE bool any(bool m) { return m; }
POUNDING_INLINE bool any(const simd::M& m) { return simd::stdx::any_of(m); }
POUNDING_INLINE bool all(bool m) { return m; }
POUNDING_INLINE bool all(const simd::M& m) { return simd::stdx::all_of(m); }

// Per-lane scalar function (pow has no SIMD form in the standard library).
template <class F> POUNDING_INLINE double map(double x, F f) { return f(x); }
template <class F> POUNDING_INLINE simd::V map(const simd::V& x, F f) {
  simd::V r;
  for (int j = 0; j < simd::W; ++j) r[j] = f(x[j]);
  return r;
}
template <class F> POUNDING_INLINE double map2(double x, double y, F f) { return f(x, y); }
template <class F> POUNDING_INLINE simd::V map2(const simd::V& x, const simd::V& y, F f) {
  simd::V r;
  for (int j = 0; j < simd::W; ++j) r[j] = f(x[j], y[j]);
  return r;
}

template <class T> POUNDING_INLINE T load(const double* p);
template <> POUNDING_INLINE double load<double>(const double* p) { return *p; }
template <> POUNDING_INLINE simd::V load<simd::V>(const double* p) { return simd::V(p, simd::stdx::element_aligned); }
POUNDING_INLINE void store(double v, double* p) { *p = v; }
POUNDING_INLINE void store(const simd::V& v, double* p) { v.copy_to(p, simd::stdx::element_aligned); }

}  // namespace pounding::lane
