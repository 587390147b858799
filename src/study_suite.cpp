// Suite resolution for studies: the [records] suite entries become real records (when real_dir holds a
// match) or synthetic stand-ins (include/pounding/suite.hpp); study-level scale applied on top.
#include <filesystem>

#include "pounding/error.hpp"
#include "pounding/study.hpp"
#include "pounding/suite.hpp"

namespace pounding {

std::vector<StudyRecord> load_suite_records(const Study& s) {
  Suite suite = s.suite == "builtin" ? default_suite() : load_suite(s.suite);
  if (suite.entries.empty()) throw InputError("the suite lists no records", s.suite, "add [[record]] entries");
  ResolveOptions ro;
  if (!s.real_dir.empty()) {
    if (!std::filesystem::is_directory(s.real_dir))
      throw InputError("real_dir is not a directory", s.real_dir, "point [records] real_dir at a folder of PEER files");
    ro.records_dir = s.real_dir;
  }
  ro.synthetic_only = s.synthetic_only;
  std::vector<StudyRecord> out;
  for (ResolvedRecord& r : resolve_suite(suite, ro)) {
    StudyRecord sr;
    sr.record = std::move(r.record);
    for (double& a : sr.record.acc) a *= s.scale;
    sr.synthetic = r.synthetic;
    sr.id = r.id;
    sr.note = r.note;
    out.push_back(std::move(sr));
  }
  return out;
}

}  // namespace pounding
