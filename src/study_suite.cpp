// Suite resolution for studies: wired to the ground-motion module's suite API.
#include "pounding/error.hpp"
#include "pounding/study.hpp"

namespace pounding {

std::vector<StudyRecord> load_suite_records(const Study& s) {
  throw InputError("suite files are not supported yet", s.suite, "list record files in [records] files");
}

}  // namespace pounding
