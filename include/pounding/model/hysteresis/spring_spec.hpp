#pragma once
// One spring's description as the system batch holds it (physics::SystemBatch::spring), packed by its hysteresis
// model (model/hysteresis/registry.hpp: pack, unpack): k, fy, alpha what validation and omega_max read (the initial
// tangent, the strength, the hardening; fy = +inf and alpha = 0 for a model without them), p the model's own numbers.
// And the roles a model may play (the registry's trait `roles`).
#include <array>
#include <limits>

namespace pounding::model {

struct SpringSpec {
  static constexpr int numbers = 12;  // the room for a model's own numbers (each model's pack checks its count)
  double k = 0.0, fy = std::numeric_limits<double>::infinity(), alpha = 0.0;
  std::array<double, numbers> p{};
};

// A spring's rows in the system stepper's pool at one lane (its numbers and state; the registry's traits load and
// stored_energy; steppers/system_central_difference.hpp maps them to its rows K, AK, QY, KP, ZA .. ZS, Z in order).
inline constexpr int spring_slots = 11;
using SpringRows = std::array<double, spring_slots>;

// Where a model may stand: a storey of a building or a frame, a base isolator, a link (bridge joints and abutments).
struct Roles {
  bool storey = false, isolator = false, link = false;
};

}  // namespace pounding::model
