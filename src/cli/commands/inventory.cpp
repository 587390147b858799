// `pounding inventory`: building inventories (issue 48; docs/inventory.md).
//   inventory check FILE [--ss 1.5 --s1 0.6 --tl 8] [--threshold 1] [--min-frontage 1] [--level-tolerance 0.05]
//                        [--high-from 1976 --moderate-from 1941] [--pairs-csv PATH]
//       reads the inventory, designs every building (ASCE 7-16 ELF at the site's Ss, S1 on its own site class) and
//       lists the adjacent pairs: shared wall, gap or corner only, the gap and facing length, floors that do not
//       coincide (floor to column).
//   inventory design --system rc-smf --storeys 5 --storey-height 3.2 --plan-area 450 (--ss --s1 --site | --sds --sd1 --s1)
//                    [--tl 8] [--unit-weight kPa] [--period T] [--design-level high] [--importance 1] [--p-delta]
//       one building's ELF design and the shear stick built on it.
//   inventory synth --buildings N --seed S --out city.geojson
//       a synthetic city for scale tests.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/inventory/elf.hpp"
#include "pounding/inventory/inventory.hpp"
#include "pounding/inventory/pair_study.hpp"
#include "pounding/inventory/synth.hpp"

namespace pounding::cli {
namespace {

struct SiteOpts {
  double ss = 1.5, s1 = 0.6, tl = 8;
};

void add_site(CLI::App* c, SiteOpts& o) {
  c->add_option("--ss", o.ss, "mapped MCER Sa at 0.2 s, g (site class B/C boundary; default 1.5)");
  c->add_option("--s1", o.s1, "mapped MCER Sa at 1 s, g (default 0.6)");
  c->add_option("--tl", o.tl, "long-period transition period TL, s (default 8)");
}

struct CheckOpts {
  std::string file, pairs_csv;
  SiteOpts site;
  inventory::AdjacencyRules rules;
  inventory::EraRule eras;
};

std::string pairs_table(const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs) {
  std::string s = "building_a,building_b,kind,gap_m,frontage_m,floors_aligned,worst_floor_offset_m\n";
  for (const auto& p : pairs)
    s += fmt::format("{},{},{},{:.4f},{:.3f},{},{:.3f}\n", inv.buildings[p.a].id, inv.buildings[p.b].id, to_string(p.kind),
                     p.gap, p.frontage, p.floors_aligned ? "yes" : "no", p.worst_offset);
  return s;
}

void check(const CheckOpts& o) {
  if (!o.pairs_csv.empty()) {
    files::check_output_path(o.pairs_csv, "--pairs-csv");
    files::check_output_not_input(o.pairs_csv, {o.file}, "--pairs-csv");
  }
  const inventory::Inventory inv = inventory::read_inventory(o.file, o.eras);
  const std::vector<inventory::Adjacency> pairs = inventory::adjacent_pairs(inv, o.rules);
  std::vector<inventory::DesignedBuilding> designed;
  for (const inventory::Building& b : inv.buildings)
    designed.push_back(inventory::design_elf(inventory::design_input(b, o.site.ss, o.site.s1, o.site.tl)));
  fmt::print("inventory {}: {} buildings, {} adjacent pairs; {}\n", o.file, inv.buildings.size(), pairs.size(), inv.coordinates);
  if (!inv.ignored.empty()) {
    std::string s;
    for (const std::string& k : inv.ignored) s += (s.empty() ? "" : ", ") + k;
    fmt::print("not used: {}\n", s);
  }
  fmt::print("design: ASCE 7-16 ELF at Ss = {} g, S1 = {} g, TL = {} s on each building's site class (site class D with "
             "S1 >= 0.2 g by 11.4.8 exception 2); T = Cu Ta unless measured; Vy/W = Omega0 x design-level factor x Cs of the "
             "family's modern ductile system (docs/inventory.md)\n", o.site.ss, o.site.s1, o.site.tl);
  fmt::print("{:<12} {:<17} {:>3} {:>7} {:<9} {:<4} {:>7} {:>7} {:>9} {:>7}\n", "id", "system", "n", "hn m", "level", "site",
             "T s", "Cs", "V kN", "Vy/W");
  for (std::size_t i = 0; i < inv.buildings.size(); ++i) {
    const auto& b = inv.buildings[i];
    const auto& d = designed[i];
    fmt::print("{:<12} {:<17} {:>3} {:>7.2f} {:<9} {:<4} {:>7.3f} {:>7.4f} {:>9.0f} {:>7.4f}\n", b.id, b.system, b.storeys,
               d.hn, to_string(b.level), to_string(b.site), d.period, d.cs.cs, d.base_shear / 1e3, d.strength.front() / d.weight);
  }
  fmt::print("\n{:<12} {:<12} {:<12} {:>8} {:>10} {}\n", "a", "b", "kind", "gap m", "facing m", "floors");
  for (const auto& p : pairs)
    fmt::print("{:<12} {:<12} {:<12} {:>8.3f} {:>10.2f} {}\n", inv.buildings[p.a].id, inv.buildings[p.b].id,
               to_string(p.kind), p.gap, p.frontage,
               p.floors_aligned ? std::string("aligned") : fmt::format("floor to column (offset {:.2f} m)", p.worst_offset));
  if (!o.pairs_csv.empty()) files::write_text_atomically(o.pairs_csv, pairs_table(inv, pairs));
}

struct DesignOpts {
  inventory::DesignInput in;
  std::string level = "high", site_class;
  double ss = 0, s1 = -1, sds = 0, sd1 = 0, tl = 8;
  std::vector<double> heights;
};

void design(DesignOpts& o) {
  o.in.level = inventory::parse_design_level(o.level, "--design-level");
  o.in.storey_height = o.heights;
  o.in.where = "inventory design";
  if (o.in.storey_height.empty())
    throw InputError("--storey-height is missing", "--storey-height", "give the storey height (m), one or one per storey");
  if (o.s1 < 0) throw InputError("--s1 is missing", "--s1", "give the mapped S1 (g): 12.8.1.1 needs it");
  if (!o.site_class.empty()) {
    if (o.sds != 0 || o.sd1 != 0)
      throw InputError("--site with --sds/--sd1", "--site", "give --ss, --s1 and --site, or --sds, --sd1 and --s1");
    Asce7MapValues maps;
    maps.ss = o.ss, maps.s1 = o.s1, maps.tl = o.tl, maps.site = parse_asce7_site_class(o.site_class, "--site");
    inventory::set_design_values(o.in, maps);
  } else {
    if (o.sds == 0 || o.sd1 == 0)
      throw InputError("neither --site nor --sds and --sd1 is given", "--sds", "give --ss, --s1 and --site, or --sds, --sd1 and --s1");
    o.in.sds = o.sds, o.in.sd1 = o.sd1, o.in.s1 = o.s1, o.in.tl = o.tl;
  }
  for (const std::string& line : inventory::describe(inventory::design_elf(o.in))) fmt::print("{}\n", line);
}

void add_check(CLI::App* inv) {
  auto o = std::make_shared<CheckOpts>();
  auto* c = inv->add_subcommand("check", "read an inventory, design its buildings and list the adjacent pairs");
  c->add_option("file", o->file, "the inventory: .geojson / .json (footprints) or .csv (street order)")->required();
  add_site(c, o->site);
  c->add_option("--threshold", o->rules.threshold, "footprints closer than this are neighbours, m (default 1)");
  c->add_option("--min-frontage", o->rules.min_frontage, "facing over less than this is corner-only contact, m (default 1)");
  c->add_option("--level-tolerance", o->rules.level_tolerance, "floors within this coincide, m (default 0.05)");
  c->add_option("--high-from", o->eras.high_from, "year_built from which a building is high-code (default 1976)");
  c->add_option("--moderate-from", o->eras.moderate_from, "year_built from which it is moderate-code, else pre-code (default 1941)");
  c->add_option("--pairs-csv", o->pairs_csv, "write the adjacent pairs as CSV here");
  c->callback([o] { check(*o); });
}

void add_design(CLI::App* inv) {
  auto o = std::make_shared<DesignOpts>();
  auto* c = inv->add_subcommand("design", "one building's ASCE 7-16 ELF design and its shear stick");
  c->add_option("--system", o->in.system, "structural system (rc-smf, steel-smf, urm-wall, ...; docs/inventory.md)")->required();
  c->add_option("--storeys", o->in.storeys, "storeys above the ground")->required();
  c->add_option("--storey-height", o->heights, "storey height, m: one, or one per storey (comma-separated)")->delimiter(',');
  c->add_option("--plan-area", o->in.plan_area, "floor plan area, m^2")->required();
  c->add_option("--unit-weight", o->in.unit_weight, "floor weight per plan area, kPa (default: the system's)");
  c->add_option("--period", o->in.period, "measured first period, s (default Cu Ta)");
  c->add_option("--design-level", o->level, "high, moderate, low or pre-code (default high)");
  c->add_option("--importance", o->in.ie, "importance factor Ie (default 1)");
  c->add_option("--overstrength", o->in.overstrength, "storey capacity over the design storey shear (default Omega0)");
  c->add_flag("--p-delta", o->in.p_delta, "subtract each storey's geometric stiffness P/h");
  c->add_option("--ss", o->ss, "mapped Ss, g (with --site)");
  c->add_option("--s1", o->s1, "mapped S1, g");
  c->add_option("--site", o->site_class, "site class A-E or D-default (with --ss and --s1)");
  c->add_option("--sds", o->sds, "design SDS, g (instead of --ss and --site)");
  c->add_option("--sd1", o->sd1, "design SD1, g");
  c->add_option("--tl", o->tl, "TL, s (default 8)");
  c->callback([o] { design(*o); });
}

struct PairOpts {
  std::string file, a, b, out;
  inventory::PairStudyOptions study;
  inventory::AdjacencyRules rules;
  inventory::EraRule eras;
};

void pair(const PairOpts& o) {
  files::check_output_path(o.out, "--out");
  files::check_output_not_input(o.out, {o.file}, "--out");
  const inventory::Inventory inv = inventory::read_inventory(o.file, o.eras);
  for (const inventory::Adjacency& p : inventory::adjacent_pairs(inv, o.rules)) {
    const std::string& x = inv.buildings[p.a].id;
    const std::string& y = inv.buildings[p.b].id;
    if ((x == o.a && y == o.b) || (x == o.b && y == o.a)) {
      files::write_text_atomically(o.out, inventory::pair_study_text(inv, p, o.study));
      fmt::print("wrote the study of {} beside {} to {}: pounding run {}\n", x, y, o.out, o.out);
      return;
    }
  }
  throw InputError(fmt::format("{} and {} are not an adjacent pair of {}", o.a, o.b, o.file), "--pair",
                   "give two ids that `pounding inventory check` lists as a pair");
}

void add_pair(CLI::App* inv) {
  auto o = std::make_shared<PairOpts>();
  auto* c = inv->add_subcommand("pair", "write one adjacent pair of an inventory as a pair study");
  c->add_option("file", o->file, "the inventory")->required();
  c->add_option("--a", o->a, "the first building's id")->required();
  c->add_option("--b", o->b, "the second building's id")->required();
  c->add_option("--out", o->out, "the study file to write (.toml)")->required();
  c->add_option("--ss", o->study.ss, "mapped MCER Sa at 0.2 s, g (default 1.5)");
  c->add_option("--s1", o->study.s1, "mapped MCER Sa at 1 s, g (default 0.6)");
  c->add_option("--tl", o->study.tl, "TL, s (default 8)");
  c->add_option("--beta-period", o->study.beta_period, "lognormal dispersion of the period (default 0.25)");
  c->add_option("--beta-strength", o->study.beta_strength, "lognormal dispersion of the strength (default 0.35)");
  c->add_option("--beta-damping", o->study.beta_damping, "lognormal dispersion of the damping ratio (default 0.4)");
  c->add_option_function<std::string>("--shaking", [o](const std::string& v) {
    if (v != "mce" && v != "design") throw InputError(fmt::format("--shaking {}", v), "--shaking", "give mce or design");
    o->study.mce = v == "mce";
  }, "mce (default: records scaled to the MCER spectrum, 16.2) or design");
  c->add_option("--samples", o->study.samples, "structure samples per record (default 20)");
  c->add_option("--seed", o->study.seed, "the study's seed (default 1)");
  c->add_option("--results", o->study.output, "the results file the study names (default <a>--<b>.h5)");
  c->add_option("--threshold", o->rules.threshold, "footprints closer than this are neighbours, m (default 1)");
  c->callback([o] { pair(*o); });
}

void add_synth(CLI::App* inv) {
  auto o = std::make_shared<inventory::SynthOptions>();
  auto out = std::make_shared<std::string>();
  auto* c = inv->add_subcommand("synth", "a synthetic city as a GeoJSON inventory, for scale tests");
  c->add_option("--buildings", o->buildings, "number of buildings, [1, 10000000]")->required();
  c->add_option("--seed", o->seed, "seed (the same seed gives the same file)");
  c->add_option("--out", *out, "the GeoJSON file to write")->required();
  c->callback([o, out] {
    if (o->buildings < 1 || o->buildings > 10000000)
      throw InputError(fmt::format("--buildings {} is outside [1, 10000000]", o->buildings), "--buildings", "give a count in range");
    files::check_output_path(*out, "--out");
    files::write_text_atomically(*out, inventory::synth_city(*o));
    fmt::print("wrote {} buildings to {}\n", o->buildings, *out);
  });
}

}  // namespace

void add_inventory_run(CLI::App* inv);  // src/cli/commands/inventory_run.cpp

void add_inventory(CLI::App& app) {
  auto* inv = app.add_subcommand("inventory", "building inventories: check and design them, make synthetic cities "
                                              "(docs/inventory.md)");
  inv->require_subcommand(1);
  add_check(inv);
  add_design(inv);
  add_pair(inv);
  add_synth(inv);
  add_inventory_run(inv);
}

}  // namespace pounding::cli
