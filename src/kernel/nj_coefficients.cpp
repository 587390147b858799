// Nigam-Jennings coefficients (kernel.hpp).
#include <algorithm>
#include <cmath>

#include "pounding/kernel/batch.hpp"

namespace pounding {

NigamJennings nigam_jennings(double w, double z, double h) {
  // Nigam & Jennings (1969), for u'' + 2 z w u' + w^2 u = -a(t), a linear between a0 and a1 on [0, h].
  // A (free response) in closed form. B are the Duhamel integrals of the unit impulse response
  // g(s) = e^(-z w s) sin(wd s) / wd against the linear load shapes:
  //   b11 = -int g(s) s/h ds, b12 = -int g(s) (1 - s/h) ds, b21, b22 the same with g'(s), s in [0, h].
  // The textbook closed forms of B lose digits to cancellation when w h is small (1e-6 relative at
  // w h = 1e-4), so B is integrated with composite 8-point Gauss-Legendre on panels of w h <= 0.25: the
  // integrands are entire functions, so this is exact to round-off for any w h.
  const double sq = std::sqrt(1.0 - z * z), wd = w * sq;
  const double E = std::exp(-z * w * h), S = std::sin(wd * h), Cs = std::cos(wd * h);
  NigamJennings c;
  c.a11 = E * (z / sq * S + Cs);
  c.a12 = E * S / wd;
  c.a21 = -w / sq * E * S;
  c.a22 = E * (Cs - z / sq * S);
  static constexpr double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                   -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
  static constexpr double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};
  const int panels = std::max(1, static_cast<int>(std::ceil(w * h / 0.25)));
  const double ph = h / panels;
  double i_gs = 0, i_g = 0, i_dgs = 0, i_dg = 0;  // int g s/h, int g, int g' s/h, int g'
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * ph, half = 0.5 * ph;
    for (int q = 0; q < 8; ++q) {
      const double sv = mid + half * gx[q], wt = half * gw[q];
      const double ex = std::exp(-z * w * sv), sn = std::sin(wd * sv), cs = std::cos(wd * sv);
      const double g = ex * sn / wd, dg = ex * (cs - z * w / wd * sn);
      i_gs += wt * g * (sv / h);
      i_g += wt * g;
      i_dgs += wt * dg * (sv / h);
      i_dg += wt * dg;
    }
  }
  c.b11 = -i_gs;
  c.b12 = -(i_g - i_gs);
  c.b21 = -i_dgs;
  c.b22 = -(i_dg - i_dgs);
  return c;
}

}  // namespace pounding
