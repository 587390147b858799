#pragma once
// A block of sampled pairs whose buildings include a shear building ([structures] model = "shear",
// sampling/building.hpp), run as Systems (docs/architecture.md §2.6.2, §2.6.4, §2.7.1).
//
// Per lane: building b gets storeys_at(h_b) storeys of storey_height each (an SDOF building facing a shear one is
// one storey that reaches the other building's floor nearest its height, its roof when that is lower), the numbers
// of shear_spec() and contact where floors face floors within [contact] level_tolerance, or columns between two
// floors (model::shear_buildings).
// Lanes are bucketed by topology (a stable sort by LaneTopology, then by position in the block, i.e. by global
// sample index) and each bucket runs as one SystemBatch; a lane's numbers depend only on its own inputs, so its
// bits do not depend on the bucketing or the batch width.
//
// Uncoupled (the study-gap group's law none): peak_u1 / peak_u2 = each building's largest |u| relative to the
// ground over its floors; closing = D = max over the study-gap elements of their peak closing (no per-level
// offsets: every element's gap is the study gap), so the lane touches at gap g exactly when D > g, for every g at
// once (the first-passage property of systems, tests/study/test_system_block.cpp). Coupled at one gap: only the
// lanes that touch (D > g) or failed are run (skip_untouched), with impact_count = the sum over elements,
// peak_force = the maximum, t_first_impact = the earliest, h_omega_contact = the largest; the others take the
// uncoupled peaks.
#include <array>
#include <compare>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "pounding/model/system.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/system_series.hpp"
#include "pounding/sampling/bridge.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

// One lane's topology: building b (0 = left) has storeys[b] storeys of storey_height[b] m; a pair has 2 buildings, a
// row ([structures] buildings = n) n.
struct LaneTopology {
  std::vector<int> storeys{1, 1};
  std::vector<double> storey_height{3.2, 3.2};
  // a shear building's storeys of different heights (storey_height as an array, bottom first; storey_height[b] is
  // then their mean); empty: every storey storey_height[b] high
  std::vector<std::vector<double>> heights{{}, {}};
  std::vector<std::uint8_t> isolated{0, 0}, moat{0, 0};  // base isolation, moat walls (the building's keys)
  // a bridge ([bridge], sampling/bridge.hpp): "buildings" are its frames (one floor each, storey_height their pier
  // heights), the System physics::bridge_system's (joints as the study-gap elements, restrainers, bearings, abutments)
  std::uint8_t bridge = 0;
  std::size_t buildings() const { return storeys.size(); }
  // The level (m) of floor k of building b: k storey_height[b], or the sum of its first k heights.
  double level(std::size_t b, int k) const;
  // Building b's storey heights as model::StickTopology takes them: {storey_height[b]} or heights[b].
  std::vector<double> stick_heights(std::size_t b) const;
  friend auto operator<=>(const LaneTopology&, const LaneTopology&) = default;
};

// The study runs Systems (SystemBlock) rather than the pair kernel: a shear building, a row, or a bridge.
inline bool runs_systems(const StructureModel& m) { return m.any_shear() || m.row() || m.bridge != nullptr; }
// The number of bodies of a lane: a bridge's frames, else the buildings.
inline std::size_t body_count(const StructureModel& m) {
  return m.bridge ? m.bridge->frames() : m.building_count();
}

// The topology of pair p under the model (both buildings resolved).
LaneTopology lane_topology(const StructureModel& model, const SampledPair& p);

// Building b's numbers for `storeys` storeys from its sample s: one storey without floor_mass / storey_stiffness is
// the SDOF of the sample (m, T1 through Structure::from_period, fy); otherwise floor masses floor_mass or m /
// storeys, storey stiffnesses storey_stiffness or the profile scaled to T1, storey yield from the yield rule per
// storey (drift/ductility as a drift ratio; Cy as the base shear), alpha, Rayleigh zeta on rayleigh_modes (default 1
// and 2; a sample of fewer storeys: model::rayleigh_modes_for).
physics::ShearSpec shear_spec(const BuildingModel& b, const SampledStructure& s, int storeys);

// The results' largest topology (results format 3, /system): per building its most storeys over every sample of the
// study (a scan of the sampled heights). nullopt when a building is an SDOF facing a shear one (its one contact
// changes level from sample to sample: the study writes format 2, the [R, M] totals only). A row of n >= 3
// buildings (all SDOF or all shear) always has one: its file is format 3.
std::optional<LaneTopology> table_topology(const StructureModel& model, std::uint64_t seed);

// Where a lane's values go in the results' per-floor / per-element rows (the table topology's floors and elements).
struct TableLayout {
  std::vector<std::size_t> floors;  // floors (DOFs) of each building, an isolated base first
  std::size_t elements = 0;
  bool empty() const { return floors.empty(); }
};

// What one run gives per lane (index = the lane's position in the block, or in the run's lanes): filled by SystemBlock
// and by both runners (study/runner.hpp).
struct RunPeaks {
  std::vector<std::uint8_t> status;
  std::vector<double> u1, u2, closing;  // closing: D (uncoupled runs)
  std::size_t buildings = 2;
  std::vector<double> u;  // [lane][building]: each building's largest floor |u| (u1, u2 its first two)
  std::vector<std::int32_t> impact_count;
  // impacts (over the study-gap elements) whose approach velocity lay outside the e(v0) curve's valid range
  // (KernelSettings::restitution; 0 without a curve, -1 for a failed lane)
  std::vector<std::int32_t> restitution_outside;
  std::vector<double> peak_force, t_first_impact, h_omega_contact;
  // the worst contact element of every group (moat walls too): the largest h omega_c / limit of its stepper x law,
  // what [analysis] coarse = "refine" reads (study/refine.hpp)
  std::vector<physics::StepResolution> worst;
  // With a TableLayout: [lane][floor] per building (peak |u|, storey drift, peak |a + ag| in g) and [lane][element]
  // (peak closing; impact count, peak force, peak penetration, first impact, h omega_c, impacts outside the e(v0)
  // curve's range), NaN / -1 where the lane's topology has no such floor or element.
  std::vector<std::vector<double>> floor_u, floor_drift, floor_acc;  // [building]
  std::vector<double> e_closing, e_force, e_penetration, e_first, e_hw;
  std::vector<std::int32_t> e_count, e_outside;
  // With SystemBlock::keep_springs: per lane, each spring's law, numbers and peak |deformation|, and whether a contact
  // element outside the study gap (a moat wall) ran with a law -- what SystemBlock::scales_linearly reads.
  struct Springs {
    std::vector<int> law;
    std::vector<physics::SpringSpec> spec;
    std::vector<double> peak;
    bool walls = false;
  };
  std::vector<Springs> springs;  // [lane], empty without keep_springs
  // A runner's coupled(): each lane's substeps ([analysis] coarse = "refine" reruns a coarse lane at more; else the
  // run's). Not touched by resize, set_scaled or set_lane.
  std::vector<std::int32_t> substeps;
  void resize(std::size_t n, std::size_t buildings = 2, const TableLayout& t = {});
  // Lane `to` = lane k of `from` (sized alike) with every displacement, closing and acceleration peak times `scale`
  // (1: a copy); the uncoupled values only (status, u1, u2, closing, u, the per-floor rows, e_closing).
  void set_scaled(std::size_t to, const RunPeaks& from, std::size_t k, double scale);
  // Lane `to` = lane k of `from` (laid out alike, of any width): every value, coupled ones and springs included.
  void set_lane(std::size_t to, const RunPeaks& from, std::size_t k);
};

// How the contacts of a coupled run are set.
struct ContactNumbers {
  double e = 0.65;
  double stiffness = 0.0;  // > 0: every element's kc; 0: the model's kh, else equivalent spheres of the two floors
};

class SystemBlock {
 public:
  // contact, e: the study's [contact] model and restitution, the moat walls' defaults; levels, gap_offsets: [contact]
  // levels and gap_offsets (per level from 1, m; a level beyond the list 0): which floors pound and what each adds to
  // the study gap. With offsets, D = max over the study-gap elements of (peak closing - offset).
  // level_tolerance: [contact] level_tolerance (m, model::shear_buildings: floors within it meet floor to floor, the
  // others a column).
  explicit SystemBlock(const StructureModel& model, const ContactModel& contact = {}, double e = 0.65,
                       model::ContactLevels levels = model::ContactLevels::common, std::vector<double> gap_offsets = {},
                       double level_tolerance = 0.05, model::ShapeFunctions shape = model::ShapeFunctions::linear)
      : model_(model), contact_(contact), e_(e), levels_(levels), offsets_(std::move(gap_offsets)),
        tolerance_(level_tolerance), shape_(shape) {}
  // For a study: its structures, [contact] model, e, levels, gap_offsets, level_tolerance and shape_functions.
  explicit SystemBlock(const Study& s)
      : SystemBlock(s.structures, s.contact, s.e, s.contact_levels, s.gap_offsets, s.level_tolerance,
                    s.shape_functions) {
    set_joint_offsets(s.joint_gap_offsets);
    set_gap_metres(s.gap_metres);
  }
  // [contact] joint_gap_offsets of a row: per joint left to right (m), added to every element of the joint besides
  // the per-level offsets; D = max over elements of (closing - both offsets). Empty: none.
  void set_joint_offsets(std::vector<double> offsets) { joint_offsets_ = std::move(offsets); }
  // [gaps] metres: coupled()'s `ratio` is the study gap in metres, not a ratio of each lane's d (Study::gap_unit)
  void set_gap_metres(bool on) { gap_metres_ = on; }

  // Every lane of `pairs`, uncoupled: `none` is the study's contact model with law none (the study-gap group's law);
  // status, u1, u2, closing = D.
  void uncoupled(std::span<const SampledPair> pairs, const ContactModel& none, const GroundMotion& gm,
                 const KernelSettings& ks, RunPeaks& out);
  // The lanes `lanes` (positions in `pairs`) coupled at gap = ratio d (with [gaps] metres, a study's block: gap =
  // ratio, in metres; Study::gap_unit) with contact model `cm`; out[j] is lane lanes[j]'s.
  void coupled(std::span<const SampledPair> pairs, std::span<const std::size_t> lanes, double ratio,
               const ContactModel& cm, const ContactNumbers& cn, const GroundMotion& gm, const KernelSettings& ks,
               RunPeaks& out);

  // pairs[0] run alone as coupled() would run it (ratio 0 and the law none: uncoupled()), recording its series
  // (physics::run_system_recorded; an SDOF pair System through the pair kernel's recorder, as run_system runs it):
  // the same numbers as that lane of any block ([outputs] histories, study/histories.hpp). Returns the lane's System.
  const model::System& record(std::span<const SampledPair> pairs, double ratio, const ContactModel& cm,
                              const ContactNumbers& cn, const GroundMotion& gm, const KernelSettings& ks,
                              RunPeaks& out, physics::SystemSeries& series);

  // A bridge on several supports: one motion per channel (the record's support 1 first; the same dt and length as
  // the motion the runs get), used instead of that motion while set; empty: uniform input.
  void set_channels(std::span<const GroundMotion> channels) { channels_ = channels; }

  // The System of a topology (built once, kept for the block's lifetime).
  const model::System& system(const LaneTopology& t);
  // The results' table System of a topology (table_topology()): system(t), except with levels = "top", where it has
  // every common level (each lane's lower roof is one of them, at a level that varies with its storeys).
  const model::System& table_system(const LaneTopology& t);
  // Fill RunPeaks' per-floor / per-element rows laid out as `table` (the System of table_topology()).
  void set_table(const model::System& table);
  const TableLayout& layout() const { return layout_; }
  // Runs keep each lane's springs in RunPeaks::springs (for scales_linearly).
  void keep_springs(bool on) { keep_springs_ = on; }
  // The model trait behind a fragility study's shortcut (multiple stripes, IDA; issue 25 §1): lane k of `p` (a run
  // with keep_springs, status ok) answers the record scaled by `ratio` >= 1 more with its peaks times `ratio` when
  // it is linear over that range -- every spring stays elastic at ratio x its peak deformation (each law's
  // stays_elastic, physics::spring_stays_elastic; a smooth bearing never does), no moat wall ran with a law, and
  // ratio x the sum over buildings of their largest |u| stays within `limit` (the divergence guard's sum, bounded).
  // False with gap_offsets (D = max(closing - offset) is not linear in the record) and for a bridge.
  bool scales_linearly(const RunPeaks& p, std::size_t k, double ratio, double limit) const;
  // Lane `lane` of b (sized for system(t)) from pair p: both buildings' numbers (shear_spec; an isolated one through
  // physics::set_isolated_building, its base mass one floor's unless given), every pounding element's gap, e and kc
  // (cn.stiffness, else the model's kh, else equivalent spheres of the two floors' masses; two one-storey buildings:
  // the pair's kh, as the SDOF study), and the moat walls' numbers (physics::set_moat).
  void set_lane(physics::SystemBatch& b, std::size_t lane, const SampledPair& p, const LaneTopology& t, double gap,
                const ContactNumbers& cn) const;

  // The contact models of a run: group 0 the pounding (`pounding`), then one per moat, building order.
  std::vector<ContactModel> groups(const LaneTopology& t, const ContactModel& pounding) const;
  // Each element's gap offset in `sys` (a study-gap element: gap_offsets[level - 1], 0 beyond the list, plus its
  // joint's offset; a moat wall, whose group is not study-gap: the whole gap, its building's moat gap): the results'
  // /system/element_gap_offset (docs/results-format.md). Empty without gap offsets and moat walls.
  std::vector<double> element_offsets(const model::System& sys) const;

 private:
  // lanes[j] of `pairs` bucketed by topology, one run_system per bucket, out[j] lane lanes[j]'s
  // lane l of the last bucket's res_ (width w) into lane k of out's per-floor / per-element rows (to_table: element order)
  void table_lane(RunPeaks& out, const model::System& sys, std::span<const std::size_t> to_table, std::size_t l,
                  std::size_t w, std::size_t k) const;
  // lane l of the last bucket's batch_/res_ (width w) into s
  void keep_lane_springs(RunPeaks::Springs& s, const model::System& sys, std::span<const ContactModel> groups,
                         std::size_t l, std::size_t w) const;
  void run(std::span<const SampledPair> pairs, std::span<const std::size_t> lanes, double ratio, const ContactModel& cm,
           const ContactNumbers& cn, const GroundMotion& gm, const KernelSettings& ks, RunPeaks& out,
           physics::SystemSeries* series = nullptr);
  // batch_ through run_system into res_ (the motions: channels_, else gm); with `series` its lane 0 recorded
  void run_lanes(std::span<const ContactModel> groups, const GroundMotion& gm, const KernelSettings& ks,
                  physics::SystemSeries* series);

  const StructureModel& model_;
  ContactModel contact_;
  double e_;
  model::ContactLevels levels_;
  std::vector<double> offsets_, joint_offsets_;
  bool gap_metres_ = false;  // [gaps] metres: a run's `ratio` is the study gap in metres (Study::gap_unit)
  double tolerance_ = 0.05;
  std::span<const GroundMotion> channels_;
  model::ShapeFunctions shape_ = model::ShapeFunctions::linear;
  std::map<LaneTopology, std::unique_ptr<model::System>> systems_, table_systems_;
  std::vector<LaneTopology> keys_;
  std::vector<std::size_t> order_, bucket_, all_;
  physics::SystemBatch batch_;
  physics::SystemResult res_;
  TableLayout layout_;
  bool keep_springs_ = false;
  std::map<std::string, std::size_t> table_elements_;  // element label -> index in the table topology
  std::map<std::string, std::size_t> table_joints_;    // "K|K+1" -> the table's element of a one-element joint
  // Each element of `sys` in the table's order (by label: level k is level k, a moat wall its wall; a row's joint of
  // one element: the table's one element of that joint), layout_.elements where the table has none.
  std::vector<std::size_t> table_indices(const model::System& sys) const;
  // "K|K+1" of a row's element label ("2|3 level 1/2"), "" for a pair's or a wall's
  static std::string joint_of(const std::string& label);
  // The joint (0 = buildings 1|2) of element e of a row's System: the lower of its two bodies
  static std::size_t joint_index(const model::System& sys, std::size_t e);
};

// Before any work: every sample's shear buildings against the integration step of every record, with
// physics::structure_step_max (central difference with damping needs h^2 omega^2 + 4 h (2 zeta omega) < 4 for every
// mode, Gershgorin's bounds on M^-1 K0 and M^-1 C; the bound physics::validate checks per lane). InputError naming
// [analysis] substeps / max_dt, the sample and the step that would do, for the study-wide worst case. Scans up to
// `max_models` models (the first of each period pair beyond that: the run's own per-lane check, physics::validate,
// still refuses the rest, later). Without [analysis] substeps / max_dt (study.step_given false) the step is chosen
// instead: max_dt lowered to the worst case's bound (rounded down to 3 digits, below 0.999 of it) and the reason
// appended to study.scene_reason (stored in the results, printed by the run) -- a study that was stable keeps its step.
void check_shear_steps(Study& study, std::span<const StudyRecord> records, std::size_t max_models = 250000);

}  // namespace pounding
