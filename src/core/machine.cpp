// The machine a run happens on (host, CPU model, cores, available memory), for the results' provenance.
#include "pounding/core/machine.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <utility>
#include <string_view>

#include <fmt/format.h>

namespace pounding {

namespace {

std::string trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return std::string(s);
}

// The first "model name" line of /proc/cpuinfo (x86), else "Hardware"/"cpu model"/"Model" (ARM, MIPS, ...).
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, fallback;
  while (std::getline(in, line)) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(std::string_view(line).substr(0, colon));
    const std::string value = trim(std::string_view(line).substr(colon + 1));
    if (value.empty()) continue;
    if (key == "model name") return value;
    if (fallback.empty() && (key == "Hardware" || key == "cpu model" || key == "Model")) fallback = value;
  }
  return fallback;
}

}  // namespace

Machine this_machine() {
  Machine m;
  char host[256] = "";
  if (gethostname(host, sizeof host - 1) == 0) m.host = host;
  m.cpu_model = cpu_model();
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  m.cpu_cores = online > 0 ? online : 0;
  return m;
}

std::string machine_text(const Machine& m) {
  std::string s;
  if (!m.host.empty()) s = fmt::format("host '{}'", m.host);
  if (!m.cpu_model.empty()) s += (s.empty() ? "" : ", ") + m.cpu_model;
  if (m.cpu_cores > 0) s += (s.empty() ? "" : ", ") + fmt::format("{} CPUs", m.cpu_cores);
  return s;
}

std::string human_bytes(double b) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int i = 0;
  while (b >= 1024.0 && i < 6) b /= 1024.0, ++i;
  return i == 0 ? fmt::format("{:.0f} bytes", b) : fmt::format("{:.3g} {}", b, units[i]);
}

double available_memory_bytes() {
  if (const char* v = std::getenv("POUNDING_TEST_MEMORY_AVAILABLE")) return std::atof(v);  // tests only
  double avail = NAN;
  {
    std::ifstream in("/proc/meminfo");
    std::string key;
    double kb = 0;
    std::string unit;
    while (in >> key >> kb) {
      std::getline(in, unit);
      if (key == "MemAvailable:") {
        avail = kb * 1024.0;
        break;
      }
    }
  }
  // a container's limit (cgroup v2, then v1): what is left of it
  auto read_number = [](const char* path) {
    std::ifstream in(path);
    std::string s;
    if (!(in >> s) || s == "max") return static_cast<double>(NAN);
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    return end && *end == 0 && v > 0 && v < 1e18 ? v : static_cast<double>(NAN);
  };
  for (const auto& [limit, usage] : {std::pair{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
                                    std::pair{"/sys/fs/cgroup/memory/memory.limit_in_bytes",
                                              "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
    const double l = read_number(limit), u = read_number(usage);
    if (std::isfinite(l) && std::isfinite(u)) avail = std::isfinite(avail) ? std::min(avail, l - u) : l - u;
  }
  return avail;
}

}  // namespace pounding
