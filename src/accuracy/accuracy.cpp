// Accuracy against speed (issue 6). See include/pounding/accuracy/accuracy.hpp.
#include "pounding/accuracy/accuracy.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "pounding/physics/single_impact.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/sampling/sampler.hpp"

namespace pounding::accuracy {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

double percentile(std::vector<double> v, double p) {  // linear interpolation (numpy's default)
  if (v.empty()) return nan;
  std::sort(v.begin(), v.end());
  double x = p / 100.0 * static_cast<double>(v.size() - 1);
  auto i = static_cast<std::size_t>(std::floor(x));
  if (i + 1 >= v.size()) return v.back();
  return v[i] + (x - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

// The run returned numbers: ok, or coarse (the resolution guard's mark; its error is what the chart measures).
bool ran(LaneStatus s) { return s == LaneStatus::ok || s == LaneStatus::coarse; }

double rel(double a, double ref) { return std::abs(a - ref) / std::abs(ref); }
// Peak closing: relative to the reference, floored at 1 mm (pairs of equal periods close by ~1e-16 m and never
// impact at any studied gap; their relative error would be noise).
constexpr double closing_floor = 1e-3;
double rel_closing(double a, double ref) { return std::abs(a - ref) / std::max(std::abs(ref), closing_floor); }

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur.push_back(c);
    }
  }
  out.push_back(cur);
  return out;
}

double parse_double(const std::string& s) {
  if (s == "inf" || s == "Infinity") return inf;
  if (s == "nan" || s == "NaN" || s.empty()) return nan;
  return std::stod(s);
}

ContactModel contact_model(const std::string& law, const std::string& damping, double n, double v0_min) {
  ContactModel cm;
  cm.law = parse_contact_law(law);
  if (!damping.empty() && damping != "-") cm.damping = parse_damping_law(damping);
  cm.n = n;
  cm.v0_min = v0_min;
  return cm;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
std::vector<RecordSpec> default_records() {
  return {{"Northridge_1994_RinaldiReceivingSta_228.AT2", 15.0},
          {"Duzce_1999_Bolu_090.txt", 15.0},
          {"Northridge_1994_CanyonCountryWLostCyn_270.txt", 15.0}};
}

// Relative to the working directory (the repository root, where docs/accuracy.md runs the commands); the
// command line also reads $POUNDING_RECORDS_DIR. No build-machine path is compiled into the library.
std::string default_record_dir() { return "../shared/records/real"; }

LoadedRecord load_record(const std::string& dir, const RecordSpec& spec) {
  Record r = read_record(dir + "/" + spec.file);
  LoadedRecord out;
  out.name = spec.file;
  out.dt = r.dt;
  std::size_t n = r.acc.size();
  if (spec.duration > 0) n = std::min(n, static_cast<std::size_t>(std::lround(spec.duration / r.dt)) + 1);
  out.ag.assign(r.acc.begin(), r.acc.begin() + static_cast<long>(n));
  return out;
}

RecordCache::RecordCache(std::string dir, std::vector<RecordSpec> records)
    : dir_(std::move(dir)), records_(std::move(records)) {}

const LoadedRecord& RecordCache::get(const std::string& name) {
  auto it = loaded_.find(name);
  if (it != loaded_.end()) return it->second;
  for (const auto& r : records_)
    if (r.file == name) return loaded_.emplace(name, load_record(dir_, r)).first->second;
  throw InputError(fmt::format("record '{}' is not in the accuracy record list", name), "record",
                   "use the records of default_records()");
}

std::vector<Model> sample_models(int n, std::uint64_t seed) {
  StructureModel sm;  // the paper's bilinear model
  StructureSampler sampler(sm, seed);
  const int np = static_cast<int>(sm.slots(0));  // both buildings share the default grid
  std::vector<Model> out;
  for (int i = 0; i < n; ++i) {
    SampleId id{static_cast<std::int32_t>(i % np), static_cast<std::int32_t>((3 * i + i / np) % np), i};
    SampledPair sp = sampler.sample(id);
    Model m;
    m.index = i;
    m.T1 = sp.s1.T, m.T2 = sp.s2.T, m.d = sp.d, m.kh = sp.kh;
    m.pair = sp.pair_params(1.0, 0.65);
    out.push_back(m);
  }
  return out;
}

double secant_linear_stiffness(double kh, double m1, double m2, double v_ref) {
  double meff = m1 * m2 / (m1 + m2);
  return kh * std::sqrt(hertz_peak_penetration(meff, v_ref, kh));
}

std::vector<Case> make_cases(const std::vector<Model>& models, const std::vector<RecordSpec>& records,
                             const std::vector<std::string>& laws, double gap_ratio, double e) {
  std::vector<Case> out;
  for (const auto& law : laws)
    for (const auto& rec : records)
      for (const auto& m : models) {
        Case c;
        c.record = rec.file;
        c.model = m.index;
        c.law = law;
        c.damping = law == "hertzdamp" ? "lankarani-nikravesh" : "-";
        c.gap_ratio = gap_ratio;
        c.d = m.d;
        c.p = m.pair;
        c.p.gap = gap_ratio * m.d;
        c.p.e = e;
        c.p.kc = (law == "linear" || law == "kelvin") ? secant_linear_stiffness(m.kh, m.pair.s1.m, m.pair.s2.m)
                                                      : m.kh;
        out.push_back(c);
      }
  return out;
}

void write_cases(const std::string& path, const std::vector<Case>& cases, const std::string& record_dir,
                 const std::vector<RecordSpec>& records) {
  std::ostringstream o;
  o << "record,model,law,damping,gap_ratio,d,m1,k1,c1,fy1,alpha1,m2,k2,c2,fy2,alpha2,gap,kc,e,n,v0_min";
  bool ref = !cases.empty() && cases[0].ref_impact_count >= 0;
  if (ref) o << ",ref_peak_closing,ref_peak_force,ref_impact_count,ref_peak_u1,ref_peak_u2";
  o << "\n";
  for (const auto& c : cases) {
    const auto& p = c.p;
    o << fmt::format("{},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                     "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}",
                     c.record, c.model, c.law, c.damping, c.gap_ratio, c.d, p.s1.m, p.s1.k, p.s1.c, p.s1.fy,
                     p.s1.alpha, p.s2.m, p.s2.k, p.s2.c, p.s2.fy, p.s2.alpha, p.gap, p.kc, p.e, c.n, c.v0_min);
    if (ref)
      o << fmt::format(",{:.17g},{:.17g},{},{:.17g},{:.17g}", c.ref_peak_closing, c.ref_peak_force,
                       c.ref_impact_count, c.ref_peak_u1, c.ref_peak_u2);
    o << "\n";
  }
  files::write_text_atomically(path, o.str());
  auto dir = std::filesystem::path(path).parent_path();
  for (const auto& r : records) {
    LoadedRecord lr = load_record(record_dir, r);
    std::ostringstream a;
    a << fmt::format("{:.17g}\n", lr.dt);
    for (double x : lr.ag) a << fmt::format("{:.17g}\n", x);
    files::write_text_atomically((dir / (r.file + ".ag")).string(), a.str());
  }
}

std::vector<Case> read_cases(const std::string& path) {
  files::check_input_file(path, "the case/reference CSV");  // a FIFO would block the ifstream
  std::ifstream f(path);
  if (!f) throw InputError(fmt::format("cannot read '{}'", path), path, "give an existing case/reference CSV");
  std::string line;
  std::getline(f, line);
  auto head = split_csv(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < head.size(); ++i) col[head[i]] = i;
  for (const char* need : {"record", "model", "law", "m1", "k1", "gap", "kc", "e"})
    if (!col.count(need))
      throw InputError(fmt::format("column '{}' missing", need), path + ":1", "regenerate the CSV");
  std::vector<Case> out;
  int lineno = 1;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty()) continue;
    auto v = split_csv(line);
    if (v.size() != head.size())
      throw InputError(fmt::format("{} fields, header has {}", v.size(), head.size()),
                       fmt::format("{}:{}", path, lineno), "regenerate the CSV");
    auto num = [&](const char* k) { return parse_double(v[col.at(k)]); };
    Case c;
    c.record = v[col["record"]];
    c.model = std::stoi(v[col["model"]]);
    c.law = v[col["law"]];
    c.damping = v[col["damping"]];
    c.gap_ratio = num("gap_ratio");
    c.d = num("d");
    c.p.s1 = {num("m1"), num("k1"), num("c1"), num("fy1"), num("alpha1")};
    c.p.s2 = {num("m2"), num("k2"), num("c2"), num("fy2"), num("alpha2")};
    c.p.gap = num("gap"), c.p.kc = num("kc"), c.p.e = num("e");
    c.n = num("n"), c.v0_min = num("v0_min");
    if (col.count("ref_peak_closing")) {
      c.ref_peak_closing = num("ref_peak_closing");
      c.ref_peak_force = num("ref_peak_force");
      c.ref_impact_count = std::stoi(v[col["ref_impact_count"]]);
      c.ref_peak_u1 = num("ref_peak_u1");
      c.ref_peak_u2 = num("ref_peak_u2");
    }
    out.push_back(c);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------
std::vector<EngineResult> run_cases(const std::vector<Case>& cases, const EngineSetting& setting, RecordCache& records,
                                    double* seconds_out, long* pair_steps_out) {
  std::vector<EngineResult> out(cases.size());
  // group by (record, law, damping, n, v0_min): one batch each
  std::map<std::string, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    groups[fmt::format("{}|{}|{}|{}|{}", c.record, c.law, c.damping, c.n, c.v0_min)].push_back(i);
  }
  double secs = 0;
  long steps = 0;
  for (const auto& [key, idx] : groups) {
    const Case& c0 = cases[idx[0]];
    const LoadedRecord& rec = records.get(c0.record);
    PairBatch b;
    b.resize(idx.size());
    for (std::size_t j = 0; j < idx.size(); ++j) b.set(j, cases[idx[j]].p);
    ContactModel cm = contact_model(c0.law, c0.damping, c0.n, c0.v0_min);
    GroundMotion gm{rec.dt, rec.ag, 0.0};
    KernelSettings ks;
    ks.stepper = setting.stepper;
    ks.substeps = setting.substeps;
    ks.locate_contact = setting.locate_contact;
    BatchResult r;
    auto t0 = std::chrono::steady_clock::now();
    run_batch(b, cm, gm, ks, r);
    secs += seconds_since(t0);
    steps += static_cast<long>(idx.size()) * std::lround(gm.total_duration() / (rec.dt / setting.substeps));
    for (std::size_t j = 0; j < idx.size(); ++j) {
      EngineResult& e = out[idx[j]];
      e.status = static_cast<LaneStatus>(r.status[j]);
      e.peak_closing = r.peak_closing[j];
      e.peak_force = cm.law == ContactLaw::none ? 0.0 : r.peak_force[j];
      e.peak_u1 = r.peak_u1[j];
      e.peak_u2 = r.peak_u2[j];
      e.peak_acc1 = r.peak_acc1[j];
      e.impact_count = r.impact_count[j];
      e.clamp_count = r.clamp_count[j];
    }
  }
  if (seconds_out) *seconds_out = secs;
  if (pair_steps_out) *pair_steps_out = steps;
  return out;
}

std::vector<Agreement> agreement(const std::vector<Case>& cases, const std::vector<EngineResult>& res) {
  std::map<std::string, std::vector<std::size_t>> by_law;
  std::vector<std::string> order;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (!by_law.count(cases[i].law)) order.push_back(cases[i].law);
    by_law[cases[i].law].push_back(i);
  }
  std::vector<Agreement> out;
  for (const auto& law : order) {
    Agreement a;
    a.law = law;
    std::vector<double> ec, ef;
    for (auto i : by_law[law]) {
      const Case& c = cases[i];
      const EngineResult& r = res[i];
      ++a.cases;
      if (!ran(r.status)) {
        ++a.count_differs, ++a.verdict_differs;
        ec.push_back(inf);
        continue;
      }
      ec.push_back(rel_closing(r.peak_closing, c.ref_peak_closing));
      if (law != "none") {
        a.count_differs += r.impact_count != c.ref_impact_count;
        a.verdict_differs += (r.impact_count > 0) != (c.ref_impact_count > 0);
        if (c.ref_impact_count > 0) {
          ++a.impacting;
          if (law != "stereomechanical") ef.push_back(rel(r.peak_force, c.ref_peak_force));
        }
      }
    }
    a.closing_median = percentile(ec, 50), a.closing_max = percentile(ec, 100);
    if (!ef.empty()) {
      a.force_median = percentile(ef, 50), a.force_p99 = percentile(ef, 99), a.force_max = percentile(ef, 100);
    } else {
      a.force_median = a.force_p99 = a.force_max = nan;
    }
    out.push_back(a);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------
std::vector<double> chart_gap_ratios() { return {0.1, 0.2, 0.3, 0.5, 0.7, 1.0}; }

namespace {

// |P_engine - P_ref| (percentage points) of at-least-one-impact at each gap ratio; at gap g a pair impacts
// <=> its uncoupled peak closing exceeds g (first passage). Adds the diverged uncoupled runs to *diverged.
std::vector<double> probability_errors(const std::vector<Case>& unc, const std::vector<EngineResult>& ru,
                                       int* diverged) {
  std::vector<double> perr;
  for (double g : chart_gap_ratios()) {
    int ne = 0, nr = 0;
    for (std::size_t i = 0; i < unc.size(); ++i) {
      double gap = g * unc[i].d;
      *diverged += !ran(ru[i].status);
      ne += ran(ru[i].status) && ru[i].peak_closing > gap;
      nr += unc[i].ref_peak_closing > gap;
    }
    perr.push_back(100.0 * std::abs(ne - nr) / static_cast<double>(unc.size()));
  }
  return perr;
}

// The uncoupled runs of one chart variant, for the amplification peak |u1| coupled / uncoupled.
struct Uncoupled {
  const std::vector<Case>& cases;
  const std::vector<EngineResult>& results;
  std::map<std::pair<std::string, int>, std::size_t> index;  // (record, model) -> case
};

// The error columns of one chart row from the engine results r of the law's cases lc.
void score_row(ChartRow& row, const std::vector<Case>& lc, const std::vector<EngineResult>& r, const Uncoupled& u) {
  const std::string& law = row.law;
  std::vector<double> ec, ef, ea;
  int cd = 0, vd = 0;
  for (std::size_t i = 0; i < lc.size(); ++i) {
    const Case& c = lc[i];
    if (law != "none" && ran(r[i].status)) {
      auto it = u.index.find({c.record, c.model});
      if (it != u.index.end() && ran(u.results[it->second].status) && c.ref_impact_count > 0) {
        double amp = r[i].peak_u1 / u.results[it->second].peak_u1;
        double amp_ref = c.ref_peak_u1 / u.cases[it->second].ref_peak_u1;
        ea.push_back(rel(amp, amp_ref));
      }
    }
    if (!ran(r[i].status)) {
      ++row.diverged, ++cd, ++vd;
      ec.push_back(inf);
      if (c.ref_impact_count > 0) ef.push_back(inf);
      continue;
    }
    ec.push_back(rel_closing(r[i].peak_closing, c.ref_peak_closing));
    cd += r[i].impact_count != c.ref_impact_count;
    vd += (r[i].impact_count > 0) != (c.ref_impact_count > 0);
    if (c.ref_impact_count > 0 && law != "stereomechanical") ef.push_back(rel(r[i].peak_force, c.ref_peak_force));
  }
  row.closing_median = percentile(ec, 50), row.closing_p99 = percentile(ec, 99);
  row.force_median = ef.empty() ? nan : percentile(ef, 50);
  row.force_p99 = ef.empty() ? nan : percentile(ef, 99);
  row.amp_p99 = ea.empty() ? nan : percentile(ea, 99);
  row.count_differs = static_cast<double>(cd) / static_cast<double>(lc.size());
  row.verdict_differs = static_cast<double>(vd) / static_cast<double>(lc.size());
}

// Runs the cases `repeats` times; the cost columns are the medians, the results those of the last run.
std::vector<EngineResult> timed_runs(ChartRow& row, const std::vector<Case>& lc, const EngineSetting& es,
                                     RecordCache& records, int repeats) {
  std::vector<double> wall, nsps;
  std::vector<EngineResult> r;
  for (int rep = 0; rep < repeats; ++rep) {
    double secs = 0;
    long ps = 0;
    r = run_cases(lc, es, records, &secs, &ps);
    wall.push_back(secs);
    nsps.push_back(1e9 * secs / static_cast<double>(ps));
  }
  row.ns_per_pair_step = percentile(nsps, 50);
  row.ms_per_analysis = 1e3 * percentile(wall, 50) / static_cast<double>(lc.size());
  return r;
}

}  // namespace

ChartRowId parse_chart_row_id(const std::string& s) {
  auto a = s.find(':'), b = s.rfind(':');
  ChartRowId id;
  if (a != std::string::npos && b != a) {
    id.stepper = s.substr(0, a), id.law = s.substr(a + 1, b - a - 1);
    const std::string k = s.substr(b + 1);
    if (!id.stepper.empty() && !id.law.empty() && !k.empty() && k.size() < 3 &&
        k.find_first_not_of("0123456789") == std::string::npos) {
      id.k = std::stoi(k);
      return id;
    }
  }
  throw InputError(fmt::format("chart row '{}' is not stepper:law:k", s), "--rows",
                   "give e.g. central-difference:hertzdamp:2 (steppers central-difference, newmark, rk4, "
                   "rk4-located, nigam-jennings; k = 0..kmax)");
}

namespace {
bool selected(const std::vector<ChartRowId>& only, const std::string& stepper, const std::string& law, int k) {
  if (only.empty()) return true;
  return std::any_of(only.begin(), only.end(), [&](const ChartRowId& r) {
    return r.stepper == stepper && r.k == k && (law.empty() || r.law == law);
  });
}
}  // namespace

std::vector<ChartRow> chart(const std::vector<Case>& cases, RecordCache& records, int repeats, int kmax,
                            const std::vector<Case>* uncoupled, const std::vector<ChartRowId>& only) {
  struct Variant {
    std::string name;
    Stepper s;
    bool locate;
  };
  const std::vector<Variant> variants = {{"central-difference", Stepper::central_difference, false},
                                         {"newmark", Stepper::newmark, false},
                                         {"rk4", Stepper::rk4, false},
                                         {"rk4-located", Stepper::rk4, true},
                                         {"nigam-jennings", Stepper::nigam_jennings, false}};
  std::map<std::string, std::vector<Case>> by_law;
  for (const auto& c : cases) by_law[c.law].push_back(c);
  if (uncoupled && !uncoupled->empty()) by_law["none"] = *uncoupled;  // a larger uncoupled set: finer probabilities
  if (!by_law.count("none"))
    throw InputError("the reference has no uncoupled ('none') cases", "reference", "regenerate it with law none");
  for (const auto& r : only)
    if (!by_law.count(r.law) || r.k < 0 || r.k > kmax ||
        std::none_of(variants.begin(), variants.end(), [&](const Variant& v) { return v.name == r.stepper; }))
      throw InputError(fmt::format("chart row {}:{}:{} is not in the chart", r.stepper, r.law, r.k), "--rows",
                       "name a stepper and law of the chart and k = 0..kmax");
  const double rec_dt = records.get(cases[0].record).dt;
  std::vector<ChartRow> rows;
  for (const auto& v : variants)
    for (int k = 0; k <= kmax; ++k) {
      if (!selected(only, v.name, "", k)) continue;
      EngineSetting es{v.s, 1 << k, v.locate};
      const auto& unc = by_law["none"];
      auto ru = run_cases(unc, es, records);
      int ndiv_unc = 0;
      const std::vector<double> perr = probability_errors(unc, ru, &ndiv_unc);
      Uncoupled u{unc, ru, {}};
      for (std::size_t i = 0; i < unc.size(); ++i) u.index[{unc[i].record, unc[i].model}] = i;
      for (const auto& [law, lc] : by_law) {
        if (!selected(only, v.name, law, k)) continue;
        ChartRow row;
        row.stepper = v.name, row.law = law, row.k = k, row.dt = rec_dt / (1 << k);
        score_row(row, lc, timed_runs(row, lc, es, records, repeats), u);
        row.prob_error_pp = perr;
        row.prob_error_max_pp = *std::max_element(perr.begin(), perr.end());
        row.diverged += ndiv_unc;
        rows.push_back(row);
      }
    }
  return rows;
}

void write_chart_csv(const std::string& path, const std::vector<ChartRow>& rows) {
  std::ostringstream o;
  o << "stepper,law,k,dt,ns_per_pair_step,ms_per_analysis,closing_median,closing_p99,force_median,force_p99,"
       "amp_p99,count_differs,verdict_differs,diverged,prob_error_max_pp";
  for (double g : chart_gap_ratios()) o << fmt::format(",prob_error_pp_{}", g);
  o << "\n";
  for (const auto& r : rows) {
    o << fmt::format("{},{},{},{:.6g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{},{:.4g}",
                     r.stepper, r.law, r.k, r.dt, r.ns_per_pair_step, r.ms_per_analysis, r.closing_median,
                     r.closing_p99, r.force_median, r.force_p99, r.amp_p99, r.count_differs, r.verdict_differs, r.diverged,
                     r.prob_error_max_pp);
    for (double p : r.prob_error_pp) o << fmt::format(",{:.4g}", p);
    o << "\n";
  }
  files::write_text_atomically(path, o.str());
}

// ---------------------------------------------------------------------------------------------------
namespace {
// Free vibration of structure 1 (m = 1, omega = 1) from u = 1 with step h: true when stable.
bool free_vibration_stable(Stepper s, double zeta, double h) {
  PairParams p;
  p.s1 = Structure{1.0, 1.0, 2.0 * zeta};
  p.s2 = Structure{1.0, 1.0, 2.0 * zeta};
  p.gap = 1e3;
  p.u1 = 1.0;
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  long nsteps = std::min<long>(20000, std::max<long>(2000, std::lround(2000.0 * 2.0 * std::numbers::pi / h)));
  std::vector<double> ag{0.0, 0.0};
  GroundMotion gm{h, ag, static_cast<double>(nsteps) * h};
  KernelSettings ks;
  ks.stepper = s;
  ks.displacement_limit = 1e300;
  ContactModel cm;
  cm.law = ContactLaw::none;
  BatchResult r;
  run_batch(b, cm, gm, ks, r);
  return r.status[0] == 0 && r.peak_u1[0] <= 1.5;
}
}  // namespace

std::vector<StabilityRow> stability_map() {
  std::vector<StabilityRow> rows;
  struct S {
    Stepper s;
    double theory0, theory5;
  };
  // theory: central difference 2 (undamped); damped: the spectral radius of the kernel's scheme (below).
  // RK4: 2 sqrt(2) = 2.828 on the imaginary axis; damped: the boundary of |R(z)| = 1 along z = w h (-zeta + i sqrt(1-zeta^2)).
  auto rk4_boundary = [](double zeta) {
    double lo = 0.1, hi = 4.0;
    for (int it = 0; it < 200; ++it) {
      double x = 0.5 * (lo + hi);
      double re = -zeta * x, im = x * std::sqrt(1 - zeta * zeta);
      // R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 (complex)
      double zr = re, zi = im, pr = 1, pi_ = 0, tr = 1, ti = 0;
      for (int k = 1; k <= 4; ++k) {
        double nr = (tr * zr - ti * zi) / k, ni = (tr * zi + ti * zr) / k;
        tr = nr, ti = ni;
        pr += tr, pi_ += ti;
      }
      (std::hypot(pr, pi_) <= 1.0 ? lo : hi) = x;
    }
    return 0.5 * (lo + hi);
  };
  // central difference as the kernel writes it (velocity Verlet with the predictor v + h a in the damping):
  // the largest h omega whose (u, v, a) amplification matrix has spectral radius <= 1
  auto cd_boundary = [](double zeta) {
    auto radius = [&](double h) {
      Eigen::Matrix3d M;
      for (int j = 0; j < 3; ++j) {
        double u = j == 0, v = j == 1, a = j == 2;
        double vh = v + 0.5 * h * a, un = u + h * vh, vp = vh + 0.5 * h * a;
        double an = -(2.0 * zeta * vp + un), vn = vh + 0.5 * h * an;
        M.col(j) << un, vn, an;
      }
      return M.eigenvalues().cwiseAbs().maxCoeff();
    };
    double lo = 0.5, hi = 0.5;
    while (radius(hi) <= 1.0 + 1e-12) hi += 0.01;
    lo = hi - 0.01;
    for (int it = 0; it < 100; ++it) {
      double x = 0.5 * (lo + hi);
      (radius(x) <= 1.0 + 1e-12 ? lo : hi) = x;
    }
    return 0.5 * (lo + hi);
  };
  for (double zeta : {0.0, 0.05}) {
    for (auto [s, name, theory] :
         {std::tuple{Stepper::central_difference, "central-difference", cd_boundary(zeta)},
          std::tuple{Stepper::rk4, "rk4", rk4_boundary(zeta)},
          std::tuple{Stepper::nigam_jennings, "nigam-jennings", inf},
          std::tuple{Stepper::newmark, "newmark", inf}}) {
      StabilityRow row;
      row.stepper = name, row.zeta = zeta, row.theory = theory;
      // scan then bisect
      double last_ok = 0, first_bad = inf;
      for (double x = 0.05; x <= 10.0 + 1e-9; x += 0.05) {
        if (free_vibration_stable(s, zeta, x)) {
          last_ok = x;
        } else {
          first_bad = x;
          break;
        }
      }
      if (std::isfinite(first_bad)) {
        double lo = last_ok, hi = first_bad;
        for (int it = 0; it < 30; ++it) {
          double mid = 0.5 * (lo + hi);
          (free_vibration_stable(s, zeta, mid) ? lo : hi) = mid;
        }
        row.measured = lo;
      } else {
        row.measured = inf;  // stable to h omega = 10
      }
      rows.push_back(row);
    }
  }
  return rows;
}

namespace {
// One steel-frame analysis (impact-stiffness-linear-viscoelastic-experiment.txt: k = 20,660 N/mm, e = 0.8,
// masses 5 and 10 kg, T1 = 0.5 s, T2 = 0.2 s, gap 1 mm); Hertzdamp with the same secant stiffness at 1 mm.
BatchResult steel_frames(const LoadedRecord& rec, Stepper s, bool locate, const std::string& law, int sub) {
  const double k_exp = 20.66e6;
  PairParams p;
  p.s1 = Structure::from_period(5.0, 0.5, 0.05);
  p.s2 = Structure::from_period(10.0, 0.2, 0.05);
  p.gap = 1e-3;
  p.e = 0.8;
  p.kc = law == "hertzdamp" ? k_exp / std::sqrt(1e-3) : k_exp;
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  ContactModel cm = contact_model(law, law == "hertzdamp" ? "lankarani-nikravesh" : "-", 1.5, 1e-3);
  GroundMotion gm{rec.dt, rec.ag, 0.0};
  KernelSettings ks;
  ks.stepper = s;
  ks.substeps = sub;
  ks.locate_contact = locate;
  BatchResult r;
  run_batch(b, cm, gm, ks, r);
  return r;
}
bool wanted(const std::vector<std::string>& subset, const std::string& x) {
  return subset.empty() || std::find(subset.begin(), subset.end(), x) != subset.end();
}
}  // namespace

std::vector<StiffRow> stiff_contact(const std::string& record_dir, const std::vector<std::string>& steppers,
                                    const std::vector<std::string>& laws, const std::vector<int>& substeps) {
  const double meff = 5.0 * 10.0 / 15.0, wc = std::sqrt(20.66e6 / meff);
  RecordSpec spec{"Northridge_1994_RinaldiReceivingSta_228.AT2", 15.0};
  LoadedRecord rec = load_record(record_dir, spec);
  std::vector<StiffRow> out;
  std::map<std::string, double> F_conv;  // the converged value: rk4 with located onset at 256 substeps (h omega_c 0.097)
  for (std::string law : {"linear", "kelvin", "hertzdamp"})
    if (wanted(laws, law)) F_conv[law] = steel_frames(rec, Stepper::rk4, true, law, 256).peak_force[0];
  for (auto [s, sname] : {std::pair{Stepper::central_difference, "central-difference"}, std::pair{Stepper::rk4, "rk4"},
                          std::pair{Stepper::nigam_jennings, "nigam-jennings"}, std::pair{Stepper::newmark, "newmark"}}) {
    if (!wanted(steppers, sname)) continue;
    for (std::string law : {"linear", "kelvin", "hertzdamp"}) {
      if (!wanted(laws, law)) continue;
      // the linear law (one constant contact frequency) is scanned finely across the stability limits
      std::vector<int> subs{1, 4, 16, 64, 256};
      if (law == "linear")
        for (int sub = 6; sub <= 30; ++sub) subs.push_back(sub);
      std::sort(subs.begin(), subs.end());
      subs.erase(std::unique(subs.begin(), subs.end()), subs.end());
      for (int sub : subs) {
        if (!substeps.empty() && std::find(substeps.begin(), substeps.end(), sub) == substeps.end()) continue;
        const BatchResult r = steel_frames(rec, s, false, law, sub);
        StiffRow row;
        row.stepper = sname, row.law = law, row.substeps = sub;
        row.h_omega_contact = rec.dt / sub * wc;
        row.h_omega_lane = r.h_omega_contact[0];
        row.status = std::string(to_string(static_cast<LaneStatus>(r.status[0])));
        row.peak_force = r.peak_force[0];
        row.force_error = std::abs(r.peak_force[0] - F_conv[law]) / F_conv[law];
        row.impacts = r.impact_count[0];
        out.push_back(row);
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------
std::vector<RestitutionRow> restitution_table(const std::vector<double>& targets,
                                              const std::vector<std::string>& laws) {
  std::vector<RestitutionRow> out;
  const double m = 1e6, kh = 2.808e10, v0 = 1.0;
  // Hertzdamp with every damping law (contact/model.hpp damping_laws), then Jankowski and Kelvin
  std::vector<std::string> all;
  for (const auto& d : damping_laws) all.emplace_back(d.name);
  all.insert(all.end(), {"jankowski", "kelvin"});
  for (const auto& l : laws)
    if (std::find(all.begin(), all.end(), l) == all.end())
      throw InputError(fmt::format("'{}' is not a law of the restitution table", l), "--laws",
                       "give some of " + [&] {
                         std::string list;
                         for (const auto& a : all) list += (list.empty() ? "" : ", ") + a;
                         return list;
                       }());
  for (const std::string& law : all) {
    if (!laws.empty() && std::find(laws.begin(), laws.end(), law) == laws.end()) continue;
    for (double e : targets) {
      ContactModel cm;
      double kc = kh;
      if (law == "jankowski") {
        cm.law = ContactLaw::jankowski;
      } else if (law == "kelvin") {
        cm.law = ContactLaw::kelvin;
        kc = kh * std::sqrt(hertz_peak_penetration(0.5 * m, v0, kh));
      } else {
        cm.law = ContactLaw::hertzdamp;
        cm.damping = parse_damping_law(law);
      }
      ImpactResult ir = single_impact(cm, Stepper::rk4, e, v0, m, m, kc, 20000);
      out.push_back({law, e, ir.e_effective, ir.clamps});
    }
  }
  return out;
}

KelvinTension kelvin_tension(double e) {
  const double m = 1e6, meff = 0.5 * m, kc = 1e9, v0 = 1.0;
  KelvinTension kt;
  kt.e = e;
  // unclamped Kelvin impact, closed form: delta = v0/wd exp(-z w t) sin(wd t) for 0 <= t <= pi/wd;
  // F = kc delta + ck ddelta = -meff delta''
  const double z = kelvin_damping_ratio(e), w = std::sqrt(kc / meff), wd = w * std::sqrt(1 - z * z);
  double fmin = 0;
  for (int i = 0; i <= 100000; ++i) {
    double t = std::numbers::pi / wd * i / 100000.0;
    double E = std::exp(-z * w * t), S = std::sin(wd * t), Cs = std::cos(wd * t);
    double d = v0 / wd * E * S, dd = v0 * E * (Cs - z * w / wd * S);
    fmin = std::min(fmin, kc * d + 2.0 * z * std::sqrt(kc * meff) * dd);
  }
  kt.tension_unclamped = fmin;
  // the kernel, with a series recorder
  const double tc = std::numbers::pi / w;
  PairParams p;
  p.s1 = {m, 0.0, 0.0};
  p.s2 = {m, 0.0, 0.0};
  p.kc = kc, p.e = e, p.v1 = v0, p.gap = 0.0, p.u1 = -0.05 * tc * v0;
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  std::vector<double> ag{0.0, 0.0};
  GroundMotion gm{3.0 * tc, ag, 0.0};
  KernelSettings ks;
  ks.stepper = Stepper::rk4;
  ks.substeps = 60000;
  ks.displacement_limit = 1e30;
  SeriesRecorder sr;
  ks.series = &sr;
  ContactModel cm;
  cm.law = ContactLaw::kelvin;
  BatchResult r;
  run_batch(b, cm, gm, ks, r);
  kt.peak_force = r.peak_force[0];
  kt.clamps = r.clamp_count[0];
  kt.e_effective_clamped = (r.final_v2[0] - r.final_v1[0]) / v0;
  kt.min_force_series = *std::min_element(sr.force.begin(), sr.force.end());
  return kt;
}

// The Muthukumar-DesRoches study: src/accuracy/muthukumar.cpp.

}  // namespace pounding::accuracy
