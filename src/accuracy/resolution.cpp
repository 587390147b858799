// The accuracy limit of every stepper x force law (the laws' declared resolution limits, physics/resolution.hpp), measured
// on one free impact. See include/pounding/accuracy/accuracy.hpp, "Resolution".
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "pounding/accuracy/accuracy.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/single_impact.hpp"

namespace pounding::accuracy {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double v0 = 1.0, m = 1.0, e_target = 0.65;
constexpr double h_omega_min = 0.01, h_omega_max = 2.0, h_omega_converged = 0.002;

struct SchemeSpec {
  Stepper stepper;
  bool locate;
};
SchemeSpec scheme_spec(const std::string& name) {
  if (name == "rk4-located") return {Stepper::rk4, true};
  return {parse_stepper(name), false};
}

// Contact stiffness kc = 0.5: N/m for linear/Kelvin (omega_c = 1 rad/s with meff = 0.5 kg), N/m^1.5 for the
// Hertz family (omega_c 1.25 rad/s at the peak of a 1 m/s impact). The structures' springs are 1e-6 of it.
double stiffness_of(ContactLaw) { return 0.5; }

struct Impact {
  ContactModel cm;
  double tc = 0;  // estimated contact duration
  double omega_nominal = 0;  // for the step grid only (the rows report the lane's own h omega_c)
};
Impact impact_of(const std::string& law) {
  Impact im;
  im.cm.law = parse_contact_law(law);
  const double kc = stiffness_of(im.cm.law);
  im.tc = estimated_contact_duration(im.cm, v0, m, m, kc);
  im.omega_nominal = std::numbers::pi / im.tc;  // exact for linear; within ~20 % for the Hertz family
  return im;
}

// One run of `phases` lanes (onset at (j + 0.5) / phases of a step) with `steps` steps over 3 tc.
BatchResult run_impact(const Impact& im, const SchemeSpec& sc, long steps, int phases) {
  const double total = 3.0 * im.tc, h = total / static_cast<double>(steps);
  const double kc = stiffness_of(im.cm.law);
  PairBatch b;
  b.resize(static_cast<std::size_t>(phases));
  for (int j = 0; j < phases; ++j) {
    PairParams p;
    p.s1 = {m, 1e-6 * kc, 0.0};
    p.s2 = {m, 1e-6 * kc, 0.0};
    p.kc = kc, p.e = e_target, p.v1 = v0;
    p.u1 = -v0 * h * (1.0 + (j + 0.5) / phases);  // closes inside the second step
    b.set(static_cast<std::size_t>(j), p);
  }
  std::vector<double> ag{0.0, 0.0};
  GroundMotion gm{total, ag, 0.0};
  KernelSettings ks;
  ks.stepper = sc.stepper, ks.locate_contact = sc.locate;
  ks.substeps = static_cast<int>(steps);
  ks.displacement_limit = 1e6;
  BatchResult r;
  run_batch(b, im.cm, gm, ks, r);
  return r;
}

int severity(std::uint8_t s) {  // ok < coarse < diverged < non-finite
  return s == 0 ? 0 : s == static_cast<std::uint8_t>(LaneStatus::coarse) ? 1 : s + 1;
}

ResolutionPoint reduce(const BatchResult& r, double F_ref, double e_ref) {
  ResolutionPoint p;
  p.h_omega_contact = nan, p.force_error = 0, p.e_error = 0;
  std::uint8_t worst = 0;
  for (std::size_t j = 0; j < r.width(); ++j) {
    if (severity(r.status[j]) > severity(worst)) worst = r.status[j];
    const double F = r.peak_force[j], e = (r.final_v2[j] - r.final_v1[j]) / v0;
    const double fe = std::abs(F - F_ref) / F_ref, ee = std::abs(e - e_ref);
    if (!(fe <= p.force_error)) p.force_error = std::isnan(fe) ? std::numeric_limits<double>::infinity() : fe, p.peak_force = F;
    if (!(ee <= p.e_error)) p.e_error = std::isnan(ee) ? std::numeric_limits<double>::infinity() : ee, p.e_effective = e;
    p.h_omega_contact = std::fmax(p.h_omega_contact, r.h_omega_contact[j]);  // a diverged lane's NaN is skipped
  }
  p.status = std::string(to_string(static_cast<LaneStatus>(worst)));
  return p;
}

}  // namespace

std::vector<std::string> resolution_schemes() {
  return {"central-difference", "newmark", "rk4", "rk4-located", "nigam-jennings"};
}
std::vector<std::string> resolution_laws() {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < contact::law_names.size(); ++i)
    if (contact::law_traits[i].has_force) out.emplace_back(contact::law_names[i]);
  return out;
}

std::vector<ResolutionPoint> resolution_sweep(const std::vector<std::string>& schemes,
                                              const std::vector<std::string>& laws, int points_per_decade,
                                              int phases) {
  require_positive(points_per_decade, "--points-per-decade");
  require_positive(phases, "--phases");
  std::vector<ResolutionPoint> out;
  for (const auto& law : laws) {
    const Impact im = impact_of(law);
    if (!contact::traits(im.cm.law).has_force)
      throw InputError("contact law '" + law + "' has no force element, so no contact frequency", "--laws",
                       "give laws with a force element (" +
                           contact::law_names_where([](const contact::LawTraits& t) { return t.has_force; }) + ")");
    // the converged impact: rk4 with located onset at h omega_c = 0.002, one phase
    const auto steps_of = [&](double x) { return std::lround(3.0 * im.tc * im.omega_nominal / x); };
    const BatchResult ref = run_impact(im, {Stepper::rk4, true}, steps_of(h_omega_converged), 1);
    const double F_ref = ref.peak_force[0], e_ref = (ref.final_v2[0] - ref.final_v1[0]) / v0;
    for (const auto& name : schemes) {
      const SchemeSpec sc = scheme_spec(name);
      long last = -1;
      for (int k = 0;; ++k) {
        const double x = h_omega_min * std::pow(10.0, static_cast<double>(k) / points_per_decade);
        if (x > h_omega_max) break;
        const long steps = steps_of(x);
        if (steps == last) continue;
        last = steps;
        ResolutionPoint p = reduce(run_impact(im, sc, steps, phases), F_ref, e_ref);
        p.scheme = name, p.law = law, p.steps = static_cast<int>(steps);
        out.push_back(p);
      }
    }
  }
  return out;
}

std::vector<ResolutionLimit> resolution_limits(const std::vector<ResolutionPoint>& points, double tolerance) {
  std::vector<ResolutionLimit> out;
  for (std::size_t i = 0; i < points.size();) {
    std::size_t j = i;
    while (j < points.size() && points[j].scheme == points[i].scheme && points[j].law == points[i].law) ++j;
    // in sweep order (the step grows; a diverged row has no h omega_c of its own)
    std::vector<const ResolutionPoint*> g;
    for (std::size_t q = i; q < j; ++q) g.push_back(&points[q]);
    ResolutionLimit L;
    L.scheme = points[i].scheme, L.law = points[i].law;
    L.first_over = std::numeric_limits<double>::infinity();
    double last_ok = 0;
    for (auto* p : g) {
      if (!(p->force_error <= tolerance) || p->status == "diverged" || p->status == "non-finite") {
        L.first_over = p->h_omega_contact;
        break;
      }
      last_ok = std::max(last_ok, p->h_omega_contact);
    }
    L.limit = std::floor(last_ok * 1000.0) / 1000.0;
    out.push_back(L);
    i = j;
  }
  return out;
}

}  // namespace pounding::accuracy
