#include "pounding/physics/validate.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"

namespace pounding::physics {

namespace {

// The wording of require_positive / require_range (core/error.hpp), as problems.
void positive(std::vector<Problem>& out, double v, const std::string& name) {
  if (!std::isfinite(v) || v <= 0.0)
    out.push_back({fmt::format("{} = {} must be positive and finite", name, v), name, "give a value > 0"});
}
void in_range(std::vector<Problem>& out, double v, double lo, double hi, const std::string& name,
              const std::string& range) {
  if (!std::isfinite(v) || v < lo || v > hi)
    out.push_back({fmt::format("{} = {} is out of range", name, v), name, fmt::format("give a value in {}", range)});
}

void structure(std::vector<Problem>& out, const Structure& s, const std::string& sfx, Stepper stepper,
               const std::string& lane) {
  auto where = [&](const std::string& what) { return fmt::format("{} (lane {})", what, lane); };
  positive(out, s.m, where("m" + sfx));
  if (!std::isfinite(s.k) || s.k < 0) positive(out, s.k, where("k" + sfx));
  if (!std::isfinite(s.c) || s.c < 0)
    out.push_back({fmt::format("c{} = {} must be >= 0", sfx, s.c), where("c" + sfx), "give c >= 0"});
  if (!(s.fy > 0)) positive(out, s.fy, where("fy" + sfx));
  in_range(out, s.alpha, 0.0, std::nextafter(1.0, 0.0), where("alpha" + sfx), "[0, 1)");
  if (stepper != Stepper::nigam_jennings) return;
  positive(out, s.k, where("k" + sfx + " (Nigam-Jennings needs k > 0)"));
  const double zeta = s.c / (2.0 * std::sqrt(s.k * s.m));
  if (!(zeta < 1.0))
    out.push_back({fmt::format("damping ratio {} of structure {} is not below 1", zeta, sfx), where("zeta"),
                   "the Nigam-Jennings stepper needs an under-damped structure"});
}

}  // namespace

std::vector<Problem> validate_lane(const PairParams& p, const ContactModel& cm, Stepper stepper, std::size_t lane) {
  std::vector<Problem> out;
  const std::string ln = std::to_string(lane);
  structure(out, p.s1, "1", stepper, ln);
  structure(out, p.s2, "2", stepper, ln);
  if (!std::isfinite(p.gap) || p.gap < 0)
    out.push_back({fmt::format("gap = {} must be >= 0", p.gap), fmt::format("gap (lane {})", ln), "give a gap >= 0 (m)"});
  const contact::LawTraits& tr = contact::traits(cm.law);
  if (tr.needs_stiffness) positive(out, p.kc, fmt::format("kc (lane {})", ln));
  if (tr.needs_restitution) in_range(out, p.e, std::nextafter(0.0, 1.0), 1.0, fmt::format("e (lane {})", ln), "(0, 1]");
  return out;
}

std::vector<Problem> validate(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion,
                              const KernelSettings& settings) {
  std::vector<Problem> out;
  if (settings.substeps < 1)
    out.push_back({fmt::format("substeps = {} must be >= 1", settings.substeps), "substeps", "give 1 or more"});
  positive(out, motion.dt, "record dt");
  if (contact::traits(cm.law).uses_exponent) in_range(out, cm.n, 1.0, 3.0, "Hertz exponent n", "[1, 3]");
  if (!out.empty()) return out;
  for (std::size_t i = 0; i < batch.width(); ++i) {
    out = validate_lane(batch.get(i), cm, settings.stepper, i);
    if (!out.empty()) return out;
  }
  return out;
}

void throw_first(const std::vector<Problem>& problems) {
  if (problems.empty()) return;
  const Problem& p = problems.front();
  throw InputError(p.what, p.where, p.fix);
}

}  // namespace pounding::physics
