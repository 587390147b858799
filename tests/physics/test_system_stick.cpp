// The system stepper's stick path (physics/steppers/system_central_difference.hpp, stick_walk; Layout::stick) against
// its generic path (physics::testing::run_system_generic): every observer of every lane bit for bit, with and without
// energy, for shear sticks side by side, a row of three, a building against a wall and a row of SDOFs, under
// several contact laws, with yielding storeys and one lane diverging (the guard's freeze).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "pounding/contact/registry.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_stepper.hpp"
#include "pounding/workloads/workloads.hpp"
#include "system_test_support.hpp"

using namespace pounding;
using namespace pounding::physics;

namespace {

// Every array of `r` as raw bytes, field by field.
std::vector<std::vector<unsigned char>> fields(const SystemResult& r) {
  std::vector<std::vector<unsigned char>> out;
  auto put = [&](const auto& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    out.emplace_back(p, p + v.size() * sizeof(v[0]));
  };
  for (const auto* v : {&r.peak_u, &r.peak_acc, &r.final_u, &r.final_v, &r.peak_drift, &r.peak_spring_force,
                        &r.peak_closing, &r.t_peak_closing, &r.t_first_impact, &r.peak_force, &r.peak_penetration,
                        &r.contact_energy, &r.contact_time, &r.h_omega_contact, &r.e_input, &r.e_kinetic, &r.e_strain,
                        &r.e_viscous, &r.e_hysteretic, &r.e_contact_stored})
    put(*v);
  put(r.impact_count), put(r.clamp_count), put(r.restitution_outside), put(r.status);
  return out;
}

const char* const field_names[] = {"peak_u", "peak_acc", "final_u", "final_v", "peak_drift", "peak_spring_force",
                                   "peak_closing", "t_peak_closing", "t_first_impact", "peak_force",
                                   "peak_penetration", "contact_energy", "contact_time", "h_omega_contact", "e_input",
                                   "e_kinetic", "e_strain", "e_viscous", "e_hysteretic", "e_contact_stored",
                                   "impact_count", "clamp_count", "restitution_outside", "status"};

// `width` lanes of system S: every body a yielding stick with Rayleigh damping whose numbers vary per lane, every
// element's gap, kc and e varied; lane 5 starts past the displacement limit (diverged in step 1), lanes 6 and 7 at
// huge velocities.
SystemBatch batch(const model::System& S, std::size_t width, double gap) {
  SystemBatch B;
  B.resize(S, width);
  std::mt19937_64 rng(2025);
  std::uniform_real_distribution<double> u(0.85, 1.15);
  for (std::size_t l = 0; l < width; ++l) {
    for (std::size_t b = 0; b < S.bodies().size(); ++b) {
      const std::size_t n = S.bodies()[b].dofs.size();
      test::Stick s;
      for (std::size_t k = 0; k < n; ++k) {
        s.m.push_back(2.5e5 * u(rng)), s.k.push_back((3.0e8 - 2.0e7 * static_cast<double>(k)) * u(rng));
        s.fy.push_back(s.k.back() * 0.012 * u(rng));
      }
      s.alpha = 0.05;
      test::rayleigh(s, 0.05 * u(rng), 12.0 / static_cast<double>(n), 40.0 / static_cast<double>(n));
      test::fill_stick(B, static_cast<int>(b), l, s);
    }
    for (std::size_t e = 0; e < S.contacts().size(); ++e) {
      const std::size_t at = SystemBatch::at(static_cast<int>(e), l, width);
      B.gap[at] = gap * u(rng), B.kc[at] = 1.0e10 * u(rng), B.e[at] = 0.6 * u(rng);
    }
  }
  if (width > 5) B.u0[SystemBatch::at(S.ndof() - 1, 5, width)] = 20.0;
  // lanes 6 and 7 diverge with |v| + |a| near and past the overflow (the walk's rate measure hands over to the
  // index-order sum, stick_walk)
  if (width > 7) B.v0[SystemBatch::at(0, 6, width)] = 3e299, B.v0[SystemBatch::at(0, 7, width)] = 1e307;
  return B;
}

ContactModel law(ContactLaw l, double n = 1.5) {
  ContactModel cm;
  cm.law = l, cm.n = n;
  return cm;
}

// Runs B through the stick path (run_system) and the generic path, with and without energy, under `cm`; every field
// bit for bit. Returns the total impact count (the runs must pound).
long compare(const SystemBatch& B, const ContactModel& cm, const std::string& what, bool lane5_diverges = true,
             const VelocityRestitution* restitution = nullptr) {
  EXPECT_TRUE(physics::testing::stick_path(*B.system)) << what << ": the stick path must run this topology";
  const std::vector<double> ag = builtin_motion(0.01, 5.0);
  const GroundMotion gm{0.01, ag, 0.0};
  std::vector<ContactModel> groups(B.system->groups().size(), cm);
  long impacts = 0;
  for (bool energy : {false, true}) {
    KernelSettings ks;
    ks.substeps = 4, ks.energy = energy, ks.restitution = restitution;
    SystemResult fast, ref;
    run_system(B, groups, gm, ks, fast);
    physics::testing::run_system_generic(B, groups, gm, ks, ref);
    const auto a = fields(fast), b = fields(ref);
    for (std::size_t f = 0; f < a.size(); ++f)
      EXPECT_TRUE(a[f] == b[f]) << what << (energy ? ", energy" : "") << ": " << field_names[f] << " differs";
    for (std::int32_t n : fast.impact_count) impacts += n;
    if (lane5_diverges) {
      EXPECT_EQ(fast.status[5], static_cast<std::uint8_t>(LaneStatus::diverged)) << what;
    }
  }
  return impacts;
}

std::vector<ContactModel> laws() {
  return {law(ContactLaw::hertzdamp), law(ContactLaw::linear), law(ContactLaw::kelvin), law(ContactLaw::hertz, 1.3)};
}

}  // namespace

// A 3- vs 5-storey pair, DOFs level-major (test::shear_row) and body by body (model::shear_buildings), Hertzdamp,
// linear, Kelvin and Hertz with n = 1.3 at the three common floors.
TEST(SystemStick, ThreeVersusFiveStoreysIsTheGenericPath) {
  if (!test::bits_claimed()) GTEST_SKIP() << std::getenv("POUNDING_BITS_NOT_CLAIMED");
  std::vector<model::StickTopology> sticks(2);
  sticks[0].storeys = 3, sticks[1].storeys = 5;
  for (const model::System& S : {test::shear_row({3, 5}, true), model::shear_buildings(sticks)})
    for (const ContactModel& cm : laws())
      EXPECT_GT(compare(batch(S, 37, 0.01), cm, std::string(to_string(cm.law))), 20);
}

// e(v0) at every onset (KernelSettings::restitution, the element's latched damping): a made-up curve e = 0.8 - 0.3 v0
// (v0 in m/s, clamped at 0.2), its Hertzdamp damping 8 (1 - e) / (5 e), v0 above 1 m/s counted outside.
TEST(SystemStick, VelocityDependentRestitutionIsTheGenericPath) {
  if (!test::bits_claimed()) GTEST_SKIP() << std::getenv("POUNDING_BITS_NOT_CLAIMED");
  VelocityRestitution r;
  r.damping = [](const void*, double v0) {
    const double e = std::max(0.8 - 0.3 * v0, 0.2);
    return 8.0 * (1.0 - e) / (5.0 * e);
  };
  r.outside = [](const void*, double v0) { return v0 > 1.0; };
  std::vector<model::StickTopology> sticks(2);
  sticks[0].storeys = 3, sticks[1].storeys = 5;
  EXPECT_GT(compare(batch(model::shear_buildings(sticks), 21, 0.01), law(ContactLaw::hertzdamp), "e(v0)", true, &r), 20);
}

// A row of three buildings (5, 3, 4 storeys) and a row of three SDOFs.
TEST(SystemStick, RowsAreTheGenericPath) {
  if (!test::bits_claimed()) GTEST_SKIP() << std::getenv("POUNDING_BITS_NOT_CLAIMED");
  std::vector<model::StickTopology> sticks(3);
  sticks[0].storeys = 5, sticks[1].storeys = 3, sticks[2].storeys = 4;
  for (const ContactModel& cm : laws())
    EXPECT_GT(compare(batch(model::shear_buildings(sticks), 21, 0.01), cm, "row 5-3-4"), 10);
  EXPECT_GT(compare(batch(test::shear_row({1, 1, 1}, true), 19, 1e-4), law(ContactLaw::hertzdamp), "SDOF row"), 10);
}

// A 4-storey building against a wall at its roof and at its second floor (wall on the right of one, on the left of
// the other), and the bench's shear pair.
TEST(SystemStick, WallAndBenchPairAreTheGenericPath) {
  if (!test::bits_claimed()) GTEST_SKIP() << std::getenv("POUNDING_BITS_NOT_CLAIMED");
  model::System::Parts P;
  P.bodies.push_back({{0, 1, 2, 3}, {3.2, 6.4, 9.6, 12.8}, 0, model::ground, true, model::DampingForm::dashpots, false,
                      "building1"});
  for (int k = 0; k < 4; ++k) P.springs.push_back({k == 0 ? model::ground : k - 1, k, 0, model::SpringRole::storey, 0, k + 1});
  P.contacts.push_back({{model::SideKind::point, 3, -1, 0}, {model::SideKind::wall, -1, -1, 0}, 0, 4, "roof wall"});
  P.contacts.push_back({{model::SideKind::wall, -1, -1, 0}, {model::SideKind::point, 1, -1, 0}, 0, 2, "floor 2 wall"});
  P.groups.push_back(model::ContactGroup{"walls", false});
  const model::System S = model::System::build(P);
  for (const ContactModel& cm : laws()) EXPECT_GT(compare(batch(S, 19, 0.004), cm, "wall"), 10);
  const model::System pair = pounding::shear_pair_system(5);
  compare(pounding::shear_pair_batch(pair, 16), law(ContactLaw::hertzdamp), "bench pair", false);
}

// What the stick path leaves to the generic path: an isolated base (floor dashpots to the base), modal damping rows,
// floor-to-column elements.
TEST(SystemStick, OtherTopologiesKeepTheGenericPath) {
  std::vector<model::StickTopology> sticks(2);
  sticks[0].storeys = 3, sticks[1].storeys = 5;
  EXPECT_TRUE(physics::testing::stick_path(model::shear_buildings(sticks)));
  sticks[0].isolated = true;
  EXPECT_FALSE(physics::testing::stick_path(model::shear_buildings(sticks)));
  sticks[0].isolated = false, sticks[1].storey_heights = {2.5};  // floors against columns
  EXPECT_FALSE(physics::testing::stick_path(model::shear_buildings(sticks)));
  EXPECT_FALSE(physics::testing::stick_path(test::shear_row({3, 5}, true, true)));
}
