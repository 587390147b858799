#pragma once
// A small JSON writer for the command line's --json outputs (`pounding simulate`, `pounding collide`): members in
// the order written, numbers in their shortest round-trip form, NaN and infinities as null (JSON has neither),
// strings escaped. The top-level object gets one member per line; nested values stay on one line.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pounding::report {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);  // inside an object, before its value
  JsonWriter& value(double v);
  JsonWriter& value(std::int64_t v);
  JsonWriter& value(int v) { return value(static_cast<std::int64_t>(v)); }
  JsonWriter& value(std::string_view s);
  JsonWriter& value(const char* s) { return value(std::string_view(s)); }
  JsonWriter& value(bool b);
  JsonWriter& values(std::span<const double> v);  // an array of numbers
  // key + value in one call
  template <class T> JsonWriter& member(std::string_view name, const T& v) { return key(name).value(v); }
  JsonWriter& member(std::string_view name, std::span<const double> v) { return key(name).values(v); }
  JsonWriter& member(std::string_view name, const std::vector<double>& v) { return key(name).values(v); }
  // The text so far (complete once every object and array is closed), ending in a newline at depth 0.
  const std::string& str() const { return out_; }

 private:
  void before_value();  // a value: after its key in an object, else with the separator
  void separator();
  void raw(std::string_view text);
  std::string out_;
  std::vector<bool> first_;   // per open container: no element yet
  std::vector<bool> object_;  // per open container: an object (true) or an array
  bool after_key_ = false;
};

std::string json_number(double v);        // shortest round trip; null for NaN and infinities
std::string json_string(std::string_view);  // quoted and escaped

}  // namespace pounding::report
