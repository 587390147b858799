// Input checks of a batch outside the kernel: every problem listed, naming the lane and the field.
#include "pounding/physics/validate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/model/hysteresis/registry.hpp"

namespace pounding::physics {

namespace {

// A message part given as a string or as a function that makes it. Validation runs on every lane of every batch
// (pounding::run_batch validates before it runs), so a place name is formatted only when its check fails:
// formatting them all eagerly cost the pair benchmark 5-11 % (256 lanes, ~20 strings each; measured 2026-11-26).
template <class S> std::string text(const S& s) {
  if constexpr (std::is_invocable_v<const S&>)
    return s();
  else
    return std::string(s);
}

// The wording of require_positive / require_range (core/error.hpp), as problems. `name` is the quantity in the
// message, `where` the place (the pair's lanes give one string for both: "m1 (lane 3)").
template <class N, class W> void positive(std::vector<Problem>& out, double v, const N& name, const W& where) {
  if (!std::isfinite(v) || v <= 0.0)
    out.push_back({fmt::format("{} = {} must be positive and finite", text(name), v), text(where), "give a value > 0"});
}
template <class N> void positive(std::vector<Problem>& out, double v, const N& name) { positive(out, v, name, name); }
template <class N, class W>
void in_range(std::vector<Problem>& out, double v, double lo, double hi, const N& name, const W& where,
              const std::string& range) {
  if (!std::isfinite(v) || v < lo || v > hi)
    out.push_back({fmt::format("{} = {} is out of range", text(name), v), text(where),
                   fmt::format("give a value in {}", range)});
}
void in_range(std::vector<Problem>& out, double v, double lo, double hi, const std::string& name,
              const std::string& range) {
  in_range(out, v, lo, hi, name, name, range);
}

// The checks of one quantity, shared by the pair's lanes and the system's (`name` the quantity, `where` the place).
template <class N, class W> void mass(std::vector<Problem>& out, double m, const N& name, const W& where) {
  positive(out, m, name, where);
}
// k > 0 (a system's springs), or k >= 0 (the pair: k = 0 is a free SDOF)
template <class N, class W>
void stiffness(std::vector<Problem>& out, double k, const N& name, const W& where, bool zero_ok) {
  if (!std::isfinite(k) || k < 0 || (!zero_ok && k == 0)) positive(out, k, name, where);
}
template <class N, class W> void dashpot(std::vector<Problem>& out, double c, const N& name, const W& where) {
  if (!std::isfinite(c) || c < 0)
    out.push_back({fmt::format("{} = {} must be >= 0", text(name), c), text(where), "give c >= 0"});
}
template <class N, class W> void yield(std::vector<Problem>& out, double fy, const N& name, const W& where) {
  if (!(fy > 0)) positive(out, fy, name, where);
}
template <class N, class W> void hardening(std::vector<Problem>& out, double alpha, const N& name, const W& where) {
  in_range(out, alpha, 0.0, std::nextafter(1.0, 0.0), name, where, "[0, 1)");
}
// The model's own checks of a spring's description (the registry's trait problems), each failure at where(field).
template <class W> void model_values(std::vector<Problem>& out, const SpringSpec& s, int law, const W& where) {
  model::visit_hysteresis(law, [&]<class H>() {
    H::problems(s, [&](std::string_view field, std::string_view what, std::string_view fix, auto... values) {
      out.push_back({fmt::format(fmt::runtime(what), values...), text(where(field)), std::string(fix)});
    });
  });
}
template <class W> void gap_value(std::vector<Problem>& out, double gap, const W& where) {
  if (!std::isfinite(gap) || gap < 0)
    out.push_back({fmt::format("gap = {} must be >= 0", gap), text(where), "give a gap >= 0 (m)"});
}
// kc and e as the law's traits require; names "kc" and "e" in the system's messages, the where strings in the pair's.
template <class KN, class KW, class EN, class EW>
void contact_values(std::vector<Problem>& out, double kc, double e, const contact::LawTraits& tr, const KN& kc_name,
                    const KW& where_kc, const EN& e_name, const EW& where_e) {
  if (tr.needs_stiffness) positive(out, kc, kc_name, where_kc);
  if (tr.needs_restitution) in_range(out, e, std::nextafter(0.0, 1.0), 1.0, e_name, where_e, "(0, 1]");
}
// Settings and motion, then the Hertz exponent of each model.
void run_settings(std::vector<Problem>& out, std::span<const ContactModel> models, const GroundMotion& motion,
                  const KernelSettings& settings) {
  if (settings.substeps < 1)
    out.push_back({fmt::format("substeps = {} must be >= 1", settings.substeps), "substeps", "give 1 or more"});
  positive(out, motion.dt, "record dt");
  for (const ContactModel& cm : models)
    if (contact::traits(cm.law).uses_exponent) in_range(out, cm.n, 1.0, 3.0, "Hertz exponent n", "[1, 3]");
}

void structure(std::vector<Problem>& out, const Structure& s, const std::string& sfx, Stepper stepper,
               const std::string& lane) {
  auto where = [&](const std::string& what) { return fmt::format("{} (lane {})", what, lane); };
  auto at = [&](const char* what) { return [&where, what, &sfx] { return where(what + sfx); }; };  // lazy
  mass(out, s.m, at("m"), at("m"));
  stiffness(out, s.k, at("k"), at("k"), true);
  dashpot(out, s.c, [&] { return "c" + sfx; }, at("c"));
  yield(out, s.fy, at("fy"), at("fy"));
  hardening(out, s.alpha, at("alpha"), at("alpha"));
  if (stepper != Stepper::nigam_jennings) return;
  positive(out, s.k, [&] { return where("k" + sfx + " (Nigam-Jennings needs k > 0)"); });
  const double zeta = s.c / (2.0 * std::sqrt(s.k * s.m));
  if (!(zeta < 1.0))
    out.push_back({fmt::format("damping ratio {} of structure {} is not below 1", zeta, sfx), where("zeta"),
                   "the Nigam-Jennings stepper needs an under-damped structure"});
}

// Names of a system's places in messages: "building1 floor 2", "building1 storey 2", "contact 'level 3'".
std::string dof_place(const model::System& sys, int d) {
  const model::Body& b = sys.bodies()[static_cast<std::size_t>(sys.body_of(d))];
  const auto pos = static_cast<int>(std::find(b.dofs.begin(), b.dofs.end(), d) - b.dofs.begin());
  if (b.isolated) return pos == 0 ? b.label + " base" : fmt::format("{} floor {}", b.label, pos);
  return fmt::format("{} floor {}", b.label, pos + 1);
}
std::string spring_place(const model::System& sys, std::size_t s) {
  const model::Spring& sp = sys.springs()[s];
  const std::string& label = sys.bodies()[static_cast<std::size_t>(sys.body_of(sp.j))].label;
  switch (sp.role) {
    case model::SpringRole::storey: return fmt::format("{} storey {}", label, sp.storey);
    case model::SpringRole::isolator: return label + " isolator";
    case model::SpringRole::link: break;
  }
  return fmt::format("link spring {}", s);
}

// h >= the structure's longest stable step (structure_step_max: Gershgorin's bounds on M^-1 K0 and, for central
// difference, M^-1 C; §2.2.7), K0 from the springs' initial stiffnesses (contact excluded: it is guarded during the
// run).
void structure_frequency(std::vector<Problem>& out, const SystemBatch& b, std::size_t lane, double dt,
                         const KernelSettings& settings) {
  const StructureStep s = structure_step_max(b, lane, settings.stepper);
  const double h = dt / settings.substeps;
  if (!(h < s.h_max))
    out.push_back({fmt::format("the time step {} s is too long for the structure's highest frequency and damping (h "
                               "<= {:.4g} s needed: h^2 omega^2 + 4 h (2 zeta omega) < 4 with omega_max <= {:.6g} rad/s, "
                               "largest at {}, and 2 zeta omega <= {:.4g} 1/s, Gershgorin bounds)",
                               h, s.h_max, s.omega_max, dof_place(*b.system, s.dof), s.damping),
                   fmt::format("substeps (lane {})", lane),
                   fmt::format("give substeps >= {} (or a smaller dt)", s.substeps(dt))});
}

std::vector<Problem> validate_system_lane(const SystemBatch& b, std::span<const ContactModel> models,
                                          const KernelSettings& settings, double dt, std::size_t lane) {
  std::vector<Problem> out;
  const model::System& sys = *b.system;
  const std::size_t w = b.width;
  // lazy: "field (place, lane N)" is formatted only for a failing check
  auto where = [&](std::string_view field, const auto& place) {
    return [field, &place, lane] { return fmt::format("{} ({}, lane {})", field, place(), lane); };
  };
  for (int d = 0; d < sys.ndof(); ++d) {
    const auto place = [&sys, d] { return dof_place(sys, d); };
    const std::size_t i = SystemBatch::at(d, lane, w);
    mass(out, b.m[i], "m", where("m", place));
    dashpot(out, b.c_floor[i], "c", where("c", place));
    for (const auto& [name, v] : {std::pair{"u0", b.u0[i]}, std::pair{"v0", b.v0[i]}})
      if (!std::isfinite(v))
        out.push_back({fmt::format("{} = {} must be finite", name, v), where(name, place)(), "give a finite value"});
  }
  for (std::size_t bi = 0; bi < sys.bodies().size(); ++bi) {  // classical modal damping: finite, symmetric
    const model::Body& body = sys.bodies()[bi];
    if (body.damping != model::DampingForm::dense) continue;
    const int n = static_cast<int>(body.dofs.size());
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double c = b.c_dense[SystemBatch::at(b.dense_entry(static_cast<int>(bi), j, k), lane, w)];
        const double ct = b.c_dense[SystemBatch::at(b.dense_entry(static_cast<int>(bi), k, j), lane, w)];
        const std::string place = fmt::format("c_dense ({} row {} column {}, lane {})", body.label, j + 1, k + 1, lane);
        if (!std::isfinite(c) || (j == k && c < 0.0))
          out.push_back({fmt::format("C = {} must be finite (and >= 0 on the diagonal)", c), place,
                         "give the classical damping matrix of the building (model::modal_damping_matrix)"});
        else if (std::abs(c - ct) > 1e-9 * (std::abs(c) + std::abs(ct)))
          out.push_back({fmt::format("C is not symmetric ({} against {})", c, ct), place,
                         "give the classical damping matrix of the building (model::modal_damping_matrix)"});
      }
  }
  for (std::size_t s = 0; s < sys.springs().size(); ++s) {
    const auto place = [&sys, s] { return spring_place(sys, s); };
    const std::size_t i = SystemBatch::at(static_cast<int>(s), lane, w);
    stiffness(out, b.spring[i].k, "k", where("k", place), false);
    yield(out, b.spring[i].fy, "fy", where("fy", place));
    hardening(out, b.spring[i].alpha, "alpha", where("alpha", place));
    model_values(out, b.spring[i], sys.springs()[s].law, [&](std::string_view field) { return where(field, place); });
    if (!b.c_storey.empty()) dashpot(out, b.c_storey[i], "c_storey", where("c_storey", place));
  }
  for (std::size_t el = 0; el < sys.contacts().size(); ++el) {
    const model::ContactElement& ce = sys.contacts()[el];
    const auto place = [&ce] { return fmt::format("contact '{}'", ce.label); };
    const std::size_t i = SystemBatch::at(static_cast<int>(el), lane, w);
    gap_value(out, b.gap[i], where("gap", place));
    in_range(out, b.weight[i], 0.0, 1.0, "weight", where("weight", place), "[0, 1]");
    const ContactModel& cm = models[static_cast<std::size_t>(ce.group)];
    contact_values(out, b.kc[i], b.e[i], contact::traits(cm.law), "kc", where("kc", place), "e", where("e", place));
  }
  if (out.empty()) structure_frequency(out, b, lane, dt, settings);
  return out;
}

// D7: Nigam-Jennings is exact for a linear SDOF only; the system layer does not run it (central difference,
// Newmark and RK4 run every system).
void nigam_jennings_bodies(std::vector<Problem>& out, const model::System& sys) {
  for (const model::Body& b : sys.bodies())
    if (b.dofs.size() > 1) {
      out.push_back({fmt::format("nigam-jennings integrates SDOF bodies only ({} has {} floors)", b.label, b.dofs.size()),
                     "stepper", "use central-difference, newmark or rk4"});
      return;
    }
  out.push_back({"nigam-jennings runs the SDOF pair only (rows, isolated bases and bridges are systems)", "stepper",
                 "use central-difference, newmark or rk4"});
}

}  // namespace

double structure_step_limit(Stepper stepper) {
  if (stepper == Stepper::central_difference) return 2.0;
  if (stepper == Stepper::rk4) return 2.8;
  return std::numeric_limits<double>::infinity();
}

// Gershgorin on M^-1 K0: row i of K0 holds k on the diagonal for every spring at i, and -k off it when the other
// end is a DOF (contact excluded: it is guarded during the run).
StructureFrequency structure_omega_max(const SystemBatch& b, std::size_t lane) {
  const model::System& sys = *b.system;
  const std::size_t w = b.width;
  std::vector<double> row(static_cast<std::size_t>(sys.ndof()), 0.0);
  for (std::size_t s = 0; s < sys.springs().size(); ++s) {
    const model::Spring& sp = sys.springs()[s];
    const double k = std::abs(b.spring[SystemBatch::at(static_cast<int>(s), lane, w)].k);
    const double both = sp.i == model::ground ? k : 2.0 * k;  // |K_jj| gains k, |K_ji| too when i is a DOF
    row[static_cast<std::size_t>(sp.j)] += both;
    if (sp.i != model::ground) row[static_cast<std::size_t>(sp.i)] += both;
  }
  double w2 = 0.0;
  int worst = 0;
  for (int d = 0; d < sys.ndof(); ++d) {
    const double r = row[static_cast<std::size_t>(d)] / b.m[SystemBatch::at(d, lane, w)];
    if (r > w2) w2 = r, worst = d;
  }
  return {std::sqrt(w2), worst};
}

// Gershgorin on M^-1 C: a dashpot between two DOFs puts c on the diagonal and -c off it in both rows; one to the
// ground only c in its DOF's row. Floor dashpots go to the ground or to the body's base (floor_dashpot_ref).
double structure_damping_bound(const SystemBatch& b, std::size_t lane) {
  const model::System& sys = *b.system;
  const std::size_t w = b.width;
  std::vector<double> row(static_cast<std::size_t>(sys.ndof()), 0.0);
  for (int d = 0; d < sys.ndof(); ++d) row[static_cast<std::size_t>(d)] = std::abs(b.c_floor[SystemBatch::at(d, lane, w)]);
  for (const model::Body& body : sys.bodies())  // floor dashpots to an isolated base: c in both rows, twice
    if (body.floor_dashpot_ref != model::ground)
      for (int d : body.dofs) {
        if (d == body.floor_dashpot_ref) continue;
        const double c = std::abs(b.c_floor[SystemBatch::at(d, lane, w)]);
        row[static_cast<std::size_t>(d)] += c;
        row[static_cast<std::size_t>(body.floor_dashpot_ref)] += 2.0 * c;
      }
  if (!b.c_storey.empty())
    for (std::size_t s = 0; s < sys.springs().size(); ++s) {
      const model::Spring& sp = sys.springs()[s];
      const double c = std::abs(b.c_storey[SystemBatch::at(static_cast<int>(s), lane, w)]);
      row[static_cast<std::size_t>(sp.j)] += sp.i == model::ground ? c : 2.0 * c;
      if (sp.i != model::ground) row[static_cast<std::size_t>(sp.i)] += 2.0 * c;
    }
  for (std::size_t bi = 0; bi < sys.bodies().size(); ++bi) {  // dense damping: sum_k |C_jk| in row j
    const model::Body& body = sys.bodies()[bi];
    if (body.damping != model::DampingForm::dense) continue;
    const int n = static_cast<int>(body.dofs.size());
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        row[static_cast<std::size_t>(body.dofs[static_cast<std::size_t>(j)])] +=
            std::abs(b.c_dense[SystemBatch::at(b.dense_entry(static_cast<int>(bi), j, k), lane, w)]);
  }
  double bound = 0.0;
  for (int d = 0; d < sys.ndof(); ++d)
    bound = std::max(bound, row[static_cast<std::size_t>(d)] / b.m[SystemBatch::at(d, lane, w)]);
  return bound;
}

double StructureStep::substeps(double dt) const { return std::floor(dt / h_max) + 1.0; }

StructureStep structure_step_max(const SystemBatch& b, std::size_t lane, Stepper stepper) {
  const StructureFrequency f = structure_omega_max(b, lane);
  StructureStep s{std::numeric_limits<double>::infinity(), f.omega_max, 0.0, f.dof};
  if (stepper == Stepper::central_difference) {
    // 2 (sqrt(C^2 + W^2) - C) / W^2 without the cancellation (and 1 / C for W = 0)
    s.damping = structure_damping_bound(b, lane);
    const double r = s.damping + std::sqrt(s.damping * s.damping + f.omega_max * f.omega_max);
    if (r > 0.0) s.h_max = 2.0 / r;
  } else if (f.omega_max > 0.0) {
    s.h_max = structure_step_limit(stepper) / f.omega_max;
  }
  return s;
}

std::vector<Problem> validate_lane(const PairParams& p, const ContactModel& cm, Stepper stepper, std::size_t lane) {
  std::vector<Problem> out;
  const std::string ln = std::to_string(lane);
  structure(out, p.s1, "1", stepper, ln);
  structure(out, p.s2, "2", stepper, ln);
  gap_value(out, p.gap, [&] { return fmt::format("gap (lane {})", ln); });
  auto kc = [&] { return fmt::format("kc (lane {})", ln); };
  auto e = [&] { return fmt::format("e (lane {})", ln); };
  contact_values(out, p.kc, p.e, contact::traits(cm.law), kc, kc, e, e);
  return out;
}

std::vector<Problem> validate(const SystemBatch& batch, std::span<const ContactModel> models,
                              const GroundMotion& motion, const KernelSettings& settings) {
  std::vector<Problem> out;
  if (batch.system == nullptr) throw std::logic_error("validate: a SystemBatch without its System");
  const model::System& sys = *batch.system;
  if (models.size() != sys.groups().size()) {
    out.push_back({fmt::format("{} contact models for {} contact groups", models.size(), sys.groups().size()),
                   "contact groups", "give one contact model per contact group of the system"});
    return out;
  }
  // The pair keeps today's checks and messages (its run goes to the pair kernel, whose guards catch the rest).
  if (sys.is_sdof_pair()) return validate(to_pair_batch(batch), models[0], motion, settings);
  run_settings(out, models, motion, settings);
  if (settings.restitution != nullptr)  // the system stepper's onset (system_central_difference.hpp restitution_onset)
    for (std::size_t g = 0; g < models.size(); ++g)
      if (models[g].law != ContactLaw::hertzdamp || models[g].damping != models[0].damping) {
        out.push_back({fmt::format("a velocity-dependent restitution e(v0) runs with hertzdamp (one damping law) in "
                                   "every contact group, and group {} ('{}') has {} with {}",
                                   g + 1, sys.groups()[g].name, to_string(models[g].law), to_string(models[g].damping)),
                       "restitution", "use hertzdamp in every contact group, or a constant e"});
        break;
      }
  if (settings.stepper == Stepper::nigam_jennings) nigam_jennings_bodies(out, sys);
  for (std::size_t g = 0; g < models.size(); ++g)
    if (contact::traits(models[g].law).impulsive && sys.contacts().size() != 1)
      out.push_back({fmt::format("the impulsive (stereomechanical) law is defined for one contact element, and the "
                                 "system has {}", sys.contacts().size()),
                     fmt::format("contact law of group '{}'", sys.groups()[g].name),
                     "use a force-based law (simultaneous impulses depend on their order)"});
  const std::size_t w = batch.width;
  const auto d = static_cast<std::size_t>(sys.ndof()), s = sys.springs().size(), e = sys.contacts().size();
  const bool sized = batch.m.size() == d * w && batch.c_floor.size() == d * w && batch.u0.size() == d * w &&
                     batch.v0.size() == d * w && batch.spring.size() == s * w && batch.gap.size() == e * w &&
                     batch.weight.size() == e * w && batch.kc.size() == e * w && batch.e.size() == e * w &&
                     batch.c_storey.size() == (sys.any_storey_dashpots() ? s * w : 0) &&
                     batch.dense_base.size() == sys.bodies().size();
  if (!sized) throw std::logic_error("validate: a SystemBatch not sized for its System (SystemBatch::resize)");
  if (!out.empty()) return out;
  for (std::size_t lane = 0; lane < w; ++lane) {
    out = validate_system_lane(batch, models, settings, motion.dt, lane);
    if (!out.empty()) return out;
  }
  return out;
}

std::vector<Problem> validate(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion,
                              const KernelSettings& settings) {
  std::vector<Problem> out;
  run_settings(out, std::span<const ContactModel>(&cm, 1), motion, settings);
  if (settings.restitution != nullptr &&
      (settings.stepper != Stepper::central_difference || cm.law != ContactLaw::hertzdamp))
    out.push_back({fmt::format("a velocity-dependent restitution e(v0) runs with hertzdamp and central-difference "
                               "only (here {} and {})",
                               to_string(cm.law), to_string(settings.stepper)),
                   "restitution", "use --contact hertzdamp --stepper central-difference, or a constant e"});
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
