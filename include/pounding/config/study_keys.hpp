#pragma once
// Every key of the study file, described once (issue 23, item 10): its type, default, units, allowed values and
// meaning. docs/study-reference.md is generated from this list (`pounding study-reference`), and the parsers
// cannot drift from it:
//   - config::TableReader refuses to look up a key that is not listed here for its section (std::logic_error,
//     so every test that parses a study fails until the key is described);
//   - TableReader::number(key) / integer(key) / ... take the default (typed_default) and the allowed range from
//     here; number(key, def) / integer(key, def) / numbers(key, def), for a computed default, the range,
//     so the documented range is the checked one (keys checked elsewhere, e.g. [structures] in
//     validate_building, give lo/hi here and tests/config/test_study_keys.cpp checks that a value just outside
//     is refused);
//   - tests/config/test_study_keys.cpp checks defaults against a parsed study and enum lists against their
//     tables; ctest `docs.study_reference` compares the committed docs/study-reference.md with the output.
//
// A new key: one entry in src/config/study_keys.cpp, in its section, then
//   build/pounding study-reference -o docs/study-reference.md
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pounding::config {

inline constexpr double no_limit = std::numeric_limits<double>::quiet_NaN();

// How a key reaches the results file's /settings/<section> (visit_settings, study/settings.hpp), checked for every
// key a study gives by tests/study/test_settings_keys.cpp:
//   always          attribute <key>, whether given or defaulted;
//   unless_default  attribute <key> only where the value is not the default (older files' bits);
//   as              stored under another attribute, `text`: a resolved value ("periods" for period_min, a
//                   building's "yield" for yield_coefficient, a bridge's "description");
//   none            not stored, `text` says why (a section; how the work runs, not what it computes).
// A key of a value table (isolation = {...}, a distribution, [[bridge.frame]]) is stored through its parent key.
enum class Store : unsigned char { always, unless_default, as, none };
struct StoreRule {
  Store rule = Store::always;
  std::string_view text;  // as: the attribute; none: the reason
};
inline constexpr StoreRule unless_default{Store::unless_default, ""};
constexpr StoreRule stored_as(std::string_view attribute) { return {Store::as, attribute}; }
constexpr StoreRule not_stored(std::string_view reason) { return {Store::none, reason}; }

struct StudyKey {
  std::string_view section;  // "" (top level), "records", "structures.buildingN", "distribution.lognormal", ...
  std::string_view key;
  std::string_view type;     // "number", "integer", "string", "boolean", "array of numbers", "table", ...
  std::string_view def;      // the default as written in a study file, or a sentence ("required", "from ...")
  std::string_view units;    // "" for dimensionless
  std::string_view range;    // the allowed values, as shown in errors ("(0, 1000]", "\"g\" | \"m/s2\"")
  std::string_view meaning;
  double lo = no_limit, hi = no_limit;  // numeric keys: the closed bounds the parser checks (NaN: no numeric check)
  StoreRule store{};
};

// A key's typed default, read from `def` where that is a TOML value of the key's type ("1.0", "\"g\"", "true",
// "[10, 5, 1]"): the documented default and the parsed one are the same literal. std::monostate ("computed") where
// `def` is a sentence ("required", "[structures] zeta", "the study's seed"): the reader's caller gives it.
using KeyDefault = std::variant<std::monostate, double, long, bool, std::string, std::vector<double>>;
KeyDefault typed_default(const StudyKey& k);

struct StudySection {
  std::string_view name;     // as in StudyKey::section
  std::string_view heading;  // "[records]", "[structures.building1] and [structures.building2]"
  std::string_view text;     // what the section is for
};

std::span<const StudySection> study_sections();
std::span<const StudyKey> study_keys();

// The registry's section of a TableReader's table name: "structures.building1" -> "structures.buildingN",
// "structures.building2.height" -> "distribution", "...height.lognormal" -> "distribution.lognormal".
std::string study_section_of(std::string_view table_name);

// The key's description, or nullptr.
const StudyKey* find_study_key(std::string_view section, std::string_view key);
// The key's description; std::logic_error when it is not described (a programming error).
const StudyKey& study_key(std::string_view section, std::string_view key);

// THE range of a quantity for every front end (issue 44 item 11): an input that means the same as a study key --
// `pounding simulate`'s and `modes`' options, the Python module's arguments, a bridge file's defaults -- is checked
// against that key's lo, hi, so the command line, Python and a study accept the same storey masses, periods,
// stiffnesses. InputError "<name> = <value> is out of range" at `name` (not finite included), the fix
// "give a value in <range> <units> (<note>as <key> in a study's <section>)". std::logic_error when the key has no
// numeric range.
void require_key_range(double value, std::string_view section, std::string_view key, const std::string& name,
                       std::string_view note = "");
// "[structures.buildingK]", "isolation = {...}", "[analysis]": where a study sets a key of `section`, for messages.
std::string study_section_text(std::string_view section);

// docs/study-reference.md.
std::string study_reference_markdown();

}  // namespace pounding::config
