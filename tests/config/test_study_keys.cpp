// The study-file key registry (src/config/study_keys.cpp, issue 23 item 10) against the parsers: every key a
// parser reads is described (TableReader refuses an undescribed one, and every shipped study parses), a value
// just outside each documented numeric range is refused naming that key, the documented defaults are the
// parsed ones, and the documented choices are the enum tables' names. docs.study_reference checks the
// committed docs/study-reference.md against the generator.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/physics/steppers/registry.hpp"
#include "pounding/study/settings.hpp"
#include "pounding/study/study.hpp"

#include "test_data.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

template <class Names>
std::string choices(const Names& names, std::string_view skip = "") {
  std::string out;
  for (const auto& n : names) {
    std::string_view name;
    if constexpr (std::is_convertible_v<decltype(n), std::string_view>) name = n;
    else name = n.name;
    if (name == skip) continue;
    out += fmt::format("{}\"{}\"", out.empty() ? "" : " | ", name);
  }
  return out;
}

// A study of sections, each a map key -> TOML literal; tables render in a fixed order.
using Section = std::map<std::string, std::string>;
struct StudyText {
  std::map<std::string, Section> sections{{"", {{"seed", "1"}}}, {"records", {{"suite", "\"builtin\""}}}};
  std::string text() const {
    std::string out;
    for (const auto& [k, v] : sections.at("")) out += fmt::format("{} = {}\n", k, v);
    for (const auto& [name, keys] : sections) {
      if (name.empty()) continue;
      out += fmt::format("[{}]\n", name);
      for (const auto& [k, v] : keys) out += fmt::format("{} = {}\n", k, v);
    }
    return out;
  }
};

StudyText with_intensity(bool sa_avg = false) {
  StudyText s;
  s.sections["intensity"] = sa_avg ? Section{{"measure", "\"Sa_avg\""}, {"periods", "[0.5, 1.0]"}, {"levels", "[0.1, 0.2]"}}
                                   : Section{{"measure", "\"Sa\""}, {"period", "1.0"}, {"levels", "[0.1, 0.2]"}};
  return s;
}

StudyText with_target(bool ec8 = false) {
  StudyText s;
  s.sections["records"]["select"] = "11";
  s.sections["target_spectrum"] = ec8 ? Section{{"code", "\"EC8\""}, {"ground", "\"B\""}, {"agr", "0.25"}}
                                      : Section{{"code", "\"ASCE 7-16\""}, {"sds", "1.0"}, {"sd1", "0.6"}};
  return s;
}

// A valid two-frame bridge study in which `key` of the bridge section `section` is read, with `value`.
std::string bridge_study_with(const std::string& section, const std::string& key, const std::string& value) {
  auto line = [&](const std::string& sec, const std::string& k, const std::string& v) {
    return section == sec && key == k ? std::string() : fmt::format("{} = {}\n", k, v);
  };
  auto inline_table = [&](const std::string& sec, Section t) {
    if (section == sec) t[key] = value;
    std::string out;
    for (const auto& [tk, tv] : t) out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", tk, tv);
    return "{" + out + "}";
  };
  std::string out = "seed = 1\n[records]\nsuite = \"builtin\"\n[bridge]\n";
  if (section == "bridge") out += fmt::format("{} = {}\n", key, value);
  out += "[[bridge.frame]]\n" + line("bridge.frame", "mass", "1e6");
  out += section == "bridge.frame" && key == "stiffness" ? "" : line("bridge.frame", "period", "0.5");
  if (section == "bridge.frame") out += fmt::format("{} = {}\n", key, value);
  if (section == "bridge.frame" && (key == "hysteresis" || key == "beta")) out += "yield_force = 1e6\n";
  out += "[[bridge.frame]]\nmass = 2e6\nperiod = 1.0\n";
  out += "[[bridge.joint]]\n" + line("bridge.joint", "gap", "0.05") + line("bridge.joint", "contact_stiffness", "1e9");
  if (section == "bridge.joint") out += fmt::format("{} = {}\n", key, value);
  if (section == "bridge.restrainer")
    out += "restrainer = " + inline_table(section, {{"stiffness", "1e7"}, {"slack", "0.05"}}) + "\n";
  if (section == "bridge.bearing") out += "bearing = " + inline_table(section, {{"stiffness", "1e6"}}) + "\n";
  if (section == "bridge.abutment") {
    const bool hyper = key == "k_max" || key == "k_ur" || key == "rf" || key == "f_ult";
    const bool wall = key == "width" || key == "height";
    Section a = hyper ? Section{{"backfill", "\"hyperbolic\""}, {"k_max", "1e8"}, {"f_ult", "1e6"}}
                : wall ? Section{{"backfill", "\"epp\""}, {"width", "10.0"}, {"height", "1.5"}}
                       : Section{{"backfill", "\"epp\""}, {"stiffness", "1e8"}, {"capacity", "1e6"}};
    a[key] = value;
    out += "[bridge.abutment.left]\n";
    for (const auto& [ak, av] : a) out += fmt::format("{} = {}\n", ak, av);
  }
  return out;
}

// A valid study in which `key` of `section` is read, with `value` (a TOML literal) for it.
std::string study_with(const config::StudyKey& k, const std::string& value) {
  const std::string key(k.key), section(k.section);
  if (section.substr(0, 6) == "bridge") return bridge_study_with(section, key, value);
  StudyText s;
  if (section == "records.files") {
    s.sections["records"] = {{"files", fmt::format("[{{path = \"a.AT2\", {} = {}}}]", key, value)}};
    return s.text();
  }
  if (section == "records.motions") {  // generated support motions: sobczyk needs loss (or beta), nzs1170.5 soil
    s.sections["records"] = {};
    Section m{{"loss", "\"high\""}, {"soil", "\"D\""}};
    if (key == "beta" || key == "luco_wong_a") m.erase("loss");
    if (key == "luco_wong_a") m["coherency"] = "\"luco-wong\"";
    if (key.rfind("hv_", 0) == 0) m.erase("loss"), m["coherency"] = "\"harichandran-vanmarcke\"";
    if (key == "site_frequency") m["site_damping"] = "[0.5]";
    if (key == "site_damping") m["site_frequency"] = "[2.0]";
    m[key] = value;
    s.sections["records.motions"] = m;
    return s.text();
  }
  if (section == "isolation" || section == "moat") {  // inline tables of a shear building
    const auto inline_table = [](const Section& t) {
      std::string out;
      for (const auto& [tk, tv] : t) out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", tk, tv);
      return "{" + out + "}";
    };
    s.sections["structures"]["model"] = "\"shear\"";
    const bool iso_key = section == "isolation";
    const bool lrb = iso_key && (key == "k1" || key == "k2" || key == "qd");
    const bool fps = iso_key && (key == "radius" || key == "mu_slow" || key == "mu_fast" || key == "rate" || key == "u_y");
    const bool bw = iso_key && (key == "a" || key == "beta" || key == "gamma" || key == "eta");
    Section iso = lrb  ? Section{{"bearing", "\"lead-rubber\""}, {"k1", "1e8"}, {"k2", "1e7"}, {"qd", "1e5"}}
                  : fps ? Section{{"bearing", "\"friction-pendulum\""}, {"radius", "2.0"}, {"mu_slow", "0.05"}}
                  : bw  ? Section{{"bearing", "\"bouc-wen\""}, {"k1", "1e8"}, {"k2", "1e7"}, {"qd", "1e5"}}
                        : Section{{"bearing", "\"linear\""}, {"k_eff", "1e6"}};
    if (section == "isolation") iso[key] = value;
    s.sections["structures.building1"]["isolation"] = inline_table(iso);
    if (section == "moat") {
      Section m{{"gap", "0.1"}};
      m[key] = value;
      s.sections["structures.building1"]["moat"] = inline_table(m);
    }
    return s.text();
  }
  if (section == "intensity") {
    s = with_intensity(key == "periods");
    if (key == "tolerance") s.sections["intensity"]["method"] = "\"ida\"";
  } else if (section == "intensity.periods") {
    s = with_intensity(true);
    Section p{{"min", "0.2"}, {"max", "2.0"}, {"count", "5"}};
    p[key] = value;
    std::string inline_table;
    for (const auto& [pk, pv] : p) inline_table += fmt::format("{}{} = {}", inline_table.empty() ? "" : ", ", pk, pv);
    s.sections["intensity"]["periods"] = "{" + inline_table + "}";
    return s.text();
  } else if (section == "hazard") {
    s = with_intensity();
    s.sections["hazard"] = {{"k0", "1e-4"}, {"k", "2.0"}};
  } else if (section == "target_spectrum") {
    s = with_target(key == "agr" || key == "importance" || key == "type");
  } else if (section == "records" && (key == "max_per_event" || key == "components")) {
    s = with_target();  // rules of a selection
  }
  const std::string table = section == "structures.buildingN" ? "structures.building1" : section;
  s.sections[table][key] = value;
  return s.text();
}

bool numeric(const config::StudyKey& k) {
  return k.type == "number" || k.type == "integer" || k.type == "array of numbers" ||
         k.type == "number or distribution" || k.type == "number or \"pair\"" ||
         k.type == "array of numbers or {min, max, count}";
}

std::string literal(const config::StudyKey& k, double v) {
  const std::string x = k.type == "integer" ? fmt::format("{:.0f}", v) : fmt::format("{:.17g}", v);
  return k.type.substr(0, 5) == "array" ? "[" + x + "]" : x;
}

}  // namespace

TEST(StudyKeys, ReadingAnUndescribedKeyIsAProgrammingError) {
  const toml::table root = config::parse("[records]\nsuite = \"builtin\"\n", "s.toml", "fix it");
  config::TableReader r(root.get_as<toml::table>("records"), "s.toml", "records");
  EXPECT_NO_THROW(r.get("suite"));
  EXPECT_THROW(r.get("no_such_key"), std::logic_error);
  config::TableReader b(nullptr, "s.toml", "structures.building2");  // maps to the shared building section
  EXPECT_NO_THROW(b.get("yield_coefficient"));
  EXPECT_THROW(b.get("code_gap_coefficient"), std::logic_error);  // a [structures]-only key
}

TEST(StudyKeys, EveryKeyIsDescribedOnceWithASectionThatExists) {
  std::map<std::pair<std::string, std::string>, int> seen;
  for (const config::StudyKey& k : config::study_keys()) {
    const std::pair<std::string, std::string> id{std::string(k.section), std::string(k.key)};
    EXPECT_EQ(++seen[id], 1) << k.section << "." << k.key;
    bool section = false;
    for (const config::StudySection& s : config::study_sections()) section |= s.name == k.section;
    EXPECT_TRUE(section) << k.section << "." << k.key;
    EXPECT_FALSE(k.type.empty()) << k.key;
    EXPECT_FALSE(k.meaning.empty()) << k.key;
  }
}

// Every shipped and test study parses: the parsers read no key the registry does not describe on their paths.
TEST(StudyKeys, EveryShippedStudyParses) {
  int n = 0;
  for (const std::string& dir : {testdata::source_dir() + "/studies", testdata::data_dir()})
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".toml") continue;
      // a base that tests complete with their own [records] (tests/data/study-select-pair.toml) gets the builtin suite
      std::string text = files::read_text(e.path().string(), "a study");
      if (text.find("\n[inventory]") != std::string::npos) continue;  // a template of `pounding inventory run`
      if (text.find("\n[records]") == std::string::npos) text += "\n[records]\nsuite = \"builtin\"\n";
      try {
        parse_study(text, e.path().string());
        ++n;
      } catch (const InputError& err) {
        ADD_FAILURE() << e.path() << ": " << err.what();
      } catch (const std::logic_error& err) {
        ADD_FAILURE() << e.path() << ": " << err.what();
      }
    }
  EXPECT_GE(n, 10);
}

// The documented range is the checked one: a value just outside [lo, hi] is refused, naming the key.
TEST(StudyKeys, AValueJustOutsideTheDocumentedRangeIsRefused) {
  int checked = 0;
  for (const config::StudyKey& k : config::study_keys()) {
    if (!numeric(k) || std::isnan(k.lo) || k.section.substr(0, 12) == "distribution") continue;
    const bool integer = k.type == "integer";
    for (const double v : {integer ? k.lo - 1 : k.lo - std::max(std::abs(k.lo) * 1e-3, 1e-3),
                           integer ? k.hi + 1 : k.hi + std::max(std::abs(k.hi) * 1e-3, 1e-3)}) {
      if (!std::isfinite(v)) continue;
      const std::string text = study_with(k, literal(k, v));
      try {
        parse_study(text, "s.toml");
        ADD_FAILURE() << "[" << k.section << "]." << k.key << " = " << literal(k, v) << " was accepted; documented "
                      << k.range << "\n" << text;
      } catch (const InputError& e) {
        EXPECT_NE(e.where().find(std::string(k.key)), std::string::npos)
            << "[" << k.section << "]." << k.key << " = " << literal(k, v) << ": " << e.what();
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 100);
}

// The documented default (where it is a TOML value) is what a study without the key gets.
TEST(StudyKeys, DocumentedDefaultsAreTheParsedOnes) {
  int compared = 0;
  for (const StudyText& st : {StudyText{}, with_intensity(), with_target()}) {
    StudyText s = st;
    if (s.sections.count("intensity")) s.sections["hazard"] = {{"k0", "1e-4"}, {"k", "2.0"}};
    const Study study = parse_study(s.text(), "s.toml");
    visit_settings(study, [&](const std::string& section, const std::string& key, const auto& value) {
      const config::StudyKey* k = config::find_study_key(section, key);
      if (!k || s.sections[section].count(key)) return;  // not a study key (resolved settings), or given
      toml::table parsed;
      try {
        parsed = toml::parse("x = " + std::string(k->def));
      } catch (const toml::parse_error&) {
        return;  // a sentence ("required", "the period-height rule")
      }
      const toml::node& d = *parsed.get("x");
      using V = std::decay_t<decltype(value)>;
      const std::string what = fmt::format("[{}].{} default {}", section, key, k->def);
      if constexpr (std::is_same_v<V, double> || std::is_same_v<V, std::int64_t>) {
        ASSERT_TRUE(d.is_number()) << what;
        EXPECT_DOUBLE_EQ(static_cast<double>(value), d.value<double>().value()) << what;
      } else if constexpr (std::is_same_v<V, bool>) {
        ASSERT_TRUE(d.is_boolean()) << what;
        EXPECT_EQ(value, d.value<bool>().value()) << what;
      } else if constexpr (std::is_same_v<V, std::string>) {
        ASSERT_TRUE(d.is_string()) << what;
        EXPECT_EQ(value, d.value<std::string>().value()) << what;
      } else if constexpr (std::is_same_v<V, std::vector<double>>) {
        ASSERT_TRUE(d.is_array()) << what;
        std::vector<double> doc;
        for (const auto& e : *d.as_array()) doc.push_back(e.value<double>().value());
        EXPECT_EQ(value, doc) << what;
      } else {
        return;
      }
      ++compared;
    });
  }
  EXPECT_GE(compared, 50);
}

// Choices are listed as the parsers' own name tables give them.
TEST(StudyKeys, DocumentedChoicesAreTheEnumTables) {
  const std::map<std::pair<std::string, std::string>, std::string> tables{
      {{"", "scene"}, choices(scene_names)},
      {{"records", "units"}, choices(acc_units_names)},
      {{"records", "polarity"}, choices(polarity_names)},
      {{"structures", "hysteresis"}, choices(hysteresis_names)},
      {{"structures.buildingN", "hysteresis"}, choices(hysteresis_names)},
      {{"structures", "model"}, choices(structure_kind_names)},
      {{"structures.buildingN", "model"}, choices(structure_kind_names)},
      {{"structures", "stiffness_profile"}, choices(model::stiffness_profile_names)},
      {{"structures.buildingN", "stiffness_profile"}, choices(model::stiffness_profile_names)},
      {{"contact", "law"}, choices(contact_law_table, "none")},
      {{"contact", "damping_law"}, choices(damping_law_table)},
      {{"contact", "levels"}, choices(model::contact_levels_names)},
      {{"analysis", "stepper"}, choices(kernel::stepper_names)},
      {{"analysis", "coarse"}, choices(coarse_policy_names)},
      {{"intensity", "measure"}, choices(im_measure_names)},
      {{"intensity", "method"}, choices(fragility_method_names)},
      {{"target_spectrum", "code"}, choices(target_code_names)},
      {{"target_spectrum", "rule"}, choices(scaling_rule_names)},
      {{"records", "components"}, choices(component_rule_names)},
      {{"isolation", "bearing"}, choices(bearing_names)},
  };
  for (const auto& [sk, names] : tables) {
    const config::StudyKey* k = config::find_study_key(sk.first, sk.second);
    ASSERT_NE(k, nullptr) << sk.first << "." << sk.second;
    EXPECT_EQ(k->range, names) << "[" << sk.first << "]." << sk.second;
  }
}

// The typed default is the documented one where that is a value of the key's type, and what TableReader::number(key)
// and its siblings give for an absent key; a computed default ("required", "[structures] zeta") has none, and reading
// such a key without a default is a programming error.
TEST(StudyKeys, TypedDefaultsAreTheDocumentedValues) {
  int typed = 0;
  for (const config::StudyKey& k : config::study_keys()) {
    const config::KeyDefault d = config::typed_default(k);
    if (std::holds_alternative<std::monostate>(d)) continue;
    ++typed;
    config::TableReader r(nullptr, "s.toml", std::string(k.section), std::string(k.section));
    const std::string what = "[" + std::string(k.section) + "]." + std::string(k.key) + " = " + std::string(k.def);
    if (const double* x = std::get_if<double>(&d)) {
      EXPECT_EQ(k.type, "number") << what;
      if (!std::isnan(k.lo)) EXPECT_EQ(r.number(k.key), *x) << what;
    } else if (const long* i = std::get_if<long>(&d)) {
      EXPECT_EQ(k.type, "integer") << what;
      if (!std::isnan(k.lo)) EXPECT_EQ(r.integer(k.key), *i) << what;
    } else if (const bool* b = std::get_if<bool>(&d)) {
      EXPECT_EQ(r.boolean(k.key), *b) << what;
    } else if (const std::string* s = std::get_if<std::string>(&d)) {
      EXPECT_EQ(r.string(k.key), *s) << what;
    } else if (const auto* v = std::get_if<std::vector<double>>(&d)) {
      EXPECT_EQ(k.type, "array of numbers") << what;
      if (!std::isnan(k.lo)) EXPECT_EQ(r.numbers(k.key), *v) << what;
    }
  }
  EXPECT_GE(typed, 100);
  const config::KeyDefault e = config::typed_default(config::study_key("contact", "e"));
  ASSERT_TRUE(std::holds_alternative<double>(e));
  EXPECT_EQ(std::get<double>(e), 0.65);
  config::TableReader computed(nullptr, "s.toml", "structures.building1");
  EXPECT_THROW(computed.number("zeta"), std::logic_error);  // "[structures] zeta": the caller gives it
  EXPECT_THROW(computed.string("zeta"), std::logic_error);  // not a string either
}
