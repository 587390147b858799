#pragma once
// A code-designed building from a few numbers (issue 48): ASCE 7-16's equivalent lateral force procedure (ch. 12.8)
// gives its period, base shear and storey shears, and a shear stick is built on them for the time-history analysis.
// Clauses (ASCE 7-16, SI units; ../shared/research/inventory-and-design.md section 2):
//   12.8.2.1  Ta = Ct hn^x (Table 12.8-2 in SI); the model's period T = Cu Ta (Table 12.8-1, interpolated in SD1):
//             the upper limit the standard lets an analysis period reach, and nearer to measured periods than Ta.
//             A measured period replaces it (the design forces then use min(measured, Cu Ta), as 12.8.2 says).
//   12.8.1.1  Cs = SDS / (R / Ie), at most SD1 / (T R / Ie) (T <= TL) or SD1 TL / (T^2 R / Ie) (T > TL), at least
//             max(0.044 SDS Ie, 0.01) and, where S1 >= 0.6 g, at least 0.5 S1 / (R / Ie).  V = Cs W (12.8-1).
//   11.4.8    site class D with S1 >= 0.2: exception 2 (Cs by 12.8-2 up to 1.5 TS, 1.5 x 12.8-3/4 beyond), the
//             engineer's usual way out of the site-specific procedure for ELF designs; site class E with S1 >= 0.2
//             and F are refused (asce7_site.hpp).
//   12.8.3    Fx = Cvx V, Cvx = wx hx^k / sum wi hi^k, k = 1 (T <= 0.5 s), 2 (T >= 2.5 s), linear between.
//   12.8.4    Vx = sum of Fi for i >= x.
//   Table 12.2-1  R, Omega0, Cd of the system;  Table 12.12-1  the allowable storey drift (risk category I/II).
// The shear stick (stated rules, not code clauses):
//   floor mass = plan area x unit weight / g (unit weight per system, kPa, overridable); the stiffness profile is
//   proportional to the storey shears Vx (a nearly straight first mode) scaled so that the first period is T
//   (model::shear_stick_modes); storey strength Vy,x = overstrength x era factor x Cs,ref W x Vx / V: the capacity
//   of the modern ductile system of the building's family (concrete frames: rc-smf, concrete walls:
//   rc-special-wall, steel frames: steel-smf, braces: steel-scbf, masonry: rm-special-wall) designed at the same
//   period and site, times its Omega0 unless given, times the era factor of the design level (strength_factor():
//   1, 1/2, 1/4, 1/4 for HAZUS-MH's high, moderate, low and pre-code levels). The system's own R (a low R for an
//   ordinary system) sets the design forces and Cd, not the capacity: a pre-code URM wall building designed today
//   with R = 1.5 would be several times stronger than the buildings it stands for.
//   P-Delta (an option): storey x carries the gravity load above it, P_x = g sum_{i >= x} m_i, whose geometric
//   stiffness P_x / h_x is subtracted from the storey's spring. For the bilinear kinematic spring this is exact as a
//   re-parametrisation: k' = k - g_x, alpha' = (alpha k - g_x) / k', Fy' = Fy k' / k gives F'(d) = F(d) - g_x d on
//   every path (elastic slopes k - g_x, post-yield slopes alpha k - g_x, the same bounds' offset (1 - alpha) Fy).
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/motion/asce7_site.hpp"

namespace pounding::inventory {

enum class Material { concrete, steel, masonry, wood };
std::string_view to_string(Material m);

// One seismic force-resisting system: its rows of ASCE 7-16's tables and our defaults for the model.
struct SystemRow {
  std::string_view key;          // "rc-smf": what an inventory writes
  std::string_view description;  // "special reinforced concrete moment frame"
  double r, omega0, cd;          // Table 12.2-1
  double ct, x;                  // Table 12.8-2 (SI): hn in m
  double drift_limit;            // Table 12.12-1, risk category I or II, times the storey height
  double unit_weight;            // kPa: floor weight per plan area (research/inventory-and-design.md section 2)
  Material material;
  double alpha;                  // post-yield stiffness ratio of its storeys
  std::string_view reference;    // the modern ductile system of its family whose design sets the capacity
};
std::span<const SystemRow> systems();
// The row of `key`; InputError naming `where` and listing the known keys otherwise.
const SystemRow& system_row(std::string_view key, const std::string& where);

// HAZUS-MH's seismic design levels. The era factor scales the modern ELF capacity: 1, 0.5, 0.25, 0.25.
enum class DesignLevel { high, moderate, low, pre_code };
DesignLevel parse_design_level(std::string_view name, const std::string& where);  // "high" ... "pre-code"
std::string_view to_string(DesignLevel d);
double strength_factor(DesignLevel d);

// Table 12.8-1: Cu by SD1 (g), straight-line between 0.1 and 0.4 g, held beyond.
double asce7_cu(double sd1);
// 12.8.1.1's Cs and the bound that governs ("SDS/(R/Ie)", "SD1/(T R/Ie)", "SD1 TL/(T^2 R/Ie)", "0.044 SDS Ie",
// "0.01", "0.5 S1/(R/Ie)").
struct SeismicCoefficient {
  double cs = 0;
  std::string governs;
};
// exception_2 (11.4.8, site class D with S1 >= 0.2): eq. 12.8-2 up to T = 1.5 TS, 1.5 x eqs. 12.8-3/4 beyond
// ("1.5 SD1/(T R/Ie)", ...); the lower bounds as always.
SeismicCoefficient asce7_cs(double sds, double sd1, double s1, double tl, double period, double r, double ie,
                            bool exception_2 = false);
// 12.8.3's exponent k at period T.
double asce7_k(double period);

struct DesignInput {
  std::string system;                 // a SystemRow key
  int storeys = 0;                    // >= 1
  std::vector<double> storey_height;  // m: one for every storey, or one per storey (bottom first)
  double plan_area = 0;               // m^2 per floor
  double unit_weight = 0;             // kPa; 0: the system's
  double period = 0;                  // s, a measured T1; 0: Cu Ta
  // The design values (g) and TL (s): from the maps and the site class by design_values(), or given.
  double sds = 0, sd1 = 0, s1 = 0, tl = 8;
  bool exception_2 = false;           // site class D with S1 >= 0.2: Cs by 11.4.8 exception 2
  double ie = 1.0;                    // importance factor (Table 1.5-2)
  DesignLevel level = DesignLevel::high;
  double overstrength = 0;            // 0: the system's Omega0
  bool p_delta = false;
  std::string where;                  // named in every error ("street.csv:4")
};

struct DesignedBuilding {
  const SystemRow* system = nullptr;
  double hn = 0, ta = 0, cu = 0;
  double period = 0;         // the model's T1, s
  std::string period_rule;   // "Cu Ta" or "measured"
  double design_period = 0;  // the period of the design forces, s
  double sds = 0, sd1 = 0;
  SeismicCoefficient cs;
  const SystemRow* reference = nullptr;  // the system whose capacity the storeys take
  SeismicCoefficient cs_reference;
  double weight = 0, base_shear = 0, k = 0;  // N, N, -
  std::vector<double> storey_height, floor_level;  // m (floor_level above the ground)
  std::vector<double> floor_mass, fx, vx;          // kg, N, N
  std::vector<double> stiffness, strength;         // N/m, N: the bare frame's storey springs
  double strength_factor = 1, overstrength = 0;
  double alpha = 0;
  std::vector<double> gravity_load;                // N above each storey (P_x)
  // The springs the analysis uses: the bare frame's, or with P-Delta the re-parametrised ones (alpha may differ
  // per storey then).
  std::vector<double> model_stiffness, model_strength, model_alpha;
  bool p_delta = false;
};
// SDS, SD1, S1 and TL of DesignInput from the mapped values and the site class (11.4).
void set_design_values(DesignInput& input, const Asce7MapValues& maps);
// InputError naming input.where and the field for a value out of range (storeys 0, a height, area, the site).
DesignedBuilding design_elf(const DesignInput& input);
// "rc-smf, 5 storeys, hn 16 m: Ta = 0.565 s, T = Cu Ta = 0.791 s, Cs = 0.0948 (SD1/(T R/Ie)), V = 2.09 MN" and one
// line per storey (bottom first): level, mass, Fx, Vx, k, Vy.
std::vector<std::string> describe(const DesignedBuilding& b);

}  // namespace pounding::inventory
