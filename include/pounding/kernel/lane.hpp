#pragma once
// Lane types of the kernel: T = double (one lane, the scalar steppers) or T = simd::V (a SIMD chunk,
// central difference). Laws, guard and observers are written once over T with these functions; each maps
// to the same operation for both types, so a lane's bits do not depend on the type it ran as
// (tests/kernel/test_lane_equivalence.cpp). max/min follow std::experimental's definition
// (a > b ? a : b, a < b ? a : b), which is also what the scalar kernel has always written out.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <experimental/simd>
#if defined(__AVX512F__) || defined(__FMA__) || defined(__AVX2__)
#include <immintrin.h>
#endif

#ifndef POUNDING_HD
#define POUNDING_HD  // __host__ __device__ under a CUDA backend
#endif
// Forced inlining makes the steppers one loop body each. Under sanitizers at -O1 (the ctest sanitize.kernel build,
// POUNDING_RELAXED_INLINE) forcing it multiplies the instrumented code: there it is only a hint, which changes what
// is inlined, never what is computed (that build claims no bits).
#ifdef POUNDING_RELAXED_INLINE
#define POUNDING_INLINE inline POUNDING_HD
#else
#define POUNDING_INLINE [[gnu::always_inline]] inline POUNDING_HD
#endif

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

// exp and expm1 written once over T (docs/architecture.md §2.4.6, issue 25 §1: the smooth laws and models): Cody-Waite
// range reduction x = n ln2 + r, |r| <= ln2/2 (n by the 1.5 2^52 shifter, both products by pinned fmas), the Taylor
// polynomial of degree 13 by Horner (pinned fmas; truncation < 3e-18 relative), then 2^n applied as 2^(n - n/2) 2^(n/2)
// so that n up to 1024 and down to -1076 needs no special case: the first product is exact, the second rounds once
// (overflow to +inf, gradual underflow to denormals and 0 as IEEE multiplication gives them). Only IEEE basic
// operations, fma and integer bit operations: a double lane and a SIMD lane give the same bits
// (tests/kernel/test_lane_math.cpp, which also measures the error against a long-double reference over 2e5 arguments:
// exp 0.957 ulp, expm1 1.721 ulp at most, 2026-11-26). NaN in, NaN out; +inf -> inf, -inf -> 0 (exp), -1 (expm1).
namespace detail {
inline constexpr double exp_shifter = 0x1.8p52;
inline constexpr double log2e = 0x1.71547652b82fep0;
inline constexpr double ln2_hi = 0x1.62e42fefa39efp-1;
inline constexpr double ln2_lo = 0x1.abc9e3b39803fp-56;
inline constexpr double exp_lo = -746.0, exp_hi = 710.0;  // clamp: beyond, the result is 0 / inf anyway
// 1/k!, k = 13 ... 2 (Horner from the highest)
inline constexpr double inv_fact[12] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0,
                                        1.0 / 362880.0, 1.0 / 40320.0, 1.0 / 5040.0, 1.0 / 720.0, 1.0 / 120.0,
                                        1.0 / 24.0, 1.0 / 6.0, 0.5};
// 2^(k - k/2) 2^(k/2) as two doubles from the shifter sum t (its low mantissa bits hold k)
POUNDING_INLINE void exp2_parts(double t, double& s1, double& s2) {
  std::int64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  const std::int64_t k = bits - std::int64_t{0x4338000000000000};
  const std::int64_t k1 = k >> 1, k2 = k - k1;
  const std::uint64_t b1 = static_cast<std::uint64_t>(k1 + 1023) << 52, b2 = static_cast<std::uint64_t>(k2 + 1023) << 52;
  std::memcpy(&s1, &b1, sizeof s1), std::memcpy(&s2, &b2, sizeof s2);
}
// The same integer operations on a whole chunk: kb = k + 2048 >= 0, h = kb >> 1 (k >> 1 = h - 1024), so the exponent
// fields are (h - 1) << 52 and (kb - h - 1) << 52 -- exact, hence the scalar form's bits.
POUNDING_INLINE void exp2_parts(const simd::V& t, simd::V& s1, simd::V& s2) {
  alignas(64) double x[simd::W], a[simd::W], b[simd::W];
  t.copy_to(x, simd::stdx::vector_aligned);
#if defined(__AVX512F__)
  if constexpr (simd::W == 8) {
    const __m512i kb = _mm512_add_epi64(_mm512_castpd_si512(_mm512_load_pd(x)),
                                        _mm512_set1_epi64(2048 - std::int64_t{0x4338000000000000}));
    const __m512i h = _mm512_srli_epi64(kb, 1), one = _mm512_set1_epi64(1);
    _mm512_store_pd(a, _mm512_castsi512_pd(_mm512_slli_epi64(_mm512_sub_epi64(h, one), 52)));
    _mm512_store_pd(b, _mm512_castsi512_pd(_mm512_slli_epi64(_mm512_sub_epi64(_mm512_sub_epi64(kb, h), one), 52)));
    s1 = simd::V(a, simd::stdx::vector_aligned), s2 = simd::V(b, simd::stdx::vector_aligned);
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (simd::W == 4) {
    const __m256i kb = _mm256_add_epi64(_mm256_castpd_si256(_mm256_load_pd(x)),
                                        _mm256_set1_epi64x(2048 - std::int64_t{0x4338000000000000}));
    const __m256i h = _mm256_srli_epi64(kb, 1), one = _mm256_set1_epi64x(1);
    _mm256_store_pd(a, _mm256_castsi256_pd(_mm256_slli_epi64(_mm256_sub_epi64(h, one), 52)));
    _mm256_store_pd(b, _mm256_castsi256_pd(_mm256_slli_epi64(_mm256_sub_epi64(_mm256_sub_epi64(kb, h), one), 52)));
    s1 = simd::V(a, simd::stdx::vector_aligned), s2 = simd::V(b, simd::stdx::vector_aligned);
    return;
  }
#endif
  for (int j = 0; j < simd::W; ++j) exp2_parts(x[j], a[j], b[j]);
  s1 = simd::V(a, simd::stdx::vector_aligned), s2 = simd::V(b, simd::stdx::vector_aligned);
}
// e^r - 1 - r for |r| <= ln2/2 (from degree 2): r^2 (1/2 + r (1/6 + ...))
template <class T> POUNDING_INLINE T expm1_tail(const T& r) {
  T p(inv_fact[0]);
  for (int k = 1; k < 12; ++k) p = lane::fma(p, r, T(inv_fact[k]));
  return (r * r) * p;
}

// x = n ln2 + r: t = the shifter sum (its low bits hold n), n, r, e^r - 1 (x clamped to [-746, 710])
template <class T> struct Reduced { T t, n, em1; };
template <class T> POUNDING_INLINE Reduced<T> reduce(const T& x) {
  const T xc = lane::min(lane::max(x, T(exp_lo)), T(exp_hi));
  const T t = lane::fma(xc, T(log2e), T(exp_shifter));
  const T n = t - T(exp_shifter);
  const T r = lane::fma(-n, T(ln2_lo), lane::fma(-n, T(ln2_hi), xc));
  return {t, n, r + expm1_tail(r)};
}
}  // namespace detail

template <class T> POUNDING_INLINE T exp(const T& x) {
  const detail::Reduced<T> q = detail::reduce(x);
  T s1, s2;
  detail::exp2_parts(q.t, s1, s2);
  const T y = ((T(1.0) + q.em1) * s1) * s2;  // e^r in [0.7, 1.42], then 2^n in two exact-then-once products
  return select(x != x, x, y);  // NaN stays NaN (the clamp would have made it a number)
}

// e^x - 1 without cancellation: |x| <= ln2/2 by the polynomial directly; |n| <= 52 as 2^n (e^r - 1) + (2^n - 1) in one
// fma (2^n and 2^n - 1 exact there); beyond, e^x - 1 (the 1 is below half an ulp of e^x, or e^x below half an ulp
// of 1). expm1(-0) = -0.
template <class T> POUNDING_INLINE T expm1(const T& x) {
  const T half_ln2(0.34657359027997264);
  const T small = x + detail::expm1_tail(lane::min(lane::max(x, -half_ln2), half_ln2));
  const detail::Reduced<T> q = detail::reduce(x);
  T s1, s2;
  detail::exp2_parts(q.t, s1, s2);
  const T s = s1 * s2;
  const T mid = lane::fma(s, q.em1, s - T(1.0));
  const T big = ((T(1.0) + q.em1) * s1) * s2 - T(1.0);
  const T y = select(lane::abs(x) <= half_ln2, small, select(lane::abs(q.n) <= T(52.0), mid, big));
  return select(x == T(0.0) || x != x, x, y);
}

}  // namespace pounding::lane
