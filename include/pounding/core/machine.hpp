#pragma once
// The machine a run happens on, for the provenance of its results (issue 29): the host name, the CPU model and the
// machine's logical CPUs (online; not this process's affinity mask: mpirun binds each rank to one core). Linux reads
// /proc/cpuinfo; elsewhere what POSIX gives.
#include <cstdint>
#include <string>

namespace pounding {

struct Machine {
  std::string host;       // gethostname(); "" when it fails
  std::string cpu_model;  // /proc/cpuinfo "model name" (or "Hardware"/"cpu model"); "" when not found
  std::int64_t cpu_cores = 0;  // logical CPUs online (sysconf); 0 unknown
};
Machine this_machine();
// "host 'h', CPU model, n CPUs" for reports; pieces that are unknown are left out, "" when all are.
std::string machine_text(const Machine& m);

// The memory this process may still use: MemAvailable, or less when a cgroup (container) limit leaves less; NaN
// when unknown. POUNDING_TEST_MEMORY_AVAILABLE (bytes) replaces it in tests. The one measure every memory check
// before work uses (a study's result arrays, simulate's time loop, the support motions of `pounding motions`).
double available_memory_bytes();
// "512 bytes", "3.5 MiB", "25 TiB" (powers of 1024, three significant digits) for messages.
std::string human_bytes(double bytes);

}  // namespace pounding
