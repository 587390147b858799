#pragma once
// The report's view of a Results (internal to src/report): the columns it reads by short names, its settings,
// and the counting helpers that report.cpp (the paper's tables) and separation_sections.cpp (separations in
// metres, code rules) share.
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pounding/analysis/code_displacement.hpp"
#include "pounding/analysis/separation.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/kernel/batch.hpp"
#include "pounding/model/modes.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/report/report.hpp"
#include "pounding/results/results.hpp"

namespace pounding::report_detail {

template <class T>
std::span<const T> column_or_empty(const results::Results& r, const char* group, const char* name) {
  return r.find(group, name) ? std::span<const T>(r.column<T>(group, name)) : std::span<const T>();
}

struct UncoupledCounts;

struct Data {
  const results::Results& res;
  const results::Header& h;
  const results::RecordTable& rec;
  const results::ModelTable& mod;
  ReportSettings set;
  std::span<const std::uint8_t> status, imp_status;
  std::span<const double> peak_u1, peak_u2, peak_closing, peak_force, imp_peak_u1, imp_peak_u2;
  std::span<const std::int32_t> impact_count;
  std::span<const double> h_omega;
  bool impacts, keep_coarse;
  // [outputs] per_model = false: the file's /reductions (study/reductions.hpp) and no per-model arrays; the counts
  // below answer from it exactly, the separations from its histograms (null for a per-model file)
  const results::Group* red = nullptr;
  std::size_t red_models = 0;

  explicit Data(const results::Results& r, const WorkHook* hook = nullptr, double* bootstrap_s = nullptr);
  const WorkHook* hook = nullptr;  // progress and stop of the bootstrap (core/progress.hpp)
  double* bootstrap_s = nullptr;   // seconds in prepared() and bootstrap() are added here (may be null)
  int* bootstrap_runs = nullptr;   // bootstraps actually run are counted here (may be null)
  // ok, or coarse kept in the statistics by [analysis] coarse = "keep"
  bool ok(std::uint8_t s) const { return s == 0 || (keep_coarse && s == static_cast<std::uint8_t>(LaneStatus::coarse)); }
  std::size_t records() const { return rec.size(); }  // rows: (record, sign) analyses with polarity "both"
  // [records] polarity: the rows per independent record (2 with "both": rows 2k, 2k + 1 are record k's two signs)
  // and the independent records, which the per-record tables list and the bootstrap resamples.
  std::size_t per_record = 1;
  // Every model identical (one fixed pair): a record's analyses repeat one analysis (or its two signs), so they
  // are not independent draws and the Wilson interval takes n = the independent records (wilson() below).
  bool fixed_pair = false;
  std::size_t independent() const { return rec.size() / per_record; }
  std::string record_label(std::size_t row) const;  // the id, "(sign reversed)" on a reversed row
  std::size_t models() const { return red ? red_models : mod.size(); }
  // The reductions' per-record histograms of z (independent records: a record's two signs summed)
  separation::HistogramDemands histograms() const;
  std::size_t gaps() const { return res.gap_ratios.size(); }
  // Model m's gap unit: its code gap d on a ratio axis, 1 (m) on a metres axis ([gaps] metres, issue 45 item 4): the
  // gap at axis value x is x unit(m) and the demand closing / unit(m) (ratio axis: the products and quotients the
  // report always took)
  double unit(std::size_t m) const { return set.metres ? 1.0 : mod.code_gap[m]; }
  // The gap axis as a column title and in a sentence: "gap ratio" / "gap ratio x", or "gap m" / "gap (m)"
  const char* axis_title() const { return set.metres ? "gap m" : "gap ratio"; }
  // the paper is in ratios of d: no comparison on a metres axis
  bool paper() const { return set.compare_with == "stochastic-pounding" && !set.metres; }
  // Damping ratio of building b (1 or 2) of model m (per building when the file has it).
  double zeta(int b, std::size_t m) const;
  // The period grids of buildings 1 and 2 (the shared grid in files without per-building grids).
  const std::vector<double>& periods(int b) const;
  // The demand of every analysis: peak closing in metres (pair study) or in code gaps d (grid study); NaN
  // where excluded. Records are the independent ones: with polarity "both" a record's two signs are its
  // 2 x models analyses (the rows are consecutive, so the flat order is the same).
  separation::Demands demands(bool metres) const;
  separation::BootstrapSettings bootstrap_settings() const;
  // The two-stage bootstrap of demands(metres) with the report's settings (and the hook): the demands are ranked
  // once per report and shared by every section's targets and gaps, which all see the same replicates. A request
  // whose targets and gaps (and lognormal) an earlier call on this Data covered is answered from that call's
  // result: one Data serving the CSV (its call covers every target and gap) and then the Markdown runs one bootstrap
  // (report_texts). The estimates of a target or gap do not depend on the others asked with it, so the digits agree.
  separation::BootstrapResult bootstrap(bool metres, std::span<const double> targets, std::span<const double> gaps,
                                        bool lognormal = false) const;
  const separation::Prepared& prepared(bool metres) const;  // demands(metres) ranked (once per report)
  // count_uncoupled's answers at gap ratio x, from one pass over the analyses (kept for the report: its tables ask
  // per record, per period pair and in total at the same few ratios).
  const UncoupledCounts& uncoupled_counts(double x) const;

 private:
  mutable std::vector<std::pair<double, std::shared_ptr<const UncoupledCounts>>> uncoupled_;
  mutable std::shared_ptr<const separation::Prepared> prepared_[2];  // demands(false), demands(true)
  struct Computed {
    bool metres, lognormal;
    std::vector<double> targets, gaps;
    separation::BootstrapResult result;
  };
  mutable std::vector<Computed> computed_;  // every bootstrap this Data ran
};

struct Count {
  std::int64_t hits = 0, n = 0;
  double pct() const { return n ? 100.0 * static_cast<double>(hits) / static_cast<double>(n) : NAN; }
};
// The uncoupled verdicts at one gap ratio per independent record, per period pair (i1 n2 + i2, the model table's
// grid indices) and in all.
struct UncoupledCounts {
  std::vector<Count> per_record, per_pair;
  std::size_t n1 = 0, n2 = 0;
  Count total;
};

std::string pct(double p);
// The 95 % Wilson interval of hits / n analyses: the models' sampling error under these records. For a fixed pair
// (Data::fixed_pair) n analyses would be false precision (issue 23, item 8): the interval is Wilson's at the
// observed fraction with n = the independent records instead; wilson_basis says which, in words.
Interval wilson(const Data& r, std::int64_t hits, std::int64_t n);
std::string wilson_basis(const Data& r);
// The uncoupled verdict "touches at least once at gap ratio x d", over one independent record (rec >= 0: both
// its signs with polarity "both") and one period pair (i1 >= 0), or all.
Count count_uncoupled(const Data& r, double ratio, int rec, int pair_i1 = -1, int pair_i2 = -1);

// A target t (a fraction) is resolved by N independent records when floor(t N) >= 1 (some record may exceed it); an
// unresolved target's empirical answer is (close to) the largest record's demand, whatever t (separation_sections.cpp).
bool resolved_by(double t, std::size_t N);
// The largest ok demand of each independent record that has one (both signs, every model): N = its size.
std::vector<double> record_peaks(const separation::Demands& d);
// What record k of the table is: "stand-in" (a synthetic stand-in for a missing recording), "generated" (a motion a
// generator made for the study, [records.motions]: its source starts "synthetic:") or "recorded" (report.cpp); and
// the report's "synthetic" cell for it: yes, generated, no.
std::string record_kind(const results::RecordTable& t, std::size_t k);
std::string synthetic_cell(const results::RecordTable& t, std::size_t k);
// The gap ratio x as a column title; "x d = g m" when the code gap is the same for every model; "x m" on a metres axis
// (report.cpp).
std::string gap_title(const Data& r, double x);
// The axis value x in a column title of the system sections: "x = 0.3", or "0.04 m" on a metres axis (report.cpp).
std::string axis_label(const Data& r, double x);

// The moat walls of the isolated buildings (moat_section.cpp): per building with a moat, its walls (elements of a group
// that is not study-gap with a wall side) and their gap (/system/element_gap_offset; NaN in files that hold 0 there).
struct MoatBuilding {
  std::size_t body = 0;
  std::string label;
  std::vector<std::size_t> walls;
  double gap = NAN;
};
std::vector<MoatBuilding> moat_buildings(const results::SystemTable& sys);
// "Moat walls: probability that the isolated base hits its moat": P(at least one moat-wall impact) with the report's
// interval, without pounding and with it at each gap ratio, and the base's peak displacement; "" without a moat.
std::string moat_section(const Data& r);
std::string moat_csv(const Data& r);  // rows "moat" of the CSV report
// [gaps] existing (m): P(uncoupled peak closing > existing) over every ok analysis (exact, the per-model closings),
// with the report's Wilson interval; the section's text (report.cpp), "" without an existing gap or per-model peaks.
Count count_existing(const Data& r);
// Why a report is made from the reductions ([outputs] per_model = false, or the run's report of "stream"; report.cpp).
std::string reductions_reason(const Data& r);
std::string existing_section(const Data& r);
// The same per stripe of a fragility study (levels: the stripes' IM values, im: their measure and units).
std::string moat_fragility_section(const results::Results& r, std::span<const double> levels, const std::string& im);

// Sections on separations (separation_sections.cpp).
std::string pair_separation_section(const Data& r);  // the pair's separation in metres (report's first section)
std::string code_rules_section(const Data& r);
std::string floors_section(const Data& r);  // per-floor (bridges: per-deck) amplification of a System (floors_section.cpp)
// Per contact element: P(hit), peak force given a hit, column shears; per floor: acceleration amplification
// (levels_section.cpp); the CSV's rows level, level_force, level_shear_below/above, floor_acc
std::string levels_section(const Data& r);
std::string levels_csv(const Data& r);
std::string bridge_section(const Data& r);  // a bridge study's joints and frames by name (bridge_section.cpp)       // the code rules: in metres for a pair, probabilities for a grid
std::string grid_advice_section(const Data& r);      // a grid study's separation advice in gap ratios
// One target of a grid (or bridge) study's advice: the target in %, the order statistic with its bootstrap interval
// (gap ratios; a bridge's in units of d) and the cubic's root (a grid's only). Built once (report.cpp), formatted by
// grid_advice_section and separation_csv (replicates: the bootstrap's, may be null).
// A bridge's row also says whether the records resolve the target (resolved_by over the independent records with an
// ok analysis, as the pair's advice) and, where they do not, carries the lognormal's estimate (units of d).
struct AdviceRow {
  double target = 0;
  separation::Estimate estimate;
  std::optional<double> cubic;
  bool resolved = true;
  std::size_t records = 0;
  separation::Estimate lognormal{NAN, NAN, NAN};
};
std::vector<AdviceRow> grid_advice_rows(const Data& r, int* replicates = nullptr);
// One code rule of a grid study: the rule (model 0's name, clause, formula; each model has its own gap), the
// analyses (ok) above their model's gap out of n, and the Wilson 95 % interval. Built once
// (separation_sections.cpp), formatted by code_rules_section and separation_csv.
struct GridRuleRow {
  separation::Rule rule;
  std::int64_t hits = 0, n = 0;
  double probability = NAN;
  Interval wilson;
};
std::vector<GridRuleRow> grid_rule_rows(const Data& r);
// "Records selected to the design spectrum" from /selection ([records] select); "" without it (selection_section.cpp)
std::string selection_section(const results::Results& r);
// "Stored time histories" from /histories ([outputs] histories, study/histories.hpp): one row per history; ""
// without it (selection_section.cpp)
std::string histories_section(const results::Results& r);
std::string separation_csv(const Data& r);           // rows pair_curve, separation, code_rule, code_design

// The codes' own design displacements (code_design.cpp): the study's design spectrum from /settings (none without
// [target_spectrum] or for files that do not store its parameters), a building as the codes see it (medians over
// the models, or one model), the rows with their notes, and the scope of Standard 2800's 0.005 h rule (marks
// rules[0] when outside it; returns the paragraph saying so, "" when nothing to say).
std::optional<TargetSpectrumSpec> study_design_spectrum(const results::Settings& s);
separation::BuildingCode building_code(const Data& r, int b, std::size_t model = static_cast<std::size_t>(-1));
separation::CodeDesign code_design(const Data& r);
std::string coefficient_scope(const Data& r, std::vector<separation::Rule>& rules);

// The code rules at each contact level of a pair of shear buildings (code_levels.cpp): each building as the codes
// see it (its period -- the study's where it states it --, storeys, storey height, the first mode's Gamma1 phi1 at
// every floor from model/modes.hpp), its contact levels (model::shear_buildings of those buildings, with the study's
// level tolerance, levels and shape functions) and the section; none for an SDOF pair (its rows above are its one
// level), an isolated building or a grid study.
struct LevelBuilding {
  separation::BuildingCode code;
  std::string period_source;  // "as given", "the study's median (lognormal ...)", "median of 160 samples"
  int storeys = 1;
  double storey_height = 0;
  std::vector<double> storey_heights;  // {storey_height}, or one per storey (storey_height as an array) bottom first
  std::string profile;        // "uniform" | "shear"
  double gamma_roof = 1;      // Gamma1 with phi1(roof) = 1
  std::vector<double> gphi;   // Gamma1 phi1 at floors 1..storeys
};
struct CodeLevels {
  LevelBuilding b[2];
  std::vector<separation::ContactLevel> levels;
  std::string levels_rule;  // how the levels were found, in words
};
std::optional<CodeLevels> code_levels(const Data& r);
// Building b's (1, 2) period as the code rules take it: the study's own number where it states one (a fixed period, or
// a distribution's median), else the median of the sampled periods; `source` says which.
double code_period(const Data& r, int b, std::string& source);
// Gamma1 phi1 at floors 1..storeys of a shear building of equal floor masses and `profile` storeys (1 for one storey)
// (storey_heights: one for every storey, or one per storey)
std::vector<double> first_mode_gphi(int storeys, const std::vector<double>& storey_heights,
                                    model::StiffnessProfile profile);
// A building's /settings storey_height: {} absent, one number, or one per storey (an array, bottom first).
std::vector<double> storey_height_setting(const results::Settings& s, std::string_view section);
// The contact levels of the two buildings (left, right) as model::shear_buildings makes them, each side's height and
// Gamma1 phi1 (a column side interpolated by `shape`)
std::vector<separation::ContactLevel> contact_levels(const LevelBuilding (&b)[2], double tolerance,
                                                    model::ContactLevels levels, model::ShapeFunctions shape);
std::string code_levels_section(const Data& r);
std::string code_levels_csv(const Data& r);  // rows code_level of the CSV report

}  // namespace pounding::report_detail
