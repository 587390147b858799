#pragma once
// Helpers of the Hertz family (hertz, hertzdamp): the Newton tangent's power terms and the stored energy
// kc delta^(n+1) / (n+1). Newton always takes std::pow (also at n = 1.5).
#include <cmath>

#include "pounding/contact/law.hpp"

namespace pounding::contact::hertz_power {

// dp^n and n dp^(n-1) for dp = max(d, 0)
template <class T> POUNDING_INLINE void pow_and_slope(T d, double n, T& pw, T& dpw) {
  const T dp = lane::max(d, T(0.0));
  pw = lane::map(dp, [n](double x) { return x > 0.0 ? std::pow(x, n) : 0.0; });
  dpw = lane::map(dp, [n](double x) { return x > 0.0 ? n * std::pow(x, n - 1.0) : 0.0; });
}
template <class T> POUNDING_INLINE T stored(T dp, T kc, double n) {
  return kc * lane::map(dp, [n](double x) { return std::pow(x, n + 1.0); }) / (n + 1.0);
}

}  // namespace pounding::contact::hertz_power
