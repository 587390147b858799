// The command line's values before any command sees them (issue 44 item 10; commands.hpp): CLI11 2.1 turns an empty
// value into 0 or the default (`--modal-zeta ''` damped every mode with 0, `--gap ''` was a gap of 0, `--record ''`
// the built-in sweep), reads an unsigned integer with strtoull (`--seed -1` became 2^64 - 1, `--seed 2^64` saturated
// to it), an integer in base 0 (`010` was 8) and drops the empty fields of a delimited list (`0.02,,0.05`).
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"

namespace pounding::cli {

namespace {

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// What is wrong with `text` as a whole number of the option's type ("" when nothing is): decimal digits only (a sign
// for a signed type), no leading zero, within [0, 2^64 - 1] or [-2^63, 2^63 - 1].
std::string integer_problem(const std::string& text, bool is_unsigned) {
  const std::string form = is_unsigned ? "a whole number in [0, 2^64 - 1], decimal digits only"
                                       : "a whole number, decimal digits (a leading - allowed)";
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const bool negative = !digits.empty() && digits.front() == '-';
  if (negative) digits.remove_prefix(1);
  bool ok = !digits.empty();
  for (char ch : digits) ok = ok && ch >= '0' && ch <= '9';
  if (!ok) return fmt::format("'{}' is not {}", escaped_excerpt(text), form);
  if (negative && is_unsigned) return fmt::format("{} is negative; the option takes {}", escaped_excerpt(text), form);
  if (digits.size() > 1 && digits.front() == '0')
    return fmt::format("'{}' has a leading zero (it would be read as octal); the option takes {}", escaped_excerpt(text),
                       form);
  std::errc ec{};
  if (is_unsigned) {
    std::uint64_t v = 0;
    ec = std::from_chars(digits.data(), digits.data() + digits.size(), v).ec;
  } else {
    std::int64_t v = 0;
    const std::string signed_text = (negative ? "-" : "") + std::string(digits);
    ec = std::from_chars(signed_text.data(), signed_text.data() + signed_text.size(), v).ec;
  }
  if (ec == std::errc::result_out_of_range)
    return fmt::format("{} is beyond the option's integer type (it would be cut to its largest value); the option "
                       "takes {}",
                       escaped_excerpt(text), form);
  return "";
}

// One validator per option kind; the option's name is put in front of the message by CLI11 ("--seed: ...").
CLI::Validator value_check(const std::string& type) {
  const bool is_unsigned = starts_with(type, "UINT"), is_integer = is_unsigned || starts_with(type, "INT");
  return CLI::Validator(
      [is_unsigned, is_integer](std::string& value) -> std::string {
        if (value.empty())
          return "the value is empty (it would silently be 0 or the default); leave the option out for its default";
        return is_integer ? integer_problem(value, is_unsigned) : std::string();
      },
      "");
}

void require_values_in(CLI::App* app) {
  for (CLI::Option* opt : app->get_options()) {
    if (opt->get_type_size_max() == 0 || opt->get_items_expected_max() == 0) continue;  // a flag
    opt->check(value_check(opt->get_type_name()));
  }
  for (CLI::App* sub : app->get_subcommands([](const CLI::App*) { return true; })) require_values_in(sub);
}

}  // namespace

void require_values(CLI::App& app) { require_values_in(&app); }

std::vector<double> number_list(const std::string& text, const std::string& option) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    const std::string field = text.substr(pos, end - pos);
    char* stop = nullptr;
    const double v = field.empty() ? 0.0 : std::strtod(field.c_str(), &stop);
    if (field.empty() || stop != field.c_str() + field.size())
      throw InputError(fmt::format("{} '{}' has {} where a number belongs", option, escaped_excerpt(text),
                                   field.empty() ? std::string("an empty field") : "'" + escaped_excerpt(field) + "'"),
                       option, "give numbers separated by commas, e.g. 0.05,0.03 (no empty field, no spaces)");
    out.push_back(v);
    if (end == text.size()) return out;
    pos = end + 1;
  }
}

namespace {

std::vector<std::string> word_list(const std::vector<std::string>& values, const std::string& option) {
  std::vector<std::string> out;
  for (const std::string& text : values) {
    std::size_t pos = 0;
    while (true) {
      const std::size_t end = std::min(text.find(',', pos), text.size());
      if (end == pos)
        throw InputError(fmt::format("{} '{}' has an empty field", option, escaped_excerpt(text)), option,
                         "give the values separated by commas or spaces, e.g. a,b or a b (no empty field)");
      out.push_back(text.substr(pos, end - pos));
      if (end == text.size()) break;
      pos = end + 1;
    }
  }
  return out;
}

}  // namespace

CLI::Option* add_list(CLI::App* c, const std::string& name, std::vector<std::string>& out, const std::string& help) {
  return c
      ->add_option_function<std::vector<std::string>>(
          name, [&out, name](const std::vector<std::string>& v) { out = word_list(v, name); }, help)
      ->type_name("A,B,...");
}

CLI::Option* add_list(CLI::App* c, const std::string& name, std::vector<double>& out, const std::string& help) {
  return c
      ->add_option_function<std::vector<std::string>>(
          name,
          [&out, name](const std::vector<std::string>& v) {
            out.clear();
            for (const std::string& w : word_list(v, name)) out.push_back(number_list(w, name).front());
          },
          help)
      ->type_name("X,Y,...");
}

CLI::Option* add_number_list(CLI::App* c, const std::string& name, std::vector<double>& out, const std::string& help) {
  return c
      ->add_option_function<std::string>(
          name, [&out, name](const std::string& text) { out = number_list(text, name); }, help)
      ->type_name("X,Y,...");
}

}  // namespace pounding::cli
