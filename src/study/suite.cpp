// Suite resolution for studies: the [records] suite entries become real records (when real_dir holds a
// match) or synthetic stand-ins (include/pounding/motion/suite.hpp); study-level scale applied on top.
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/study/study.hpp"
#include "pounding/motion/suite.hpp"

namespace pounding {

RecordPlan plan_suite_records(const Study& s) {
  auto suite = std::make_shared<const Suite>(s.suite == "builtin" ? default_suite() : load_suite(s.suite));
  if (suite->entries.empty()) throw InputError("the suite lists no records", s.suite, "add [[record]] entries");
  ResolveOptions ro;
  if (!s.real_dir.empty()) {
    if (!std::filesystem::is_directory(s.real_dir))
      throw InputError("real_dir is not a directory", s.real_dir, "point [records] real_dir at a folder of PEER files");
    ro.records_dir = s.real_dir;
  }
  ro.synthetic_only = s.synthetic_only;
  // entry i alone: resolved (a file, a directory match or a synthetic stand-in), scaled, checked as an input
  auto make = [suite, ro, scale = s.scale, path = s.path](std::size_t i) {
    const SuiteEntry& e = suite->entries[i];
    ResolvedRecord r = resolve_entry(*suite, e, ro);
    StudyRecord sr;
    sr.record = std::move(r.record);
    for (double& a : sr.record.acc) a *= scale;
    // the suite entry's scale times the study's (a synthetic stand-in's fit to pga_g is not the user's scale)
    const std::string entry = fmt::format("record {} of {} (line {})", e.id, suite->path, e.line);
    AnalysisContext ctx;
    ctx.scale = e.scale * scale;
    ctx.scale_setting = e.scale != 1.0 ? fmt::format("scale of {} x [records] scale of {}", entry, path)
                                       : "[records] scale in " + path;
    ctx.units_setting = "set units = \"cm/s2\" in " + entry;
    require_analysable(sr.record, ctx);
    sr.synthetic = r.synthetic;
    sr.id = r.id;
    sr.note = r.note;
    return sr;
  };
  return {suite->entries.size(), std::move(make), {}, {}};
}

}  // namespace pounding
