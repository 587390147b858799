// The serial executor (POUNDING_WITH_MPI=OFF, or no MPI found): one rank, no MPI. The semantics are those of
// src/parallel/mpi_executor.cpp on one rank. Started by mpirun/srun with more than one rank, it refuses instead of letting
// N independent copies compute the same study and write one results file.
#include <algorithm>
#include <cstdlib>
#include <string>

#include "pounding/core/error.hpp"
#include "pounding/parallel/executor.hpp"
#include "unit_pool.hpp"

namespace pounding::parallel {

namespace {

// The launchers' rank and size variables (Open MPI, PMI/PMIx, Slurm, MPICH's Hydra), as src/parallel/mpi_executor.cpp
// reads them to decide whether to initialise MPI.
long env_number(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::strtol(v, nullptr, 10) : -1;
}

long launched_size() {
  long size = -1;
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS", "MPI_LOCALNRANKS"})
    size = std::max(size, env_number(v));
  return size;
}

long launched_rank() {
  long rank = -1;
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID", "MPI_LOCALRANKID"})
    rank = std::max(rank, env_number(v));
  return rank;
}

}  // namespace

Session::Session(int&, char**&) {
  const long size = launched_size(), rank = launched_rank();
  if (size <= 1 && rank <= 0) return;  // alone, or `mpirun -np 1`: one rank either way
  // Only the first rank explains and fails (exit 2, the launcher's exit code). The others leave quietly with 0:
  // a non-zero exit there would make mpirun kill the first rank, possibly before it has printed why.
  if (rank > 0) std::exit(0);
  throw InputError("this pounding was built without MPI (POUNDING_WITH_MPI=OFF) but was started as " +
                       (size > 1 ? std::to_string(size) + " ranks" : std::string("several ranks")),
                   "mpirun/srun", "run it without mpirun, or rebuild with MPI (cmake -DPOUNDING_WITH_MPI=ON)");
}

Session::~Session() = default;

void Session::barrier() const {}

void Session::broadcast(std::string&) const {}

void Session::broadcast(int&) const {}

std::vector<std::string> Session::allgather(const std::string& mine) const { return {mine}; }

void Session::max_to_root(std::vector<double>&) const {}

void Session::sum_to_root(std::vector<std::int64_t>&) const {}

std::vector<double> Session::gather_to_root(const std::vector<double>& mine) const { return mine; }

void Session::abort(int code) const { std::exit(code); }

void Session::agree(const std::function<void()>& phase) const { phase(); }

void Session::lend_cpus_to_root() const {}

bool run_units(const Session&, const std::vector<std::size_t>& todo, const ComputeFn& compute,
               const ResultFn& on_result, const DoneFn&, const TickFn& tick, const std::atomic<bool>& stop) {
  for (std::size_t u : todo) {
    if (stop.load()) return false;
    Payload d;
    try {
      d = compute(u);
    } catch (const StopRequested&) {
      return false;  // stopped inside the unit: nothing of it is stored
    }
    on_result(u, std::move(d));
    tick();
  }
  return true;
}

bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
               const ResultFn& on_result, const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop,
               MasterStats*) {
  if (threads > 1) return run_units_threaded(todo, compute, threads, on_result, tick, stop);
  return run_units(s, todo, [&](std::size_t u) { return compute(u, 0); }, on_result, on_done, tick, stop);
}

}  // namespace pounding::parallel
