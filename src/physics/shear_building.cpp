// Per-lane numbers of shear buildings (physics/shear_building.hpp; docs/architecture.md §2.2.3).
#include "pounding/physics/shear_building.hpp"

#include "pounding/model/hysteresis/registry.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "pounding/contact/model.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding::physics {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("shear building: " + what);
}

// One value for all n, or n values: the n values.
std::vector<double> per_storey(const std::vector<double>& v, std::size_t n, const char* what) {
  require(v.size() == 1 || v.size() == n, std::string(what) + ": give one value or one per floor/storey");
  return v.size() == 1 ? std::vector<double>(n, v[0]) : v;
}

std::vector<double> strengths(const ShearSpec& spec, std::span<const double> h, const std::vector<double>& m,
                              const std::vector<double>& k) {
  const std::size_t n = k.size();
  if (!spec.storey_yield.empty()) return per_storey(spec.storey_yield, n, "storey_yield");
  std::vector<double> fy(n, std::numeric_limits<double>::infinity());
  if (spec.yield_drift > 0.0) {
    for (std::size_t i = 0; i < n; ++i) fy[i] = k[i] * (spec.yield_drift * h[i]);
  } else if (spec.yield_coefficient > 0.0) {
    const std::vector<double> v = model::stiffness_shape(m, h, model::StiffnessProfile::shear);  // V_i / V_1
    double total = 0.0;
    for (double mi : m) total += mi;
    for (std::size_t i = 0; i < n; ++i) fy[i] = spec.yield_coefficient * total * standard_gravity * v[i];
  }
  return fy;
}

}  // namespace

ShearNumbers shear_numbers(std::span<const double> h, const ShearSpec& spec) {
  const std::size_t n = h.size();
  require(n >= 1, "no storeys");
  require(std::isfinite(spec.zeta) && spec.zeta >= 0.0 && spec.zeta < 1.0, "zeta must be in [0, 1)");
  ShearNumbers out;
  out.m = per_storey(spec.floor_mass, n, "floor_mass");
  if (!spec.storey_stiffness.empty()) {
    out.k = per_storey(spec.storey_stiffness, n, "storey_stiffness");
  } else {
    require(std::isfinite(spec.period) && spec.period > 0.0, "give storey stiffnesses or a period > 0");
    out.k = n == 1 ? std::vector<double>{Structure::from_period(out.m[0], spec.period, spec.zeta).k}
                   : model::stiffness_for_period(out.m, h, spec.profile, spec.period);
  }
  const std::string defect = model::stick_defect(out.m, out.k);
  require(defect.empty(), defect);
  out.fy = strengths(spec, h, out.m, out.k);
  out.modes = model::shear_stick_modes(out.m, out.k);
  out.c_storey.assign(n, 0.0);
  for (double z : spec.modal_zeta) require(std::isfinite(z) && z >= 0.0 && z < 1.0, "modal zeta must be in [0, 1)");
  if (n == 1) {
    // today's SDOF: Structure::from_period's damping expression, as a floor dashpot (modal: mode 1's ratio)
    const double zeta = spec.modal && !spec.modal_zeta.empty() ? spec.modal_zeta[0] : spec.zeta;
    out.c_floor = {spec.storey_stiffness.empty()
                       ? Structure::from_period(out.m[0], spec.period, zeta).c
                       : 2.0 * zeta * std::sqrt(out.k[0] * out.m[0])};
    out.zeta_modes = {out.c_floor[0] / (2.0 * std::sqrt(out.k[0] * out.m[0]))};
    return out;
  }
  if (spec.modal) {  // classical modal damping: the dense C, no dashpots
    const std::vector<double> zl = spec.modal_zeta.empty() ? std::vector<double>{spec.zeta} : spec.modal_zeta;
    out.c_dense = model::modal_damping_matrix(out.m, out.modes, zl);
    out.c_floor.assign(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) out.zeta_modes.push_back(model::modal_ratio(zl, j));
    return out;
  }
  require(spec.mode_i >= 1 && spec.mode_i < spec.mode_j && spec.mode_j <= static_cast<int>(n),
          "Rayleigh modes must satisfy 1 <= i < j <= storeys");
  const double wi = out.modes.omega[static_cast<std::size_t>(spec.mode_i - 1)];
  const double wj = out.modes.omega[static_cast<std::size_t>(spec.mode_j - 1)];
  out.rayleigh = model::rayleigh(wi, spec.zeta, wj, spec.zeta);
  out.c_floor.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.c_floor[i] = out.rayleigh.a0 * out.m[i];
    out.c_storey[i] = out.rayleigh.a1 * out.k[i];  // K0: initial storey stiffnesses only (SB §1 pitfall 2)
  }
  for (double w : out.modes.omega) out.zeta_modes.push_back(model::rayleigh_ratio(out.rayleigh, w));
  return out;
}

ShearNumbers set_shear_building(SystemBatch& batch, std::size_t lane, int body, const ShearSpec& spec) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::System& sys = *batch.system;
  require(body >= 0 && static_cast<std::size_t>(body) < sys.bodies().size(), "no such body");
  const model::Body& b = sys.bodies()[static_cast<std::size_t>(body)];
  require(!b.isolated, "an isolated body is not a shear building (set_isolated_building)");
  std::vector<double> h(b.heights.size());
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = i == 0 ? b.heights[0] : b.heights[i] - b.heights[i - 1];
  ShearNumbers num = shear_numbers(h, spec);
  const bool dashpots = b.storey_dashpots && !batch.c_storey.empty();
  for (double c : num.c_storey)
    require(dashpots || c == 0.0, "Rayleigh's stiffness part needs storey dashpots (StickTopology::storey_dashpots)");
  const bool dense = b.damping == model::DampingForm::dense;
  require(dense == !num.c_dense.empty(), dense ? "a body with dense damping needs modal damping (ShearSpec::modal)"
                                               : "modal damping needs a body with DampingForm::dense (StickTopology::damping)");
  const std::size_t w = batch.width;
  const std::size_t n = b.dofs.size();
  for (std::size_t j = 0; j < num.c_dense.size(); ++j)
    batch.c_dense[SystemBatch::at(batch.dense_entry(body, static_cast<int>(j / n), static_cast<int>(j % n)), lane, w)] =
        num.c_dense[j];
  for (std::size_t i = 0; i < b.dofs.size(); ++i) {
    const int d = b.dofs[i], s = sys.spring_below(d);
    batch.m[SystemBatch::at(d, lane, w)] = num.m[i];
    batch.c_floor[SystemBatch::at(d, lane, w)] = num.c_floor[i];
    batch.spring[SystemBatch::at(s, lane, w)] = {num.k[i], num.fy[i], spec.alpha};
    if (!batch.c_storey.empty()) batch.c_storey[SystemBatch::at(s, lane, w)] = num.c_storey[i];
  }
  return num;
}

IsolationNumbers isolation_numbers(std::span<const double> h, const ShearSpec& spec, const IsolationSpec& iso) {
  require(std::isfinite(iso.base_mass) && iso.base_mass > 0.0, "the base mass must be finite and > 0");
  IsolationNumbers out;
  out.super = shear_numbers(h, spec);
  out.m_base = iso.base_mass;
  out.m_total = iso.base_mass;
  for (double m : out.super.m) out.m_total += m;
  if (iso.bearing == Bearing::linear) {
    require(std::isfinite(iso.k_eff) && iso.k_eff > 0.0, "k_eff must be finite and > 0");
    require(std::isfinite(iso.zeta_eff) && iso.zeta_eff >= 0.0 && iso.zeta_eff < 1.0, "zeta_eff must be in [0, 1)");
    out.isolator = {iso.k_eff, std::numeric_limits<double>::infinity(), 0.0};
    out.c_base = 2.0 * iso.zeta_eff * std::sqrt(iso.k_eff * out.m_total);
  } else if (iso.bearing == Bearing::friction_pendulum) {
    require(std::isfinite(iso.radius) && iso.radius > 0.0, "the radius must be finite and > 0");
    require(std::isfinite(iso.mu_slow) && iso.mu_slow > 0.0 && iso.mu_slow < 1.0, "mu_slow must be in (0, 1)");
    require(std::isfinite(iso.mu_fast) && iso.mu_fast > 0.0 && iso.mu_fast < 1.0, "mu_fast must be in (0, 1)");
    require(std::isfinite(iso.rate) && iso.rate >= 0.0, "the rate must be finite and >= 0");
    require(std::isfinite(iso.uy) && iso.uy > 0.0, "u_y must be finite and > 0");
    out.weight = standard_gravity * out.m_total;
    out.isolator = model::FrictionPendulum::pack({out.weight, iso.radius, iso.mu_slow, iso.mu_fast, iso.rate, iso.uy});
  } else {
    require(std::isfinite(iso.k1) && iso.k1 > 0.0, "k1 must be finite and > 0");
    require(std::isfinite(iso.k2) && iso.k2 >= 0.0 && iso.k2 < iso.k1, "k2 must be in [0, k1)");
    require(std::isfinite(iso.qd) && iso.qd > 0.0, "Qd must be finite and > 0");
    if (iso.bearing == Bearing::bouc_wen) {
      require(std::isfinite(iso.bw_a) && iso.bw_a > 0.0, "A must be finite and > 0");
      require(std::isfinite(iso.bw_beta) && std::isfinite(iso.bw_gamma) && iso.bw_beta + iso.bw_gamma > 0.0,
              "beta + gamma must be > 0");
      require(iso.bw_eta >= 1 && iso.bw_eta <= model::smooth_max_eta, "eta must be an integer in [1, 8]");
      const double alpha = iso.k2 / iso.k1;
      out.isolator =
          model::BoucWen::pack({iso.k1, alpha, iso.qd / (iso.k1 - iso.k2), iso.bw_a, iso.bw_beta, iso.bw_gamma, iso.bw_eta});
    } else {
      out.isolator = {iso.k1, iso.qd * iso.k1 / (iso.k1 - iso.k2), iso.k2 / iso.k1};  // SB §2: Fy = Qd/(1 - k2/k1)
      require(std::isfinite(iso.zeta_eff) && iso.zeta_eff >= 0.0 && iso.zeta_eff < 1.0, "zeta_eff must be in [0, 1)");
      // the rubber's viscous damping on the post-yield (rubber) stiffness; 0: the hysteresis alone, as before
      if (iso.zeta_eff > 0.0) out.c_base = 2.0 * iso.zeta_eff * std::sqrt(iso.k2 * out.m_total);
    }
  }
  return out;
}

int isolator_law(Bearing bearing) {
  switch (bearing) {
    case Bearing::friction_pendulum: return model::law_of<model::FrictionPendulum>;
    case Bearing::bouc_wen: return model::law_of<model::BoucWen>;
    default: return model::law_of<model::BilinearKinematic>;  // linear and lead-rubber bearings
  }
}

std::vector<double> isolated_damping_matrix(std::span<const double> c_super, double c_base) {
  const auto n = static_cast<std::size_t>(std::lround(std::sqrt(static_cast<double>(c_super.size()))));
  require(n >= 1 && n * n == c_super.size(), "the superstructure's C must be square");
  // C = T' C_s T + c_b e0 e0', T = [-1 | I] (relative velocities of the floors to the base): row 0 and column 0 are
  // minus the column and row sums of C_s, (0, 0) their total plus the bearing's dashpot
  const std::size_t N = n + 1;
  std::vector<double> c(N * N, 0.0);
  double total = 0.0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k) {
      const double x = c_super[j * n + k];
      c[(j + 1) * N + (k + 1)] = x;
      c[(j + 1) * N] -= x;  // row j + 1, column 0: -sum_k C_jk
      c[k + 1] -= x;        // row 0, column k + 1: -sum_j C_jk
      total += x;
    }
  c[0] = total + c_base;
  return c;
}

IsolationNumbers set_isolated_building(SystemBatch& batch, std::size_t lane, int body, const ShearSpec& spec,
                                       const IsolationSpec& iso) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::System& sys = *batch.system;
  require(body >= 0 && static_cast<std::size_t>(body) < sys.bodies().size(), "no such body");
  const model::Body& b = sys.bodies()[static_cast<std::size_t>(body)];
  require(b.isolated && b.dofs.size() >= 2 && b.floor_dashpot_ref == b.dofs[0],
          "not an isolated stick (model::StickTopology::isolated)");
  std::vector<double> h(b.heights.size() - 1);
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = b.heights[i + 1] - b.heights[i];
  IsolationNumbers num = isolation_numbers(h, spec, iso);
  const bool dashpots = b.storey_dashpots && !batch.c_storey.empty();
  for (double c : num.super.c_storey)
    require(dashpots || c == 0.0, "Rayleigh's stiffness part needs storey dashpots (StickTopology::storey_dashpots)");
  const bool dense = b.damping == model::DampingForm::dense;
  require(dense == !num.super.c_dense.empty(),
          dense ? "a body with dense damping needs modal damping (ShearSpec::modal)"
                : "modal damping needs a body with DampingForm::dense (StickTopology::damping)");
  const std::size_t w = batch.width;
  const int base = b.dofs[0], sb = sys.spring_below(base);
  batch.m[SystemBatch::at(base, lane, w)] = num.m_base;
  // to ground: the isolator's deformation rate (with dense damping the bearing's dashpot is C's (0, 0) term)
  batch.c_floor[SystemBatch::at(base, lane, w)] = dense ? 0.0 : num.c_base;
  if (dense) {
    const std::vector<double> c = isolated_damping_matrix(num.super.c_dense, num.c_base);
    const std::size_t n = b.dofs.size();
    for (std::size_t j = 0; j < c.size(); ++j)
      batch.c_dense[SystemBatch::at(batch.dense_entry(body, static_cast<int>(j / n), static_cast<int>(j % n)), lane, w)] =
          c[j];
  }
  batch.spring[SystemBatch::at(sb, lane, w)] = num.isolator;
  if (!batch.c_storey.empty()) batch.c_storey[SystemBatch::at(sb, lane, w)] = 0.0;
  for (std::size_t i = 1; i < b.dofs.size(); ++i) {
    const int d = b.dofs[i], s = sys.spring_below(d);
    batch.m[SystemBatch::at(d, lane, w)] = num.super.m[i - 1];
    batch.c_floor[SystemBatch::at(d, lane, w)] = num.super.c_floor[i - 1];
    batch.spring[SystemBatch::at(s, lane, w)] = {num.super.k[i - 1], num.super.fy[i - 1], spec.alpha};
    if (!batch.c_storey.empty()) batch.c_storey[SystemBatch::at(s, lane, w)] = num.super.c_storey[i - 1];
  }
  return num;
}

void set_moat(SystemBatch& batch, std::size_t lane, int body, double gap_left, double gap_right, double kc, double e) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::System& sys = *batch.system;
  require(body >= 0 && static_cast<std::size_t>(body) < sys.bodies().size(), "no such body");
  const int base = sys.bodies()[static_cast<std::size_t>(body)].dofs[0];
  int found = 0;
  for (int el : sys.elements_at(base)) {
    const model::ContactElement& ce = sys.contacts()[static_cast<std::size_t>(el)];
    const bool wall_left = ce.left.kind == model::SideKind::wall, wall_right = ce.right.kind == model::SideKind::wall;
    if (!wall_left && !wall_right) continue;
    const std::size_t i = SystemBatch::at(el, lane, batch.width);
    batch.gap[i] = wall_left ? gap_left : gap_right;
    batch.kc[i] = kc;
    batch.e[i] = e;
    ++found;
  }
  require(found == 2, "the body has no moat (model::StickTopology::moat)");
}

void set_contacts(SystemBatch& batch, std::size_t lane, double gap, double kc, double e,
                  std::span<const double> level_offsets, model::ShapeFunctions shape) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::System& sys = *batch.system;
  const std::size_t w = batch.width;
  for (std::size_t el = 0; el < sys.contacts().size(); ++el) {
    const model::ContactElement& ce = sys.contacts()[el];
    const std::size_t i = SystemBatch::at(static_cast<int>(el), lane, w);
    if (sys.groups()[static_cast<std::size_t>(ce.group)].study_gap) {
      if (level_offsets.empty()) {
        batch.gap[i] = gap;  // no "+ 0.0": the pair's gap bits as given
      } else {
        require(ce.level >= 1 && static_cast<std::size_t>(ce.level) <= level_offsets.size(),
                "no gap offset for level " + std::to_string(ce.level));
        batch.gap[i] = gap + level_offsets[static_cast<std::size_t>(ce.level - 1)];
      }
    }
    batch.kc[i] = kc;
    batch.e[i] = e;
    batch.weight[i] = ce.left.kind == model::SideKind::interpolated || ce.right.kind == model::SideKind::interpolated
                          ? model::column_weight(ce.xi, shape)
                          : 0.0;
  }
}

std::array<double, 2> contact_masses(const SystemBatch& batch, std::size_t lane, int element) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::ContactElement& ce = batch.system->contacts().at(static_cast<std::size_t>(element));
  const auto mass = [&](const model::Side& s) {
    if (s.kind == model::SideKind::wall) return -1.0;
    const bool upper = s.kind == model::SideKind::interpolated && (ce.xi >= 0.5 || s.p < 0);
    const int d = upper ? s.q : s.p;
    return batch.m[SystemBatch::at(d, lane, batch.width)];
  };
  double l = mass(ce.left), r = mass(ce.right);
  if (l < 0) l = r;
  if (r < 0) r = l;
  return {l, r};
}

void set_sphere_stiffness(SystemBatch& batch, std::size_t lane, double density, double youngs, double poisson) {
  require(batch.system != nullptr && lane < batch.width, "the batch is not sized (SystemBatch::resize)");
  const model::System& sys = *batch.system;
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    if (!sys.groups()[static_cast<std::size_t>(sys.contacts()[e].group)].study_gap) continue;  // a moat: set_moat's
    const std::array<double, 2> mm = contact_masses(batch, lane, static_cast<int>(e));  // a column: its nearer floor
    batch.kc[SystemBatch::at(static_cast<int>(e), lane, batch.width)] =
        hertz_stiffness_spheres(mm[0], mm[1], density, youngs, poisson);
  }
}

}  // namespace pounding::physics
