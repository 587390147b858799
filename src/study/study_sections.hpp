// The readers of a study file's own sections (src/study/study_sections.cpp), called by parse_study in order.
#pragma once

#include <string>

#include <toml++/toml.h>

#include "pounding/study/study.hpp"

namespace pounding {

// Each reads its table (null: absent, every key at its default) of the study file `path` into `s`; InputError at
// file:line [section].key for a bad value. parse_report reads after parse_gaps (its fit range is on the gap axis).
void parse_records(Study& s, const toml::table* t, const std::string& path);
void parse_gaps(Study& s, const toml::table* t, const std::string& path);
void parse_contact(Study& s, const toml::table* t, const std::string& path);
void parse_analysis(Study& s, const toml::table* t, const std::string& path);
void parse_report(Study& s, const toml::table* t, const std::string& path);
void parse_outputs(Study& s, const toml::table* t, const std::string& path);

}  // namespace pounding
