// InputError: bad input as what, where and how to fix it.
#include "pounding/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace pounding {

InputError::InputError(std::string what, std::string where, std::string fix)
    : std::runtime_error(fmt::format("{}, {}, {}", what, where, fix)),
      what_(std::move(what)), where_(std::move(where)), fix_(std::move(fix)) {}

void require_range(double value, double lo, double hi, const std::string& name, const std::string& range_text) {
  if (!std::isfinite(value) || value < lo || value > hi)
    throw InputError(fmt::format("{} = {} is out of range", name, value), name,
                     fmt::format("give a value in {}", range_text));
}

void require_positive(double value, const std::string& name) {
  if (!std::isfinite(value) || value <= 0.0)
    throw InputError(fmt::format("{} = {} must be positive and finite", name, value), name,
                     "give a value > 0");
}

std::string escaped_excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  const std::size_t n = std::min(text.size(), max_chars);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
    else out += fmt::format("\\x{:02X}", c);
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

InputError unknown_key_error(std::string_view name, std::string_view section, std::string where,
                             std::string_view allowed, std::string_view kind) {
  return InputError(fmt::format("unknown {} '{}' in {}", kind, escaped_excerpt(name), section), std::move(where),
                    fmt::format("check the spelling; {} takes: {}", section, allowed));
}

}  // namespace pounding
