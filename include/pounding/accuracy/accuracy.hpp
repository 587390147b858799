#pragma once
// Accuracy against speed (issue 6): the model set the engine is measured on, the bridge to the independent
// SciPy reference (tools/reference_solver.py), the accuracy/cost chart, stability limits, restitution of
// every damping law, Kelvin's tension and the Muthukumar-DesRoches validation. Orchestration layer: it runs
// the kernel on plain batches and reduces to rows; no MPI, no HDF5.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"

namespace pounding::accuracy {

// ---------------------------------------------------------------------------------------------------
// Records and the model set
struct RecordSpec {
  std::string file;       // file name in the real-record directory
  double duration = 0.0;  // seconds kept from the start (0: the whole record)
};
// The three records of the accuracy set: Northridge Rinaldi 228 (0.87 g), Duzce Bolu 090 (0.82 g), Northridge
// Canyon Country W Lost Cyn 270 (0.48 g), all at 0.01 s, truncated to their first 15 s.
std::vector<RecordSpec> default_records();
std::string default_record_dir();  // POUNDING_SOURCE_DIR "/../shared/records/real"

struct LoadedRecord {
  std::string name;  // file name
  double dt = 0.0;
  std::vector<double> ag;  // m/s^2, truncated
};
LoadedRecord load_record(const std::string& dir, const RecordSpec& spec);

// The records of one directory, each read once, on first use (the caller owns it: one per command or test,
// so nothing outlives the run or is shared between threads).
class RecordCache {
 public:
  RecordCache(std::string dir, std::vector<RecordSpec> records);
  // The record of that file name; InputError when it is not in the list.
  const LoadedRecord& get(const std::string& name);

 private:
  std::string dir_;
  std::vector<RecordSpec> records_;
  std::map<std::string, LoadedRecord> loaded_;
};

// One model of the set: a sampled pair (paper's bilinear structure model) and its code gap d.
struct Model {
  int index = 0;
  double T1 = 0, T2 = 0, d = 0, kh = 0;
  PairParams pair;  // at gap ratio 1 (gap = d), kc = kh, e = 0.65
};
// n models from StructureSampler (default model, seed), identities spread over the 11 x 11 period grid.
std::vector<Model> sample_models(int n, std::uint64_t seed = 6);

// Linear/Kelvin stiffness used for a model on the chart: the secant kh sqrt(delta_m) of the Hertz law at the
// Hertz peak penetration delta_m of an elastic impact at v_ref = 0.5 m/s (documented choice, docs/accuracy.md).
double secant_linear_stiffness(double kh, double m1, double m2, double v_ref = 0.5);

// One case: model x record x contact law, at a gap ratio.
struct Case {
  std::string record;
  int model = 0;
  std::string law, damping;  // contact law and (Hertzdamp) damping-law names
  double gap_ratio = 0.1, d = 0;
  PairParams p;              // gap, kc, e set for this law
  double n = 1.5, v0_min = 1e-3;
  // reference results (NaN / -1 until read from a reference CSV)
  double ref_peak_closing = 0, ref_peak_force = 0, ref_peak_u1 = 0, ref_peak_u2 = 0;
  int ref_impact_count = -1;
};
// Every (model, record, law) case; laws: "none", "hertzdamp", "kelvin", "linear", "stereomechanical".
std::vector<Case> make_cases(const std::vector<Model>& models, const std::vector<RecordSpec>& records,
                             const std::vector<std::string>& laws, double gap_ratio, double e);
// Writes the cases as CSV (the reference solver's input) and, beside it, <record>.ag files (dt, then m/s^2).
void write_cases(const std::string& path, const std::vector<Case>& cases, const std::string& record_dir,
                 const std::vector<RecordSpec>& records);
// Reads a case CSV, with or without the reference columns.
std::vector<Case> read_cases(const std::string& path);

// ---------------------------------------------------------------------------------------------------
// Running the engine on cases
struct EngineResult {
  double peak_closing = 0, peak_force = 0, peak_u1 = 0, peak_u2 = 0, peak_acc1 = 0;
  int impact_count = 0, clamp_count = 0;
  LaneStatus status = LaneStatus::ok;
};
struct EngineSetting {
  Stepper stepper = Stepper::rk4;
  int substeps = 64;
  bool locate_contact = true;
};
// Runs every case (grouped by record and law into batches). seconds_out (optional): wall time summed.
std::vector<EngineResult> run_cases(const std::vector<Case>& cases, const EngineSetting& setting, RecordCache& records,
                                    double* seconds_out = nullptr, long* pair_steps_out = nullptr);

// Agreement of engine results with the stored reference, per law.
struct Agreement {
  std::string law;
  int cases = 0, impacting = 0;
  double closing_median = 0, closing_max = 0;  // relative errors
  double force_median = 0, force_p99 = 0, force_max = 0;
  int count_differs = 0, verdict_differs = 0;
};
std::vector<Agreement> agreement(const std::vector<Case>& cases, const std::vector<EngineResult>& res);

// ---------------------------------------------------------------------------------------------------
// The chart: stepper x dt x contact law. The probability table (at-least-one-impact at each gap ratio) comes
// from the uncoupled ("none") cases -- first passage: the coupled run equals the uncoupled one up to the first
// impact -- taken from `uncoupled` when given (a larger model set resolves smaller probability errors).
struct ChartRow {
  std::string stepper, law;
  int k = 0;                   // dt = record dt x 2^-k (substeps 2^k)
  double dt = 0;               // integration step (s)
  double ns_per_pair_step = 0, ms_per_analysis = 0;  // medians over repeats
  double closing_median = 0, closing_p99 = 0, force_median = 0, force_p99 = 0;
  double amp_p99 = 0;  // p99 relative error of the displacement amplification peak|u1| / uncoupled peak|u1|
  double count_differs = 0, verdict_differs = 0;  // fractions of cases
  int diverged = 0;
  std::vector<double> prob_error_pp;  // |P_engine - P_ref| in percentage points at each gap ratio
  double prob_error_max_pp = 0;
};
std::vector<double> chart_gap_ratios();  // 0.1, 0.2, 0.3, 0.5, 0.7, 1.0
// One chart row by its key (stepper name as in the CSV, law, k): `only` restricts the chart to these rows.
// Each selected row is computed exactly as in the full chart (same cases, same uncoupled runs for its
// probability and amplification columns), so its error columns equal the full chart's (tests/docs).
struct ChartRowId {
  std::string stepper, law;
  int k = 0;
};
// "stepper:law:k" (e.g. "central-difference:hertzdamp:2"); InputError otherwise.
ChartRowId parse_chart_row_id(const std::string& s);
std::vector<ChartRow> chart(const std::vector<Case>& cases, RecordCache& records, int repeats, int kmax,
                            const std::vector<Case>* uncoupled = nullptr, const std::vector<ChartRowId>& only = {});
void write_chart_csv(const std::string& path, const std::vector<ChartRow>& rows);

// ---------------------------------------------------------------------------------------------------
// Stability
struct StabilityRow {
  std::string stepper;
  double zeta = 0;
  double measured = 0;  // largest stable h omega found (bisection); inf when stable to the scan's end
  double theory = 0;
};
// Free vibration of one undamped/damped SDOF (the other structure at rest, no contact) for 2000 periods or
// 20,000 steps: stable when |u| never exceeds 1.5 x the initial amplitude.
std::vector<StabilityRow> stability_map();
// The steel frames of impact-stiffness-linear-viscoelastic-experiment.txt (k = 20,660 N/mm, masses 5 and
// 10 kg) under a real record (Rinaldi 228, 15 s): one row per stepper x contact law x substeps (1, 4, 16, 64,
// 256; the linear law also every substep count 6..30, h omega_c = 4.1 ... 0.83, across the limits).
// The lane's h_omega_contact (tangent at its own peak penetration) beside the nominal one (the linear spring's
// omega_c = sqrt(k / meff) = 2490 rad/s times h); force_error against the converged peak force of the same law
// (rk4 with located onset at 256 substeps).
struct StiffRow {
  std::string stepper, law;
  int substeps = 1;
  double h_omega_contact = 0;  // nominal: h sqrt(k / meff)
  double h_omega_lane = 0;     // the resolution guard's: tangent at the lane's peak penetration (NaN: diverged)
  std::string status;
  double peak_force = 0;
  double force_error = 0;      // |F - F_converged| / F_converged (NaN when diverged)
  int impacts = 0;
};
// steppers/laws: subsets to run (empty: all); substeps: a subset of the grid (empty: all).
std::vector<StiffRow> stiff_contact(const std::string& record_dir, const std::vector<std::string>& steppers = {},
                                    const std::vector<std::string>& laws = {}, const std::vector<int>& substeps = {});

// ---------------------------------------------------------------------------------------------------
// Resolution: the accuracy limit of every stepper x force law (physics/resolution.hpp holds the table)
// One free impact of two 1 kg masses (negligible springs, omega 1e-3 of the contact's), v0 = 1 m/s, e = 0.65
// (Hertzdamp: lankarani-nikravesh), at `phases` onset positions inside a step (the contact opens at the fraction
// (j + 0.5) / phases of a step), h swept so that h omega_c spans about 0.01 .. 2. Errors against the same impact
// by rk4 with located onset at h omega_c = 0.002 (the converged value); the row keeps the worst phase.
struct ResolutionPoint {
  std::string scheme, law;  // scheme: central-difference, newmark, rk4, rk4-located, nigam-jennings
  int steps = 0;            // integration steps over the run (3 estimated contact durations)
  double h_omega_contact = 0;          // largest over the phases (the lane's own BatchResult::h_omega_contact)
  double peak_force = 0, force_error = 0;   // worst phase; error relative to the converged peak force
  double e_effective = 0, e_error = 0;      // exit-velocity ratio, worst |e - e_converged|
  std::string status;                       // worst lane status (ok < coarse < diverged < non-finite)
};
struct ResolutionLimit {
  std::string scheme, law;
  double limit = 0;       // largest h omega_c of the sweep below the first point over the tolerance, 3 decimals down
  double first_over = 0;  // h omega_c of that first point (inf: none to the sweep's end; NaN: it diverged)
};
std::vector<std::string> resolution_schemes();  // the five scheme names above
std::vector<std::string> resolution_laws();     // every registered law with a force element
// `points_per_decade` sets the h grid (geometric); `phases` the onset positions per h.
std::vector<ResolutionPoint> resolution_sweep(const std::vector<std::string>& schemes,
                                              const std::vector<std::string>& laws, int points_per_decade = 150,
                                              int phases = 8);
std::vector<ResolutionLimit> resolution_limits(const std::vector<ResolutionPoint>& points, double tolerance);

// ---------------------------------------------------------------------------------------------------
// Restitution and Kelvin's tension
struct RestitutionRow {
  std::string law;  // damping law or "jankowski" / "kelvin"
  double e_target = 0, e_effective = 0;
  int clamps = 0;
};
// laws: the damping-law names of the table (lankarani-nikravesh ... calibrated, jankowski, kelvin) in its
// order; empty = all. A subset gives exactly the rows of the full table (tests/docs/restitution.sh).
std::vector<RestitutionRow> restitution_table(const std::vector<double>& targets,
                                              const std::vector<std::string>& laws = {});

struct KelvinTension {
  double e = 0;
  double peak_force = 0;           // clamped kernel (N)
  double tension_unclamped = 0;    // most tensile force the unclamped Kelvin law reaches before delta = 0 (N)
  double e_effective_clamped = 0;  // what the clamped law delivers
  int clamps = 0;
  double min_force_series = 0;     // smallest force the kernel ever returned in the run (>= 0 when clamped)
};
KelvinTension kelvin_tension(double e);

// The Muthukumar-DesRoches parameter study: pounding/accuracy/muthukumar.hpp.

}  // namespace pounding::accuracy
