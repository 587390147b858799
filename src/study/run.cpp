#include "pounding/study/run.hpp"

#include <map>
#include <type_traits>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/study/checkpoint.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/io/hdf5.hpp"
#include "pounding/kernel.hpp"
#include "pounding/report/report.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/settings.hpp"
#include "pounding/core/version.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t results_format_version = 1;
// per lane: uncoupled status, peak |u1|, peak |u2|, peak closing
constexpr int unc_fields = 4;
// per lane and gap: status, impact count, peak force, peak |u1|, peak |u2|, first impact time
constexpr int gap_fields = 6;


// Work units: unit = (record r, period pair p, block b), numbered r-major.
struct Layout {
  std::size_t records = 0, pairs = 0, blocks = 0, batch = 0, samples = 0, gaps = 0;
  bool impacts = false;
  std::size_t units() const { return records * pairs * blocks; }
  std::size_t models() const { return pairs * samples; }
  void decode(std::size_t u, std::size_t& r, std::size_t& p, std::size_t& b) const {
    b = u % blocks;
    p = (u / blocks) % pairs;
    r = u / (blocks * pairs);
  }
  std::size_t lanes(std::size_t b) const { return std::min(batch, samples - b * batch); }
  std::size_t payload_size(std::size_t b) const {
    return lanes(b) * (unc_fields + (impacts ? gaps * gap_fields : 0));
  }
};

// Test-only fault injection: POUNDING_INJECT_FAULT=<phase>[@rank] makes `phase` (load, compute, write)
// throw on that rank (default 0); `compute` throws on the rank's third unit. The fault tests in
// tests/faults/ use it to check that an error anywhere ends the whole job promptly with one message.
void inject_fault(std::string_view phase, int rank) {
  static const char* spec = std::getenv("POUNDING_INJECT_FAULT");
  if (!spec) return;
  std::string_view v(spec);
  int at = 0;
  if (auto k = v.find('@'); k != std::string_view::npos) {
    at = std::atoi(std::string(v.substr(k + 1)).c_str());
    v = v.substr(0, k);
  }
  if (v == phase && at == rank)
    throw std::runtime_error(fmt::format("injected fault in phase '{}' on rank {} (POUNDING_INJECT_FAULT)", phase, rank));
}

std::string now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}


// Per-model results gathered on rank 0 in fixed arrays: any completion order gives the same file.
struct Tally {
  std::vector<std::uint8_t> unc_status, imp_status;           // [R x M], [R x M x G]
  std::vector<double> pu1, pu2, pclose, ipu1, ipu2, iforce, ifirst;
  std::vector<std::int32_t> icount;
  std::vector<char> done;  // per unit
  std::size_t n_done = 0;

  void init(const Layout& L) {
    const std::size_t RM = L.records * L.models(), RMG = RM * L.gaps;
    unc_status.assign(RM, 255);
    pu1.assign(RM, NAN), pu2.assign(RM, NAN), pclose.assign(RM, NAN);
    if (L.impacts) {
      imp_status.assign(RMG, 255);
      icount.assign(RMG, -1);
      iforce.assign(RMG, NAN), ipu1.assign(RMG, NAN), ipu2.assign(RMG, NAN), ifirst.assign(RMG, NAN);
    }
    done.assign(L.units(), 0);
  }

  // Scatters one unit's payload (UnitComputer's layout) into the arrays.
  void store(const Layout& L, std::size_t unit, const std::vector<double>& d) {
    std::size_t r, p, b;
    L.decode(unit, r, p, b);
    const std::size_t n = L.lanes(b), M = L.models(), G = L.gaps;
    if (d.size() != L.payload_size(b)) throw std::runtime_error(fmt::format("unit {}: payload size mismatch", unit));
    const std::size_t m0 = p * L.samples + b * L.batch;
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i, k += unc_fields) {
      const std::size_t idx = r * M + m0 + i;
      unc_status[idx] = static_cast<std::uint8_t>(d[k]);
      pu1[idx] = d[k + 1], pu2[idx] = d[k + 2], pclose[idx] = d[k + 3];
    }
    if (L.impacts)
      for (std::size_t g = 0; g < G; ++g)
        for (std::size_t i = 0; i < n; ++i, k += gap_fields) {
          const std::size_t idx = (r * M + m0 + i) * G + g;
          imp_status[idx] = static_cast<std::uint8_t>(d[k]);
          icount[idx] = static_cast<std::int32_t>(d[k + 1]);
          iforce[idx] = d[k + 2], ipu1[idx] = d[k + 3], ipu2[idx] = d[k + 4], ifirst[idx] = d[k + 5];
        }
    if (!done[unit]) ++n_done;
    done[unit] = 1;
  }
};

// One work unit: sample the block, run the uncoupled pairs (and, in the impacts scene, the coupled ones per
// gap); the payload is [per lane: unc_fields] then [per gap, per lane: gap_fields].
class UnitComputer {
 public:
  UnitComputer(const Study& s, const std::vector<StudyRecord>& records, const StructureSampler& sampler,
               const Layout& L, int rank)
      : s_(s), records_(records), sampler_(sampler), L_(L), rank_(rank), nper_(s.structures.periods.size()) {
    ks_base_.stepper = s.stepper;
    ks_base_.displacement_limit = s.displacement_limit;
    uncoupled_ = s.contact;
    uncoupled_.law = ContactLaw::none;
  }

  std::vector<double> operator()(std::size_t unit) {
    if (++computed_ == 3) inject_fault("compute", rank_);
    std::size_t r, p, b;
    L_.decode(unit, r, p, b);
    const std::size_t n = L_.lanes(b);
    pairs_.resize(n);
    sampler_.sample_block(static_cast<std::int32_t>(p / nper_), static_cast<std::int32_t>(p % nper_),
                          static_cast<std::int64_t>(b * L_.batch), pairs_);
    const Record& rec = records_[r].record;
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + s_.free_vibration};
    KernelSettings ks = ks_base_;
    ks.substeps = substeps_for(rec.dt);
    PairBatch batch;
    batch.resize(n);
    for (std::size_t i = 0; i < n; ++i) batch.set(i, pairs_[i].pair_params(0.0, s_.e));
    run_batch(batch, uncoupled_, gm, ks, res_);
    std::vector<double> payload;
    payload.reserve(L_.payload_size(b));
    for (std::size_t i = 0; i < n; ++i)
      payload.insert(payload.end(), {double(res_.status[i]), res_.peak_u1[i], res_.peak_u2[i], res_.peak_closing[i]});
    if (L_.impacts)
      for (std::size_t g = 0; g < L_.gaps; ++g) coupled(g, gm, ks, payload);
    return payload;
  }

 private:
  int substeps_for(double dt) const {
    const int q = s_.max_dt > 0 ? static_cast<int>(std::ceil(dt / s_.max_dt - 1e-9)) : 1;
    return std::max(s_.substeps, q);
  }

  // A pair whose uncoupled peak closing stays <= g never touches at gap g, and its coupled run is
  // bit-identical to the uncoupled one (the first-passage property, tested): only the pairs that touch are
  // run with contact; the others take the uncoupled results (unless [analysis] skip_untouched = false).
  void coupled(std::size_t g, const GroundMotion& gm, const KernelSettings& ks, std::vector<double>& payload) {
    const std::size_t n = pairs_.size();
    lanes_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const bool untouched = res_.status[i] == 0 && !(res_.peak_closing[i] > s_.gap_ratios[g] * pairs_[i].d);
      if (!s_.skip_untouched || !untouched) lanes_.push_back(i);
    }
    sub_.resize(lanes_.size());
    for (std::size_t j = 0; j < lanes_.size(); ++j) {
      PairParams pp = pairs_[lanes_[j]].pair_params(s_.gap_ratios[g], s_.e);
      if (s_.contact_stiffness > 0) pp.kc = s_.contact_stiffness;
      sub_.set(j, pp);
    }
    if (!lanes_.empty()) run_batch(sub_, s_.contact, gm, ks, cres_);
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      if (j < lanes_.size() && lanes_[j] == i) {
        payload.insert(payload.end(), {double(cres_.status[j]), double(cres_.impact_count[j]), cres_.peak_force[j],
                                       cres_.peak_u1[j], cres_.peak_u2[j], cres_.t_first_impact[j]});
        ++j;
      } else {
        payload.insert(payload.end(), {double(res_.status[i]), 0.0, 0.0, res_.peak_u1[i], res_.peak_u2[i], NAN});
      }
    }
  }

  const Study& s_;
  const std::vector<StudyRecord>& records_;
  const StructureSampler& sampler_;
  const Layout& L_;
  int rank_, computed_ = 0;
  std::size_t nper_;
  KernelSettings ks_base_;
  ContactModel uncoupled_;
  std::vector<SampledPair> pairs_;
  std::vector<std::size_t> lanes_;
  PairBatch sub_;
  BatchResult res_, cres_;
};

// Analyses excluded from the probabilities (diverged or non-finite), and whether they are too many to trust
// the results: a whole record lost, or more than [analysis] max_excluded_fraction of all analyses.
struct Exclusions {
  std::int64_t excluded = 0, total = 0;
  std::string verdict;  // empty when acceptable; otherwise the banner's text
};

Exclusions count_exclusions(const Study& study, const Layout& L, const Tally& t,
                            const std::vector<StudyRecord>& records) {
  Exclusions ex;
  const std::size_t M = L.models(), G = L.gaps;
  std::vector<std::string> lost;
  for (std::size_t r = 0; r < L.records; ++r) {
    std::int64_t bad_unc = 0, bad_cpl = 0;
    for (std::size_t m = 0; m < M; ++m) bad_unc += t.unc_status[r * M + m] != 0;
    if (L.impacts)
      for (std::size_t i = r * M * G; i < (r + 1) * M * G; ++i) bad_cpl += t.imp_status[i] != 0;
    ex.excluded += bad_unc + bad_cpl;
    ex.total += static_cast<std::int64_t>(M + (L.impacts ? M * G : 0));
    if (M > 0 && (bad_unc == static_cast<std::int64_t>(M) || (L.impacts && bad_cpl == static_cast<std::int64_t>(M * G))))
      lost.push_back(records[r].id);
  }
  const double frac = ex.total ? static_cast<double>(ex.excluded) / static_cast<double>(ex.total) : 0.0;
  if (!lost.empty())
    ex.verdict = fmt::format("every {}analysis of record(s) {} diverged or was non-finite",
                             L.impacts ? "uncoupled or every coupled " : "", fmt::join(lost, ", "));
  if (frac > study.max_excluded_fraction)
    ex.verdict += fmt::format("{}{} of {} analyses ({:.3g} %) were excluded, more than [analysis] "
                              "max_excluded_fraction = {:.3g} %",
                              ex.verdict.empty() ? "" : "; ", ex.excluded, ex.total, 100.0 * frac,
                              100.0 * study.max_excluded_fraction);
  if (!ex.verdict.empty())
    ex.verdict += "; the probabilities may be biased: check the record units and scale, the contact stiffness "
                  "and the step (substeps, max_dt)";
  return ex;
}

// Every setting at /settings/<section>/<key> (study_settings.hpp); booleans as 0/1 integers.
void write_settings(h5::hid root, const Study& study) {
  auto settings = h5::create_group(root, "settings");
  std::map<std::string, h5::Handle> sections;
  visit_settings(study, [&](const std::string& section, const std::string& key, const auto& value) {
    h5::hid g = settings.get();
    if (!section.empty()) {
      auto it = sections.find(section);
      if (it == sections.end()) it = sections.emplace(section, h5::create_group(settings.get(), section)).first;
      g = it->second.get();
    }
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, bool>) h5::write_attribute(g, key, static_cast<std::int64_t>(value));
    else if constexpr (std::is_same_v<T, std::vector<double>>) h5::write_attribute(g, key, std::span<const double>(value));
    else h5::write_attribute(g, key, value);
  });
}

void write_exclusions(h5::hid root, const Study& study, const Exclusions& ex) {
  h5::write_attribute(root, "excluded_analyses", ex.excluded);
  h5::write_attribute(root, "total_analyses", ex.total);
  h5::write_attribute(root, "max_excluded_fraction", study.max_excluded_fraction);
  h5::write_attribute(root, "exclusion_warning", ex.verdict);
}

// The results file: built in memory and written atomically (files::write_atomically), so a full disk or
// an interrupt leaves neither a partial file under `out` nor a temporary.
void write_results(const std::string& out, const Study& study, const std::vector<StudyRecord>& records,
                   const Layout& L, const std::string& build, int ranks, double wall, const Exclusions& ex,
                   const Tally& t) {
  const StructureSampler sampler(study.structures, study.seed);
  const std::size_t M = L.models(), R = L.records, G = L.gaps;
  const std::size_t nper = study.structures.periods.size();
  {
    h5::AtomicFile f(out);
    const auto root = f.root();
    h5::write_attribute(root, "format_version", results_format_version);
    h5::write_attribute(root, "program_version", std::string(program_version));
    h5::write_attribute(root, "git_commit", std::string(git_commit));
    h5::write_attribute(root, "date", now_iso());
    h5::write_attribute(root, "seed", static_cast<std::int64_t>(study.seed));
    h5::write_attribute(root, "study_text", study.text);
    h5::write_attribute(root, "study_path", study.path);
    h5::write_attribute(root, "title", study.title);
    h5::write_attribute(root, "scene", std::string(to_string(study.scene)));
    h5::write_attribute(root, "scene_reason", study.scene_reason);
    h5::write_attribute(root, "contact_law", std::string(to_string(study.contact.law)));
    h5::write_attribute(root, "damping_law", std::string(to_string(study.contact.damping)));
    h5::write_attribute(root, "restitution", study.e);
    h5::write_attribute(root, "stepper", std::string(to_string(study.stepper)));
    h5::write_attribute(root, "substeps", static_cast<std::int64_t>(study.substeps));
    h5::write_attribute(root, "max_dt", study.max_dt);
    h5::write_attribute(root, "ranks", static_cast<std::int64_t>(ranks));
    h5::write_attribute(root, "build", build);
    write_settings(root, study);
    write_exclusions(root, study, ex);
    h5::write_attribute(root, "wall_time_s", wall);
    {
      auto g = h5::create_group(root, "records");
      std::vector<std::string> ids, names, sources, notes;
      std::vector<std::uint8_t> synth;
      std::vector<double> dt, dur, pga;
      std::vector<std::int64_t> npts;
      for (const auto& rr : records) {
        ids.push_back(rr.id), names.push_back(rr.record.name), sources.push_back(rr.record.source);
        notes.push_back(rr.note), synth.push_back(rr.synthetic ? 1 : 0);
        dt.push_back(rr.record.dt), dur.push_back(rr.record.duration()), pga.push_back(rr.record.pga() / g_accel);
        npts.push_back(static_cast<std::int64_t>(rr.record.acc.size()));
      }
      h5::write_strings(g.get(), "id", ids);
      h5::write_strings(g.get(), "name", names);
      h5::write_strings(g.get(), "source", sources);
      h5::write_strings(g.get(), "note", notes);
      h5::write_dataset(g.get(), "synthetic", synth);
      h5::write_dataset(g.get(), "dt", dt);
      h5::write_dataset(g.get(), "duration", dur);
      h5::write_dataset(g.get(), "pga_g", pga);
      h5::write_dataset(g.get(), "npts", npts);
    }
    {
      auto g = h5::create_group(root, "models");
      std::vector<double> T1(M), T2(M), h1(M), h2(M), m1(M), m2(M), k1(M), k2(M), fy1(M), fy2(M), d(M), kh(M);
      std::vector<double> a1(M), a2(M), rho1(M), rho2(M), mb1(M), mb2(M), c1(M), c2(M);
      std::vector<std::int32_t> i1(M), i2(M);
      std::vector<std::int64_t> sample(M);
      for (std::size_t p = 0; p < L.pairs; ++p) {
        std::vector<SampledPair> sp(L.samples);
        sampler.sample_block(static_cast<std::int32_t>(p / nper), static_cast<std::int32_t>(p % nper), 0, sp);
        for (std::size_t s = 0; s < L.samples; ++s) {
          const std::size_t m = p * L.samples + s;
          const auto& q = sp[s];
          T1[m] = q.s1.T, T2[m] = q.s2.T, h1[m] = q.s1.h, h2[m] = q.s2.h, m1[m] = q.s1.m, m2[m] = q.s2.m;
          k1[m] = q.s1.k, k2[m] = q.s2.k, fy1[m] = q.s1.fy, fy2[m] = q.s2.fy, d[m] = q.d, kh[m] = q.kh;
          i1[m] = q.id.i1, i2[m] = q.id.i2, sample[m] = q.id.sample;
          a1[m] = q.s1.aspect, a2[m] = q.s2.aspect, rho1[m] = q.s1.rho, rho2[m] = q.s2.rho;
          mb1[m] = q.s1.mbar, mb2[m] = q.s2.mbar, c1[m] = q.s1.c, c2[m] = q.s2.c;
        }
      }
      for (auto& [name, v] : std::vector<std::pair<const char*, std::vector<double>*>>{
               {"T1", &T1}, {"T2", &T2}, {"h1", &h1}, {"h2", &h2}, {"m1", &m1}, {"m2", &m2}, {"k1", &k1},
               {"k2", &k2}, {"fy1", &fy1}, {"fy2", &fy2}, {"code_gap", &d}, {"kh", &kh}, {"aspect1", &a1},
               {"aspect2", &a2}, {"rho1", &rho1}, {"rho2", &rho2}, {"mbar1", &mb1}, {"mbar2", &mb2}, {"c1", &c1},
               {"c2", &c2}})
        h5::write_dataset(g.get(), name, *v);
      h5::write_dataset(g.get(), "i1", i1);
      h5::write_dataset(g.get(), "i2", i2);
      h5::write_dataset(g.get(), "sample", sample);
      h5::write_dataset(g.get(), "periods", study.structures.periods);
      h5::write_attribute(g.get(), "zeta", study.structures.zeta);
    }
    {
      auto g = h5::create_group(root, "uncoupled");
      h5::write_attribute(g.get(), "shape", std::string("[records, models]"));
      h5::write_dataset(g.get(), "status", t.unc_status);
      h5::write_dataset(g.get(), "peak_u1", t.pu1, R, M);
      h5::write_dataset(g.get(), "peak_u2", t.pu2, R, M);
      h5::write_dataset(g.get(), "peak_closing", t.pclose, R, M);
    }
    if (L.impacts) {
      auto g = h5::create_group(root, "impacts");
      h5::write_attribute(g.get(), "shape", std::string("[records, models, gaps]"));
      h5::write_dataset(g.get(), "gap_ratios", study.gap_ratios);
      h5::write_dataset(g.get(), "status", t.imp_status);
      h5::write_dataset(g.get(), "impact_count", t.icount);
      h5::write_dataset(g.get(), "peak_force", t.iforce);
      h5::write_dataset(g.get(), "peak_u1", t.ipu1);
      h5::write_dataset(g.get(), "peak_u2", t.ipu2);
      h5::write_dataset(g.get(), "t_first_impact", t.ifirst);
      // response amplification: peak with pounding / peak without (the uncoupled run of the same model)
      std::vector<double> amp1(R * M * G), amp2(R * M * G);
      for (std::size_t q = 0; q < R * M; ++q)
        for (std::size_t g2 = 0; g2 < G; ++g2) {
          amp1[q * G + g2] = t.ipu1[q * G + g2] / t.pu1[q];
          amp2[q * G + g2] = t.ipu2[q * G + g2] / t.pu2[q];
        }
      h5::write_dataset(g.get(), "amplification_u1", amp1);
      h5::write_dataset(g.get(), "amplification_u2", amp2);
    }
    f.commit();
  }
}

}  // namespace

namespace {

// ---- phase 1: the inputs, identical on every rank -------------------------------------------------
struct Inputs {
  Study study;
  std::string out, out_where;
  std::vector<StudyRecord> records;
};

// Every rank parses the same text (rank 0 reads the file) and loads the same records. The output is checked
// and the checkpoint locked (rank 0) before any work: a bad path or a second run on one output stops here.
Inputs load_inputs(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                   std::optional<Checkpoint>& ckpt) {
  std::string text;
  session.agree([&] {
    if (session.root()) text = files::read_text(study_path, "the study file");
  });
  session.broadcast(text);
  std::optional<Inputs> in;
  session.agree([&] { in.emplace(Inputs{parse_study(text, study_path), {}, {}, {}}); });
  in->out = opt.out_given ? opt.out : in->study.output;
  in->out_where = opt.out_given ? "--out" : study_path + ": output";
  session.agree([&] {
    if (!session.root()) return;
    files::check_output_path(in->out, in->out_where);
    ckpt.emplace(in->out + ".ckpt");
    files::remove_stale_temporaries(in->out);
  });
  session.agree([&] {
    inject_fault("load", session.rank());
    in->records = load_study_records(in->study);
    if (in->records.empty()) throw InputError("the study resolves to no records", study_path, "check [records]");
  });
  return std::move(*in);
}

// ---- phase 2: the work plan ---------------------------------------------------------------------
Layout plan_work(const Inputs& in) {
  const Study& s = in.study;
  Layout L;
  L.records = in.records.size();
  L.pairs = static_cast<std::size_t>(s.structures.period_pair_count());
  L.samples = static_cast<std::size_t>(s.structures.samples_per_pair);
  L.batch = static_cast<std::size_t>(s.batch);
  L.blocks = (L.samples + L.batch - 1) / L.batch;
  L.gaps = s.gap_ratios.size();
  L.impacts = s.scene == Scene::impacts;
  return L;
}

// The study, its records and the build: a checkpoint of anything else is not resumed.
CheckpointKey checkpoint_key(const Inputs& in, const Layout& L) {
  CheckpointKey key = this_build();
  std::uint64_t hash = files::fnv1a(in.study.text.data(), in.study.text.size());
  hash = files::fnv1a(&results_format_version, sizeof results_format_version, hash);
  for (const auto& rr : in.records) {
    hash = files::fnv1a(rr.record.acc.data(), rr.record.acc.size() * sizeof(double), hash);
    hash = files::fnv1a(&rr.record.dt, sizeof(double), hash);
  }
  key.study_hash = hash;
  key.units = L.units();
  return key;
}

// ---- phase 3: checkpoint and resume (rank 0); every rank learns which units remain ---------------
std::vector<std::size_t> open_checkpoint(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                                         const Layout& L, Checkpoint* ckpt, const CheckpointKey& key, Tally& tally,
                                         const RunContext& ctx) {
  std::string todo_text;
  session.agree([&] {
    if (!session.root()) return;
    open_for_run(*ckpt, key, opt.resume, opt.force,
                 [&](std::size_t u, std::vector<double>&& d) { tally.store(L, u, d); });
    for (std::size_t u = 0; u < L.units(); ++u)
      if (!tally.done[u]) todo_text += fmt::format("{} ", u);
    if (opt.resume) ctx.say(fmt::format("resuming: {} of {} units already done", tally.n_done, L.units()));
  });
  session.broadcast(todo_text);
  std::vector<std::size_t> todo;
  std::istringstream is(todo_text);
  for (std::size_t u; is >> u;) todo.push_back(u);
  (void)in;
  return todo;
}

void announce(const parallel::Session& session, const Inputs& in, const Layout& L, const RunContext& ctx) {
  if (!session.root()) return;
  ctx.say(fmt::format("pounding run: {} ({} records, {} models, scene {}, {} units on {} rank{})", in.study.title,
                      L.records, L.models(), to_string(in.study.scene), L.units(), session.size(),
                      session.size() > 1 ? "s" : ""));
  ctx.say(in.study.scene_reason);
  for (const auto& rr : in.records)
    if (rr.synthetic) ctx.say(fmt::format("record {}: synthetic stand-in ({})", rr.id, rr.note));
}

// ---- phase 4: the work (every rank computes; rank 0 gathers, checkpoints and reports progress) -----
bool execute(const parallel::Session& session, const Inputs& in, const Layout& L, const std::vector<std::size_t>& todo,
             Checkpoint* ckpt, Tally& tally, const RunContext& ctx, double& wall) {
  const StructureSampler sampler(in.study.structures, in.study.seed);
  UnitComputer compute(in.study, in.records, sampler, L, session.rank());
  const auto t0 = std::chrono::steady_clock::now();
  auto last_sync = t0;
  const std::size_t at_start = tally.n_done;
  auto tick = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_sync > std::chrono::seconds(5)) ckpt->sync(), last_sync = now;
    if (!ctx.progress) return;
    ProgressReport p;
    p.units_done = tally.n_done, p.units_total = L.units(), p.units_at_start = at_start;
    p.models_per_unit = static_cast<double>(L.samples) / static_cast<double>(L.blocks);
    p.elapsed_s = std::chrono::duration<double>(now - t0).count();
    p.final = tally.n_done == L.units();
    ctx.progress(p);
  };
  static const std::atomic<bool> never{false};
  const bool complete = parallel::run_units(
      session, todo, [&](std::size_t u) { return compute(u); },
      [&](std::size_t u, std::vector<double>&& d) {
        tally.store(L, u, d);
        ckpt->append(u, d);
      },
      tick, ctx.cancel ? *ctx.cancel : never);
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (session.root()) ckpt->sync();
  return complete && (!session.root() || tally.n_done == L.units());
}

// ---- phase 5: the results file (rank 0; the others wait for its outcome), then the checkpoint goes --
int finish(const parallel::Session& session, const Inputs& in, const Layout& L, Checkpoint* ckpt, const Tally& tally,
           const CheckpointKey& key, double wall, const RunContext& ctx) {
  int rc = 0;
  session.agree([&] {
    if (!session.root()) return;
    inject_fault("write", 0);
    const Exclusions ex = count_exclusions(in.study, L, tally, in.records);
    try {
      write_results(in.out, in.study, in.records, L, key.build, session.size(), wall, ex, tally);
    } catch (const InputError& e) {
      throw InputError(e.what_part(), e.where(),
                       e.fix() + "; the checkpoint keeps every unit: --resume writes the results without recomputing");
    }
    ckpt->remove();
    rc = ex.verdict.empty() ? 0 : 3;
  });
  session.broadcast(rc);
  if (session.root()) {
    ctx.say(fmt::format("results: {} (wall time {:.2f} s, {} ranks)", in.out, wall, session.size()));
    if (rc == 3) ctx.say(" WARNING: too many excluded analyses; the results file says so (exit code 3)");
  }
  return rc;
}

}  // namespace

RunOutcome run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                     const RunContext& ctx) {
  // Every phase runs inside session.agree() or run_units: an error on any rank stops every rank together,
  // and rank 0 prints one message.
  std::optional<Checkpoint> ckpt;  // rank 0 only
  const Inputs in = load_inputs(session, study_path, opt, ckpt);
  const Layout L = plan_work(in);
  Tally tally;
  if (session.root()) tally.init(L);
  const CheckpointKey key = session.root() ? checkpoint_key(in, L) : CheckpointKey{};
  const std::vector<std::size_t> todo = open_checkpoint(session, opt, in, L, ckpt ? &*ckpt : nullptr, key, tally, ctx);
  announce(session, in, L, ctx);
  double wall = 0.0;
  if (!execute(session, in, L, todo, ckpt ? &*ckpt : nullptr, tally, ctx, wall)) {
    if (session.root())
      ctx.say(tally.n_done > 0
                  ? fmt::format("\ninterrupted: {} of {} units done and checkpointed in {}; continue with --resume",
                                tally.n_done, L.units(), ckpt->path())
                  : fmt::format("\ninterrupted before any unit finished: nothing to keep, no checkpoint left"));
    return {130, in.out};
  }
  return {finish(session, in, L, ckpt ? &*ckpt : nullptr, tally, key, wall, ctx), in.out};
}

}  // namespace pounding
