// Configuration errors (C19): a wrong type, an unknown key, a missing or misplaced table and a bad enum name
// each give one InputError whose where() names file:line and [table].key (include/pounding/config/config.hpp),
// read directly through config::TableReader and through a whole study file (parse_study).
#include <gtest/gtest.h>

#include <string>

#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/study/study.hpp"

#include "input_error.hpp"

using namespace pounding;

namespace {


const std::string records = "seed = 1\n[records]\nsuite = \"builtin\"\n";  // lines 1-3 of every study below

InputError study_error(const std::string& text) { return testdata::input_error([&] { parse_study(text, "s.toml"); }); }

}  // namespace

TEST(ConfigErrors, WrongTypeNamesFileLineTableAndKey) {
  const toml::table root = config::parse("[contact]\nlaw = \"hertz\"\ne = \"high\"\n", "c.toml", "fix it");
  config::TableReader top(&root, "c.toml", "");
  config::TableReader c(top.table("contact"), "c.toml", "contact");
  const InputError e = testdata::input_error([&] { c.number("e", 0.65, 0.0, 1.0, "(0, 1]"); });
  EXPECT_EQ(e.what_part(), "e must be a number, not a string");
  EXPECT_EQ(e.where(), "c.toml:3 [contact].e");
  EXPECT_EQ(e.fix(), "write e = <number>");

  const InputError s = study_error(records + "[analysis]\nsubsteps = 2.5\n");
  EXPECT_EQ(s.what_part(), "substeps must be an integer, not a float");
  EXPECT_EQ(s.where(), "s.toml:5 [analysis].substeps");
}

TEST(ConfigErrors, UnknownKeyNamesFileLineTableAndKey) {
  const toml::table root = config::parse("[gaps]\nratios = [0.1]\nratio = 0.2\n", "g.toml", "fix it");
  config::TableReader g(root.get_as<toml::table>("gaps"), "g.toml", "gaps");
  g.numbers("ratios", {0.5}, 0.0, 1.0, "(0, 1]");
  const InputError e = testdata::input_error([&] { g.finish("ratios"); });
  EXPECT_EQ(e.what_part(), "unknown key 'ratio' in [gaps]");
  EXPECT_EQ(e.where(), "g.toml:3 [gaps].ratio");
  EXPECT_EQ(e.fix(), "check the spelling; [gaps] takes: ratios");

  // [structures] is read by the sampler's parser: its keys keep their lines too
  const InputError s = study_error(records + "[structures]\nsamples_per_pair = 2\nsample_per_pair = 3\n");
  EXPECT_EQ(s.where(), "s.toml:6 [structures].sample_per_pair");
  const InputError top = study_error(records + "outputs = 1\n");  // a top-level key after [records] is in it
  EXPECT_EQ(top.where(), "s.toml:4 [records].outputs");
}

TEST(ConfigErrors, MissingOrMisplacedTable) {
  // A table that must be there: the study names no records. There is no line to name, so where() is the
  // file and the table.
  const InputError none = study_error("seed = 1\n[contact]\nlaw = \"hertz\"\n");
  EXPECT_EQ(none.what_part(), "the study names no records");
  EXPECT_EQ(none.where(), "s.toml [records]");
  // An absent optional table takes its defaults; an error about one of its keys names file and [table].key.
  config::TableReader absent(nullptr, "a.toml", "report");
  EXPECT_EQ(absent.where("h1"), "a.toml [report].h1");
  // A key where a table belongs.
  const InputError flat = study_error("seed = 1\ngaps = 0.1\n" + records.substr(9));
  EXPECT_EQ(flat.what_part(), "gaps must be a table, not a float");
  EXPECT_EQ(flat.where(), "s.toml:2 gaps");
  EXPECT_EQ(flat.fix(), "write [gaps] on its own line");
}

TEST(ConfigErrors, BadEnumNameListsTheNamesAtFileLineTableAndKey) {
  const toml::table root = config::parse("[contact]\n\nlaw = \"hertzian\"\n", "l.toml", "fix it");
  config::TableReader c(root.get_as<toml::table>("contact"), "l.toml", "contact");
  const InputError e = testdata::input_error([&] { c.choice("law", "hertzdamp", parse_contact_law); });
  EXPECT_EQ(e.what_part(), "unknown contact law 'hertzian'");
  EXPECT_EQ(e.where(), "l.toml:3 [contact].law");
  EXPECT_EQ(e.fix(), "use one of: " + std::string(contact_law_names));

  const InputError units = study_error(records + "units = \"furlong\"\n");
  EXPECT_EQ(units.where(), "s.toml:4 [records].units");
  EXPECT_EQ(units.fix(), "use g, m/s2 or cm/s2");
  const InputError scene = study_error("scene = \"both\"\n" + records);
  EXPECT_EQ(scene.where(), "s.toml:1 scene");
  EXPECT_EQ(scene.fix(), "use \"probability\", \"impacts\" or \"auto\"");
  const InputError hyst = study_error(records + "[structures]\nhysteresis = \"plastic\"\n");
  EXPECT_EQ(hyst.where(), "s.toml:5 [structures].hysteresis");
  EXPECT_EQ(hyst.fix(), "write hysteresis = \"bilinear\" or \"elastic\"");
}

TEST(ConfigErrors, SyntaxErrorNamesFileAndLine) {
  const InputError e = testdata::input_error([] { config::parse("a = 1\nb = = 2\n", "x.toml", "fix the syntax"); });
  EXPECT_EQ(e.where(), "x.toml:2");
  EXPECT_EQ(e.fix(), "fix the syntax");
  EXPECT_NE(e.what_part().find("TOML syntax error"), std::string::npos);
}
