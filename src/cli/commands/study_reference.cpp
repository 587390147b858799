// `pounding study-reference [-o FILE]`: the study-file reference (every key: type, default, units, allowed
// values, meaning), generated from src/config/study_keys.cpp -- the list the parsers check keys and ranges
// against. docs/study-reference.md is this output (ctest docs.study_reference).
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/core/files.hpp"

namespace pounding::cli {

void add_study_reference(CLI::App& app) {
  auto* cmd = app.add_subcommand("study-reference",
                                 "print the study-file reference (every key, its type, default, units, allowed values "
                                 "and meaning; docs/study-reference.md is this output)");
  auto out = std::make_shared<std::string>();
  cmd->add_option("-o,--output", *out, "write it to this file instead of standard output");
  cmd->callback([out] {
    const std::string text = config::study_reference_markdown();
    if (out->empty()) {
      std::fwrite(text.data(), 1, text.size(), stdout);
      return;
    }
    files::check_output_path(*out, "--output");
    files::write_text_atomically(*out, text);
  });
}

}  // namespace pounding::cli
