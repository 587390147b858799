#pragma once
// Ground-motion records: one Record type and the readers for the formats earthquake engineers use.
#include <map>
#include <string>
#include <vector>

namespace pounding {

inline constexpr double g_accel = 9.80665;  // m/s^2 per g

enum class AccUnits { g, m_s2, cm_s2 };
AccUnits parse_units(const std::string& name);  // "g", "m/s2", "cm/s2"; InputError otherwise

struct Record {
  std::string name;                          // file stem or generated name
  std::string source;                        // path, or "synthetic:..." for generated records
  double dt = 0.0;                           // s
  std::vector<double> acc;                   // m/s^2
  std::map<std::string, std::string> meta;   // format, event, station, units, ...
  double duration() const { return acc.empty() ? 0.0 : dt * static_cast<double>(acc.size() - 1); }
  double pga() const;                        // m/s^2
};

struct ReadOptions {
  AccUnits units = AccUnits::g;  // units of the values in the file
  double dt = 0.0;               // required for one-column files, ignored otherwise
};

// Reads PEER NGA-West2/West1 .AT2, the 4-line El Centro variant, two-column time/acc text, or one-column
// text (format detected from the content). Throws InputError naming file, line and what was expected.
Record read_record(const std::string& path, const ReadOptions& options = {});

}  // namespace pounding
