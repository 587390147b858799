// An adjacent pair of an inventory as a pair study (TOML text), from the two buildings' ELF designs.
#include "pounding/inventory/pair_study.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "pounding/core/error.hpp"

namespace pounding::inventory {
namespace {

double cov_of(double beta) { return std::sqrt(std::exp(beta * beta) - 1.0); }

// TOML basic string: quotes and backslashes escaped, control characters as \uXXXX.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += static_cast<char>(c);
    else if (c < 0x20 || c == 0x7f) out += fmt::format("\\u{:04x}", c);
    else out += static_cast<char>(c);
  }
  return out + "\"";
}

std::string building_table(int k, const Building& b, const DesignedBuilding& d, const PairStudyOptions& o) {
  const double mass = d.weight / 9.80665;
  return fmt::format(
      "[structures.building{}]   # {}: {} ({}), {} storeys of {:g} m, {} ({}), site class {} ({})\n"
      "period = {{lognormal = {{median = {:.6g}, cov = {:.4g}}}}}   # s, {} = {:.4g} s\n"
      "height = {:.6g}\n"
      "storeys = {}\n"
      "storey_height = {:.6g}\n"
      "mass = {:.6g}                 # kg: plan area {:.4g} m2 x {:.3g} kPa per floor\n"
      "yield_coefficient = {{lognormal = {{median = {:.6g}, cov = {:.4g}}}}}   # Vy/W: {:g} x {:g} x Cs {:.4g} of {}\n"
      "zeta = {{lognormal = {{median = 0.05, cov = {:.4g}}}}}\n"
      "alpha = {:g}\n"
      "stiffness_profile = \"shear\"\n"
      "asce7_r = {:g}\nasce7_cd = {:g}\nasce7_ie = {:g}\n\n",
      k, b.id, d.system->key, d.system->description, b.storeys, b.storey_height.front(), to_string(b.level),
      b.level_source, to_string(b.site), b.site_source, d.period, cov_of(o.beta_period), d.period_rule, d.period, d.hn,
      b.storeys, b.storey_height.front(), mass, b.plan_area, d.weight / b.plan_area / b.storeys / 1e3,
      d.strength.front() / d.weight, cov_of(o.beta_strength), d.overstrength, d.strength_factor, d.cs_reference.cs,
      d.reference->key, cov_of(o.beta_damping), d.alpha, d.system->r, d.system->cd, b.importance);
}

}  // namespace

std::string pair_study_text(const Inventory& inv, const Adjacency& pair, const PairStudyOptions& o) {
  const Building& a = inv.buildings[pair.a];
  const Building& b = inv.buildings[pair.b];
  const DesignInput ia = design_input(a, o.ss, o.s1, o.tl), ib = design_input(b, o.ss, o.s1, o.tl);
  const DesignedBuilding da = design_elf(ia), db = design_elf(ib);
  const DesignInput& site = ia.sd1 >= ib.sd1 ? ia : ib;  // the softer site: the larger design values
  const Building& on = ia.sd1 >= ib.sd1 ? a : b;
  std::vector<double> gaps{0.01, 0.02, 0.04, 0.06, 0.08, 0.10, 0.15, 0.20, 0.30, 0.50};
  // the measured gap on the axis too (a fragility study answers at axis gaps only), unless a shared wall
  if (pair.gap > 0 && std::find(gaps.begin(), gaps.end(), pair.gap) == gaps.end()) {
    gaps.push_back(pair.gap);
    std::sort(gaps.begin(), gaps.end());
  }
  std::string out = fmt::format(
      "# {} beside {} in {}: {}, {:.3g} m apart today, facing {:.3g} m{}.\n"
      "# Written by `pounding inventory pair` from the buildings' ASCE 7-16 ELF designs (docs/inventory.md).\n"
      "title = {}\nseed = {}\nscene = \"impacts\"\noutput = {}\n\n"
      "[records]\nsuite = \"builtin\"\nsynthetic_only = true\nselect = {}\npolarity = \"both\"\n\n"
      "[target_spectrum]          # Ss = {:g} g, S1 = {:g} g on site class {} ({}'s, the softer of the two){}\n"
      "code = \"ASCE 7-16\"\nsds = {:.6g}\nsd1 = {:.6g}\ntl = {:g}\nmcer = {}          # {}\n\n"
      "[structures]\nmodel = \"shear\"\nsamples_per_pair = {}\n\n",
      a.id, b.id, inv.file, to_string(pair.kind), pair.gap, pair.frontage,
      pair.floors_aligned ? ", floors level" : fmt::format(", floors up to {:.2f} m apart (floor to column)", pair.worst_offset),
      quoted(fmt::format("{} beside {} ({} m apart)", a.id, b.id, fmt::format("{:.3g}", pair.gap))), o.seed,
      quoted(o.output.empty() ? a.id + "--" + b.id + ".h5" : o.output), o.records, o.ss, o.s1, to_string(on.site), on.id,
      site.exception_2 ? "; D with S1 >= 0.2 g: Table 11.4-2's Fv (11.4.8 exception 2)" : "", site.sds, site.sd1, o.tl,
      o.mce ? "true" : "false", o.mce ? "MCER shaking (1.5 x design, ASCE 7-16 16.2)" : "design-level shaking", o.samples);
  out += building_table(1, a, da, o) + building_table(2, b, db, o);
  std::string list;
  for (double g : gaps) list += (list.empty() ? "" : ", ") + fmt::format("{:g}", g);
  out += fmt::format("[gaps]\nmetres = [{}]\nexisting = {:.4g}\ncurve_max = 0.6\n\n", list, pair.gap);
  out += "[contact]\nlaw = \"hertzdamp\"\ndamping_law = \"lankarani-nikravesh\"\ne = 0.65\n\n[report]\ntargets = [10, 5]\n";
  return out;
}

}  // namespace pounding::inventory
