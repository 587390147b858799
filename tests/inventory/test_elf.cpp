// ASCE 7-16 ELF design of a building from a few numbers against a hand calculation and tools/elf_reference.py.
#include <gtest/gtest.h>

#include <cmath>

#include "pounding/core/error.hpp"
#include "pounding/inventory/elf.hpp"
#include "pounding/model/modes.hpp"

using namespace pounding;
using namespace pounding::inventory;

namespace {

// research/inventory-and-design.md section 3: 5-storey special RC moment frame, storeys 3.2 m (hn 16 m), 4.5e5 kg per
// floor (450 m^2 at 9.80665 kPa), Ie 1, SDS 1.0 g, SD1 0.6 g, S1 0.6 g, TL 8 s.
DesignInput worked_example() {
  DesignInput in;
  in.system = "rc-smf";
  in.storeys = 5;
  in.storey_height = {3.2};
  in.plan_area = 450;
  in.unit_weight = 9.80665;
  in.sds = 1.0;
  in.sd1 = 0.6;
  in.s1 = 0.6;
  in.tl = 8;
  in.where = "test";
  return in;
}

}  // namespace

// By hand: Ta = 0.0466 x 16^0.9 = 0.0466 x 12.1258 = 0.56506 s (12.8-7, Table 12.8-2); Cu = 1.4 (SD1 >= 0.4);
// T = 0.79108 s. Cs: SDS/(R/Ie) = 0.125; SD1/(T R/Ie) = 0.6/(0.79108 x 8) = 0.094807 (governs); 0.044 SDS Ie = 0.044;
// 0.5 S1/(R/Ie) = 0.0375. W = 5 x 4.5e5 x 9.80665 = 22.065 MN; V = 2.0919 MN; k = 1 + (0.79108 - 0.5)/2 = 1.14554.
TEST(Elf, WorkedExampleByHand) {
  const DesignedBuilding b = design_elf(worked_example());
  EXPECT_NEAR(b.hn, 16.0, 1e-12);
  EXPECT_NEAR(b.ta, 0.56506, 5e-5);
  EXPECT_DOUBLE_EQ(b.cu, 1.4);
  EXPECT_NEAR(b.period, 0.79108, 5e-5);
  EXPECT_EQ(b.period_rule, "Cu Ta");
  EXPECT_NEAR(b.cs.cs, 0.094807, 5e-6);
  EXPECT_EQ(b.cs.governs, "SD1/(T R/Ie)");
  EXPECT_NEAR(b.weight, 22.0650e6, 100);
  EXPECT_NEAR(b.base_shear, 2.0919e6, 100);
  EXPECT_NEAR(b.k, 1.14554, 5e-5);
  double sum = 0;
  for (double f : b.fx) sum += f;
  EXPECT_NEAR(sum, b.base_shear, 1e-6 * b.base_shear);  // 12.8-11: the forces add up to V
  EXPECT_NEAR(b.vx.front(), b.base_shear, 1e-6 * b.base_shear);
}

// tools/elf_reference.py --storeys 5 --storey-height 3.2 --floor-mass 4.5e5 --sds 1.0 --sd1 0.6 --s1 0.6 --tl 8 --r 8
// --omega0 3 --ct 0.0466 --x 0.9 (an independent script: scipy's eigensolver for the period scaling).
TEST(Elf, WorkedExampleAgainstTheReferenceScript) {
  const DesignedBuilding b = design_elf(worked_example());
  const double fx[] = {116564.0654, 257873.6736, 410323.9187, 570491.6974, 736654.3536};
  const double vx[] = {2091907.709, 1975343.643, 1717469.97, 1307146.051, 736654.3536};
  const double k[] = {417365476.4, 394109279.9, 342659797.6, 260794313.3, 146973068.6};
  const double vy[] = {6275723.126, 5926030.93, 5152409.909, 3921438.153, 2209963.061};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(b.fx[i], fx[i], 1e-8 * fx[i]) << i;
    EXPECT_NEAR(b.vx[i], vx[i], 1e-8 * vx[i]) << i;
    EXPECT_NEAR(b.stiffness[i], k[i], 1e-8 * k[i]) << i;
    EXPECT_NEAR(b.strength[i], vy[i], 1e-8 * vy[i]) << i;
    EXPECT_DOUBLE_EQ(b.model_stiffness[i], b.stiffness[i]);  // no P-Delta asked
  }
  const model::Modes m = model::shear_stick_modes(b.floor_mass, b.stiffness);
  EXPECT_NEAR(m.period.front(), b.period, 1e-12 * b.period);
}

TEST(Elf, PDeltaReparametrisesTheBilinearSpring) {
  DesignInput in = worked_example();
  in.p_delta = true;
  const DesignedBuilding b = design_elf(in);
  // tools/elf_reference.py: Kpd1, alpha_pd1, Vy_pd1 and storey 5's
  EXPECT_NEAR(b.model_stiffness[0], 410470175.6, 1e-8 * 410470175.6);
  EXPECT_NEAR(b.model_alpha[0], 0.03404138441, 1e-9);
  EXPECT_NEAR(b.model_strength[0], 6172041.818, 1e-8 * 6172041.818);
  EXPECT_NEAR(b.model_stiffness[4], 145594008.5, 1e-8 * 145594008.5);
  EXPECT_NEAR(b.model_alpha[4], 0.04100164106, 1e-9);
  // Post-yield slope and the bounds' offset are those of F(d) - (P/h) d.
  for (std::size_t i = 0; i < 5; ++i) {
    const double kg = b.gravity_load[i] / b.storey_height[i];
    EXPECT_NEAR(b.model_alpha[i] * b.model_stiffness[i], b.alpha * b.stiffness[i] - kg, 1e-6 * b.stiffness[i]);
    EXPECT_NEAR((1 - b.model_alpha[i]) * b.model_strength[i], (1 - b.alpha) * b.strength[i], 1e-6 * b.strength[i]);
  }
  EXPECT_NEAR(b.gravity_load[0], b.weight, 1e-6 * b.weight);
}

TEST(Elf, CoefficientBounds) {
  // Cu: Table 12.8-1 interpolated
  EXPECT_DOUBLE_EQ(asce7_cu(0.5), 1.4);
  EXPECT_DOUBLE_EQ(asce7_cu(0.05), 1.7);
  EXPECT_NEAR(asce7_cu(0.25), 1.45, 1e-12);
  EXPECT_NEAR(asce7_cu(0.125), 1.65, 1e-12);
  // Cs: each bound governs somewhere
  EXPECT_EQ(asce7_cs(1.0, 0.6, 0.5, 8, 0.3, 8, 1).governs, "SDS/(R/Ie)");
  EXPECT_EQ(asce7_cs(1.0, 0.6, 0.5, 4, 6.0, 8, 1).governs, "0.044 SDS Ie");
  EXPECT_EQ(asce7_cs(0.1, 0.08, 0.05, 4, 6.0, 8, 1).governs, "0.01");
  const SeismicCoefficient s1 = asce7_cs(1.0, 0.9, 1.2, 8, 3.0, 8, 1);  // SD1/(T R) = 0.0375 < 0.5 S1 / R = 0.075
  EXPECT_EQ(s1.governs, "0.5 S1/(R/Ie)");
  EXPECT_NEAR(s1.cs, 0.075, 1e-12);
  const SeismicCoefficient tl = asce7_cs(2.0, 2.0, 0.5, 4, 5.0, 3, 1);  // SD1 TL / (T^2 R) = 8 / 75
  EXPECT_EQ(tl.governs, "SD1 TL/(T^2 R/Ie)");
  EXPECT_NEAR(tl.cs, 8.0 / 75.0, 1e-12);
  EXPECT_DOUBLE_EQ(asce7_k(0.4), 1.0);
  EXPECT_DOUBLE_EQ(asce7_k(3.0), 2.0);
  EXPECT_DOUBLE_EQ(asce7_k(1.5), 1.5);
}

TEST(Elf, MeasuredPeriodAndEras) {
  DesignInput in = worked_example();
  in.period = 1.2;  // longer than Cu Ta: the forces use Cu Ta (12.8.2), the model the measured period
  in.level = DesignLevel::moderate;
  const DesignedBuilding b = design_elf(in);
  EXPECT_EQ(b.period_rule, "measured");
  EXPECT_NEAR(b.design_period, 0.79108, 5e-5);
  EXPECT_NEAR(model::shear_stick_modes(b.floor_mass, b.stiffness).period.front(), 1.2, 1e-12);
  EXPECT_NEAR(b.strength[0], 3 * 0.5 * b.vx[0], 1e-9 * b.vx[0]);
}

// An ordinary frame of a pre-code era takes the capacity of the modern special frame (its family's reference) at the
// same period, times Omega0 3 and the era factor 1/4; its own R = 3 sets its design forces only.
TEST(Elf, OldBuildingsTakeTheirFamilysModernCapacity) {
  DesignInput in = worked_example();
  in.system = "rc-omf";
  in.level = DesignLevel::pre_code;
  const DesignedBuilding b = design_elf(in);
  EXPECT_NEAR(b.cs.cs, 0.25282, 5e-5);  // SD1/(T R/Ie) = 0.6 / (0.79108 x 3) with its own R = 3
  EXPECT_EQ(b.reference->key, "rc-smf");
  EXPECT_NEAR(b.cs_reference.cs, 0.094807, 5e-6);    // the worked example's Cs
  EXPECT_NEAR(b.strength[0], 3 * 0.25 * 0.0948068 * b.weight, 1e-5 * b.strength[0]);
  in.system = "urm-wall";
  EXPECT_EQ(design_elf(in).reference->key, "rm-special-wall");
}

TEST(Elf, BadInputNamesTheField) {
  auto refused = [](DesignInput in, const char* field) {
    try {
      design_elf(in);
      ADD_FAILURE() << field << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(e.where().find(field), std::string::npos) << e.where();
    }
  };
  DesignInput in = worked_example();
  in.storeys = 0;
  refused(in, "storeys");
  in = worked_example();
  in.system = "rc-sfm";
  refused(in, "system");
  in = worked_example();
  in.storey_height = {3, 3};
  refused(in, "storey_height");
  in = worked_example();
  in.plan_area = 0;
  refused(in, "plan_area");
  in = worked_example();
  in.sd1 = 0;
  refused(in, "SD1");
}

// The P-Delta re-parametrisation against the spring itself: on a cyclic path with small inner loops the bilinear
// kinematic spring (k', Fy', alpha') gives F(d; k, Fy, alpha) - (P/h) d at every step.
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
TEST(Elf, PDeltaSpringOnACyclicPath) {
  DesignInput in = worked_example();
  in.p_delta = true;
  const DesignedBuilding b = design_elf(in);
  const std::size_t i = 0;
  const double kg = b.gravity_load[i] / b.storey_height[i];
  using BK = model::BilinearKinematic;
  Structure bare{}, pd{};
  bare.k = b.stiffness[i], bare.fy = b.strength[i], bare.alpha = b.alpha;
  pd.k = b.model_stiffness[i], pd.fy = b.model_strength[i], pd.alpha = b.model_alpha[i];
  const auto p0 = BK::params(bare), p1 = BK::params(pd);
  const double dy = b.strength[i] / b.stiffness[i];
  double d = 0, f0 = 0, f1 = 0, worst = 0;
  for (int s = 1; s <= 4000; ++s) {  // 4 dy amplitude, with an inner loop of 0.3 dy every 50 steps
    const double t = s / 4000.0;
    const double next = 4 * dy * std::sin(6 * M_PI * t) + 0.3 * dy * std::sin(2 * M_PI * s / 50.0);
    f0 = BK::restoring(p0, f0, next - d, next);
    f1 = BK::restoring(p1, f1, next - d, next);
    d = next;
    worst = std::max(worst, std::abs(f1 - (f0 - kg * d)));
  }
  EXPECT_LT(worst, 1e-8 * b.strength[i]);
}

// 11.4.8 exception 2 (site class D, S1 >= 0.2): Ss 1.5, S1 0.6 on D: Fa 1.0, Fv 1.7 (for TS only): SDS 1.0, SD1 0.68,
// TS 0.68 s. The worked example's T = Cu Ta = 0.791 s <= 1.5 TS = 1.02 s: Cs = SDS/(R/Ie) = 0.125 (no 12.8-3 cap).
// A 12-storey frame: hn 38.4 m, Ta = 0.0466 x 38.4^0.9 = 0.0466 x 26.662 = 1.24246 s, T = 1.73945 s > 1.02 s:
// Cs = 1.5 SD1/(T R/Ie) = 1.5 x 0.68 / (1.73945 x 8) = 0.073299.
TEST(Elf, SiteClassDByException2) {
  DesignInput in = worked_example();
  Asce7MapValues maps;
  maps.ss = 1.5, maps.s1 = 0.6, maps.site = Asce7SiteClass::D, maps.tl = 8;
  set_design_values(in, maps);
  EXPECT_TRUE(in.exception_2);
  EXPECT_NEAR(in.sds, 1.0, 1e-12);
  EXPECT_NEAR(in.sd1, 0.68, 1e-12);
  const DesignedBuilding low = design_elf(in);
  EXPECT_NEAR(low.cs.cs, 0.125, 1e-12);
  EXPECT_NE(low.cs.governs.find("exception 2"), std::string::npos) << low.cs.governs;
  in.storeys = 12;
  const DesignedBuilding tall = design_elf(in);
  EXPECT_NEAR(tall.period, 1.73945, 5e-5);
  EXPECT_NEAR(tall.cs.cs, 1.5 * 0.68 / (tall.period * 8), 1e-12);
  EXPECT_NEAR(tall.cs.cs, 0.073299, 5e-6);
  EXPECT_EQ(tall.cs.governs, "1.5 SD1/(T R/Ie)");
  maps.site = Asce7SiteClass::E;  // exception 3 is not taken: refused
  EXPECT_THROW(set_design_values(in, maps), InputError);
}
