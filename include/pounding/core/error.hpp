#pragma once
// One exception type for bad input (study files, record files, command line).
// main() prints " ERROR: <what>, <where>, <how to fix>" once and exits with code 2.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

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

// A stop (SIGINT, SIGTERM, a batch system's time limit) reached inside a unit of work: the unit is abandoned
// unfinished, never stored, and computed again by --resume. Thrown by the steppers' callers when
// KernelSettings::stop was raised during the run; the executors put the unit back among those still to do.
class StopRequested : public std::exception {
 public:
  const char* what() const noexcept override { return "stopped inside a unit of work (it is computed again on --resume)"; }
};

// Throws InputError unless lo <= value <= hi (and value is finite). name is the option or key.
void require_range(double value, double lo, double hi, const std::string& name, const std::string& range_text);
// Throws InputError unless value > 0 and finite.
void require_positive(double value, const std::string& name);

// Text from a user's file made safe to print in a message: printable ASCII kept, every other byte as \xNN,
// at most `max_chars` characters of the input (then "..."), so binary garbage never reaches the terminal raw.
std::string escaped_excerpt(std::string_view text, std::size_t max_chars = 40);

// The one wording of every unknown-name error (study file, [structures], suite files, command line):
//   what  "unknown <kind> '<name>' in <section>"      kind: "key" for files; "option", "argument" or
//   where <where>                                     "command" on the command line
//   fix   "check the spelling; <section> takes: <allowed>"
// name is escaped (escaped_excerpt).
InputError unknown_key_error(std::string_view name, std::string_view section, std::string where,
                             std::string_view allowed, std::string_view kind = "key");

}  // namespace pounding
