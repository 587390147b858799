// Per-lane numbers of shear buildings (physics/shear_building.hpp; docs/architecture.md §2.2.3).
#include "pounding/physics/shear_building.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

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
  if (n == 1) {
    // today's SDOF: Structure::from_period's damping expression, as a floor dashpot
    out.c_floor = {spec.storey_stiffness.empty()
                       ? Structure::from_period(out.m[0], spec.period, spec.zeta).c
                       : 2.0 * spec.zeta * std::sqrt(out.k[0] * out.m[0])};
    out.zeta_modes = {out.c_floor[0] / (2.0 * std::sqrt(out.k[0] * out.m[0]))};
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
  require(!b.isolated, "an isolated body is not a shear building");
  std::vector<double> h(b.heights.size());
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = i == 0 ? b.heights[0] : b.heights[i] - b.heights[i - 1];
  ShearNumbers num = shear_numbers(h, spec);
  const bool dashpots = b.storey_dashpots && !batch.c_storey.empty();
  for (double c : num.c_storey)
    require(dashpots || c == 0.0, "Rayleigh's stiffness part needs storey dashpots (StickTopology::storey_dashpots)");
  const std::size_t w = batch.width;
  for (std::size_t i = 0; i < b.dofs.size(); ++i) {
    const int d = b.dofs[i], s = sys.spring_below(d);
    batch.m[SystemBatch::at(d, lane, w)] = num.m[i];
    batch.c_floor[SystemBatch::at(d, lane, w)] = num.c_floor[i];
    batch.spring[SystemBatch::at(s, lane, w)] = {num.k[i], num.fy[i], spec.alpha};
    if (!batch.c_storey.empty()) batch.c_storey[SystemBatch::at(s, lane, w)] = num.c_storey[i];
  }
  return num;
}

void set_contacts(SystemBatch& batch, std::size_t lane, double gap, double kc, double e,
                  std::span<const double> level_offsets) {
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
  }
}

}  // namespace pounding::physics
