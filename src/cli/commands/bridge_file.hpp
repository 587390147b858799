#pragma once
// The bridge description of `pounding simulate --bridge FILE.toml` (issue 26 §1): frames left to right, the joints
// between them with their restrainers and bearings, and the abutments; SI units. Keys (every one optional unless
// said):
//   [[frame]]   mass (kg, required), period (s) | stiffness (N/m) (one required), zeta (0.05), yield_force (N; absent:
//               linear), alpha (0), hysteresis = "bilinear" | "q-hyst", beta (Q-Hyst's 0.5), height (m, 10),
//               support (the ground-motion record of its pier, 1-based: --support-record order; 1), label;
//               a short shear stick: storeys = n (1: the SDOF), then mass / stiffness / yield_force are each level's /
//               storey's (or storey_mass, storey_stiffness, storey_yield lists, bottom first, deck last), period is T1
//               (uniform storeys), storey_height (height / n), damping = "rayleigh" (zeta at modes 1, 2) | "modal"
//               (modal_zeta per mode); the joints, restrainers, bearings and abutments act on the deck (top level)
//   [[joint]]   gap (m, required), contact_stiffness (law units; default --kh), restitution (default --e)
//   [joint.restrainer] stiffness (N/m), yield_force (N; absent: elastic), alpha (0.05), slack (m; default the gap)
//   [joint.bearing]    stiffness (N/m), yield_force (N; absent: linear), alpha (0)
//   [abutment.left], [abutment.right]  backfill = "none" | "epp" | "hyperbolic" (none), gap (m), support (1);
//       epp: stiffness (N/m) and capacity (N), or width and height (m) of the back wall for Caltrans SDC's K_abut and
//       P_bw (model::caltrans_abutment); alpha (0); hyperbolic: k_max (N/m), k_ur (N/m; k_max), rf (0.7), f_ult (N)
//   [abutment.left.bearing] ... as a joint's bearing
// The reader is sampling/bridge.hpp's read_bridge, shared with a study's [bridge] section; every key is registered in
// src/config/study_keys.cpp (docs/study-reference.md, sections "bridge.*"). Bad input: one InputError naming
// FILE:line [frame2].key.
#include <string>

#include "pounding/physics/bridge.hpp"

namespace pounding::cli {

// kc_default: --kh when given, else NaN (a joint must then give contact_stiffness); e_default: --e.
// restitution_given_by: non-empty when an option gives every joint its restitution (a joint's own is then refused).
physics::BridgeSpec read_bridge_file(const std::string& path, double kc_default, double e_default,
                                     const std::string& restitution_given_by = "");

}  // namespace pounding::cli
