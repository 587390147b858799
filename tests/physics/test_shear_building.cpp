// physics::set_shear_building / shear_numbers / set_contacts (docs/architecture.md §2.2.3; issue 25 §2): a
// one-storey building is today's SDOF bit for bit; Rayleigh dashpots give the modal damping ratios (checked
// against the closed-form modes of a uniform stick and T1.2 of systems-and-bridges.md, and for a non-uniform stick
// through the modes API); T1 profiles; storey strengths; gaps per level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <algorithm>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "pounding/model/shear_building.hpp"
#include "pounding/physics/shear_building.hpp"

namespace pounding::physics {
namespace {

constexpr double pi = std::numbers::pi;

template <class T> bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
bool same_springs(const std::vector<SpringSpec>& a, const std::vector<SpringSpec>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i].k, &b[i].k, 8) || std::memcmp(&a[i].fy, &b[i].fy, 8) || std::memcmp(&a[i].alpha, &b[i].alpha, 8))
      return false;
  return true;
}

model::StickTopology stick(int n, double h = 3.2) {
  model::StickTopology s;
  s.storeys = n;
  s.storey_heights = {h};
  return s;
}

// C = diag(c_floor) + storey dashpots assembled like K (independently of the code under test), [i][j].
std::vector<std::vector<double>> damping_matrix(const SystemBatch& b, int body, std::size_t lane) {
  const model::Body& bd = b.system->bodies()[static_cast<std::size_t>(body)];
  const std::size_t n = bd.dofs.size(), w = b.width;
  std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    c[i][i] += b.c_floor[SystemBatch::at(bd.dofs[i], lane, w)];
    const double cs = b.c_storey[SystemBatch::at(b.system->spring_below(bd.dofs[i]), lane, w)];
    c[i][i] += cs;  // storey i acts on u_i - u_{i-1}
    if (i > 0) c[i - 1][i - 1] += cs, c[i][i - 1] -= cs, c[i - 1][i] -= cs;
  }
  return c;
}
double quad(const std::vector<std::vector<double>>& a, const std::vector<double>& x, const std::vector<double>& y) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < y.size(); ++j) s += x[i] * a[i][j] * y[j];
  return s;
}

// Lane l: building 1 from its period, building 2 from a given k; every yield rule; the same numbers through
// PairBatch::set. All arrays bit-identical.
TEST(ShearBuilding, OneStoreyIsTodaysSdofBitForBit) {
  const std::vector<model::StickTopology> sticks{stick(1), stick(1)};
  const model::System sys = model::shear_buildings(sticks);
  ASSERT_EQ(sys, model::System::sdof_pair());
  const std::size_t w = 5;
  SystemBatch got;
  got.resize(sys, w);
  PairBatch want;
  want.resize(w);
  for (std::size_t l = 0; l < w; ++l) {
    const double m1 = 1.3e5 * (1 + 0.37 * l), T1 = 0.31 + 0.17 * l, z1 = 0.02 + 0.011 * l;
    const double m2 = 2.1e5 / (1 + 0.23 * l), k2 = 7.7e7 * (1 + 0.5 * l), z2 = 0.05 + 0.003 * l;
    ShearSpec a;
    a.floor_mass = {m1}, a.period = T1, a.zeta = z1, a.alpha = 0.1;
    double fy1 = std::numeric_limits<double>::infinity();
    if (l % 3 == 1) a.yield_coefficient = 0.13 + 0.01 * l, fy1 = a.yield_coefficient * m1 * standard_gravity;
    if (l % 3 == 2) a.storey_yield = {3.3e5 + l}, fy1 = 3.3e5 + l;
    ShearSpec b;
    b.floor_mass = {m2}, b.storey_stiffness = {k2}, b.zeta = z2, b.alpha = 0.02;
    b.yield_drift = 0.004;
    set_shear_building(got, l, 0, a);
    set_shear_building(got, l, 1, b);
    set_contacts(got, l, 0.01 * l, 1.1e9, 0.65);
    PairParams p;
    p.s1 = Structure::from_period(m1, T1, z1, fy1, 0.1);
    p.s2 = Structure{m2, k2, 2.0 * z2 * std::sqrt(k2 * m2), k2 * (0.004 * 3.2), 0.02};  // today's expressions
    p.gap = 0.01 * l, p.kc = 1.1e9, p.e = 0.65;
    want.set(l, p);
  }
  const SystemBatch ref = to_system(want, sys);
  EXPECT_TRUE(same_bits(got.m, ref.m));
  EXPECT_TRUE(same_bits(got.c_floor, ref.c_floor));
  EXPECT_TRUE(same_springs(got.spring, ref.spring));
  EXPECT_TRUE(same_bits(got.gap, ref.gap) && same_bits(got.kc, ref.kc) && same_bits(got.e, ref.e));
  EXPECT_TRUE(got.c_storey.empty());
  const PairBatch back = to_pair_batch(got);
  EXPECT_TRUE(same_bits(back.k1, want.k1) && same_bits(back.c1, want.c1) && same_bits(back.fy1, want.fy1));
  EXPECT_TRUE(same_bits(back.c2, want.c2) && same_bits(back.fy2, want.fy2));
}

// T1.1/T1.2 of systems-and-bridges.md: n = 5, m = 1e5 kg, k = 1e8 N/m, zeta = 0.05 on modes 1 and 3. The ratio of
// each mode from the batch's dashpots with the closed-form shapes phi_j(i) = sin(i (2j-1) pi / (2n+1)) and
// omega_j = 2 sqrt(k/m) sin((2j-1) pi / (2(2n+1))): zeta_j = phi' C phi / (2 omega_j phi' M phi).
TEST(ShearBuilding, RayleighDashpotsGiveTheModalRatiosOfTheUniformStick) {
  const std::vector<model::StickTopology> sticks{stick(5, 3.0), stick(2, 3.0)};
  const model::System sys = model::shear_buildings(sticks);
  SystemBatch b;
  b.resize(sys, 3);
  ShearSpec s;
  s.floor_mass = {1e5}, s.storey_stiffness = {1e8}, s.zeta = 0.05, s.mode_i = 1, s.mode_j = 3;
  const ShearNumbers num = set_shear_building(b, 2, 0, s);
  // the vector's 9 digits: half a unit of its last digit
  EXPECT_NEAR(num.rayleigh.a0, 0.739392681, 0.5e-9);
  EXPECT_NEAR(num.rayleigh.a1, 1.98342609e-3, 0.5e-11);
  const auto c = damping_matrix(b, 0, 2);
  const double want[] = {0.05, 0.0401266873, 0.05, 0.0597130883, 0.0662729700};
  const int n = 5;
  for (int j = 1; j <= n; ++j) {
    std::vector<double> phi(n);
    for (int i = 1; i <= n; ++i) phi[static_cast<std::size_t>(i - 1)] = std::sin(i * (2 * j - 1) * pi / (2 * n + 1));
    double mj = 0.0;
    for (double f : phi) mj += 1e5 * f * f;
    const double omega = 2.0 * std::sqrt(1e8 / 1e5) * std::sin((2 * j - 1) * pi / (2.0 * (2 * n + 1)));
    const double zeta = quad(c, phi, phi) / (2.0 * omega * mj);
    EXPECT_NEAR(zeta, want[j - 1], 1e-9) << "mode " << j;
    EXPECT_NEAR(num.zeta_modes[static_cast<std::size_t>(j - 1)], want[j - 1], 1e-9) << "mode " << j;
  }
  // the other lanes and body are untouched
  EXPECT_EQ(b.m[SystemBatch::at(0, 1, 3)], 0.0);
  EXPECT_EQ(b.c_storey[SystemBatch::at(1, 2, 3)], 0.0);
}

// T1.3's non-uniform stick, Rayleigh 0.05 on modes 1 and 2 (the default): modes 1 and 2 get 0.05 exactly, mode 3
// the formula's value, and C is classical (phi_1' C phi_2 = 0), with the modes API's mass-normalised shapes.
TEST(ShearBuilding, RayleighOnANonUniformStick) {
  model::StickTopology t;
  t.storeys = 3, t.storey_heights = {4.0, 3.0, 3.0};
  const std::vector<model::StickTopology> sticks{t};
  const model::System sys = model::shear_buildings(sticks);
  SystemBatch b;
  b.resize(sys, 1);
  ShearSpec s;
  s.floor_mass = {2e5, 2e5, 1.5e5}, s.storey_stiffness = {3e8, 2.5e8, 2e8}, s.zeta = 0.05;
  const ShearNumbers num = set_shear_building(b, 0, 0, s);
  const model::Modes modes = model::shear_stick_modes(s.floor_mass, s.storey_stiffness);
  EXPECT_NEAR(modes.omega[0], 17.5697891, 1e-7);
  const auto c = damping_matrix(b, 0, 0);
  for (std::size_t j = 0; j < 3; ++j) {
    const double zeta = quad(c, modes.phi[j], modes.phi[j]) / (2.0 * modes.omega[j]);
    const double want = j < 2 ? 0.05 : model::rayleigh_ratio(num.rayleigh, modes.omega[j]);
    EXPECT_NEAR(zeta, want, 1e-12) << j;
    EXPECT_NEAR(num.zeta_modes[j], want, 1e-12) << j;
  }
  EXPECT_GT(num.zeta_modes[2], 0.05);  // above mode 2 Rayleigh over-damps
  EXPECT_NEAR(quad(c, modes.phi[0], modes.phi[1]), 0.0, 1e-12);
  // storey dashpots are a1 times the INITIAL storey stiffnesses
  for (int d = 0; d < 3; ++d)
    EXPECT_EQ(b.c_storey[static_cast<std::size_t>(d)], num.rayleigh.a1 * s.storey_stiffness[static_cast<std::size_t>(d)]);
}

TEST(ShearBuilding, PeriodProfilesAndStrengths) {
  const std::vector<model::StickTopology> sticks{stick(4, 3.5)};
  const model::System sys = model::shear_buildings(sticks);
  SystemBatch b;
  b.resize(sys, 1);
  ShearSpec s;
  s.floor_mass = {3e5}, s.period = 0.6, s.profile = model::StiffnessProfile::shear, s.yield_drift = 0.005;
  s.alpha = 0.03;
  const ShearNumbers num = set_shear_building(b, 0, 0, s);
  EXPECT_NEAR(num.modes.period[0], 0.6, 1e-12);
  // shear profile: k_i proportional to V_i = sum_{j >= i} m z_j with z = 3.5, 7, 10.5, 14
  const double v[] = {35.0, 31.5, 24.5, 14.0};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(num.k[i] / num.k[0], v[i] / v[0], 1e-14);
    const SpringSpec& sp = b.spring[static_cast<std::size_t>(sys.spring_below(sys.bodies()[0].dofs[i]))];
    EXPECT_EQ(sp.k, num.k[i]);
    EXPECT_NEAR(sp.fy, num.k[i] * 0.005 * 3.5, 1e-9 * sp.fy);  // Vy = k theta_y h
    EXPECT_EQ(sp.alpha, 0.03);
  }
  // base-shear coefficient distributed with the shear profile: Vy_1 = Cy M g
  s.yield_drift = 0.0, s.yield_coefficient = 0.2;
  const ShearNumbers cy = shear_numbers(std::vector<double>(4, 3.5), s);
  EXPECT_NEAR(cy.fy[0], 0.2 * 12e5 * 9.80665, 1e-6);
  EXPECT_NEAR(cy.fy[3] / cy.fy[0], 14.0 / 35.0, 1e-14);
  s.yield_coefficient = 0.0;
  EXPECT_TRUE(std::isinf(shear_numbers(std::vector<double>(4, 3.5), s).fy[2]));  // elastic
}

TEST(ShearBuilding, RefusesWhatItCannotCompute) {
  const std::vector<model::StickTopology> sticks{stick(3)};
  const model::System sys = model::shear_buildings(sticks);
  SystemBatch b;
  b.resize(sys, 1);
  ShearSpec s;
  s.floor_mass = {1e5, 1e5}, s.storey_stiffness = {1e8};
  EXPECT_THROW(set_shear_building(b, 0, 0, s), std::invalid_argument);  // 2 masses for 3 floors
  s.floor_mass = {1e5};
  s.mode_j = 4;
  EXPECT_THROW(set_shear_building(b, 0, 0, s), std::invalid_argument);
  s.mode_j = 2, s.storey_stiffness.clear();
  EXPECT_THROW(set_shear_building(b, 0, 0, s), std::invalid_argument);  // neither k nor T1
  s.storey_stiffness = {1e8};
  EXPECT_THROW(set_shear_building(b, 1, 0, s), std::invalid_argument);  // no lane 1
  // a stick without storey dashpots cannot hold Rayleigh's stiffness part
  std::vector<model::StickTopology> plain{stick(3)};
  plain[0].storey_dashpots = false;
  const model::System ps = model::shear_buildings(plain);
  SystemBatch pb;
  pb.resize(ps, 1);
  EXPECT_THROW(set_shear_building(pb, 0, 0, s), std::invalid_argument);
  s.zeta = 0.0;
  EXPECT_NO_THROW(set_shear_building(pb, 0, 0, s));
}

TEST(ShearBuilding, GapsPerLevel) {
  const std::vector<model::StickTopology> sticks{stick(3, 3.0), stick(5, 3.0)};
  const model::System sys = model::shear_buildings(sticks);
  SystemBatch b;
  b.resize(sys, 2);
  const std::vector<double> offsets{0.0, 0.01, 0.03, 0.5, 0.5};
  set_contacts(b, 1, 0.04, 2e9, 0.7, offsets);
  for (int e = 0; e < 3; ++e) {
    EXPECT_EQ(b.gap[SystemBatch::at(e, 1, 2)], 0.04 + offsets[static_cast<std::size_t>(e)]);
    EXPECT_EQ(b.kc[SystemBatch::at(e, 1, 2)], 2e9);
    EXPECT_EQ(b.e[SystemBatch::at(e, 1, 2)], 0.7);
    EXPECT_EQ(b.gap[SystemBatch::at(e, 0, 2)], 0.0);
  }
  const std::vector<double> short_list{0.0, 0.0};
  EXPECT_THROW(set_contacts(b, 0, 0.04, 2e9, 0.7, short_list), std::invalid_argument);
}

// Classical modal damping (issue 25 §2): the C that set_shear_building gives a building with DampingForm::dense,
// checked through the QUADRATIC eigenproblem of the damped system (Eigen's general eigensolver on the state matrix
// [[0, I], [-M^-1 K, -M^-1 C]], none of modes.cpp): each pair lambda = -zeta w +- i w sqrt(1 - zeta^2) gives
// zeta = -Re(lambda) / |lambda|, which must be the ratio asked for each mode (2 %, 5 %, 3 %, then 3 %) to 1e-9, and
// w the undamped frequency; ShearNumbers::zeta_modes reports the same ratios. Rayleigh with zeta = 5 % on modes 1, 2
// gives the higher modes more (mode 5: 9.1 %; the contrast that motivates modal damping).
TEST(ShearBuilding, ModalDampingGivesEachModeItsRatio) {
  const std::vector<model::StickTopology> sticks{[] {
    model::StickTopology t = stick(5, 3.0);
    t.damping = model::DampingForm::dense;
    return t;
  }()};
  const model::System sys = model::shear_buildings(sticks);
  ASSERT_EQ(sys.bodies()[0].damping, model::DampingForm::dense);
  EXPECT_FALSE(sys.bodies()[0].storey_dashpots);
  SystemBatch b;
  b.resize(sys, 2);
  ShearSpec s;
  s.floor_mass = {3.0e5, 2.8e5, 2.6e5, 2.4e5, 2.0e5};
  s.storey_stiffness = {5.0e8, 4.4e8, 3.6e8, 2.8e8, 2.0e8};
  s.modal = true;
  s.modal_zeta = {0.02, 0.05, 0.03};
  const ShearNumbers num = set_shear_building(b, 1, 0, s);
  const int n = 5;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = Eigen::MatrixXd::Zero(n, n), C(n, n);
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    M(i, i) = s.floor_mass[ui];
    K(i, i) += s.storey_stiffness[ui];
    if (i + 1 < n) K(i, i) += s.storey_stiffness[ui + 1], K(i, i + 1) = K(i + 1, i) = -s.storey_stiffness[ui + 1];
    const int dof = sys.bodies()[0].dofs[ui];
    EXPECT_EQ(b.c_floor[SystemBatch::at(dof, 1, 2)], 0.0) << "no floor dashpot with modal damping";
    for (int k = 0; k < n; ++k) {
      C(i, k) = b.c_dense[SystemBatch::at(b.dense_entry(0, i, k), 1, 2)];
      EXPECT_EQ(b.c_dense[SystemBatch::at(b.dense_entry(0, i, k), 0, 2)], 0.0) << "lane 0 untouched";
    }
  }
  EXPECT_LT((C - C.transpose()).norm(), 1e-12 * C.norm());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  const Eigen::MatrixXd Mi = M.inverse();
  A.topRightCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Mi * K;
  A.bottomRightCorner(n, n) = -Mi * C;
  const Eigen::VectorXcd lam = Eigen::EigenSolver<Eigen::MatrixXd>(A).eigenvalues();
  std::vector<std::pair<double, double>> modes;  // (w, zeta) of the roots with Im > 0
  for (int i = 0; i < 2 * n; ++i)
    if (lam(i).imag() > 0) modes.push_back({std::abs(lam(i)), -lam(i).real() / std::abs(lam(i))});
  std::sort(modes.begin(), modes.end());
  ASSERT_EQ(modes.size(), 5u);
  const double want[] = {0.02, 0.05, 0.03, 0.03, 0.03};
  for (std::size_t j = 0; j < 5; ++j) {
    EXPECT_NEAR(modes[j].second, want[j], 1e-9) << "mode " << j + 1;
    EXPECT_NEAR(num.zeta_modes[j], want[j], 1e-15) << "mode " << j + 1;
    EXPECT_NEAR(modes[j].first, num.modes.omega[j], 1e-9 * num.modes.omega[j]) << "mode " << j + 1;
  }
  // Rayleigh on the same building (5 % at modes 1 and 2): mode 5 gets well above 5 %
  ShearSpec r = s;
  r.modal = false, r.zeta = 0.05;
  const ShearNumbers rn = shear_numbers(std::vector<double>(5, 3.0), r);
  EXPECT_GT(rn.zeta_modes[4], 0.085);  // 9.1 %
  // a body without dense damping refuses modal numbers, and the other way round
  const std::vector<model::StickTopology> plain_sticks{stick(5, 3.0)};
  const model::System plain = model::shear_buildings(plain_sticks);
  SystemBatch pb;
  pb.resize(plain, 1);
  EXPECT_TRUE(pb.c_dense.empty());
  EXPECT_THROW(set_shear_building(pb, 0, 0, s), std::invalid_argument);
  EXPECT_THROW(set_shear_building(b, 0, 0, r), std::invalid_argument);
}

}  // namespace
}  // namespace pounding::physics
