#include "pounding/core/machine.hpp"

#include <unistd.h>

#include <fstream>
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

}  // namespace pounding
