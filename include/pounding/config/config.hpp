#pragma once
// Typed reading of TOML configuration -- the study file, its [structures] table and records suite files: the
// one place that turns toml++ nodes into values, and a wrong type, a value out of range or an unknown key
// into an InputError naming file:line and the key. One wording per error:
//   "<key> must be a number, not a string"          fix "write <key> = <number>"   (likewise integer, string,
//   "<key> = 1.5 is out of range"                   fix "give a value in <range>"   boolean, array of numbers)
//   unknown keys: unknown_key_error (error.hpp)
//
// toml++ appears in this header for now, because sampler.hpp and the suite parser pass toml tables;
// architecture.md (P3, the `config` module of section 2.1) wants it private to this module later, behind a
// config-owned table type.
#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "pounding/core/error.hpp"

namespace pounding::config {

// "file:line" of a source region, or "file" where toml++ knows no line (a table built in code).
std::string location(const std::string& file, const toml::source_region& src);

// Parses TOML text. A syntax error throws InputError "TOML syntax error (column c): <description>" at
// file:line, with `fix` as the advice (e.g. "fix the study file's syntax").
toml::table parse(std::string_view text, const std::string& file, std::string_view fix);

// What a node holds, with its article, for messages: "a string", "an integer", "a float", "a boolean",
// "an array", "a table", "a date/time".
std::string_view type_name(const toml::node& n);

// One value of the wanted type; `where` is where an error points (file:line [table].key, or file:line).
double number(const toml::node& n, std::string_view key, const std::string& where);  // integer or float
std::int64_t integer(const toml::node& n, std::string_view key, const std::string& where);
std::uint64_t seed(const toml::node& n, std::string_view key, const std::string& where);  // integer >= 0
std::string string(const toml::node& n, std::string_view key, const std::string& where);
bool boolean(const toml::node& n, std::string_view key, const std::string& where);
std::vector<double> numbers(const toml::node& n, std::string_view key, const std::string& where);  // non-empty

// Throws unknown_key_error for the first key of `t` (in toml++'s order) that `known` rejects. `section`
// and `allowed` are as in unknown_key_error; `where` gives the location of a key.
void check_keys(const toml::table& t, const std::function<bool(std::string_view key)>& known,
                std::string_view section, std::string_view allowed,
                const std::function<std::string(std::string_view key, const toml::node& value)>& where);

// One table with a fixed set of keys. Every key is looked up through this reader, which remembers it;
// finish() then rejects any key of the table that was never asked for. Errors point at
// "file:line [name].key" (line of the key, or of the table when the key is absent; name empty: the top level).
class TableReader {
 public:
  // t may be null (the table is absent: every key takes its default). `name` is the table's dotted name in the
  // study file ("records", "structures.building1"; "" the top level); its keys must be described in
  // study_keys.cpp (study_section_of(name) maps it to the registry's section).
  TableReader(const toml::table* t, std::string file, std::string name);
  // The same with the registry's section given (a table whose name does not map to it: the tables of a bridge
  // file, "frame2", read with the keys of "bridge.frame").
  TableReader(const toml::table* t, std::string file, std::string name, std::string section);

  std::string where(std::string_view key) const;
  // The node of `key` (null when absent), marking the key as known. std::logic_error when study_keys.cpp does
  // not describe the key (a programming error: describe every key the parser reads).
  const toml::node* get(std::string_view key);
  // Sub-table `key` (null when absent); InputError when `key` holds something else.
  const toml::table* table(std::string_view key);
  // The same for a key of a numbered family described once: `key` ("building3") is looked up in study_keys.cpp
  // as `described_as` ("buildingK").
  const toml::table* table(std::string_view key, std::string_view described_as);

  // Typed reads whose default (typed_default) and allowed range are the key's description's: the literal is
  // written once, in study_keys.cpp. std::logic_error when the description's default is computed or of another type
  // (then give it: the overloads below).
  double number(std::string_view key);
  long integer(std::string_view key);
  std::vector<double> numbers(std::string_view key);
  std::string string(std::string_view key);
  bool boolean(std::string_view key);
  // Typed reads with a default for an absent key, the allowed range taken from the key's description
  // (study_keys.cpp: lo, hi, range, units); a value outside it (or not finite) is an error naming the range.
  double number(std::string_view key, double def);
  long integer(std::string_view key, long def);
  std::vector<double> numbers(std::string_view key, std::vector<double> def);
  // The same with a range the caller computes (one that depends on other keys); numbers outside [lo, hi] (or
  // not finite) are errors naming `range`.
  double number(std::string_view key, double def, double lo, double hi, std::string_view range);
  long integer(std::string_view key, long def, long lo, long hi);
  std::string string(std::string_view key, std::string def);
  bool boolean(std::string_view key, bool def);
  std::vector<double> numbers(std::string_view key, std::vector<double> def, double lo, double hi,
                              std::string_view range);
  // A name turned into a value by its owner's parser (parse_stepper, parse_contact_law, ...): an InputError
  // from `parse` keeps its message and fix but points at the key.
  template <class Parse>
  auto choice(std::string_view key, std::string def, Parse parse) {
    const std::string name = string(key, std::move(def));
    try {
      return parse(name);
    } catch (const InputError& e) {
      throw InputError(e.what_part(), where(key), e.fix());
    }
  }

  // Every key of the table must have been asked for; `allowed` is the list shown in the fix.
  void finish(std::string_view allowed) const;

 private:
  const toml::table* t_;
  std::string file_, name_, section_;
  std::set<std::string, std::less<>> seen_;
};

}  // namespace pounding::config
