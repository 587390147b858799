// The JSON writer of the --json outputs (report/json.hpp).
#include "pounding/report/json.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pounding::report {

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  return fmt::format("{}", v);  // shortest round-trip: 0.1, 1e-05, 3 -- all valid JSON numbers
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) out += fmt::format("\\u{:04x}", c);
        else out += ch;
    }
  }
  return out + "\"";
}

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!object_.empty() && object_.back()) throw std::logic_error("JsonWriter: a value in an object without its key");
  separator();
}

void JsonWriter::separator() {
  if (first_.empty()) {
    if (!out_.empty()) throw std::logic_error("JsonWriter: a second top-level value");
    return;
  }
  if (!first_.back()) out_ += first_.size() == 1 ? ",\n  " : ", ";
  else if (first_.size() == 1) out_ += "\n  ";
  first_.back() = false;
}

void JsonWriter::raw(std::string_view text) {
  before_value();
  out_ += text;
}

JsonWriter& JsonWriter::begin_object() {
  raw("{");
  first_.push_back(true);
  object_.push_back(true);
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  if (first_.empty() || !object_.back() || after_key_)
    throw std::logic_error("JsonWriter: end_object without an open object (or after a key)");
  object_.pop_back();
  const bool top = first_.size() == 1, empty = first_.back();
  first_.pop_back();
  out_ += top && !empty ? "\n}" : "}";
  if (first_.empty()) out_ += "\n";
  return *this;
}
JsonWriter& JsonWriter::begin_array() {
  raw("[");
  first_.push_back(true);
  object_.push_back(false);
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  if (first_.empty() || object_.back()) throw std::logic_error("JsonWriter: end_array without an open array");
  object_.pop_back();
  first_.pop_back();
  out_ += "]";
  if (first_.empty()) out_ += "\n";
  return *this;
}
JsonWriter& JsonWriter::key(std::string_view name) {
  if (first_.empty() || !object_.back() || after_key_) throw std::logic_error("JsonWriter: a key outside an object");
  separator();
  out_ += json_string(name) + ": ";
  after_key_ = true;
  return *this;
}
JsonWriter& JsonWriter::value(double v) {
  raw(json_number(v));
  return *this;
}
JsonWriter& JsonWriter::value(std::int64_t v) {
  raw(std::to_string(v));
  return *this;
}
JsonWriter& JsonWriter::value(std::string_view s) {
  raw(json_string(s));
  return *this;
}
JsonWriter& JsonWriter::value(bool b) {
  raw(b ? "true" : "false");
  return *this;
}
JsonWriter& JsonWriter::values(std::span<const double> v) {
  begin_array();
  for (double x : v) value(x);
  return end_array();
}

}  // namespace pounding::report
