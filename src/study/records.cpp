// Resolving a study's [records] into scaled ground motions (real files or synthetic stand-ins).
#include <algorithm>
#include <filesystem>

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
