// Muthukumar-DesRoches (2006) parameter study. See include/pounding/accuracy/muthukumar.hpp and
// docs/validation.md (what it shows and what it cannot).
#include "pounding/accuracy/muthukumar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "pounding/accuracy/accuracy.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding::accuracy {

std::vector<TableIRecord> muthukumar_table_i() {
  // Table I of muthukumar-desroches-2006-hertzdamp.txt (p. 820), in the paper's order. Matched = same event
  // and station; the component column is lost, so every component of ours whose PGA lies in the paper's band.
  const std::string other_event = "same station name, other earthquake: not matched";
  return {
      {"low", "Northridge", "Wonderland Ave", {}, ""},
      {"low", "Imperial Valley", "Bonds Corner", {}, ""},
      {"low", "San Fernando", "Pasadena", {}, ""},
      {"low", "Loma Prieta", "Fremont", {}, ""},
      {"low", "Morgan Hill", "Gilroy Array # (digit lost)", {},
       "ours: Gilroy Array 4 (Coyote Lake 1979), Array 3 (Loma Prieta 1989); " + other_event},
      {"low", "N. Palm Springs", "Morongo Valley", {}, ""},
      {"low", "Whittier Narrows", "E Grand Ave", {}, ""},
      {"low", "Landers", "Joshua Tree", {}, "ours from Landers: Lucerne, Coolwater, Yermo (other stations)"},
      {"low", "Morgan Hill", "Gilroy Array # (digit lost)", {}, "as above"},
      {"moderate", "Loma Prieta", "WAHO", {}, ""},
      {"moderate", "Northridge", "Mulhol(land)",
       {"Northridge_1994_BeverlyHillsMulhol_009.txt", "Northridge_1994_BeverlyHillsMulhol_279.txt"},
       "Beverly Hills 12520 Mulhol; both components in 0.4-0.6 g"},
      {"moderate", "Cape Mendocino", "Rio Dell Overpass", {"CapeMendocino_1992_RioDellOverpassFF_360.txt"},
       "270 (0.385 g) is below the band"},
      {"moderate", "Northridge", "Old Ridge Route", {},
       "ours: Castaic Old Ridge Route, San Fernando 1971; " + other_event},
      {"moderate", "Loma Prieta", "Coyote Lake Dam", {},
       "ours: Coyote Lake Dam Downstream (0.16/0.18 g), another instrument, low band: not matched"},
      {"moderate", "Northridge", "W Lost Cany(on)",
       {"Northridge_1994_CanyonCountryWLostCyn_000.txt", "Northridge_1994_CanyonCountryWLostCyn_270.txt"},
       "Canyon Country W Lost Cyn; both components in 0.4-0.6 g"},
      {"moderate", "Loma Prieta", "Saratoga Aloha Ave", {}, ""},
      {"moderate", "N Palm Springs", "N Palm Springs", {}, ""},
      {"moderate", "Cape Mendocino", "Petrolia", {}, ""},
      {"high", "Loma Prieta", "LGPC", {}, ""},
      {"high", "Coalinga", "Pleasant Valley P.P", {}, ""},
      {"high", "Northridge", "Old Ridge Route", {}, "as above"},
      {"high", "Cape Mendocino", "Petrolia", {}, ""},
      {"high", "Duzce", "Bolu", {"Duzce_1999_Bolu_000.txt", "Duzce_1999_Bolu_090.txt"},
       "both components in 0.7-0.9 g"},
      {"high", "Coalinga", "Transmitter Hill", {}, ""},
      {"high", "Northridge", "Rinaldi", {"Northridge_1994_RinaldiReceivingSta_228.AT2"},
       "Rinaldi Receiving Sta; 318 (0.472 g) is below the band"},
      {"high", "Superstition Hills", "Superstition Mtn", {}, ""},
      {"high", "Cape Mendocino", "Cape Mendocino", {}, ""},
  };
}

namespace {

// A record of the study with its PGA group: low 0.1-0.3 g, moderate 0.4-0.6 g, high 0.7-0.9 g.
struct LevelRecord {
  std::string file, level;
  double pga;
};

std::string pga_level(double pga) {
  return (pga >= 0.1 && pga <= 0.3)   ? "low"
         : (pga >= 0.4 && pga <= 0.6) ? "moderate"
         : (pga >= 0.7 && pga <= 0.9) ? "high"
                                      : "";
}

std::vector<LevelRecord> banded_records(const std::string& record_dir) {
  std::vector<LevelRecord> recs;
  files::check_input_file(record_dir + "/MANIFEST.tsv", "the records manifest MANIFEST.tsv");  // never a FIFO
  std::ifstream f(record_dir + "/MANIFEST.tsv");
  if (!f) throw InputError("cannot read MANIFEST.tsv", record_dir, "give the real-record directory");
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    std::vector<std::string> v;
    std::stringstream ss(line);
    std::string x;
    while (std::getline(ss, x, '\t')) v.push_back(x);
    if (v.size() < 9) continue;
    double pga = std::stod(v[8]);
    std::string lvl = pga_level(pga);
    if (!lvl.empty()) recs.push_back({v[0], lvl, pga});
  }
  return recs;
}

// The records of the run in MANIFEST order (the means are summed in that order): the set, then the levels.
std::vector<LevelRecord> selected_records(const std::string& record_dir, const MuthukumarOptions& opt) {
  std::vector<LevelRecord> recs = banded_records(record_dir);
  if (opt.records == "matched") {
    std::map<std::string, std::string> want;  // file -> the paper's level
    for (const auto& t : muthukumar_table_i())
      for (const auto& f : t.files) want[f] = t.level;
    std::vector<LevelRecord> kept;
    for (const auto& r : recs)
      if (auto it = want.find(r.file); it != want.end() && it->second == r.level) kept.push_back(r);
    if (kept.size() != want.size())
      throw InputError(fmt::format("--records matched: {} of the {} matched records are in the directory's "
                                   "MANIFEST.tsv at the paper's PGA band", kept.size(), want.size()),
                       record_dir,
                       "use the real records of ../shared/records/real (docs/ground-motions.md)");
    recs = std::move(kept);
  }
  if (!opt.levels.empty())
    std::erase_if(recs, [&](const LevelRecord& r) {
      return std::find(opt.levels.begin(), opt.levels.end(), r.level) == opt.levels.end();
    });
  return recs;
}

struct ContactSpec {
  std::string name, law;
  double e;
  std::string damping = "-";
};
// the paper's six, plus Hertzdamp with the calibrated xibar (delivers e = 0.6; Lankarani-Nikravesh gives ~0.74)
std::vector<ContactSpec> muthukumar_models() {
  return {{"stereomechanical", "stereomechanical", 1.0},
          {"stereomechanical", "stereomechanical", 0.6},
          {"kelvin", "linear", 1.0},
          {"kelvin", "kelvin", 0.6},
          {"hertzdamp", "hertz", 1.0},
          {"hertzdamp", "hertzdamp", 0.6, "lankarani-nikravesh"},
          {"hertzdamp-calibrated", "hertzdamp", 0.6, "calibrated"}};
}
constexpr std::array<double, 3> muthukumar_ratios = {0.3, 0.5, 0.7};
const std::array<std::string, 3> muthukumar_levels = {"low", "moderate", "high"};

ContactModel contact_model(const ContactSpec& ms) {
  ContactModel cm;
  cm.law = parse_contact_law(ms.law);
  if (ms.damping != "-") cm.damping = parse_damping_law(ms.damping);
  cm.n = 1.5;
  cm.v0_min = 1e-3;
  return cm;
}

// muthukumar-desroches-2006-hertzdamp.txt: equal masses 7.8 kip s^2/in, gap 0.5 in, kh = 25,000 kip/in^1.5,
// 5 % damping, elastic. 1 kip s^2/in = 175,126.8 kg; 1 kip = 4448.222 N; 1 in = 0.0254 m.
struct MuthukumarSetup {
  static constexpr double kip = 4448.2216152605, in = 0.0254;
  double m = 7.8 * kip / in;
  double gap = 0.5 * in;
  double kh = 25000.0 * kip / std::pow(in, 1.5);
  double kk, T2;
  std::vector<double> ratios;
  explicit MuthukumarSetup(const MuthukumarOptions& opt)
      : kk((opt.kelvin_k > 0 ? opt.kelvin_k : 25000.0 * kip / in) * opt.kelvin_scale),
        T2(opt.T2),  // flexible system period (not in the paper's text: assumed)
        ratios(opt.ratios.empty() ? std::vector<double>(muthukumar_ratios.begin(), muthukumar_ratios.end())
                                  : opt.ratios) {}
};

void check_options(const MuthukumarOptions& opt) {
  if (!(opt.T2 > 0) || !std::isfinite(opt.T2))
    throw InputError(fmt::format("--T2 {} is not a period", opt.T2), "--T2", "give seconds > 0, e.g. --T2 1");
  if (!(opt.kelvin_k >= 0) || !std::isfinite(opt.kelvin_k))
    throw InputError(fmt::format("--kelvin-k {} is not a stiffness", opt.kelvin_k), "--kelvin-k",
                     "give N/m > 0, or leave it out for 25,000 kip/in");
  if (!(opt.kelvin_scale > 0) || !std::isfinite(opt.kelvin_scale))
    throw InputError(fmt::format("--kelvin-scale {} is not a factor", opt.kelvin_scale), "--kelvin-scale",
                     "give a number > 0, e.g. 0.5 or 2");
  if (opt.records != "all" && opt.records != "matched")
    throw InputError(fmt::format("--records {} is not a record set", opt.records), "--records",
                     "use all (every record in a PGA band) or matched (the paper's Table I records we hold)");
  for (const auto& l : opt.levels)
    if (std::find(muthukumar_levels.begin(), muthukumar_levels.end(), l) == muthukumar_levels.end())
      throw InputError(fmt::format("--levels {} is not a PGA level", l), "--levels", "use low, moderate, high");
  for (double r : opt.ratios)
    if (std::find(muthukumar_ratios.begin(), muthukumar_ratios.end(), r) == muthukumar_ratios.end())
      throw InputError(fmt::format("--ratios {} is not one of the paper's T1/T2", r), "--ratios",
                       "use 0.3, 0.5, 0.7");
}

// (level, period ratio, model, e) -> (sum of displacement amplifications, of acceleration ones, runs, diverged)
using AmpSums = std::map<std::tuple<std::string, double, std::string, double>, std::tuple<double, double, int, int>>;

// One record through every model at every period ratio, added to the sums; returns the substeps used.
int add_muthukumar_record(AmpSums& acc, const LevelRecord& rc, const LoadedRecord& lr, const MuthukumarSetup& su,
                          int substeps) {
  const auto& ratios = su.ratios;
  int sub = substeps > 0 ? substeps : std::max(1, static_cast<int>(std::ceil(lr.dt / 5e-4)));
  GroundMotion gm{lr.dt, lr.ag, lr.dt * static_cast<double>(lr.ag.size() - 1) + 5.0};
  KernelSettings ks;
  ks.stepper = Stepper::rk4;
  ks.substeps = sub;
  ks.locate_contact = true;
  PairBatch b;
  b.resize(ratios.size());
  for (std::size_t j = 0; j < ratios.size(); ++j) {
    PairParams p;
    p.s1 = Structure::from_period(su.m, ratios[j] * su.T2, 0.05);
    p.s2 = Structure::from_period(su.m, su.T2, 0.05);
    p.gap = su.gap;
    b.set(j, p);
  }
  ContactModel none;
  none.law = ContactLaw::none;
  BatchResult r0;
  run_batch(b, none, gm, ks, r0);
  for (const auto& ms : muthukumar_models()) {
    PairBatch bb = b;
    for (std::size_t j = 0; j < ratios.size(); ++j) {
      bb.kc[j] = (ms.law == "linear" || ms.law == "kelvin") ? su.kk : su.kh;
      bb.e[j] = ms.e;
    }
    BatchResult r;
    run_batch(bb, contact_model(ms), gm, ks, r);
    for (std::size_t j = 0; j < ratios.size(); ++j) {
      auto& [sd, sa, n, ndiv] = acc[{rc.level, ratios[j], ms.name, ms.e}];
      // the run returned numbers: ok, or coarse (the resolution guard's mark; none occurs here: h omega_c stays
      // below ~0.07 at h <= 0.5 ms for these masses, the limits are >= 0.17)
      if (const auto st = static_cast<LaneStatus>(r.status[j]); st != LaneStatus::ok && st != LaneStatus::coarse) {
        ++ndiv;
        continue;
      }
      sd += r.peak_u1[j] / r0.peak_u1[j];
      sa += r.peak_acc1[j] / r0.peak_acc1[j];
      ++n;
    }
  }
  return sub;
}

}  // namespace

std::vector<MuthukumarRow> muthukumar(const std::string& record_dir, const MuthukumarOptions& opt,
                                      std::vector<std::string>* log) {
  check_options(opt);
  const MuthukumarSetup setup(opt);
  AmpSums acc;
  for (const auto& rc : selected_records(record_dir, opt)) {
    LoadedRecord lr = load_record(record_dir, {rc.file, 0.0});
    const int sub = add_muthukumar_record(acc, rc, lr, setup, opt.substeps);
    if (log) log->push_back(fmt::format("{} ({}, PGA {} g, {} substeps)", rc.file, rc.level, rc.pga, sub));
  }
  std::vector<MuthukumarRow> out;
  for (const auto& lvl : muthukumar_levels)
    for (double rt : muthukumar_ratios)
      for (const auto& ms : muthukumar_models()) {
        auto it = acc.find({lvl, rt, ms.name, ms.e});
        if (it == acc.end()) continue;
        auto [sd, sa, n, ndiv] = it->second;
        MuthukumarRow row;
        row.level = lvl, row.period_ratio = rt, row.model = ms.name, row.e = ms.e;
        row.records = n, row.diverged = ndiv;
        row.disp_amp = sd / n, row.acc_amp = sa / n;
        out.push_back(row);
      }
  return out;
}

}  // namespace pounding::accuracy
