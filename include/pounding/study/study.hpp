#pragma once
// A study file (studies/*.toml) parsed once into a validated, immutable Study.
// Every key's type, default, units, range and meaning: src/config/study_keys.cpp (the parsers read no key it
// does not describe), published as docs/study-reference.md (`pounding study-reference`). Overview:
//
//   title = "..."                 seed = 20240601 (required)
//   scene = "probability" | "impacts" | "auto"
//   output = "results/quick.h5"   (relative to the working directory; default <study stem>.h5)
//   [records]    suite = "..." (relative to the study file, or "builtin" for the embedded 25-record suite)
//                | files = ["a.AT2", {path = "b.AT2", scale = 1.2}]
//                | directory = "..."; real_dir = "..." (resolve suite entries to real PEER files);
//                scale = 1.0; units = "g" | "m/s2" | "cm/s2"; dt = <s, one-column files>; limit = <first N>;
//                synthetic_only = false; select = N (choose N records from that library and scale them to the
//                [target_spectrum]; not with limit); with select: max_per_event = 2 (records of one earthquake at
//                most, 0: no limit; FEMA P-695's far-field set takes 2) and components = "one" | "both" (one: one
//                component per station, the better match); a second copy of one recording is never chosen
//                (motion/library.hpp says how event, station and component are read);
//                polarity = "recorded" | "both" (default "both" in a pair study -- both buildings' heights given --,
//                "recorded" in a grid study): "both" applies every record with both signs, as two analyses of the
//                same record (study/records.cpp): a ground motion's sign is arbitrary, and pounding counts only
//                when building 1 moves towards building 2 (peak of u1 - u2). The statistics over records (bootstrap,
//                jackknife, per-record tables) keep a record's two signs together as ONE record. A grid study's
//                default is the published method's ("recorded"; its period grid holds both (Ta, Tb) and (Tb, Ta),
//                which mirror each other's closing); the paper studies state it.
//   [structures] the stochastic structure model (see sampler.hpp): the defaults of both buildings; equal_heights = false
//                [structures.building1] / [structures.building2]: one building's overrides and its own period, height,
//                mass, zeta, yield_coefficient (a number or {lognormal = {median, cov}} / {uniform = {min, max}};
//                see building.hpp); heights given to both make a "pair study" (answers in metres)
//   [gaps]       ratios = [0.1, 0.2, 0.3, 0.5, 0.7, 1.0]; curve_max = 1.5; curve_step = 0.005
//   [contact]    law = "hertzdamp"; damping_law = "lankarani-nikravesh"; e = 0.65; n = 1.5; v0_min = 1e-3;
//                stiffness = <N/m^n for the Hertz family (default: equivalent spheres), N/m for linear/Kelvin (required)>;
//                restitution = "lindsay2011" | {preset | polynomial = [c0, c1, ...] | table = [[v, e], ...], units =
//                "m/s", valid = [vmin, vmax]} (e(v0) at each impact instead of e: SDOF pairs, hertzdamp, central
//                difference, the impacts scene; impacts outside the valid range counted: impacts/restitution_outside)
//   [analysis]   stepper = "central-difference"; substeps = 1; max_dt = <s; 0: no cap; default 0.0025 in the impacts
//                scene (cheapest step with 1 % peak force, docs/accuracy.md), 0 in the probability scene>; batch = 256; free_vibration = 0.0 (s);
//                displacement_limit = 10.0 (m); skip_untouched = true (impacts scene: pairs whose uncoupled
//                peak closing stays below the gap are not rerun with contact; their results are identical);
//                scale_elastic = true (multiple stripes: a model whose buildings stay elastic -- peak |u| below fy / k at
//                the lowest stripe times the ratio of the factors -- takes the lowest stripe's peaks times that ratio at
//                the higher stripe instead of a run: the elastic response scales exactly with the record);
//                max_excluded_fraction = 0.001 (in [0, 1]: the largest fraction of all analyses that may be
//                excluded (diverged, non-finite) before the run ends with exit code 3 and a warning banner);
//                coarse = "exclude" | "keep" (default "exclude"): what to do with a coupled analysis the resolution
//                guard marks coarse (it ran, but its h omega_c exceeds the accuracy limit of the stepper x law,
//                physics/resolution.hpp: its peak force is off by more than 1 %). "exclude" treats it like a diverged
//                analysis (left out of the statistics, counted in max_excluded_fraction): a number known to be
//                wrong is not averaged in silently. "keep" keeps it in the statistics (impact verdicts and counts
//                are much less sensitive to the step than the peak force) but still counts and reports it.
//   [report]     targets = [10, 5, 1] (% probability); fit_min = 0.1; fit_max = 1.0 (gap ratios of the cubic fit);
//                confidence = 0.95 and bootstrap = 2000 (the two-stage bootstrap over records and models within
//                records behind the intervals of a pair study's separation in metres, analysis/separation.hpp;
//                0 replicates: no interval); compare_with = "" | "stochastic-pounding" (print the published
//                study's Table 3 and eq. 10 beside ours; the paper studies set it); html = false (also write the HTML
//                report, report/html.hpp, next to the results: the output path with .html). The old h1/h2 keys are refused:
//                metres come from the buildings' own heights ([structures.building1/2] height).
//   [outputs]    forces = true; amplification = true   (what the impacts scene must deliver; `auto` reads it)
//                per_model = true: false keeps only the reductions (study/reductions.hpp: counts per record, gap
//                ratio and period pair, the gap curve, per-record histograms of the peak-closing ratio) so a study
//                larger than memory runs in bounded memory; probability scene of an SDOF pair only
//   [intensity]  [hazard]   a fragility study: records scaled to IM levels (stripes), fragility per gap, the site's
//                annual rate of pounding and the risk-targeted separation (study/intensity.hpp)
//   [target_spectrum] code = "ASCE 7-16" | "EC8" | "Standard 2800" | "csv" and its parameters; rule, t_min, t_max,
//                points = 30, damping = 0.05, min_scale = 0.25, max_scale = 4: the records of [records] select = N
//                are chosen and amplitude-scaled to this design spectrum (study/target_spectrum.hpp lists every key;
//                one without the other is an error)
//
// Sanity limits (errors naming the file, line and key, not a report full of nan or a std::bad_alloc):
//   - every record must pass require_analysable (records.hpp) after units and scale: at least 2 s long,
//     PGA at most 5 g (a PGA of 499 g is a file in cm/s^2 read as g, or a wrong scale);
//   - the per-model result arrays rank 0 holds (result_bytes) must fit in max_result_bytes (64 GiB): a
//     [structures] samples_per_pair of 2^40 is refused with the memory it would need.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/contact/restitution.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/intensity.hpp"
#include "pounding/study/target_spectrum.hpp"

namespace pounding {

enum class Scene : std::uint8_t { probability, impacts, automatic };
inline constexpr EnumName<Scene> scene_names[] = {
    {Scene::probability, "probability"}, {Scene::impacts, "impacts"}, {Scene::automatic, "auto"}};
constexpr const auto& enum_names(Scene) { return scene_names; }  // to_string(Scene), enum_names.hpp

// [analysis] coarse: LaneStatus::coarse analyses excluded from the statistics (like diverged) or kept (counted).
enum class CoarsePolicy : std::uint8_t { exclude, keep };
inline constexpr EnumName<CoarsePolicy> coarse_policy_names[] = {{CoarsePolicy::exclude, "exclude"},
                                                                 {CoarsePolicy::keep, "keep"}};
constexpr const auto& enum_names(CoarsePolicy) { return coarse_policy_names; }
CoarsePolicy parse_coarse_policy(std::string_view name);  // InputError naming the allowed values

// [records] polarity: every record as recorded, or with both signs (record r's two analyses are rows 2r, 2r+1).
enum class Polarity : std::uint8_t { recorded, both };
inline constexpr EnumName<Polarity> polarity_names[] = {{Polarity::recorded, "recorded"}, {Polarity::both, "both"}};
constexpr const auto& enum_names(Polarity) { return polarity_names; }
Polarity parse_polarity(std::string_view name);  // InputError naming the allowed values
inline int polarity_count(Polarity p) { return p == Polarity::both ? 2 : 1; }

struct RecordFile {
  std::string path;
  double scale = 1.0;
};

struct Study {
  std::string path;  // the study file
  std::string text;  // its full text (echoed into the results)
  std::string title;
  std::uint64_t seed = 0;
  Scene scene_requested = Scene::probability;
  Scene scene = Scene::probability;  // after resolving "auto"
  std::string scene_reason;
  std::string output;
  // records
  std::string suite, real_dir, directory;
  std::vector<RecordFile> files;
  double scale = 1.0;
  AccUnits units = AccUnits::g;
  double dt_one_column = 0.0;
  int record_limit = 0;
  bool synthetic_only = false;  // suite: every entry a synthetic stand-in, even where a real file exists
  int select = 0;               // [records] select: choose this many records to [target_spectrum] (0: keep all)
  std::string select_where;     // "file:line [records].select" for errors found when the records load
  std::size_t max_per_event = default_max_per_event;  // [records] max_per_event (with select; selection.hpp)
  ComponentRule components = ComponentRule::one;      // [records] components (with select)
  Polarity polarity = Polarity::recorded;  // [records] polarity, after its default (pair study: both)
  bool polarity_given = false;
  // [records] supports = N (a bridge on several supports): the directory's files *_s01 .. *_sNN with one prefix are
  // one realisation's N support motions (pounding motions' rRRR_sJJ.AT2); 0: one record per analysis
  int supports = 0;
  std::string supports_where;  // "file:line [records].supports" for errors found when the records load
  // structures
  StructureModel structures;
  // gaps
  std::vector<double> gap_ratios{0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
  double curve_max = 1.5, curve_step = 0.005;
  // contact and analysis
  ContactModel contact;
  double e = 0.65;
  // [contact] restitution: e(v0) at the latched approach velocity of each impact (contact/restitution.hpp), used
  // instead of e by the coupled runs (physics::HertzdampRestitution); absent: e
  std::optional<contact::RestitutionCurve> restitution;
  double contact_stiffness = 0.0;  // > 0 overrides the sampled Hertz kh; required (N/m) for linear/Kelvin
  // [contact] levels and gap_offsets (shear buildings and rows, docs/architecture.md §2.7.1): which facing floors
  // pound, and per level from level 1 the offset (m, >= 0) added to the study gap (levels beyond the list: 0)
  model::ContactLevels contact_levels = model::ContactLevels::common;
  std::vector<double> gap_offsets;
  // [contact] joint_gap_offsets (a row of n buildings): per joint left to right (n - 1 values, m, >= 0) the offset
  // added to the study gap of every element of that joint, besides gap_offsets' per level (empty: none)
  std::vector<double> joint_gap_offsets;
  // [contact] level_tolerance (m): floors of neighbouring shear buildings whose levels differ by at most this meet
  // floor to floor; any other floor below the neighbour's roof meets its column (model::shear_buildings)
  double level_tolerance = 0.05;
  // [contact] shape_functions: the column side's weights (model::column_weight), linear or the fixed-fixed cubic
  model::ShapeFunctions shape_functions = model::ShapeFunctions::linear;
  Stepper stepper = Stepper::central_difference;
  int substeps = 1;
  double max_dt = 0.0;  // step cap (s): substeps = max(substeps, ceil(dt / max_dt)); default 2.5 ms (impacts), 0 (probability)
  int batch = 256;
  // [analysis] threads: worker threads per rank (0: the CPUs of the affinity mask on one rank, 1 per rank under
  // mpirun with several ranks); how the work runs, not what it computes: not in /settings, the results' bits do
  // not depend on it (pounding run --threads overrides it)
  int threads = 0;
  double free_vibration = 0.0;
  double displacement_limit = 10.0;
  bool skip_untouched = true;  // impacts scene: pairs that never touch take their uncoupled results
  bool scale_elastic = true;   // stripes: models elastic at the lowest stripe and within yield take its peaks x ratio
  double max_excluded_fraction = 0.001;  // [analysis]: more excluded analyses than this fraction -> exit code 3
  CoarsePolicy coarse = CoarsePolicy::exclude;  // [analysis] coarse: analyses marked coarse by the resolution guard
  // report
  std::vector<double> targets{10.0, 5.0, 1.0};
  double fit_min = 0.1, fit_max = 1.0;
  double confidence = 0.95;
  int bootstrap = 2000;
  std::string compare_with;  // "" or "stochastic-pounding"
  bool html = false;         // [report] html: the HTML report next to the results (report/html.hpp)
  // outputs wanted from the impacts scene
  bool want_forces = true, want_amplification = true;
  bool per_model = true;  // [outputs] per_model: false = reductions only (study/reductions.hpp)
  std::string per_model_where;  // "file:line [outputs].per_model"
  // [intensity] and [hazard] (study/intensity.hpp): a fragility study
  IntensitySpec intensity;
  HazardSpec hazard;
  // [target_spectrum] (study/target_spectrum.hpp): the design spectrum the `select` records are scaled to
  TargetSpectrumSection target;
};

// Bytes of the per-model result arrays rank 0 gathers for `records` records (src/study/run.cpp): per record
// and model, the uncoupled status (1 byte) and three peaks (8 bytes each) = 25 bytes; in the impacts scene,
// per gap, a status (1), an impact count (4) and five doubles (40) = 45 bytes more. A double, so that absurd
// sizes do not overflow.
// With [outputs] per_model = false: the reductions' bytes instead (study/reductions.hpp reduction_bytes).
double result_bytes(const Study& study, std::size_t records);
inline constexpr double max_result_bytes = 64.0 * 1024 * 1024 * 1024;  // 64 GiB
// Rank 0's peak memory is about result_peak_factor x result_bytes + model_peak_bytes per sampled model (the models'
// table and its copies in the results and the HDF5 image) + rank_base_bytes, and each other rank on the node needs
// about rank_base_bytes. Measured 2026-11-25 on this 2-core VM: 1 record x 1 period pair x 1e6 samples (probability
// scene, 25 MB of result arrays) peaked at 610 MB RSS against 24 MB for 1,000 samples: 586 bytes per model.
inline constexpr double result_peak_factor = 4.0;
inline constexpr double model_peak_bytes = 500.0;
inline constexpr double rank_base_bytes = 256.0 * 1024 * 1024;
// The memory this process may still use: MemAvailable, or less when a cgroup (container) limit leaves less;
// NaN when unknown (then only max_result_bytes applies). POUNDING_TEST_MEMORY_AVAILABLE (bytes) replaces it in tests.
double available_memory_bytes();
// Throws InputError naming [structures] samples_per_pair (file:line), the memory needed and the largest
// samples_per_pair that fits, when result_bytes(study, records) > max_result_bytes, or when rank 0's peak
// (result_peak_factor x result_bytes + rank_base_bytes) exceeds the memory available on this machine less
// rank_base_bytes for each other rank on the node (OMPI_COMM_WORLD_LOCAL_SIZE, ...).
void check_result_memory(const Study& study, std::size_t records);

// Integration steps per record step of spacing dt: max(substeps, ceil(dt / max_dt)).
inline int study_substeps(const Study& s, double dt) {
  const int q = s.max_dt > 0 ? static_cast<int>(std::ceil(dt / s.max_dt - 1e-9)) : 1;
  return std::max(s.substeps, q);
}

// Parses and validates; every problem is an InputError naming file:line, the key and the allowed values.
// The memory check runs here with a lower bound on the record count (files, or limit); load_study_records
// repeats it with the real count.
Study parse_study(const std::string& text, const std::string& path);
Study load_study(const std::string& path);

// One input record of the study, resolved (real file or synthetic stand-in), scaled, in m/s^2.
struct StudyRecord {
  Record record;
  bool synthetic = false;
  std::string id;    // suite id (EQ1...) or file stem
  std::string note;  // how it was resolved
  int polarity = 1;  // +1: as recorded; -1: the record with its sign reversed ([records] polarity = "both")
  // [records] supports = N: supports 2..N of the realisation (record is support 1), same dt and length
  std::vector<Record> more_supports;
};
// With [records] polarity = "both" every record (after select and limit) is followed by its reversed copy
// (-acc, polarity -1, the same id): record r's two analyses are rows 2r and 2r + 1.
// With [records] select: the chosen records, best match first, each multiplied by its factor f_i F; the
// selection goes to *selection when given (the run log prints it, /selection stores it). Deterministic: every
// rank computes the same records bit for bit.
std::vector<StudyRecord> load_study_records(const Study& study, StudySelection* selection = nullptr);

// load_study_records in parts, so that ranks and threads share the reading and synthesis (issue 27 item 3):
// the records the [records] section names, before selection, are `count` independent makers (make(i) reads or
// synthesises record i alone), then finish_study_records selects, limits, checks memory and adds polarities.
struct RecordPlan {
  std::size_t count = 0;
  std::function<StudyRecord(std::size_t)> make;
};
RecordPlan plan_study_records(const Study& study);
// make(i) for every i on `threads` threads (0: the CPUs this process may use); the records in order, or the error
// of the first record (in order) that failed, whichever thread met it.
std::vector<StudyRecord> make_records(const RecordPlan& plan, int threads = 0);
// The records i = rank, rank + ranks, ... (each, or the error making it) as bytes for an exchange between ranks;
// join_record_shares of every rank's share gives make_records' result (records or first error) bit for bit.
std::string make_record_share(const RecordPlan& plan, int rank, int ranks, int threads = 0);
std::vector<StudyRecord> join_record_shares(const std::vector<std::string>& shares, std::size_t count);
std::vector<StudyRecord> finish_study_records(const Study& study, std::vector<StudyRecord> library,
                                              StudySelection* selection = nullptr);
// The selection step of load_study_records (src/study/target_spectrum.cpp): `library` is every record the
// [records] section names.
std::vector<StudyRecord> select_study_records(const Study& study, std::vector<StudyRecord> library,
                                              StudySelection& selection);
// The suite part of plan_study_records (src/study/suite.cpp).
RecordPlan plan_suite_records(const Study& study);

}  // namespace pounding
