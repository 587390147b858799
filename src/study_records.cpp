// Resolving a study's [records] into scaled ground motions (real files or synthetic stand-ins).
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "pounding/error.hpp"
#include "pounding/study.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {
StudyRecord from_file(const std::string& path, double scale, const Study& s) {
  ReadOptions ro;
  ro.units = s.units;
  ro.dt = s.dt_one_column;
  StudyRecord r;
  r.record = read_record(path, ro);
  for (double& a : r.record.acc) a *= scale;
  r.id = fs::path(path).stem().string();
  r.note = fmt::format("file {} x {}", path, scale);
  return r;
}
}  // namespace

std::vector<StudyRecord> load_study_records(const Study& s) {
  std::vector<StudyRecord> out;
  if (!s.files.empty()) {
    for (const auto& f : s.files) out.push_back(from_file(f.path, f.scale * s.scale, s));
  } else if (!s.directory.empty()) {
    if (!fs::is_directory(s.directory))
      throw InputError("records directory not found", s.directory, "fix [records] directory");
    std::vector<std::string> paths;
    for (const auto& e : fs::directory_iterator(s.directory)) {
      auto ext = e.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
      if (e.is_regular_file() && (ext == ".at2" || ext == ".txt")) paths.push_back(e.path().string());
    }
    std::sort(paths.begin(), paths.end());
    if (paths.empty()) throw InputError("no .AT2 or .txt records in the directory", s.directory, "point [records] directory at PEER files");
    for (const auto& p : paths) out.push_back(from_file(p, s.scale, s));
  } else {
    out = load_suite_records(s);
  }
  if (s.record_limit > 0 && out.size() > static_cast<std::size_t>(s.record_limit)) out.resize(static_cast<std::size_t>(s.record_limit));
  return out;
}

}  // namespace pounding
