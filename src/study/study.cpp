// A study file parsed once into a validated, immutable Study.
#include "pounding/study/study.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/reductions.hpp"
#include "pounding/study/histories.hpp"
#include "study_sections.hpp"

#include "pounding/sampling/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/machine.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

using config::TableReader;

// [outputs] per_model = false keeps only the reductions of the probability scene of an SDOF pair (study/reductions.hpp);
// what else would need per-model values it does not keep is refused before any work.
void check_per_model(const Study& s) {
  if (s.per_model && !s.stream) return;
  const char* what = s.stream ? "[outputs] per_model = \"stream\" makes the run's report from the reductions, which "
                                "cover only the probability scene of an SDOF pair,"
                              : "[outputs] per_model = false keeps only the reductions of the probability scene of an "
                                "SDOF pair,";
  const char* why = s.scene == Scene::impacts ? "the impacts scene's forces and amplification are per model and gap"
                    : s.intensity.enabled     ? "a fragility study fits each model's stripes and IDA curves"
                    : runs_systems(s.structures)
                        ? "shear buildings, rows and bridges keep per-floor and per-element peaks (their reductions are "
                          "not written yet)"
                    : s.html ? "the HTML report's figures (tools/pounding_plots.py) read per-model peaks"
                        : nullptr;
  if (why)
    throw InputError(fmt::format("{} and {}", what, why), s.per_model_where,
                     "write scene = \"probability\" for an SDOF pair or grid study without [intensity] or [report] "
                     "html, or delete per_model (per-model outputs in memory)");
}

// The scene actually run (auto resolved from [outputs]), why, and the scene's default step cap (docs/accuracy.md):
// the coupled runs need h <= 2.5 ms for 1 % peak forces; the at-least-one-impact probability of the full paper study
// moves by at most 0.02 percentage points between the record step (10 ms) and 2.5 ms, so the probability scene
// integrates at the record step. The scene's default batch too (default_batch: shorter units for the impacts scene's
// long ones, so 1,000 ranks find work).
void choose_scene(Study& s) {
  const bool max_dt_given = s.max_dt >= 0.0;
  s.scene = s.scene_requested;
  if (s.scene_requested == Scene::automatic) {
    if (s.want_forces || s.want_amplification) {
      s.scene = Scene::impacts;
      s.scene_reason = "auto: [outputs] asks for impact forces/amplification, which need the coupled contact runs";
    } else {
      s.scene = Scene::probability;
      s.scene_reason = "auto: only the at-least-one-impact probability is asked for; it depends only on the "
                       "uncoupled motion before the first contact, so one uncoupled run per model answers every gap";
    }
  } else if (s.scene == Scene::probability) {
    s.scene_reason = "probability scene: whether a pair touches at gap g depends only on the motion before the first "
                     "contact, i.e. the uncoupled motion; one uncoupled run per model and record answers every gap";
  } else {
    s.scene_reason = std::string("impacts scene: one uncoupled run per model, then coupled contact runs at every ") +
                     (s.gap_metres ? "gap" : "gap ratio");
  }
  if (!max_dt_given) s.max_dt = s.scene == Scene::impacts ? 0.0025 : 0.0;
  if (s.batch == 0) s.batch = default_batch(s.scene);
}

// [records] select and [target_spectrum] come together.
void check_selection(const Study& s, const TableReader& top) {
  if (s.select > 0 && !s.target.enabled)
    throw InputError("[records] select = N chooses records to a design spectrum, but the study has no [target_spectrum]",
                     s.select_where,
                     "add [target_spectrum] with code = \"ASCE 7-16\" (sds, sd1, tl), \"EC8\" (type, ground, agr), "
                     "\"Standard 2800\" (a, soil) or \"csv\" (file), or delete select");
  if (s.target.enabled && s.select == 0)
    throw InputError("[target_spectrum] is given but [records] has no select = N", top.where("target_spectrum"),
                     "add select = N to [records] (N records are chosen from the library and scaled to the spectrum; "
                     "ASCE 7-16 asks for at least 11), or delete [target_spectrum]");
}

}  // namespace

static std::string_view bearing_name(physics::Bearing b) {
  for (const auto& n : bearing_names)
    if (n.value == b) return n.name;
  return "smooth";
}

// Studies of systems (shear buildings, rows) run with central difference, Newmark or RK4 (physics::run_system;
// Newmark and RK4: physics/system_lane_stepper.hpp, bilinear springs only); Nigam-Jennings integrates SDOF bodies only
// (docs/architecture.md D7). Refused here, before any work, with the key's line.
static void check_system_stepper(const Study& s, TableReader& top, const std::string& path, const std::string& what,
                                 const std::string& other_fix) {
  if (s.stepper == Stepper::central_difference) return;
  const toml::table* a = top.table("analysis");
  const toml::node* n = a ? a->get("stepper") : nullptr;
  const std::string where =
      n ? fmt::format("{}:{} [analysis].stepper", path, n->source().begin.line) : path + " [analysis].stepper";
  if (s.stepper == Stepper::nigam_jennings)
    throw InputError(fmt::format("nigam-jennings integrates SDOF bodies only (the pair), and the study has {}", what),
                     where, "write stepper = \"central-difference\", \"newmark\" or \"rk4\", " + other_fix);
  for (std::size_t b = 0; b < s.structures.building_count(); ++b)
    if (const BuildingModel m = s.structures.row_building(b);
        m.isolated && !model::runs_on_lane_stepper(physics::isolator_law(m.isolation.bearing)))
      throw InputError(fmt::format("the {} stepper runs systems of bilinear springs (storeys, linear and lead-rubber "
                                   "bearings), and building {} has a {} bearing", to_string(s.stepper), b + 1,
                                   bearing_name(m.isolation.bearing)),
                       where, "write stepper = \"central-difference\", or bearing = \"lead-rubber\"");
}

// A study with a shear building (model = "shear") runs the system steppers: central difference, Newmark or RK4
// (check_system_stepper), force laws only (a contact at every common floor). [intensity] runs (stripes, IDA:
// study/run.cpp, the Systems' scaling by the model trait SystemBlock::scales_linearly).
static void check_row_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path);

// [contact] level_tolerance below half the smallest storey height of the shear buildings (an SDOF of a row of SDOFs:
// its 3.2 m floor), so that a floor meets at most one floor of its neighbour (the floors within the tolerance of it).
static void check_level_tolerance(const Study& s, config::TableReader& top, const std::string& path) {
  if (!s.structures.any_shear() && !s.structures.row()) return;
  double h = INFINITY;
  for (std::size_t b = 0; b < s.structures.building_count(); ++b) {
    const BuildingModel x = s.structures.row_building(b);
    if (x.shear() || s.structures.row()) h = std::min(h, x.shear() ? x.storey_height() : 3.2);
    for (double y : x.storey_heights) h = std::min(h, y);  // storeys of different heights: the lowest
  }
  if (s.level_tolerance < 0.5 * h) return;
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("level_tolerance") : nullptr;
  throw InputError(fmt::format("[contact] level_tolerance = {:g} m is not below half the smallest storey height ({:g} m): a "
                               "floor could meet two floors of its neighbour",
                               s.level_tolerance, h),
                   n ? fmt::format("{}:{} [contact].level_tolerance", path, n->source().begin.line)
                     : path + " [contact].level_tolerance",
                   fmt::format("give level_tolerance < {:g} m (default 0.05 m)", 0.5 * h));
}

// [contact] joint_gap_offsets: a row's, one value per joint (a pair's one joint takes the gap ratios; a bridge's
// joints their own gaps)
static void check_joint_offsets(const Study& s, config::TableReader& top, const std::string& path) {
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("joint_gap_offsets") : nullptr;
  if (!n) return;
  const std::string where = fmt::format("{}:{} [contact].joint_gap_offsets", path, n->source().begin.line);
  const std::size_t joints = s.structures.building_count() - 1;
  if (!s.structures.row())
    throw InputError("[contact] joint_gap_offsets is given, and the study is a pair (one joint: its gap is the ratio "
                     "x d)", where, "give buildings = 3 or more for a row, or remove the key (use [gaps] ratios)");
  if (s.joint_gap_offsets.size() != joints)
    throw InputError(fmt::format("[contact] joint_gap_offsets has {} values, and the row of {} buildings has {} joints",
                                 s.joint_gap_offsets.size(), joints + 1, joints),
                     where, fmt::format("give one offset (m) per joint, left to right: {} values", joints));
}

static void check_shear_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path) {
  check_row_study(s, top, structures, path);
  // [contact] levels / gap_offsets act on the floors of shear buildings and the joints of a row
  if (!s.structures.any_shear() && !s.structures.row())
    for (const char* key : {"gap_offsets", "levels", "level_tolerance", "shape_functions"}) {
      const toml::table* c = top.table("contact");
      const toml::node* n = c ? c->get(key) : nullptr;
      if (!n) continue;
      throw InputError(fmt::format("[contact] {} is given, and the study is a pair of SDOF buildings (one contact at "
                                   "one level)",
                                   key),
                       fmt::format("{}:{} [contact].{}", path, n->source().begin.line, key),
                       "give the buildings storeys (model = \"shear\") or a row (buildings = 3 or more), or remove the key");
    }
  check_level_tolerance(s, top, path);
  check_joint_offsets(s, top, path);
  if (!s.structures.any_shear()) return;
  check_system_stepper(s, top, path, "a shear building", "or use model = \"sdof\"");
  if (s.contact.law == ContactLaw::stereomechanical) {
    const toml::table* c = top.table("contact");
    const toml::node* n = c ? c->get("law") : nullptr;
    throw InputError("the stereomechanical law runs one contact element (the SDOF pair), and the study has a shear "
                     "building (a contact at every common floor)",
                     n ? fmt::format("{}:{} [contact].law", path, n->source().begin.line) : path + " [contact].law",
                     "choose a force law (hertzdamp, kelvin, ...), or use model = \"sdof\"");
  }
}

// A row of n >= 3 buildings ([structures] buildings) runs the system stepper too, SDOF or shear: central difference,
// a force law (several contact elements). [intensity] runs (stripes and IDA through SystemBlock, as for shear pairs).
static void check_row_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path) {
  (void)structures;  // (its buildings key located the [intensity] refusal, gone: rows run fragility studies)
  if (!s.structures.row()) return;
  const std::size_t n = s.structures.building_count();
  auto at = [&](const char* table, const char* key) {
    const toml::table* t = top.table(table);
    const toml::node* k = t ? t->get(key) : nullptr;
    return k ? fmt::format("{}:{} [{}].{}", path, k->source().begin.line, table, key)
             : fmt::format("{} [{}].{}", path, table, key);
  };
  check_system_stepper(s, top, path, fmt::format("a row of {} buildings", n), "or buildings = 2");
  if (s.contact.law == ContactLaw::stereomechanical)
    throw InputError(fmt::format("the stereomechanical law runs one contact element (the SDOF pair), and a row of {} "
                                 "buildings has a contact at every joint",
                                 n),
                     at("contact", "law"), "choose a force law (hertzdamp, kelvin, ...), or buildings = 2");
}

// [contact] restitution (e(v0)) runs where central difference reads it at each impact's onset (physics::
// HertzdampRestitution; the pair kernel and the system stepper): the coupled runs of the impacts scene with Hertzdamp,
// for SDOF pairs, shear buildings, rows and bridges (every study-gap element); elsewhere it would do nothing. A moat's
// walls (their own e) would take the curve too: refused.
static void check_restitution(const Study& s, TableReader& top, const std::string& path) {
  if (!s.restitution) return;
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("restitution") : nullptr;
  const std::string where = n ? fmt::format("{}:{} [contact].restitution", path, n->source().begin.line) : path + " [contact].restitution";
  const char* fix = "remove restitution (and give e), or run with law = \"hertzdamp\", stepper = "
                    "\"central-difference\" in the impacts scene";
  if (s.contact.law != ContactLaw::hertzdamp)
    throw InputError(fmt::format("a velocity-dependent restitution runs with law = \"hertzdamp\", and the law is \"{}\"",
                                 to_string(s.contact.law)), where, fix);
  if (s.stepper != Stepper::central_difference)
    throw InputError(fmt::format("a velocity-dependent restitution runs with the central-difference stepper, and the "
                                 "stepper is \"{}\"", to_string(s.stepper)), where, fix);
  for (std::size_t b = 0; !s.structures.bridge && b < s.structures.building_count(); ++b)
    if (const BuildingModel m = s.structures.row_building(b); m.isolated && m.moat)
      throw InputError(fmt::format("a velocity-dependent restitution acts at every contact of the system, and building "
                                   "{} has a moat (its walls have their own restitution)", b + 1),
                       where, "remove restitution (and give e), or remove the moat");
  if (s.scene != Scene::impacts)
    throw InputError(fmt::format("a velocity-dependent restitution acts in the coupled runs of the impacts scene, and "
                                 "the scene is \"{}\" (no coupled run: whether a pair touches is decided by the "
                                 "uncoupled motion)", to_string(s.scene)), where, fix);
}

// A bridge study ([bridge], sampling/bridge.hpp): the frames come from [bridge], not [structures]; the structure
// model only numbers the samples (one period slot each, [bridge] samples per record). The system stepper runs it:
// central difference and a force law at the joints, no [intensity], no [contact] levels / gap_offsets (the joints
// are the contact elements; their own gaps give the offsets).
static void parse_bridge(Study& s, TableReader& top, const toml::table* bridge, const toml::table* structures,
                         const std::string& path) {
  if (structures)
    throw InputError("a bridge study takes its frames from [bridge], and the study also has [structures]",
                     top.where("structures"), "remove [structures] (frames, periods and masses are [[bridge.frame]] keys)");
  std::int64_t samples = 1;
  auto model = std::make_shared<BridgeModel>(
      parse_bridge_model(bridge, path, s.contact_stiffness > 0 ? s.contact_stiffness : NAN, s.e, &samples,
                         s.restitution ? "[contact] restitution" : ""));
  toml::table t;
  t.insert("periods", toml::array{1.0});
  t.insert("samples_per_pair", samples);
  s.structures = parse_structure_model(t, path);
  s.structures.bridge = std::move(model);
  auto at = [&](const char* table, const char* key) {
    const toml::table* x = top.table(table);
    const toml::node* k = x ? x->get(key) : nullptr;
    return k ? fmt::format("{}:{} [{}].{}", path, k->source().begin.line, table, key) : fmt::format("{} [{}].{}", path, table, key);
  };
  if (s.stepper != Stepper::central_difference)
    throw InputError(fmt::format("the {} stepper runs SDOF pairs, shear buildings and rows, and the study is a bridge "
                                 "(its links' gap laws and support channels run with central difference only)",
                                 to_string(s.stepper)),
                     at("analysis", "stepper"), "write stepper = \"central-difference\" (the system stepper)");
  if (s.contact.law == ContactLaw::stereomechanical)
    throw InputError("the stereomechanical law runs one contact element (the SDOF pair), and a bridge has a contact at "
                     "every joint",
                     at("contact", "law"), "choose a force law (hertzdamp, kelvin, ...)");
  if (s.intensity.enabled)
    throw InputError("a fragility study ([intensity]: stripes, IDA) runs a pair of buildings, and the study is a bridge",
                     top.where("intensity"), "remove [intensity] to run the bridge in the probability or impacts scene");
  for (const char* key : {"gap_offsets", "levels", "joint_gap_offsets"}) {
    const toml::table* c = top.table("contact");
    if (c && c->get(key))
      throw InputError(fmt::format("[contact] {} is given, and the study is a bridge (its joints are the contacts)", key),
                       at("contact", key), "give each [[bridge.joint]] its own gap instead, or remove the key");
  }
  const int channels = s.structures.bridge->spec.channels();
  if (channels > std::max(1, s.supports))
    throw InputError(fmt::format("the bridge stands on {} supports (its largest support = {}), and the records give {}",
                                 channels, channels, std::max(1, s.supports)),
                     s.supports > 0 ? s.supports_where : fmt::format("{} [records].supports", path),
                     s.motions ? fmt::format("give [records.motions] supports = {} (or {} positions), or put every "
                                             "frame on support 1", channels, channels)
                               : fmt::format("give [records] supports = {} and a directory of support motions (pounding "
                                             "motions --supports {} --out DIR), or put every frame on support 1",
                                             channels, channels));
}

Study parse_study(const std::string& text, const std::string& path) {
  Study s;
  s.path = path;
  s.text = text;
  const toml::table root = config::parse(text, path, "fix the study file's syntax");
  if (root.contains("inventory"))  // docs/inventory.md: a template for every pair of an inventory
    throw InputError("the study has an [inventory] section: it is an inventory study", path,
                     "run it with `pounding inventory run " + path + "` (every adjacent pair of the inventory)");
  TableReader top(&root, path, "");
  s.title = top.string("title", fs::path(path).stem().string());
  top.get("seed");
  s.seed = parse_study_seed(root, path);
  s.scene_requested = top.choice("scene", "probability", [](const std::string& name) {
    if (auto scene = parse_enum(scene_names, name)) return *scene;
    throw InputError(fmt::format("unknown scene '{}'", name), "scene", "use " + enum_name_list(scene_names, " or ", "\""));
  });
  s.output = top.string("output", fs::path(path).stem().string() + ".h5");
  if (s.output.empty()) throw InputError("output is empty", top.where("output"), "give a results file name");

  parse_records(s, top.table("records"), path);
  const toml::table* structures = top.table("structures");
  const toml::table empty;  // a named table, not `t ? *t : toml::table{}`: that copies *t and loses its lines
  s.structures = parse_structure_model(structures ? *structures : empty, path);
  parse_gaps(s, top.table("gaps"), path);
  parse_contact(s, top.table("contact"), path);
  parse_analysis(s, top.table("analysis"), path);
  parse_report(s, top.table("report"), path);
  parse_outputs(s, top.table("outputs"), path);
  s.intensity = parse_intensity(top.table("intensity"), path, s.structures);
  s.hazard = parse_hazard(top.table("hazard"), path, s.intensity);
  s.target = parse_target_spectrum(top.table("target_spectrum"), path, s.structures);
  if (const toml::table* bridge = top.table("bridge")) parse_bridge(s, top, bridge, structures, path);
  top.finish("title, seed, scene, output, records, structures, gaps, contact, analysis, report, outputs, intensity, "
             "hazard, target_spectrum, bridge");
  check_selection(s, top);
  // a ground motion's sign is arbitrary: a pair study (one pair, answers in metres) takes both by default
  if (!s.polarity_given) s.polarity = s.structures.heights_specified() ? Polarity::both : Polarity::recorded;
  // ida: linear pairs take every capacity exactly from one run; yielding ones need the bisection (study/run.cpp)
  s.intensity.bisection =
      s.intensity.method == FragilityMethod::ida &&
      !(s.structures.building(0).hysteresis == Hysteresis::elastic && s.structures.building(1).hysteresis == Hysteresis::elastic);
  if (!s.structures.bridge) check_shear_study(s, top, structures, path);
  if (s.motions && !s.structures.bridge)
    throw InputError("[records.motions] generates a bridge's support motions, and the study has no [bridge]",
                     s.motions->where, "add a [bridge] whose frames name their support, or name records another way");
  if (s.supports > 0 && !s.structures.bridge)
    throw InputError("[records] supports feeds a bridge's supports, and the study has no [bridge]", s.supports_where,
                     "add a [bridge] whose frames name their support, or delete supports");
  if (s.intensity.enabled && s.scene_requested != Scene::probability)
    throw InputError("a fragility study ([intensity]) runs in the probability scene", top.where("scene"),
                     "write scene = \"probability\": whether a pair touches at a gap is decided by the uncoupled motion");

  choose_scene(s);
  check_per_model(s);
  check_histories(s);
  check_restitution(s, top, path);
  // the results must fit in memory; the suite's record count is not known yet, so count at least one record
  check_result_memory(s, s.select > 0 ? static_cast<std::size_t>(s.select)
                                      : std::max<std::size_t>({std::size_t{1}, s.files.size(),
                                                               static_cast<std::size_t>(std::max(0, s.record_limit))}));
  if (s.intensity.stripes())
    s.scene_reason += s.scale_elastic
                          ? "; at each stripe above the lowest, a model whose buildings stayed elastic at the lowest "
                            "stripe and stay within yield at this one takes the lowest stripe's peaks times the ratio of "
                            "the scale factors (an elastic response scales exactly with the record) instead of a run"
                          : "; every model is analysed at every stripe (scale_elastic = false)";
  if (s.scene == Scene::impacts)
    s.scene_reason += s.skip_untouched
                          ? "; pairs whose uncoupled peak closing stays below a gap never touch there and are not rerun "
                            "with contact (their coupled run would be bit-identical to the uncoupled one)"
                          : "; every pair is rerun with contact at every gap (skip_untouched = false)";
  return s;
}

double result_bytes(const Study& s, std::size_t records) {
  if (!s.per_model || s.stream) {  // the reductions; "stream": and where each unit lies in the checkpoint (16 bytes)
    const std::size_t rows = records * static_cast<std::size_t>(polarity_count(s.polarity));
    const double units = s.stream ? static_cast<double>(rows) * static_cast<double>(s.structures.period_pair_count()) *
                                        std::ceil(static_cast<double>(s.structures.samples_per_pair) / std::max(1, s.batch))
                                  : 0.0;
    return reduction_bytes(rows, static_cast<std::size_t>(s.structures.period_pair_count()), s.gap_ratios.size(),
                           static_cast<std::size_t>(std::floor(s.curve_max / s.curve_step + 1e-9))) +
           16.0 * units;
  }
  const double per_gap = 45.0 + (s.coarse == CoarsePolicy::refine ? 4.0 : 0.0);  // refine: impacts/substeps
  const double per_model = 25.0 + (s.scene == Scene::impacts ? per_gap * static_cast<double>(s.gap_ratios.size()) : 0.0);
  return static_cast<double>(records) * polarity_count(s.polarity) *
         static_cast<double>(std::max<std::size_t>(1, s.intensity.stripes())) * static_cast<double>(s.structures.period_pair_count()) *
         static_cast<double>(s.structures.samples_per_pair) * per_model;
}

int ranks_on_this_node() {
  for (const char* v : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "MPI_LOCAL_NRANKS", "PMI_LOCAL_SIZE"})
    if (const char* s = std::getenv(v); s && std::atoi(s) > 0) return std::atoi(s);
  return 1;
}

// [outputs] per_model = "stream": rank 0's peak (docs/studies.md, "Studies larger than memory"): the reductions and
// the unit index (`need`), each model's code gap (8 bytes), the write's chunks with their shuffled and deflated copies
// (at most 512 MiB of them and the window's deflated chunks, or 4 copies of one record row of 8 M bytes when that is
// more: h5::write_dataset with a Fill), the models' window (64 MiB) and the base.
double stream_peak_bytes(const Study& s, double need) {
  const double M = static_cast<double>(s.structures.period_pair_count()) * static_cast<double>(s.structures.samples_per_pair);
  constexpr double MiB = 1024.0 * 1024;
  return need + 8.0 * M + std::max(640.0 * MiB, 4.0 * 8.0 * M) + 64.0 * MiB + rank_base_bytes;
}

void check_result_memory(const Study& s, std::size_t records) {
  const double need = result_bytes(s, records);
  const double avail = available_memory_bytes();
  const int local = ranks_on_this_node();
  // rank 0's peak: the gathered arrays, the results built from them, the HDF5 image and its copy written out
  // per_model = false builds no models' table (its reductions hold the period grids only)
  const double models = s.per_model && !s.stream ? static_cast<double>(s.structures.period_pair_count()) *
                                                       static_cast<double>(s.structures.samples_per_pair)
                                                 : 0.0;
  const double peak = s.stream ? stream_peak_bytes(s, need) : need * result_peak_factor + models * model_peak_bytes + rank_base_bytes;
  const double share = avail - static_cast<double>(local - 1) * rank_base_bytes;  // the other ranks' part
  const bool over_machine = std::isfinite(avail) && peak > share;
  if (need <= max_result_bytes && !over_machine) return;
  // where samples_per_pair is (or would be) written
  std::string where = fmt::format("{} [structures].samples_per_pair", s.path);
  try {
    const toml::table root = toml::parse(s.text, s.path);
    if (const toml::node* n = root.at_path("structures.samples_per_pair").node())
      where = fmt::format("{}:{} [structures].samples_per_pair", s.path, n->source().begin.line);
    else
      where += fmt::format(" (default {})", s.structures.samples_per_pair);
  } catch (const toml::parse_error&) {
  }
  const double stripes = static_cast<double>(std::max<std::size_t>(1, s.intensity.stripes()));
  const double per_model = need / (static_cast<double>(records) * stripes *
                                   static_cast<double>(s.structures.period_pair_count()) *
                                   static_cast<double>(s.structures.samples_per_pair));
  const double per_sample = need / static_cast<double>(s.structures.samples_per_pair);
  const std::string sizes = fmt::format("{} record{} x {}{} period pairs x {} samples x {} bytes per model", records,
                                        records == 1 ? "" : "s",
                                        stripes > 1 ? fmt::format("{:.0f} stripes x ", stripes) : std::string(),
                                        s.structures.period_pair_count(), s.structures.samples_per_pair, per_model);
  if (need > max_result_bytes) {
    const double fits = std::floor(max_result_bytes / per_sample);
    throw InputError(fmt::format("samples_per_pair = {} needs {} of result arrays ({}), more than the {} limit",
                                 s.structures.samples_per_pair, human_bytes(need), sizes, human_bytes(max_result_bytes)),
                     where,
                     fits >= 1 ? fmt::format("give samples_per_pair <= {:.0f} (the paper uses 256), or split the study, or "
                                             "keep only the reductions ([outputs] per_model = false), or write every "
                                             "model's peaks in bounded memory ([outputs] per_model = \"stream\")", fits)
                               : std::string("split the study into fewer records, period pairs or gaps"));
  }
  const double per_sample_peak = per_sample * result_peak_factor +
                                 static_cast<double>(s.structures.period_pair_count()) * model_peak_bytes;
  const double fits = std::floor((share - rank_base_bytes) / per_sample_peak);
  throw InputError(
      fmt::format("samples_per_pair = {} needs {} of result arrays ({}); with the models' table and the copies made while "
                  "the results are written rank 0 needs about {}, more than the {} of memory available on this machine{}",
                  s.structures.samples_per_pair, human_bytes(need), sizes, human_bytes(peak),
                  human_bytes(share),
                  local > 1 ? fmt::format(" for rank 0 (MemAvailable less the other {} ranks on this node)", local - 1)
                            : std::string(" (MemAvailable)")),
      where,
      fits >= 1 ? fmt::format("give samples_per_pair <= {:.0f}, or split the study (fewer records, period pairs, "
                              "stripes or gaps), or run on a machine with more memory, or keep only the reductions "
                              "([outputs] per_model = false), or write every model's peaks from the checkpoint in "
                              "bounded memory ([outputs] per_model = \"stream\", probability scene of an SDOF pair)",
                              fits)
                : std::string("split the study (fewer records, period pairs, stripes or gaps), or run on a machine with "
                              "more memory"));
}

Study load_study(const std::string& path) { return parse_study(files::read_text(path, "the study file"), path); }

}  // namespace pounding
