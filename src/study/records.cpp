// Resolving a study's [records] into scaled ground motions (real files or synthetic stand-ins).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <variant>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/motion/suite.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

// [records] files naming the real records beside the clone (../shared/records/real: 85 PEER accelerograms, not the
// project's to redistribute, so not in the repository): one error for every missing one, saying where they go, before
// any is read (issue 45 item 3: studies/four-frame-bridge.toml stopped on the first path, "check the path")
void require_real_records(const Study& s) {
  std::vector<std::string> missing;
  for (const auto& f : s.files)
    if (f.path.find("shared/records/real/") != std::string::npos && !fs::exists(f.path)) missing.push_back(f.path);
  if (missing.empty()) return;
  const fs::path dir = fs::absolute(fs::path(missing.front()).parent_path()).lexically_normal();
  throw InputError(
      fmt::format("{} of the study's {} record files are missing from the real records ({}{}), expected in {}",
                  missing.size(), s.files.size(), fs::path(missing.front()).filename().string(),
                  missing.size() > 1 ? ", ..." : "", dir.string()),
      s.path + " [records] files",
      fmt::format("put the real records (the folder records/real with MANIFEST.tsv that ../shared/records/README.md "
                  "describes; the project does not redistribute them) at {}, i.e. ../shared/records/real beside the "
                  "clone, or change the paths in [records] files to where they are",
                  dir.string()));
}

// [records] supports = N: the directory's files grouped per realisation -- stem PREFIX_sJJ is support JJ of
// realisation PREFIX (pounding motions' rRRR_sJJ.AT2) -- each group exactly supports 1..N (checked here, before
// any file is read; their dt and length when the group is read).
std::map<std::string, std::vector<std::string>> support_sets(const Study& s) {
  std::map<std::string, std::map<int, std::string>> sets;
  const std::string where = s.supports_where;
  for (const auto& p : record_files_in(s.directory, "[records] directory in " + s.path)) {
    const std::string stem = fs::path(p).stem().string();
    const std::size_t at = stem.rfind("_s");
    const std::string digits = at == std::string::npos ? std::string() : stem.substr(at + 2);
    if (digits.empty() || digits.size() > 3 || !std::all_of(digits.begin(), digits.end(), ::isdigit))
      throw InputError(fmt::format("the record file {} is not named PREFIX_sJJ (support JJ of realisation PREFIX)", p),
                       where, "keep only pounding motions' rRRR_sJJ files in the directory, or delete supports");
    const int j = std::stoi(digits);
    if (j < 1 || j > s.supports)
      throw InputError(fmt::format("{} is support {}, outside 1..{}", p, j, s.supports), where,
                       fmt::format("give supports = {} or remove the file", std::max(j, s.supports)));
    sets[stem.substr(0, at)][j] = p;
  }
  std::map<std::string, std::vector<std::string>> out;
  for (const auto& [prefix, files] : sets) {
    if (files.size() != static_cast<std::size_t>(s.supports))
      throw InputError(fmt::format("realisation {} in {} has {} of the {} support files", prefix, s.directory,
                                   files.size(), s.supports),
                       where, fmt::format("give every realisation the files {}_s01 .. {}_s{:02d}", prefix, prefix, s.supports));
    for (const auto& [j, p] : files) out[prefix].push_back(p);  // support order
  }
  return out;
}

}  // namespace

std::vector<std::string> study_input_files(const Study& s) {
  std::vector<std::string> out{s.path};
  for (const auto& f : s.files) out.push_back(f.path);
  auto folder = [&](const std::string& dir) {
    if (dir.empty()) return;
    try {
      for (auto& p : record_files_in(dir, "")) out.push_back(std::move(p));
    } catch (const InputError&) {  // missing or empty: the records phase says so
    }
    std::error_code ec;
    if (const fs::path m = fs::path(dir) / "MANIFEST.tsv"; fs::exists(m, ec)) out.push_back(m.string());
  };
  folder(s.directory);
  folder(s.real_dir);
  if (!s.suite.empty() && s.suite != "builtin") {
    out.push_back(s.suite);
    try {
      for (const SuiteEntry& e : load_suite(s.suite).entries) out.push_back(e.file);
    } catch (const InputError&) {  // the records phase says why
    }
  }
  out.push_back(s.hazard.curve);
  if (s.target.enabled && s.target.spec.code == TargetCode::csv) out.push_back(s.target.spec.table.source);
  if (s.motions)  // spectrum = "csv": the table each support's target was read from
    for (const DesignSpectrum& t : s.motions->settings.targets)
      if (const auto* table = std::get_if<TabulatedSpectrum>(&t.params())) out.push_back(table->source);
  return out;
}

RecordPlan plan_study_records(const Study& s) {
  if (s.motions) return plan_motion_records(s);
  if (s.files.empty() && s.directory.empty()) return plan_suite_records(s);
  // one analysis input: a file, or the files of a realisation's supports (support 1 first)
  struct Source {
    std::vector<std::string> paths;
    std::string scale_setting, id, note;
    double scale = 1.0;
  };
  std::vector<Source> sources;
  require_real_records(s);
  if (!s.files.empty()) {
    for (const auto& f : s.files)
      sources.push_back({{f.path},
                         f.scale != 1.0 ? fmt::format("the [records] files entry's scale ({}) x [records] scale ({}) "
                                                      "in {}", f.scale, s.scale, s.path)
                                        : "[records] scale in " + s.path,
                         "", "", f.scale * s.scale});
  } else if (s.supports > 0) {
    for (auto& [prefix, paths] : support_sets(s))
      sources.push_back({std::move(paths), "[records] scale in " + s.path, prefix,
                         fmt::format("{} supports of {} ({}_s01 .. _s{:02d}) x {}", s.supports, s.directory, prefix,
                                     s.supports, s.scale),
                         s.scale});
  } else {
    // the one directory reader (motion/library.hpp), the files `records select --directory` reads
    for (const auto& p : record_files_in(s.directory, "[records] directory in " + s.path))
      sources.push_back({{p}, "[records] scale in " + s.path, "", "", s.scale});
  }
  // the MANIFEST.tsv rows read so far, shared by the makers (the rows do not depend on who read them first)
  struct Manifests {
    std::mutex lock;
    RecordManifests rows;
  };
  auto manifests = std::make_shared<Manifests>();
  auto shared = std::make_shared<const std::vector<Source>>(std::move(sources));
  ReadOptions ro;
  ro.units = s.units;
  ro.dt = s.dt_one_column;
  auto make = [shared, manifests, ro, study_path = s.path, where = s.supports_where](std::size_t i) {
    const Source& src = (*shared)[i];
    auto read = [&](const std::string& path) {
      StudyRecord r;
      r.record = read_record(path, ro);
      {
        const std::lock_guard<std::mutex> hold(manifests->lock);
        manifests->rows.annotate(r.record);
      }
      for (double& a : r.record.acc) a *= src.scale;
      // a PGA of 499 g (a file in cm/s^2 read as g, or scale = 1000) would make every analysis diverge
      require_analysable(r.record, {src.scale, src.scale_setting, "set [records] units = \"cm/s2\" in " + study_path});
      r.id = fs::path(path).stem().string();
      r.note = fmt::format("file {} x {}", path, src.scale);
      return r;
    };
    StudyRecord r = read(src.paths[0]);
    if (src.paths.size() == 1) return r;
    r.id = src.id, r.note = src.note;
    for (std::size_t j = 1; j < src.paths.size(); ++j) {
      StudyRecord one = read(src.paths[j]);
      if (one.record.dt != r.record.dt || one.record.acc.size() != r.record.acc.size())
        throw InputError(fmt::format("{}: support {} has dt {} s and {} points, support 1 dt {} s and {} points", src.id,
                                     j + 1, one.record.dt, one.record.acc.size(), r.record.dt, r.record.acc.size()),
                         where, "give every support of a realisation the same time step and length (pounding motions does)");
      r.more_supports.push_back(std::move(one.record));
    }
    return r;
  };
  return {shared->size(), std::move(make), {}, {}};
}

namespace {

// What making record i gave: the record, or its error (local: the exception itself; from another rank: its parts).
struct Made {
  std::optional<StudyRecord> record;
  std::exception_ptr error;
  bool stopped = false;  // not made: a stop was raised first (RecordPlan::phase)
};

constexpr const char* records_phase = "making the records";

std::vector<std::size_t> share_of(std::size_t count, int rank, int ranks) {
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(rank); i < count; i += static_cast<std::size_t>(ranks)) mine.push_back(i);
  return mine;
}

// make(i) for every i of `which` on this process's threads; an error stays with its index.
// With a plan's phase and a hook: progress on a Meter, and no record started after a stop (marked stopped).
std::vector<Made> make_each(const RecordPlan& plan, const std::vector<std::size_t>& which, int threads,
                           const WorkHook* hook) {
  std::vector<Made> made(which.size());
  std::optional<Meter> meter;
  if (hook && !plan.phase.empty()) meter.emplace(hook, plan.phase, which.size(), plan.unit);
  parallel_blocks(which.size(), thread_count(threads, which.size()), [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      if (meter && meter->stopped()) {
        made[k].stopped = true;
        continue;
      }
      try {
        made[k].record.emplace(plan.make(which[k]));
      } catch (...) {
        made[k].error = std::current_exception();
      }
      if (meter) meter->step();
    }
  });
  if (meter) try {
      meter->finish();  // the final progress line
    } catch (const Cancelled&) {
      // a stop after the last record: every record of the share was made
    }
  return made;
}

// ---- bytes of a share (native byte order: the ranks of one job share one build)
void put_raw(std::string& b, const void* p, std::size_t n) { b.append(static_cast<const char*>(p), n); }
void put_u64(std::string& b, std::uint64_t v) { put_raw(b, &v, sizeof v); }
void put_str(std::string& b, const std::string& s) { put_u64(b, s.size()), b.append(s); }

struct Reader {
  const std::string& b;
  std::size_t at = 0;
  void raw(void* p, std::size_t n) {
    if (n > b.size() - at) throw std::runtime_error("record share: truncated bytes");
    std::memcpy(p, b.data() + at, n), at += n;
  }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    raw(&v, sizeof v);
    return v;
  }
  std::string str() {
    const std::uint64_t n = u64();
    if (n > b.size() - at) throw std::runtime_error("record share: truncated bytes");
    std::string s = b.substr(at, n);
    at += n;
    return s;
  }
};

void put_motion(std::string& b, const Record& m) {
  put_str(b, m.name), put_str(b, m.source);
  put_raw(b, &m.dt, sizeof m.dt);
  put_u64(b, m.acc.size()), put_raw(b, m.acc.data(), m.acc.size() * sizeof(double));
  put_u64(b, m.meta.size());
  for (const auto& [k, v] : m.meta) put_str(b, k), put_str(b, v);
  put_u64(b, static_cast<std::uint64_t>(static_cast<std::int64_t>(m.peak_line)));
}

void put_record(std::string& b, const StudyRecord& r) {
  put_motion(b, r.record);
  put_u64(b, r.more_supports.size());
  for (const Record& m : r.more_supports) put_motion(b, m);
  put_u64(b, r.synthetic ? 1 : 0), put_str(b, r.id), put_str(b, r.note);
  put_u64(b, static_cast<std::uint64_t>(static_cast<std::int64_t>(r.polarity)));
}

Record get_motion(Reader& in) {
  Record m;
  m.name = in.str(), m.source = in.str();
  in.raw(&m.dt, sizeof m.dt);
  const std::uint64_t n = in.u64();
  if (n > (in.b.size() - in.at) / sizeof(double)) throw std::runtime_error("record share: truncated bytes");
  m.acc.resize(n);
  in.raw(m.acc.data(), m.acc.size() * sizeof(double));
  for (std::uint64_t k = in.u64(); k > 0; --k) {
    std::string key = in.str();
    m.meta[key] = in.str();
  }
  m.peak_line = static_cast<int>(static_cast<std::int64_t>(in.u64()));
  return m;
}

StudyRecord get_record(Reader& in) {
  StudyRecord r;
  r.record = get_motion(in);
  for (std::uint64_t n = in.u64(); n > 0; --n) r.more_supports.push_back(get_motion(in));
  r.synthetic = in.u64() != 0;
  r.id = in.str(), r.note = in.str();
  r.polarity = static_cast<int>(static_cast<std::int64_t>(in.u64()));
  return r;
}

// an error as bytes: kind 1 InputError (what, where, fix), kind 2 anything else (its message); kind 3 (no bytes
// after it, make_record_share): not made, stopped
void put_error(std::string& b, const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const InputError& x) {
    put_u64(b, 1), put_str(b, x.what_part()), put_str(b, x.where()), put_str(b, x.fix());
  } catch (const std::exception& x) {
    put_u64(b, 2), put_str(b, x.what());
  } catch (...) {
    put_u64(b, 2), put_str(b, "unknown error while reading or synthesising a record");
  }
}

std::exception_ptr get_error(Reader& in, std::uint64_t kind) {
  if (kind == 1) {
    std::string what = in.str(), where = in.str(), fix = in.str();
    return std::make_exception_ptr(InputError(std::move(what), std::move(where), std::move(fix)));
  }
  return std::make_exception_ptr(std::runtime_error(in.str()));
}

// The records in order, or the error of the first record that failed (the same on every rank).
std::vector<StudyRecord> in_order(std::vector<Made> made) {
  std::vector<StudyRecord> out;
  out.reserve(made.size());
  for (Made& m : made) {
    if (m.stopped) throw Cancelled(records_phase);
    if (m.error) std::rethrow_exception(m.error);
    out.push_back(std::move(*m.record));
  }
  return out;
}

}  // namespace

std::vector<StudyRecord> make_records(const RecordPlan& plan, int threads, const WorkHook* hook) {
  return in_order(make_each(plan, share_of(plan.count, 0, 1), threads, hook));
}

std::string make_record_share(const RecordPlan& plan, int rank, int ranks, int threads, const WorkHook* hook) {
  const std::vector<std::size_t> mine = share_of(plan.count, rank, ranks);
  const std::vector<Made> made = make_each(plan, mine, threads, hook);
  std::string b;
  put_u64(b, made.size());
  for (std::size_t k = 0; k < made.size(); ++k) {
    put_u64(b, mine[k]);
    if (made[k].stopped) {
      put_u64(b, 3);
    } else if (made[k].error) {
      put_error(b, made[k].error);
    } else {
      put_u64(b, 0), put_record(b, *made[k].record);
    }
  }
  return b;
}

std::vector<StudyRecord> join_record_shares(const std::vector<std::string>& shares, std::size_t count) {
  std::vector<Made> made(count);
  std::vector<bool> seen(count, false);
  for (const std::string& s : shares) {
    Reader in{s};
    for (std::uint64_t n = in.u64(); n > 0; --n) {
      const std::uint64_t i = in.u64();
      if (i >= count || seen[i]) throw std::runtime_error("record share: a record index out of place");
      seen[i] = true;
      const std::uint64_t kind = in.u64();
      if (kind == 0) {
        made[i].record.emplace(get_record(in));
      } else if (kind == 3) {
        made[i].stopped = true;
      } else {
        made[i].error = get_error(in, kind);
      }
    }
  }
  if (std::find(seen.begin(), seen.end(), false) != seen.end())
    throw std::runtime_error("record share: a record no rank made");
  return in_order(std::move(made));
}

std::vector<StudyRecord> load_study_records(const Study& s, StudySelection* selection) {
  return finish_study_records(s, make_records(plan_study_records(s)), selection);
}

std::vector<StudyRecord> finish_study_records(const Study& s, std::vector<StudyRecord> out, StudySelection* selection) {
  if (s.select > 0) {
    StudySelection local;
    out = select_study_records(s, std::move(out), selection ? *selection : local);
  }
  if (s.record_limit > 0 && out.size() > static_cast<std::size_t>(s.record_limit)) out.resize(static_cast<std::size_t>(s.record_limit));
  check_result_memory(s, out.size());  // parse_study could only count a lower bound of the records
  if (s.polarity == Polarity::both) {
    // Every record, then its sign reversed: two analyses of one record (rows 2r, 2r + 1). Negation is exact, so
    // the reversed record's intensity (Sa, PGA) is the recorded one's bit for bit, and so are its stripes' factors.
    std::vector<StudyRecord> both;
    both.reserve(2 * out.size());
    for (auto& rr : out) {
      StudyRecord rev = rr;
      for (double& a : rev.record.acc) a = -a;
      for (Record& m : rev.more_supports)
        for (double& a : m.acc) a = -a;
      rev.polarity = -1;
      rev.note += rev.note.empty() ? "sign reversed ([records] polarity = \"both\")"
                                   : "; sign reversed ([records] polarity = \"both\")";
      both.push_back(std::move(rr));
      both.push_back(std::move(rev));
    }
    out = std::move(both);
  }
  return out;
}

}  // namespace pounding
