// Resolving a study's [records] into scaled ground motions (real files or synthetic stand-ins).
#include <algorithm>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {
// scale_setting: where the user set `scale` ("[records] scale", or a files entry's scale).
// manifests: the MANIFEST.tsv rows read so far (event, station, component for the selection's rules).
StudyRecord from_file(const std::string& path, double scale, const Study& s, const std::string& scale_setting,
                      RecordManifests& manifests) {
  ReadOptions ro;
  ro.units = s.units;
  ro.dt = s.dt_one_column;
  StudyRecord r;
  r.record = read_record(path, ro);
  manifests.annotate(r.record);
  for (double& a : r.record.acc) a *= scale;
  // a PGA of 499 g (a file in cm/s^2 read as g, or scale = 1000) would make every analysis diverge
  require_analysable(r.record, {scale, scale_setting, "set [records] units = \"cm/s2\" in " + s.path});
  r.id = fs::path(path).stem().string();
  r.note = fmt::format("file {} x {}", path, scale);
  return r;
}
// [records] supports = N: the directory's files grouped per realisation -- stem PREFIX_sJJ is support JJ of
// realisation PREFIX (pounding motions' rRRR_sJJ.AT2) -- each group exactly supports 1..N with one dt and length.
std::vector<StudyRecord> support_sets(const Study& s, RecordManifests& manifests) {
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
  std::vector<StudyRecord> out;
  for (const auto& [prefix, files] : sets) {
    if (files.size() != static_cast<std::size_t>(s.supports))
      throw InputError(fmt::format("realisation {} in {} has {} of the {} support files", prefix, s.directory,
                                   files.size(), s.supports),
                       where, fmt::format("give every realisation the files {}_s01 .. {}_s{:02d}", prefix, prefix, s.supports));
    StudyRecord r;
    for (const auto& [j, p] : files) {
      StudyRecord one = from_file(p, s.scale, s, "[records] scale in " + s.path, manifests);
      if (j == 1) {
        r = std::move(one);
        r.id = prefix;
        r.note = fmt::format("{} supports of {} ({}_s01 .. _s{:02d}) x {}", s.supports, s.directory, prefix, s.supports, s.scale);
        continue;
      }
      if (one.record.dt != r.record.dt || one.record.acc.size() != r.record.acc.size())
        throw InputError(fmt::format("{}: support {} has dt {} s and {} points, support 1 dt {} s and {} points", prefix,
                                     j, one.record.dt, one.record.acc.size(), r.record.dt, r.record.acc.size()),
                         where, "give every support of a realisation the same time step and length (pounding motions does)");
      r.more_supports.push_back(std::move(one.record));
    }
    out.push_back(std::move(r));
  }
  return out;
}
}  // namespace

std::vector<StudyRecord> load_study_records(const Study& s, StudySelection* selection) {
  std::vector<StudyRecord> out;
  RecordManifests manifests;
  if (!s.files.empty()) {
    for (const auto& f : s.files)
      out.push_back(from_file(f.path, f.scale * s.scale, s,
                              f.scale != 1.0 ? fmt::format("the [records] files entry's scale ({}) x [records] scale ({}) "
                                                           "in {}", f.scale, s.scale, s.path)
                                             : "[records] scale in " + s.path,
                              manifests));
  } else if (!s.directory.empty() && s.supports > 0) {
    out = support_sets(s, manifests);
  } else if (!s.directory.empty()) {
    // the one directory reader (motion/library.hpp), the files `records select --directory` reads
    for (const auto& p : record_files_in(s.directory, "[records] directory in " + s.path))
      out.push_back(from_file(p, s.scale, s, "[records] scale in " + s.path, manifests));
  } else {
    out = load_suite_records(s);
  }
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
