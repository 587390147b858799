#pragma once
// Systems for the system-stepper tests, built from model::System::Parts directly (the tests state their own
// topology: level-major DOFs, storey springs, floor-to-floor elements at the common levels), and their batches.
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "pounding/model/modes.hpp"
#include "pounding/model/system.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::test {

// Identical bits are claimed for the Release build only ($POUNDING_BITS_NOT_CLAIMED says why not, NOTES.md).
inline bool bits_claimed() {
  const char* why = std::getenv("POUNDING_BITS_NOT_CLAIMED");
  return !why || !*why;
}

// Shear buildings side by side (bodies left to right, storey counts n[b]), DOFs level-major, storey dashpots
// when `rayleigh`, one point-point element per common level between neighbours b and b+1 in group 0. `dense`:
// classical modal damping (DampingForm::dense) on every body of more than one storey, no storey dashpots.
inline model::System shear_row(const std::vector<int>& n, bool rayleigh, bool dense = false) {
  model::System::Parts P;
  int top = 0;
  for (int x : n) top = std::max(top, x);
  std::vector<std::vector<int>> dof(n.size());
  int next = 0;
  for (int level = 1; level <= top; ++level)
    for (std::size_t b = 0; b < n.size(); ++b)
      if (level <= n[b]) dof[b].push_back(next++);
  for (std::size_t b = 0; b < n.size(); ++b) {
    model::Body body;
    body.dofs = dof[b];
    for (int k = 1; k <= n[b]; ++k) body.heights.push_back(3.2 * k);
    body.storey_dashpots = rayleigh && !(dense && n[b] > 1);
    if (dense && n[b] > 1) body.damping = model::DampingForm::dense;
    body.label = "building" + std::to_string(b + 1);
    P.bodies.push_back(body);
    for (int k = 0; k < n[b]; ++k)
      P.springs.push_back({k == 0 ? model::ground : dof[b][static_cast<std::size_t>(k - 1)],
                           dof[b][static_cast<std::size_t>(k)], 0, model::SpringRole::storey, static_cast<int>(b), k + 1});
  }
  for (std::size_t b = 0; b + 1 < n.size(); ++b)
    for (int k = 0; k < std::min(n[b], n[b + 1]); ++k) {
      model::ContactElement e;
      e.left = {model::SideKind::point, dof[b][static_cast<std::size_t>(k)], -1, 0};
      e.right = {model::SideKind::point, dof[b + 1][static_cast<std::size_t>(k)], -1, 0};
      e.level = k + 1;
      e.label = "level " + std::to_string(k + 1);
      P.contacts.push_back(e);
    }
  if (!P.contacts.empty()) P.groups.push_back(model::ContactGroup{});
  return model::System::build(P);
}

// One building's numbers in every lane: storey masses m, storey stiffnesses k (bottom first), Rayleigh a0 (floor
// dashpots a0 m) and a1 (storey dashpots a1 k), yield forces fy (inf: elastic) with hardening alpha; `modal_zeta`
// for a body with dense damping (C = model::modal_damping_matrix, per mode from 1, the last repeating).
struct Stick {
  std::vector<double> m, k, fy;
  double a0 = 0.0, a1 = 0.0, alpha = 0.0;
  std::vector<double> modal_zeta;
};

// Fills body b's DOFs and springs in lane l from `s` (springs in body order, as shear_row lists them).
inline void fill_stick(physics::SystemBatch& B, int b, std::size_t l, const Stick& s) {
  const model::System& S = *B.system;
  const auto& dofs = S.bodies()[static_cast<std::size_t>(b)].dofs;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const std::size_t at = physics::SystemBatch::at(dofs[k], l, B.width);
    B.m[at] = s.m[k], B.c_floor[at] = s.a0 * s.m[k];
  }
  for (std::size_t sp = 0; sp < S.springs().size(); ++sp) {
    const model::Spring& x = S.springs()[sp];
    if (x.body != b) continue;
    const std::size_t k = static_cast<std::size_t>(x.storey - 1), at = physics::SystemBatch::at(static_cast<int>(sp), l, B.width);
    B.spring[at] = {s.k[k], s.fy.empty() ? INFINITY : s.fy[k], s.alpha};
    if (!B.c_storey.empty()) B.c_storey[at] = s.a1 * s.k[k];
  }
  if (S.bodies()[static_cast<std::size_t>(b)].damping == model::DampingForm::dense) {
    const std::vector<double> C = model::modal_damping_matrix(s.m, model::shear_stick_modes(s.m, s.k), s.modal_zeta);
    const std::size_t n = dofs.size();
    for (std::size_t j = 0; j < n; ++j) {
      B.c_floor[physics::SystemBatch::at(dofs[j], l, B.width)] = 0.0;
      for (std::size_t k = 0; k < n; ++k)
        B.c_dense[physics::SystemBatch::at(B.dense_entry(b, static_cast<int>(j), static_cast<int>(k)), l, B.width)] =
            C[j * n + k];
    }
  }
}

// Rayleigh coefficients for ratio zeta at circular frequencies w1, w2 (SB §1, equal ratios).
inline void rayleigh(Stick& s, double zeta, double w1, double w2) {
  s.a0 = 2.0 * zeta * w1 * w2 / (w1 + w2);
  s.a1 = 2.0 * zeta / (w1 + w2);
}

}  // namespace pounding::test
