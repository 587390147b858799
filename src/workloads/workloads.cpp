// Named, deterministic workloads for `pounding bench`, the Google Benchmark and the examples.
#include "pounding/workloads/workloads.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "pounding/contact/model.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/physics/shear_building.hpp"

namespace pounding {

std::vector<double> builtin_motion(double dt, double duration) {
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / dt)) + 1;
  std::vector<double> a(n);
  const double f0 = 0.3, f1 = 3.0, Tsw = duration;
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double t = static_cast<double>(i) * dt;
    double env = std::pow(t / (0.25 * duration), 2) * std::exp(2.0 * (1.0 - t / (0.25 * duration)));
    double phase = 2.0 * std::numbers::pi * (f0 * t + 0.5 * (f1 - f0) * t * t / Tsw);
    a[i] = env * std::sin(phase);
    peak = std::max(peak, std::abs(a[i]));
  }
  for (double& x : a) x *= 0.4 * g_accel / peak;
  return a;
}

PairBatch benchmark_batch(std::size_t width) {
  PairBatch b;
  b.resize(width);
  for (std::size_t i = 0; i < width; ++i) {
    double s = std::fmod(0.6180339887498949 * static_cast<double>(i + 1), 1.0);  // low-discrepancy in [0,1)
    double r = std::fmod(0.7548776662466927 * static_cast<double>(i + 1), 1.0);
    double T1 = 1.0 + 0.5 * s, T2 = 1.0 + 0.5 * r;
    double h1 = 30.0 + 20.0 * s, h2 = 30.0 + 20.0 * r;
    double m1 = 1.0e7 * (0.8 + 0.4 * r), m2 = 1.0e7 * (0.8 + 0.4 * s);
    Structure s1 = Structure::from_period(m1, T1, 0.05), s2 = Structure::from_period(m2, T2, 0.05);
    s1.fy = s1.k * 0.02 * h1 / 6.0, s1.alpha = 0.05;
    s2.fy = s2.k * 0.02 * h2 / 6.0, s2.alpha = 0.05;
    PairParams p;
    p.s1 = s1, p.s2 = s2;
    p.gap = 0.3 * 0.005 * (h1 + h2);
    p.kc = hertz_stiffness_spheres(m1, m2, 2400.0, 24.86e9, 0.15);
    p.e = 0.65;
    b.set(i, p);
  }
  return b;
}

model::System shear_pair_system(int storeys, bool modal) {
  model::System::Parts P;
  for (int b = 0; b < 2; ++b) {
    model::Body body;
    for (int k = 0; k < storeys; ++k) body.dofs.push_back(2 * k + b), body.heights.push_back(3.2 * (k + 1));
    body.storey_dashpots = storeys > 1 && !modal;
    if (modal && storeys > 1) body.damping = model::DampingForm::dense;
    body.label = b == 0 ? "building1" : "building2";
    P.bodies.push_back(body);
    for (int k = 0; k < storeys; ++k)
      P.springs.push_back({k == 0 ? model::ground : 2 * (k - 1) + b, 2 * k + b, 0, model::SpringRole::storey, b, k + 1});
  }
  for (int k = 0; k < storeys; ++k) {
    model::ContactElement e;
    e.left = {model::SideKind::point, 2 * k, -1, 0}, e.right = {model::SideKind::point, 2 * k + 1, -1, 0};
    e.level = k + 1, e.label = "level " + std::to_string(k + 1);
    P.contacts.push_back(e);
  }
  P.groups.push_back(model::ContactGroup{});
  return model::System::build(P);
}

physics::SystemBatch shear_pair_batch(const model::System& S, std::size_t width) {
  physics::SystemBatch B;
  B.resize(S, width);
  const int n = static_cast<int>(S.bodies()[0].dofs.size());
  for (std::size_t l = 0; l < width; ++l) {
    const double s = std::fmod(0.6180339887498949 * static_cast<double>(l + 1), 1.0);
    const double r = std::fmod(0.7548776662466927 * static_cast<double>(l + 1), 1.0);
    for (int b = 0; b < 2; ++b) {
      const double x = b == 0 ? s : r, m = 2.5e5 * (0.8 + 0.4 * (b == 0 ? r : s));
      const double T1 = (b == 0 ? 0.1 : 0.13) * n * (1.0 + 0.5 * x), w1 = 2.0 * std::numbers::pi / T1;
      // uniform stick: omega_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2n + 1))) (SB §1)
      auto sine = [n](int j) { return std::sin((2 * j - 1) * std::numbers::pi / (2.0 * (2 * n + 1))); };
      const double k = m * std::pow(w1 / (2.0 * sine(1)), 2), w2 = n > 1 ? w1 * sine(2) / sine(1) : 3.0 * w1;
      const double a0 = 2.0 * 0.05 * w1 * w2 / (w1 + w2), a1 = 2.0 * 0.05 / (w1 + w2);
      for (int f = 0; f < n; ++f) {
        const int dof = S.bodies()[static_cast<std::size_t>(b)].dofs[static_cast<std::size_t>(f)];
        const int spring = b * n + f;
        B.m[physics::SystemBatch::at(dof, l, width)] = m;
        B.c_floor[physics::SystemBatch::at(dof, l, width)] = n > 1 ? a0 * m : 2.0 * 0.05 * std::sqrt(k * m);
        B.spring[physics::SystemBatch::at(spring, l, width)] = {k, k * 0.032, 0.05};
        if (!B.c_storey.empty()) B.c_storey[physics::SystemBatch::at(spring, l, width)] = a1 * k;
      }
      if (S.bodies()[static_cast<std::size_t>(b)].damping == model::DampingForm::dense) {  // 5 % in every mode
        const std::vector<double> ms(static_cast<std::size_t>(n), m), ks(static_cast<std::size_t>(n), k);
        const std::vector<double> C = model::modal_damping_matrix(ms, model::shear_stick_modes(ms, ks), {{0.05}});
        for (int f = 0; f < n; ++f) {
          B.c_floor[physics::SystemBatch::at(S.bodies()[static_cast<std::size_t>(b)].dofs[static_cast<std::size_t>(f)], l, width)] = 0.0;
          for (int g = 0; g < n; ++g)
            B.c_dense[physics::SystemBatch::at(B.dense_entry(b, f, g), l, width)] =
                C[static_cast<std::size_t>(f * n + g)];
        }
      }
    }
    for (int e = 0; e < n; ++e) {
      const std::size_t at = physics::SystemBatch::at(e, l, width);
      B.gap[at] = 0.3 * 0.005 * 3.2 * n * (2.0 + s + r), B.kc[at] = 2e9 * (0.8 + 0.4 * s), B.e[at] = 0.65;
    }
  }
  return B;
}

namespace {
physics::Bearing bench_bearing(const std::string& name) {
  if (name == "friction-pendulum") return physics::Bearing::friction_pendulum;
  if (name == "bouc-wen") return physics::Bearing::bouc_wen;
  return physics::Bearing::lead_rubber;
}
}  // namespace

model::System isolated_pair_system(int storeys, const std::string& bearing) {
  std::vector<model::StickTopology> t(2);
  t[0].storeys = t[1].storeys = storeys;
  t[0].isolated = true, t[0].isolator_law = physics::isolator_law(bench_bearing(bearing));
  return model::shear_buildings(t);
}

physics::SystemBatch isolated_pair_batch(const model::System& S, std::size_t width, const std::string& bearing) {
  physics::SystemBatch B;
  B.resize(S, width);
  const int n = static_cast<int>(S.bodies()[1].dofs.size());
  for (std::size_t l = 0; l < width; ++l) {
    const double s = std::fmod(0.6180339887498949 * static_cast<double>(l + 1), 1.0);
    const double r = std::fmod(0.7548776662466927 * static_cast<double>(l + 1), 1.0);
    physics::ShearSpec left, right;
    left.floor_mass = {2.5e5 * (0.8 + 0.4 * r)};
    left.storey_stiffness = {9.81e7 * n / 3.0 * (1.0 + 0.5 * s)};
    right.floor_mass = {2.5e5 * (0.8 + 0.4 * s)};
    right.period = 0.13 * n * (1.0 + 0.5 * r);
    physics::IsolationSpec iso;
    iso.bearing = bench_bearing(bearing), iso.base_mass = 2.5e5;
    const double mt = iso.base_mass + n * left.floor_mass[0], W = physics::standard_gravity * mt;
    iso.k2 = mt * std::pow(2.0 * std::numbers::pi / 2.5, 2), iso.k1 = 10.0 * iso.k2, iso.qd = 0.05 * W;
    iso.bw_eta = 2, iso.bw_beta = 0.9, iso.bw_gamma = 0.1;
    iso.radius = 1.55, iso.mu_slow = 0.05, iso.mu_fast = 0.10, iso.rate = 20.0, iso.uy = 5e-4;
    physics::set_isolated_building(B, l, 0, left, iso);
    physics::set_shear_building(B, l, 1, right);
    physics::set_contacts(B, l, 0.1 * (1.0 + s), 2e9 * (0.8 + 0.4 * r), 0.65);
  }
  return B;
}

}  // namespace pounding
