// Every study key reaches the results file's /settings by its store rule (issue 46, docs/runner-design.md section 6):
// parsing every study of studies/ and the fixtures tests/data/study_keys/*.toml (together they give every key),
// each (section, key) a study text gives is found among visit_settings' attributes under its name (always,
// unless_default) or its `as` attribute, or its rule is `none` with the reason. The report reads only the results
// file, so a key parsed but not stored is a key the report cannot state. (tests/cli/settings_keys.sh checks the same
// on the shipped studies' results files, by rules of its own; this test reads the rules from the key table.)
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/study/settings.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/study_fields.hpp"

#include "test_data.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

using Pair = std::pair<std::string, std::string>;  // (section as in the study text, key)
using Given = std::map<Pair, std::string>;          // -> the value's TOML text

// The tables whose keys are settings of their own section; any other table (isolation = {...}, a distribution,
// [[bridge.frame]], [intensity] periods = {...}) is a value of its parent key, stored through that key.
bool settings_section(const std::string& registry_section) {
  static const std::set<std::string, std::less<>> sections = {
      "",        "records",  "records.motions", "structures", "structures.buildingN", "gaps",
      "contact", "analysis", "report",          "outputs",    "intensity",            "hazard",
      "target_spectrum", "bridge"};
  return sections.count(registry_section) > 0;
}

// (section, key) of every leaf the study text gives, in the registry's terms through study_section_of.
void given_keys(const toml::table& t, const std::string& name, Given& out) {
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    const std::string child = name.empty() ? key : name + "." + key;
    if (v.is_table() && settings_section(config::study_section_of(child))) {
      given_keys(*v.as_table(), child, out);
      continue;
    }
    std::ostringstream text;
    v.visit([&](const auto& value) { text << value; });
    out.emplace(Pair{name, key}, text.str());
  }
}

// An unless_default key given at its default value need not be stored.
bool at_default(const config::StudyKey& k, const std::string& value) {
  config::StudyKey as_given = k;
  as_given.def = value;
  const config::KeyDefault d = config::typed_default(k);
  return !std::holds_alternative<std::monostate>(d) && config::typed_default(as_given) == d;
}

std::set<Pair> stored_keys(const Study& s) {
  std::set<Pair> out;
  visit_settings(s, [&](const std::string& section, const std::string& key, const auto&) { out.emplace(section, key); });
  return out;
}

struct Parsed {
  std::string path;
  Given given;
  std::set<Pair> stored;
};

// Every study of studies/ and tests/data/study_keys/ (a study without [records] gets the builtin suite; an inventory
// template, whose pairs' studies are made by `pounding inventory run`, is not a study).
std::vector<Parsed> parse_all() {
  std::vector<Parsed> out;
  for (const std::string dir : {testdata::source_dir() + "/studies", testdata::data_dir() + "/study_keys"})
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".toml") continue;
      std::string text = files::read_text(e.path().string(), "a study");
      if (toml::parse(text).contains("inventory")) continue;  // an inventory template (pounding inventory run)
      if (!toml::parse(text).contains("records")) text += "\n[records]\nsuite = \"builtin\"\n";
      Parsed p{e.path().string(), {}, {}};
      given_keys(toml::parse(text, p.path), "", p.given);
      try {
        p.stored = stored_keys(parse_study(text, p.path));
      } catch (const std::exception& err) {
        ADD_FAILURE() << p.path << ": " << err.what();
        continue;
      }
      out.push_back(std::move(p));
    }
  return out;
}

const config::StudyKey* key_of(const Pair& given) {
  return config::find_study_key(config::study_section_of(given.first), given.second);
}

// Where the key's rule says it is stored: "attr" in its own section, or "section/attr" ("structures.buildingN":
// every building's section).
bool reached(const Pair& given, const config::StudyKey& k, const std::set<Pair>& stored) {
  std::string section = given.first, attribute = given.second;
  if (k.store.rule == config::Store::as) {
    const std::string_view text = k.store.text;
    const auto slash = text.find('/');
    attribute = std::string(slash == text.npos ? text : text.substr(slash + 1));
    if (slash != text.npos) section = std::string(text.substr(0, slash));
  }
  if (section != "structures.buildingN") return stored.count({section, attribute}) > 0;
  int buildings = 0;
  for (const auto& [sec, key] : stored)
    if (key == attribute && config::study_section_of(sec) == "structures.buildingN") ++buildings;
  return buildings >= 2;
}

}  // namespace

template <class Obj, class T>
T member_type(T Obj::*);

// Each field of study_fields.hpp's lists binds a described key of its section, once, of the member's type, with a
// typed default (its reader takes it from the table).
TEST(SettingsKeys, FieldListsBindEachKeyOnce) {
  std::map<Pair, int> bound;
  const auto count = [&](const std::string& section, const auto& fields) {
    fields([&](const char* key, auto member) {
      const std::string what = "[" + section + "]." + key;
      ++bound[{section, key}];
      const config::StudyKey* k = config::find_study_key(section, key);
      ASSERT_NE(k, nullptr) << what;
      using T = std::decay_t<decltype(member_type(member))>;
      const std::string_view type = std::is_same_v<T, double>                ? "number"
                                    : std::is_same_v<T, int> || std::is_same_v<T, long> ? "integer"
                                    : std::is_same_v<T, bool>                ? "boolean"
                                    : std::is_same_v<T, std::string>         ? "string"
                                    : std::is_same_v<T, std::vector<double>> ? "array of numbers"
                                                                             : "?";
      EXPECT_EQ(k->type, type) << what;
      EXPECT_FALSE(std::holds_alternative<std::monostate>(config::typed_default(*k))) << what;
    });
  };
  count("records", study_fields::records);
  count("gaps", study_fields::gaps);
  count("contact", study_fields::contact);
  count("analysis", study_fields::analysis);
  count("report", study_fields::report);
  count("outputs", study_fields::outputs);
  count("hazard", study_fields::hazard);
  count("target_spectrum", study_fields::target_spectrum);
  for (const auto& [key, n] : bound) EXPECT_EQ(n, 1) << "[" << key.first << "]." << key.second << " listed " << n << " times";
  EXPECT_GE(bound.size(), 20u);
}

// Every rule is complete: `as` names its attribute, `none` its reason, `unless_default` has a typed default to
// compare with.
TEST(SettingsKeys, EveryKeyHasAStoreRule) {
  for (const config::StudyKey& k : config::study_keys()) {
    const std::string what = "[" + std::string(k.section) + "]." + std::string(k.key);
    switch (k.store.rule) {
      case config::Store::always: break;
      case config::Store::unless_default:
        EXPECT_FALSE(std::holds_alternative<std::monostate>(config::typed_default(k))) << what;
        break;
      case config::Store::as:
      case config::Store::none: EXPECT_FALSE(k.store.text.empty()) << what; break;
    }
    if (k.store.rule != config::Store::always)
      EXPECT_TRUE(settings_section(std::string(k.section))) << what << ": a value table's key is stored by its parent";
  }
}

// Each key a study gives reaches /settings by its rule, and the studies together give every stored key.
TEST(SettingsKeys, EveryGivenKeyReachesSettings) {
  const std::vector<Parsed> studies = parse_all();
  ASSERT_GE(studies.size(), 20u);
  std::set<Pair> given_anywhere;  // in the registry's sections
  for (const Parsed& p : studies)
    for (const auto& [g, value] : p.given) {
      const config::StudyKey* k = key_of(g);
      ASSERT_NE(k, nullptr) << p.path << ": [" << g.first << "]." << g.second << " is not described";
      given_anywhere.emplace(k->section, k->key);
      if (k->store.rule == config::Store::none) continue;
      if (k->store.rule == config::Store::unless_default && at_default(*k, value)) continue;
      EXPECT_TRUE(reached(g, *k, p.stored))
          << p.path << ": [" << g.first << "]." << g.second << " is given but not in /settings"
          << (k->store.rule == config::Store::as ? " as " + std::string(k->store.text) : std::string());
    }
  for (const config::StudyKey& k : config::study_keys()) {
    if (!settings_section(std::string(k.section)) || k.store.rule == config::Store::none || k.type == "table") continue;
    if (k.type.find("refused") != std::string_view::npos) continue;  // [report] h1, h2: a study never gives them
    EXPECT_TRUE(given_anywhere.count({std::string(k.section), std::string(k.key)}))
        << "[" << k.section << "]." << k.key << ": no study of studies/ or tests/data/study_keys/ gives it";
  }
}

// The check can fail: a stored key dropped from a parsed study's settings is reported.
TEST(SettingsKeys, ALostKeyIsFound) {
  const std::vector<Parsed> studies = parse_all();
  ASSERT_FALSE(studies.empty());
  const Parsed& p = studies.front();
  std::set<Pair> lost = p.stored;
  const Pair e{"contact", "e"};
  lost.erase(e);
  const config::StudyKey* k = key_of(e);
  ASSERT_NE(k, nullptr);
  EXPECT_TRUE(reached(e, *k, p.stored));
  EXPECT_FALSE(reached(e, *k, lost));
}
