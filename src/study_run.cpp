#include "pounding/study_run.hpp"

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
#include <sstream>

#include <fmt/format.h>

#include "pounding/error.hpp"
#include "pounding/hdf5io.hpp"
#include "pounding/kernel.hpp"
#include "pounding/report.hpp"
#include "pounding/sampler.hpp"
#include "pounding/version.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t results_format_version = 1;
// per lane: uncoupled status, peak |u1|, peak |u2|, peak closing
constexpr int unc_fields = 4;
// per lane and gap: status, impact count, peak force, peak |u1|, peak |u2|, first impact time
constexpr int gap_fields = 6;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = 1469598103934665603ULL) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  return h;
}

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

// ------------------------------------------------------------------------------------------------
// Checkpoint: <out>.ckpt, append-only. Header: magic, study hash, unit count. Record: unit, count,
// count doubles, FNV-1a checksum. A torn last record (kill -9 during a write) fails its checksum and is
// dropped on --resume; the file is truncated to the last good record.
class Checkpoint {
 public:
  static constexpr char magic[8] = {'P', 'N', 'D', 'C', 'K', 'P', 'T', '1'};
  Checkpoint(std::string path, std::uint64_t hash, std::uint64_t units) : path_(std::move(path)), hash_(hash), units_(units) {}

  // Loads finished units (unit -> payload). Throws InputError if the checkpoint belongs to another study.
  void load(const std::function<void(std::size_t, std::vector<double>&&)>& on_unit) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw InputError("no checkpoint to resume from", path_, "run without --resume to start the study");
    char m[8];
    std::uint64_t h = 0, n = 0;
    in.read(m, 8);
    in.read(reinterpret_cast<char*>(&h), 8);
    in.read(reinterpret_cast<char*>(&n), 8);
    if (!in || std::memcmp(m, magic, 8) != 0)
      throw InputError("the checkpoint file is not a pounding checkpoint", path_, "delete it and run without --resume");
    if (h != hash_ || n != units_)
      throw InputError("the checkpoint belongs to a different study (study text or program format changed)", path_,
                       "resume with the study file that started the run, or run without --resume to start afresh");
    std::uint64_t good = 24;
    for (;;) {
      std::uint64_t unit = 0, count = 0, sum = 0;
      in.read(reinterpret_cast<char*>(&unit), 8);
      in.read(reinterpret_cast<char*>(&count), 8);
      if (!in || count > (1u << 28) || unit >= units_) break;
      std::vector<double> data(count);
      in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(count * 8));
      in.read(reinterpret_cast<char*>(&sum), 8);
      if (!in) break;
      std::uint64_t c = fnv1a(&unit, 8);
      c = fnv1a(&count, 8, c);
      c = fnv1a(data.data(), count * 8, c);
      if (c != sum) break;
      good += 24 + count * 8;
      on_unit(static_cast<std::size_t>(unit), std::move(data));
    }
    in.close();
    fs::resize_file(path_, good);
  }
  void open(bool append) {
    f_ = std::fopen(path_.c_str(), append ? "ab" : "wb");
    if (!f_) throw InputError("cannot write the checkpoint", path_, "check that the directory is writable");
    if (!append) {
      std::fwrite(magic, 1, 8, f_);
      std::fwrite(&hash_, 8, 1, f_);
      std::fwrite(&units_, 8, 1, f_);
      std::fflush(f_);
    }
  }
  void append(std::size_t unit, const std::vector<double>& data) {
    std::uint64_t u = unit, count = data.size();
    std::uint64_t c = fnv1a(&u, 8);
    c = fnv1a(&count, 8, c);
    c = fnv1a(data.data(), count * 8, c);
    std::fwrite(&u, 8, 1, f_);
    std::fwrite(&count, 8, 1, f_);
    std::fwrite(data.data(), 8, count, f_);
    std::fwrite(&c, 8, 1, f_);
    std::fflush(f_);
  }
  void sync() {
    if (f_) fsync(fileno(f_));
  }
  void close() {
    if (f_) std::fclose(f_);
    f_ = nullptr;
  }
  ~Checkpoint() { close(); }

 private:
  std::string path_;
  std::uint64_t hash_, units_;
  std::FILE* f_ = nullptr;
};

std::string now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--:--";
  long t = std::lround(s);
  return fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60);
}

}  // namespace

int run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& opt) {
  // Every rank parses the same text (rank 0 reads the file), so every rank holds the same immutable Study.
  std::string text;
  int read_ok = 1;
  if (session.root()) {
    std::ifstream in(study_path, std::ios::binary);
    if (in) {
      std::stringstream ss;
      ss << in.rdbuf();
      text = ss.str();
    } else {
      read_ok = 0;
    }
  }
  session.broadcast(read_ok);
  if (!read_ok) throw InputError("cannot read the study file", study_path, "check the path");
  session.broadcast(text);
  const Study study = parse_study(text, study_path);
  const std::string out = opt.out.empty() ? study.output : opt.out;
  const std::vector<StudyRecord> records = load_study_records(study);
  if (records.empty()) throw InputError("the study resolves to no records", study_path, "check [records]");
  const StructureSampler sampler(study.structures, study.seed);

  Layout L;
  L.records = records.size();
  L.pairs = static_cast<std::size_t>(study.structures.period_pair_count());
  L.samples = static_cast<std::size_t>(study.structures.samples_per_pair);
  L.batch = static_cast<std::size_t>(study.batch);
  L.blocks = (L.samples + L.batch - 1) / L.batch;
  L.gaps = study.gap_ratios.size();
  L.impacts = study.scene == Scene::impacts;
  const std::size_t nper = study.structures.periods.size();

  KernelSettings ks_base;
  ks_base.stepper = study.stepper;
  ks_base.displacement_limit = study.displacement_limit;
  auto substeps_for = [&](double dt) {
    int q = study.max_dt > 0 ? static_cast<int>(std::ceil(dt / study.max_dt - 1e-9)) : 1;
    return std::max(study.substeps, q);
  };
  ContactModel uncoupled = study.contact;
  uncoupled.law = ContactLaw::none;

  // ---- one work unit: sample the block, run the uncoupled pairs (and the coupled ones per gap)
  auto compute = [&](std::size_t unit) {
    std::size_t r, p, b;
    L.decode(unit, r, p, b);
    const std::size_t n = L.lanes(b);
    std::vector<SampledPair> pairs(n);
    sampler.sample_block(static_cast<std::int32_t>(p / nper), static_cast<std::int32_t>(p % nper),
                         static_cast<std::int64_t>(b * L.batch), pairs);
    const Record& rec = records[r].record;
    GroundMotion gm{rec.dt, rec.acc, rec.duration() + study.free_vibration};
    KernelSettings ks = ks_base;
    ks.substeps = substeps_for(rec.dt);
    PairBatch batch;
    batch.resize(n);
    for (std::size_t i = 0; i < n; ++i) batch.set(i, pairs[i].pair_params(0.0, study.e));
    BatchResult res;
    run_batch(batch, uncoupled, gm, ks, res);
    std::vector<double> payload;
    payload.reserve(L.payload_size(b));
    for (std::size_t i = 0; i < n; ++i) {
      payload.push_back(res.status[i]);
      payload.push_back(res.peak_u1[i]);
      payload.push_back(res.peak_u2[i]);
      payload.push_back(res.peak_closing[i]);
    }
    if (L.impacts) {
      // A pair whose uncoupled peak closing stays <= g never touches at gap g, and its coupled run is
      // bit-identical to the uncoupled one (the first-passage property, tested): only the pairs that touch
      // are run with contact; the others take the uncoupled results (unless [analysis] skip_untouched = false).
      std::vector<std::size_t> lanes;
      PairBatch sub;
      BatchResult cres;
      for (std::size_t g = 0; g < L.gaps; ++g) {
        lanes.clear();
        for (std::size_t i = 0; i < n; ++i) {
          const bool untouched = res.status[i] == 0 && !(res.peak_closing[i] > study.gap_ratios[g] * pairs[i].d);
          if (!study.skip_untouched || !untouched) lanes.push_back(i);
        }
        sub.resize(lanes.size());
        for (std::size_t j = 0; j < lanes.size(); ++j) {
          PairParams pp = pairs[lanes[j]].pair_params(study.gap_ratios[g], study.e);
          if (study.contact_stiffness > 0) pp.kc = study.contact_stiffness;
          sub.set(j, pp);
        }
        if (!lanes.empty()) run_batch(sub, study.contact, gm, ks, cres);
        std::size_t j = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (j < lanes.size() && lanes[j] == i) {
            payload.push_back(cres.status[j]);
            payload.push_back(cres.impact_count[j]);
            payload.push_back(cres.peak_force[j]);
            payload.push_back(cres.peak_u1[j]);
            payload.push_back(cres.peak_u2[j]);
            payload.push_back(cres.t_first_impact[j]);
            ++j;
          } else {
            payload.push_back(res.status[i]);
            payload.push_back(0.0);
            payload.push_back(0.0);
            payload.push_back(res.peak_u1[i]);
            payload.push_back(res.peak_u2[i]);
            payload.push_back(NAN);
          }
        }
      }
    }
    return payload;
  };

  // ---- rank 0 gathers per-model results in fixed arrays: any completion order gives the same file
  const std::size_t M = L.models(), R = L.records, G = L.gaps;
  std::vector<std::uint8_t> unc_status, imp_status;
  std::vector<double> pu1, pu2, pclose, ipu1, ipu2, iforce, ifirst;
  std::vector<std::int32_t> icount;
  std::vector<char> done(L.units(), 0);
  std::size_t n_done = 0;
  if (session.root()) {
    unc_status.assign(R * M, 255);
    pu1.assign(R * M, NAN), pu2.assign(R * M, NAN), pclose.assign(R * M, NAN);
    if (L.impacts) {
      imp_status.assign(R * M * G, 255);
      icount.assign(R * M * G, -1);
      iforce.assign(R * M * G, NAN), ipu1.assign(R * M * G, NAN), ipu2.assign(R * M * G, NAN);
      ifirst.assign(R * M * G, NAN);
    }
  }
  auto store = [&](std::size_t unit, const std::vector<double>& d) {
    std::size_t r, p, b;
    L.decode(unit, r, p, b);
    const std::size_t n = L.lanes(b);
    if (d.size() != L.payload_size(b)) throw std::runtime_error(fmt::format("unit {}: payload size mismatch", unit));
    const std::size_t m0 = p * L.samples + b * L.batch;
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t idx = r * M + m0 + i;
      unc_status[idx] = static_cast<std::uint8_t>(d[k]);
      pu1[idx] = d[k + 1], pu2[idx] = d[k + 2], pclose[idx] = d[k + 3];
      k += unc_fields;
    }
    if (L.impacts) {
      for (std::size_t g = 0; g < G; ++g)
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t idx = (r * M + m0 + i) * G + g;
          imp_status[idx] = static_cast<std::uint8_t>(d[k]);
          icount[idx] = static_cast<std::int32_t>(d[k + 1]);
          iforce[idx] = d[k + 2], ipu1[idx] = d[k + 3], ipu2[idx] = d[k + 4], ifirst[idx] = d[k + 5];
          k += gap_fields;
        }
    }
    if (!done[unit]) ++n_done;
    done[unit] = 1;
  };

  // ---- checkpoint / resume (rank 0), then tell every rank which units remain
  std::uint64_t hash = fnv1a(study.text.data(), study.text.size());
  hash = fnv1a(&results_format_version, sizeof results_format_version, hash);
  for (const auto& rr : records) {
    hash = fnv1a(rr.record.acc.data(), rr.record.acc.size() * sizeof(double), hash);
    hash = fnv1a(&rr.record.dt, sizeof(double), hash);
  }
  Checkpoint ckpt(out + ".ckpt", hash, L.units());
  std::string todo_text;
  if (session.root()) {
    if (opt.resume) ckpt.load([&](std::size_t u, std::vector<double>&& d) { store(u, d); });
    ckpt.open(opt.resume);
    for (std::size_t u = 0; u < L.units(); ++u)
      if (!done[u]) todo_text += fmt::format("{} ", u);
    if (opt.resume) fmt::print(stderr, "resuming: {} of {} units already done\n", n_done, L.units());
  }
  session.broadcast(todo_text);
  std::vector<std::size_t> todo;
  {
    std::istringstream is(todo_text);
    std::size_t u;
    while (is >> u) todo.push_back(u);
  }

  // ---- progress on rank 0: a bar on a terminal, periodic lines otherwise
  const bool tty = isatty(fileno(stderr));
  const auto t0 = std::chrono::steady_clock::now();
  auto last = t0, last_sync = t0;
  const std::size_t done_at_start = n_done;
  const double models_per_unit = static_cast<double>(L.samples) / static_cast<double>(L.blocks);
  auto tick = [&] {
    auto now = std::chrono::steady_clock::now();
    if (now - last_sync > std::chrono::seconds(5)) {
      ckpt.sync();
      last_sync = now;
    }
    bool final = n_done == L.units();
    if (!opt.progress || (!final && now - last < std::chrono::milliseconds(tty ? 250 : 10000))) return;
    last = now;
    double el = std::chrono::duration<double>(now - t0).count();
    double rate = static_cast<double>(n_done - done_at_start) * models_per_unit / std::max(el, 1e-9);
    double frac = static_cast<double>(n_done) / static_cast<double>(L.units());
    double eta = (static_cast<double>(L.units() - n_done) * models_per_unit) / std::max(rate, 1e-9);
    if (tty) {
      int w = 30, fill = static_cast<int>(frac * w);
      fmt::print(stderr, "\r[{}{}] {:5.1f}%  units {}/{}  {:.0f} models/s  ETA {}{}", std::string(fill, '#'),
                 std::string(w - fill, '.'), 100 * frac, n_done, L.units(), rate, hms(eta), final ? "\n" : "");
    } else {
      fmt::print(stderr, "progress: units {}/{} ({:.1f}%), {:.0f} models/s, elapsed {}, ETA {}\n", n_done, L.units(),
                 100 * frac, rate, hms(el), hms(eta));
    }
  };

  if (session.root()) {
    fmt::print(stderr, "pounding run: {} ({} records, {} models, scene {}, {} units on {} rank{})\n", study.title, R, M,
               to_string(study.scene), L.units(), session.size(), session.size() > 1 ? "s" : "");
    fmt::print(stderr, "{}\n", study.scene_reason);
    for (const auto& rr : records)
      if (rr.synthetic) fmt::print(stderr, "record {}: synthetic stand-in ({})\n", rr.id, rr.note);
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const auto t_start = std::chrono::steady_clock::now();
  bool complete = parallel::run_units(
      session, todo, compute,
      [&](std::size_t u, std::vector<double>&& d) {
        store(u, d);
        ckpt.append(u, d);
      },
      tick, g_stop);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (!session.root()) return 0;
  ckpt.sync();
  ckpt.close();
  if (!complete || n_done != L.units()) {
    fmt::print(stderr, "\ninterrupted: {} of {} units done and checkpointed in {}; continue with --resume\n", n_done,
               L.units(), out + ".ckpt");
    return 130;
  }

  // ---- the results file, written under a temporary name and renamed
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
    h5::write_attribute(root, "ranks", static_cast<std::int64_t>(session.size()));
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
      h5::write_dataset(g.get(), "status", unc_status);
      h5::write_dataset(g.get(), "peak_u1", pu1, R, M);
      h5::write_dataset(g.get(), "peak_u2", pu2, R, M);
      h5::write_dataset(g.get(), "peak_closing", pclose, R, M);
    }
    if (L.impacts) {
      auto g = h5::create_group(root, "impacts");
      h5::write_attribute(g.get(), "shape", std::string("[records, models, gaps]"));
      h5::write_dataset(g.get(), "gap_ratios", study.gap_ratios);
      h5::write_dataset(g.get(), "status", imp_status);
      h5::write_dataset(g.get(), "impact_count", icount);
      h5::write_dataset(g.get(), "peak_force", iforce);
      h5::write_dataset(g.get(), "peak_u1", ipu1);
      h5::write_dataset(g.get(), "peak_u2", ipu2);
      h5::write_dataset(g.get(), "t_first_impact", ifirst);
      // response amplification: peak with pounding / peak without (the uncoupled run of the same model)
      std::vector<double> amp1(R * M * G), amp2(R * M * G);
      for (std::size_t q = 0; q < R * M; ++q)
        for (std::size_t g2 = 0; g2 < G; ++g2) {
          amp1[q * G + g2] = ipu1[q * G + g2] / pu1[q];
          amp2[q * G + g2] = ipu2[q * G + g2] / pu2[q];
        }
      h5::write_dataset(g.get(), "amplification_u1", amp1);
      h5::write_dataset(g.get(), "amplification_u2", amp2);
    }
    f.commit();
  }
  std::remove((out + ".ckpt").c_str());
  fmt::print(stderr, "results: {} (wall time {:.2f} s, {} ranks)\n", out, wall, session.size());
  fmt::print("{}", report_markdown(load_results(out)));
  return 0;
}

}  // namespace pounding
