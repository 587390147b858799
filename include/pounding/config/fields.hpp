#pragma once
// Reading a list of fields (issue 46 step 8, docs/runner-design.md section 6): a list is a generic lambda calling
// v(key, &Type::member) once per field (study/study_fields.hpp holds the Study's), and read_fields reads each
// member through the section's TableReader with its key's default and range from src/config/study_keys.cpp. The
// member is a double, int, long, bool, std::string or std::vector<double>; its key must have a typed default
// (TableReader::number(key) and siblings, std::logic_error otherwise).
#include <string>
#include <type_traits>
#include <vector>

#include "pounding/config/config.hpp"

namespace pounding::config {

template <class Obj, class Fields>
void read_fields(Obj& obj, TableReader& r, const Fields& fields) {
  fields([&](const char* key, auto member) {
    auto& x = obj.*member;
    using T = std::decay_t<decltype(x)>;
    if constexpr (std::is_same_v<T, double>) x = r.number(key);
    else if constexpr (std::is_same_v<T, int>) x = static_cast<int>(r.integer(key));
    else if constexpr (std::is_same_v<T, long>) x = r.integer(key);
    else if constexpr (std::is_same_v<T, bool>) x = r.boolean(key);
    else if constexpr (std::is_same_v<T, std::string>) x = r.string(key);
    else {
      static_assert(std::is_same_v<T, std::vector<double>>, "a field is a number, integer, boolean, string or numbers");
      x = r.numbers(key);
    }
  });
}

}  // namespace pounding::config
