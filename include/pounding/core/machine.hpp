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

}  // namespace pounding
