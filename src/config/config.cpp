// Typed reading of TOML configuration (see config.hpp).
#include "pounding/config/config.hpp"

#include <cmath>
#include <stdexcept>
#include <typeinfo>

#include <fmt/format.h>

#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"

namespace pounding::config {

std::string location(const std::string& file, const toml::source_region& src) {
  return src.begin.line > 0 ? fmt::format("{}:{}", file, src.begin.line) : file;
}

toml::table parse(std::string_view text, const std::string& file, std::string_view fix) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("TOML syntax error (column {}): {}", e.source().begin.column,
                                 escaped_excerpt(e.description(), 200)),
                     location(file, e.source()), std::string(fix));
  }
}

std::string_view type_name(const toml::node& n) {
  return n.is_string()           ? "a string"
         : n.is_integer()        ? "an integer"
         : n.is_floating_point() ? "a float"
         : n.is_boolean()        ? "a boolean"
         : n.is_array()          ? "an array"
         : n.is_table()          ? "a table"
                                 : "a date/time";
}

namespace {
// "<key> must be <wanted>, not <what it holds>", fix "write <key> = <example>".
[[noreturn]] void wrong_type(const toml::node& n, std::string_view key, const std::string& where,
                             std::string_view wanted, std::string_view example) {
  throw InputError(fmt::format("{} must be {}, not {}", key, wanted, type_name(n)), where,
                   fmt::format("write {} = {}", key, example));
}
}  // namespace

double number(const toml::node& n, std::string_view key, const std::string& where) {
  if (auto i = n.as_integer()) return static_cast<double>(i->get());
  if (auto f = n.as_floating_point()) return f->get();
  wrong_type(n, key, where, "a number", "<number>");
}

std::int64_t integer(const toml::node& n, std::string_view key, const std::string& where) {
  if (auto i = n.as_integer()) return i->get();
  wrong_type(n, key, where, "an integer", "<integer>");
}

std::uint64_t seed(const toml::node& n, std::string_view key, const std::string& where) {
  auto i = n.as_integer();
  if (!i || i->get() < 0)
    throw InputError(fmt::format("{} must be an integer >= 0", key), where,
                     fmt::format("write {} = <integer in [0, 2^63 - 1]>", key));
  return static_cast<std::uint64_t>(i->get());
}

std::string string(const toml::node& n, std::string_view key, const std::string& where) {
  if (auto s = n.as_string()) return s->get();
  wrong_type(n, key, where, "a string", "\"...\"");
}

bool boolean(const toml::node& n, std::string_view key, const std::string& where) {
  if (auto b = n.as_boolean()) return b->get();
  wrong_type(n, key, where, "true or false", "true");
}

std::vector<double> numbers(const toml::node& n, std::string_view key, const std::string& where) {
  const toml::array* a = n.as_array();
  if (!a) wrong_type(n, key, where, "a non-empty array of numbers", "[x1, x2, ...]");
  if (a->empty())
    throw InputError(fmt::format("{} must be a non-empty array of numbers", key), where,
                     fmt::format("write {} = [x1, x2, ...]", key));
  std::vector<double> out;
  out.reserve(a->size());
  for (const toml::node& e : *a) {
    if (auto i = e.as_integer()) out.push_back(static_cast<double>(i->get()));
    else if (auto f = e.as_floating_point()) out.push_back(f->get());
    else
      throw InputError(fmt::format("{} must hold numbers only, not {}", key, type_name(e)), where,
                       "remove the non-numeric entries");
  }
  return out;
}

void check_keys(const toml::table& t, const std::function<bool(std::string_view key)>& known,
                std::string_view section, std::string_view allowed,
                const std::function<std::string(std::string_view key, const toml::node& value)>& where) {
  for (auto&& [k, v] : t)
    if (!known(k.str())) throw unknown_key_error(k.str(), section, where(k.str(), v), allowed);
}

// ---------------------------------------------------------------- TableReader

TableReader::TableReader(const toml::table* t, std::string file, std::string name)
    : t_(t), file_(std::move(file)), name_(std::move(name)), section_(study_section_of(name_)) {}
TableReader::TableReader(const toml::table* t, std::string file, std::string name, std::string section)
    : t_(t), file_(std::move(file)), name_(std::move(name)), section_(std::move(section)) {}

std::string TableReader::where(std::string_view key) const {
  const toml::node* n = t_ ? t_->get(key) : nullptr;
  const auto line = n ? n->source().begin.line : (t_ ? t_->source().begin.line : 0);
  const std::string shown = escaped_excerpt(key);  // a key of control or non-ASCII bytes is shown escaped
  const std::string k = name_.empty() ? shown : fmt::format("[{}].{}", name_, shown);
  return line > 0 ? fmt::format("{}:{} {}", file_, line, k) : fmt::format("{} {}", file_, k);
}

namespace {
const StudyKey& described(std::string_view section, std::string_view key) {
  const StudyKey* k = find_study_key(section, key);
  if (!k)
    throw std::logic_error(fmt::format("the study key [{}].{} is read but not described: add it to "
                                       "src/config/study_keys.cpp and regenerate docs/study-reference.md",
                                       section, key));
  return *k;
}

bool has_range(const StudyKey& k) { return !std::isnan(k.lo) && !std::isnan(k.hi); }

std::string range_text(const StudyKey& k) {
  return k.units.empty() ? std::string(k.range) : fmt::format("{} {}", k.range, k.units);
}
}  // namespace

// ---------------------------------------------------------------- typed defaults (study_keys.hpp)

KeyDefault typed_default(const StudyKey& k) {
  toml::table parsed;
  try {
    parsed = toml::parse("x = " + std::string(k.def));
  } catch (const toml::parse_error&) {
    return {};  // a sentence: computed by the caller
  }
  const toml::node& d = *parsed.get("x");
  if (k.type == "number" && d.is_number()) return d.value<double>().value();
  if (k.type == "integer" && d.is_integer()) return static_cast<long>(d.as_integer()->get());
  if (k.type == "boolean" && d.is_boolean()) return d.as_boolean()->get();
  if (k.type == "string" && d.is_string()) return d.as_string()->get();
  if (k.type == "array of numbers" && d.is_array()) {
    std::vector<double> out;
    for (const toml::node& e : *d.as_array()) {
      if (!e.is_number()) return {};
      out.push_back(e.value<double>().value());
    }
    return out;
  }
  return {};
}

namespace {
template <class T>
T default_of(std::string_view section, std::string_view key) {
  const KeyDefault d = typed_default(described(section, key));
  if (const T* v = std::get_if<T>(&d)) return *v;
  throw std::logic_error(fmt::format("study key [{}].{} has no {} default in src/config/study_keys.cpp: give the "
                                     "default at the call",
                                     section, key, typeid(T).name()));
}
}  // namespace

double TableReader::number(std::string_view key) { return number(key, default_of<double>(section_, key)); }
long TableReader::integer(std::string_view key) { return integer(key, default_of<long>(section_, key)); }
std::vector<double> TableReader::numbers(std::string_view key) {
  return numbers(key, default_of<std::vector<double>>(section_, key));
}
std::string TableReader::string(std::string_view key) { return string(key, default_of<std::string>(section_, key)); }
bool TableReader::boolean(std::string_view key) { return boolean(key, default_of<bool>(section_, key)); }

const toml::node* TableReader::get(std::string_view key) {
  described(section_, key);
  seen_.emplace(key);
  return t_ ? t_->get(key) : nullptr;
}

const toml::table* TableReader::table(std::string_view key) {
  const toml::node* n = get(key);
  if (n && !n->is_table())
    throw InputError(fmt::format("{} must be a table, not {}", key, type_name(*n)), where(key),
                     fmt::format("write [{}] on its own line", key));
  return n ? n->as_table() : nullptr;
}

const toml::table* TableReader::table(std::string_view key, std::string_view described_as) {
  described(section_, described_as);
  seen_.emplace(key);
  const toml::node* n = t_ ? t_->get(key) : nullptr;
  if (n && !n->is_table())
    throw InputError(fmt::format("{} must be a table, not {}", key, type_name(*n)), where(key),
                     fmt::format("write [{}] on its own line", key));
  return n ? n->as_table() : nullptr;
}

double TableReader::number(std::string_view key, double def, double lo, double hi, std::string_view range) {
  const toml::node* n = get(key);
  if (!n) return def;
  const double v = config::number(*n, key, where(key));
  if (!std::isfinite(v))
    throw InputError(fmt::format("{} = {} is not a finite number", key, v), where(key),
                     fmt::format("give a finite number ({})", range));
  if (v < lo || v > hi)
    throw InputError(fmt::format("{} = {} is out of range", key, v), where(key), fmt::format("give a value in {}", range));
  return v;
}

double TableReader::number(std::string_view key, double def) {
  const StudyKey& k = described(section_, key);
  if (!has_range(k)) throw std::logic_error(fmt::format("study key [{}].{} has no lo, hi", section_, key));
  return number(key, def, k.lo, k.hi, range_text(k));
}

long TableReader::integer(std::string_view key, long def) {
  const StudyKey& k = described(section_, key);
  if (!has_range(k)) throw std::logic_error(fmt::format("study key [{}].{} has no lo, hi", section_, key));
  return integer(key, def, static_cast<long>(k.lo), static_cast<long>(k.hi));
}

std::vector<double> TableReader::numbers(std::string_view key, std::vector<double> def) {
  const StudyKey& k = described(section_, key);
  if (!has_range(k)) throw std::logic_error(fmt::format("study key [{}].{} has no lo, hi", section_, key));
  return numbers(key, std::move(def), k.lo, k.hi, range_text(k));
}

long TableReader::integer(std::string_view key, long def, long lo, long hi) {
  const toml::node* n = get(key);
  if (!n) return def;
  const auto v = static_cast<long>(config::integer(*n, key, where(key)));
  if (v < lo || v > hi)
    throw InputError(fmt::format("{} = {} is out of range", key, v), where(key),
                     fmt::format("give an integer in [{}, {}]", lo, hi));
  return v;
}

std::string TableReader::string(std::string_view key, std::string def) {
  const toml::node* n = get(key);
  return n ? config::string(*n, key, where(key)) : def;
}

bool TableReader::boolean(std::string_view key, bool def) {
  const toml::node* n = get(key);
  return n ? config::boolean(*n, key, where(key)) : def;
}

std::vector<double> TableReader::numbers(std::string_view key, std::vector<double> def, double lo, double hi,
                                         std::string_view range) {
  const toml::node* n = get(key);
  if (!n) return def;
  std::vector<double> out = config::numbers(*n, key, where(key));
  for (double v : out)
    if (!std::isfinite(v) || v < lo || v > hi)
      throw InputError(fmt::format("{} holds {}, out of range", key, v), where(key), fmt::format("give values in {}", range));
  return out;
}

void TableReader::finish(std::string_view allowed) const {
  if (!t_) return;
  const std::string section = name_.empty() ? std::string("the study file's top level") : "[" + name_ + "]";
  check_keys(
      *t_, [&](std::string_view k) { return seen_.count(k) > 0; }, section, allowed,
      [&](std::string_view k, const toml::node&) { return where(k); });
}

}  // namespace pounding::config
