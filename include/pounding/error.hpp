#pragma once
// One exception type for bad input (study files, record files, command line).
// main() prints " ERROR: <what>, <where>, <how to fix>" once and exits with code 2.
#include <stdexcept>
#include <string>

namespace pounding {

class InputError : public std::runtime_error {
 public:
  // what: what is wrong (with the offending value); where: file[:line] or option/key; fix: how to fix it.
  InputError(std::string what, std::string where, std::string fix);
  const std::string& what_part() const { return what_; }
  const std::string& where() const { return where_; }
  const std::string& fix() const { return fix_; }

 private:
  std::string what_, where_, fix_;
};

// Throws InputError unless lo <= value <= hi (and value is finite). name is the option or key.
void require_range(double value, double lo, double hi, const std::string& name, const std::string& range_text);
// Throws InputError unless value > 0 and finite.
void require_positive(double value, const std::string& name);

}  // namespace pounding
