// Modes of a shear stick by implicit QL on M^{-1/2} K M^{-1/2}; Rayleigh coefficients; stiffness profiles
// (include/pounding/model/modes.hpp).
#include "pounding/model/modes.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pounding::model {

namespace {

std::string num(double v) {  // 6 significant digits, as %g (no <cstdio> in the model layer)
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 6);
  return std::string(buf, res.ptr);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

// Eigenvalues d and unit eigenvectors (columns of z, z[row][col]) of the symmetric tridiagonal matrix with
// diagonal d and off-diagonal e (e[i] couples rows i and i+1; e.size() == d.size(), the last entry unused):
// the implicit QL algorithm with Wilkinson shifts (the tqli scheme of Numerical Recipes §11.4, written here
// from the algorithm). z enters as the identity. Returns false when an eigenvalue does not converge in 60
// sweeps (never seen for a stick; a guard, not a path).
bool tridiagonal_ql(std::vector<double>& d, std::vector<double>& e, std::vector<std::vector<double>>& z) {
  const int n = static_cast<int>(d.size());
  const double eps = std::numeric_limits<double>::epsilon();
  e[n - 1] = 0.0;
  for (int l = 0; l < n; ++l) {
    int iter = 0, m = l;
    do {
      for (m = l; m < n - 1; ++m) {  // a negligible off-diagonal splits the matrix at m
        const double dd = std::abs(d[m]) + std::abs(d[m + 1]);
        if (std::abs(e[m]) <= eps * dd) break;
      }
      if (m == l) break;
      if (iter++ == 60) return false;
      // shift: the eigenvalue of the leading 2x2 block nearer d[l]
      double g = (d[l + 1] - d[l]) / (2.0 * e[l]);
      double r = std::hypot(g, 1.0);
      g = d[m] - d[l] + e[l] / (g + std::copysign(r, g));
      double s = 1.0, c = 1.0, p = 0.0;
      int i = m - 1;
      for (; i >= l; --i) {  // plane rotations chase the bulge from m up to l
        const double f = s * e[i], b = c * e[i];
        r = std::hypot(f, g);
        e[i + 1] = r;
        if (r == 0.0) {  // underflow: deflate and restart this l
          d[i + 1] -= p;
          e[m] = 0.0;
          break;
        }
        s = f / r;
        c = g / r;
        g = d[i + 1] - p;
        r = (d[i] - g) * s + 2.0 * c * b;
        p = s * r;
        d[i + 1] = g + p;
        g = c * r - b;
        for (int k = 0; k < n; ++k) {
          const double zk = z[k][i + 1];
          z[k][i + 1] = s * z[k][i] + c * zk;
          z[k][i] = c * z[k][i] - s * zk;
        }
      }
      if (r == 0.0 && i >= l) continue;
      d[l] -= p;
      e[l] = g;
      e[m] = 0.0;
    } while (m != l);
  }
  return true;
}

// Γ, M*, their shares and the roof-normalised shapes of mass-normalised φ (M_j = 1).
void participation(std::span<const double> m, Modes& out) {
  const std::size_t n = m.size();
  const double total = std::accumulate(m.begin(), m.end(), 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const std::vector<double>& phi = out.phi[j];
    double L = 0.0, Mj = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      L += m[i] * phi[i];
      Mj += m[i] * phi[i] * phi[i];
    }
    double peak = 0.0;
    for (double v : phi) peak = std::max(peak, std::abs(v));
    const bool roof_moves = phi[n - 1] >= 1e-6 * peak;  // phi[n - 1] >= 0 by the sign convention
    const double scale = roof_moves ? phi[n - 1] : peak;
    std::vector<double> shape(n);
    for (std::size_t i = 0; i < n; ++i) shape[i] = phi[i] / scale;
    out.phi_roof.push_back(std::move(shape));
    out.roof_normalised.push_back(roof_moves);
    out.gamma.push_back(L / Mj);
    out.gamma_roof.push_back(L / Mj * scale);  // the shape φ/scale: Γ scales by `scale`
    out.meff.push_back(L * L / Mj);
    out.meff_ratio.push_back(L * L / Mj / total);
  }
}

}  // namespace

std::string stick_defect(std::span<const double> m, std::span<const double> k) {
  if (m.empty()) return "no floors";
  if (m.size() != k.size())
    return std::to_string(m.size()) + " floor masses but " + std::to_string(k.size()) + " storey stiffnesses";
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (!positive(m[i])) return "floor " + std::to_string(i + 1) + " mass " + num(m[i]) + " is not > 0";
    if (!positive(k[i])) return "storey " + std::to_string(i + 1) + " stiffness " + num(k[i]) + " is not > 0";
  }
  const auto [mlo, mhi] = std::minmax_element(m.begin(), m.end());
  const auto [klo, khi] = std::minmax_element(k.begin(), k.end());
  if (*mhi / *mlo > 1e12 || *khi / *klo > 1e12)
    return "masses or stiffnesses spread over more than 12 decades (" + num(*mlo) + " to " + num(*mhi) + " kg, " +
           num(*klo) + " to " + num(*khi) + " N/m)";
  return "";
}

Modes shear_stick_modes(std::span<const double> m, std::span<const double> k) {
  if (const std::string defect = stick_defect(m, k); !defect.empty())
    throw std::invalid_argument("shear_stick_modes: " + defect);
  const std::size_t n = m.size();
  std::vector<double> d(n), e(n, 0.0), rs(n);
  for (std::size_t i = 0; i < n; ++i) rs[i] = 1.0 / std::sqrt(m[i]);
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = (k[i] + (i + 1 < n ? k[i + 1] : 0.0)) / m[i];
    if (i + 1 < n) e[i] = -k[i + 1] * rs[i] * rs[i + 1];
  }
  std::vector<std::vector<double>> z(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) z[i][i] = 1.0;
  if (!tridiagonal_ql(d, e, z)) throw std::runtime_error("shear_stick_modes: QL iteration did not converge");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return d[a] < d[b]; });
  Modes out;
  for (std::size_t col : order) {
    std::vector<double> phi(n);
    for (std::size_t i = 0; i < n; ++i) phi[i] = z[i][col] * rs[i];
    // sign: roof positive; for a mode confined below the roof (roof < 1e-6 of its largest, where the roof's
    // sign is rounding noise) its largest value positive, as participation() scales it
    const auto big = std::max_element(phi.begin(), phi.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    const double ref = std::abs(phi[n - 1]) >= 1e-6 * std::abs(*big) ? phi[n - 1] : *big;
    if (ref < 0.0)
      for (double& v : phi) v = -v;
    // ω² as the Rayleigh quotient Σ k_i d_i² / Σ m_i φ_i² (d_i the storey drift): sums of positive terms, and
    // its error is quadratic in the eigenvector's. QL's own eigenvalue carries an absolute error ε ω_n², which
    // is 1e-12 relative on ω_1 of a 100-storey stick; the quotient keeps ω_1 to a few ε (measured: T1 of
    // stiffness_for_period to 2.5e-11 from QL's eigenvalue at 200 storeys, to 4.4e-16 with the quotient).
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double drift = phi[i] - (i > 0 ? phi[i - 1] : 0.0);
      num += k[i] * drift * drift;
      den += m[i] * phi[i] * phi[i];
    }
    const double w = std::sqrt(num / den);
    out.omega.push_back(w);
    out.period.push_back(2.0 * std::numbers::pi / w);
    out.phi.push_back(std::move(phi));
  }
  participation(m, out);
  return out;
}

Rayleigh rayleigh(double omega_i, double zeta_i, double omega_j, double zeta_j) {
  if (!(positive(omega_i) && positive(omega_j) && omega_i < omega_j && std::isfinite(zeta_i) && std::isfinite(zeta_j)))
    throw std::invalid_argument("rayleigh: needs 0 < omega_i < omega_j and finite ratios");
  const double den = omega_j * omega_j - omega_i * omega_i;
  return {2.0 * omega_i * omega_j * (zeta_i * omega_j - zeta_j * omega_i) / den,
          2.0 * (zeta_j * omega_j - zeta_i * omega_i) / den};
}

double rayleigh_ratio(const Rayleigh& r, double omega) { return r.a0 / (2.0 * omega) + r.a1 * omega / 2.0; }

ModePair rayleigh_modes_for(int i, int j, int n) {
  if (!(i >= 1 && i < j && n >= 1)) throw std::invalid_argument("rayleigh_modes_for: needs 1 <= i < j and n >= 1");
  if (n == 1) return {1, 1};
  const int jj = std::min(j, n);
  return {std::min(i, jj - 1), jj};
}

double modal_ratio(std::span<const double> zeta, std::size_t j) {
  if (zeta.empty()) throw std::invalid_argument("modal_ratio: no ratios");
  return zeta[std::min(j, zeta.size() - 1)];
}

std::vector<double> modal_damping_matrix(std::span<const double> m, const Modes& modes, std::span<const double> zeta) {
  const std::size_t n = m.size();
  if (modes.phi.size() != n || modes.omega.size() != n || zeta.empty() ||
      !std::all_of(zeta.begin(), zeta.end(), [](double z) { return std::isfinite(z); }))
    throw std::invalid_argument("modal_damping_matrix: modes of other masses, or no finite ratios");
  // φ mass-normalised (M_j = 1): C_ab = m_a m_b Σ_j 2 ζ_j ω_j φ_j(a) φ_j(b)
  std::vector<double> C(n * n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const double c = 2.0 * modal_ratio(zeta, j) * modes.omega[j];
    const std::vector<double>& phi = modes.phi[j];
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) C[a * n + b] += c * phi[a] * phi[b];
  }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) C[a * n + b] *= m[a] * m[b];
  return C;
}

std::vector<double> stiffness_shape(std::span<const double> m, std::span<const double> storey_heights,
                                    StiffnessProfile profile) {
  const std::size_t n = m.size();
  if (n == 0 || !std::all_of(m.begin(), m.end(), positive))
    throw std::invalid_argument("stiffness_shape: masses must be finite and > 0");
  if (profile == StiffnessProfile::uniform) return std::vector<double>(n, 1.0);
  if (!(storey_heights.size() == 1 || storey_heights.size() == n) ||
      !std::all_of(storey_heights.begin(), storey_heights.end(), positive))
    throw std::invalid_argument("stiffness_shape: one storey height or one per storey, each finite and > 0");
  std::vector<double> V(n);
  double z = 0.0;
  for (std::size_t i = 0; i < n; ++i) {  // V temporarily holds m_i z_i
    z += storey_heights.size() == 1 ? storey_heights[0] : storey_heights[i];
    V[i] = m[i] * z;
  }
  for (std::size_t i = n - 1; i-- > 0;) V[i] += V[i + 1];  // V_i = Σ_{j>=i} m_j z_j
  const double base = V[0];
  for (double& v : V) v /= base;
  return V;
}

std::vector<double> stiffness_for_period(std::span<const double> m, std::span<const double> storey_heights,
                                         StiffnessProfile profile, double T1) {
  if (!positive(T1)) throw std::invalid_argument("stiffness_for_period: T1 must be finite and > 0");
  std::vector<double> k = stiffness_shape(m, storey_heights, profile);
  const double w1 = shear_stick_modes(m, k).omega.front();
  const double target = 2.0 * std::numbers::pi / T1;
  const double scale = (target / w1) * (target / w1);
  for (double& v : k) v *= scale;
  return k;
}

}  // namespace pounding::model
