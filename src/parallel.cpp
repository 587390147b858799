// MPI lives here and nowhere else.
#include "pounding/parallel.hpp"

#include <mpi.h>

#include <cstdint>
#include <cstdlib>
#include <deque>

namespace pounding::parallel {

namespace {
constexpr int tag_work = 1, tag_result = 2;
constexpr std::int64_t stop_unit = -1;

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "SLURM_STEP_NUM_TASKS", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}
}  // namespace

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
}

Session::~Session() {
  if (mpi_) MPI_Finalize();
}

void Session::barrier() const {
  if (mpi_) MPI_Barrier(MPI_COMM_WORLD);
}

void Session::broadcast(std::string& s) const {
  if (!mpi_) return;
  long long n = static_cast<long long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  s.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void Session::broadcast(int& v) const {
  if (mpi_) MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

void Session::abort(int code) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ComputeFn& compute,
               const ResultFn& on_result, const TickFn& tick, const std::atomic<bool>& stop) {
  if (s.size() == 1) {
    for (std::size_t u : todo) {
      if (stop.load()) return false;
      on_result(u, compute(u));
      tick();
    }
    return true;
  }

  if (!s.root()) {  // worker: receive a unit, compute, send [unit, payload...]; -1 ends
    // Results go out with MPI_Isend from two alternating buffers: a result larger than the eager limit
    // waits for the master to post its receive (it may be busy computing a unit), and the worker goes on
    // computing its next unit meanwhile instead of blocking in MPI_Send.
    std::vector<double> msg[2];
    MPI_Request req[2] = {MPI_REQUEST_NULL, MPI_REQUEST_NULL};
    for (int k = 0;; k ^= 1) {
      std::int64_t unit = stop_unit;
      MPI_Recv(&unit, 1, MPI_INT64_T, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (unit == stop_unit) break;
      std::vector<double> payload = compute(static_cast<std::size_t>(unit));
      MPI_Wait(&req[k], MPI_STATUS_IGNORE);
      msg[k].assign(1, static_cast<double>(unit));
      msg[k].insert(msg[k].end(), payload.begin(), payload.end());
      MPI_Isend(msg[k].data(), static_cast<int>(msg[k].size()), MPI_DOUBLE, 0, tag_result, MPI_COMM_WORLD, &req[k]);
    }
    MPI_Waitall(2, req, MPI_STATUSES_IGNORE);
    return true;
  }

  // master
  std::deque<std::size_t> queue(todo.begin(), todo.end());
  const int workers = s.size() - 1;
  std::vector<int> in_flight(static_cast<std::size_t>(s.size()), 0);
  auto send_unit = [&](int rank) {
    std::int64_t unit = stop_unit;
    if (!queue.empty() && !stop.load()) {
      unit = static_cast<std::int64_t>(queue.front());
      queue.pop_front();
      ++in_flight[static_cast<std::size_t>(rank)];
    }
    if (unit != stop_unit) MPI_Send(&unit, 1, MPI_INT64_T, rank, tag_work, MPI_COMM_WORLD);
    return unit != stop_unit;
  };
  for (int r = 1; r <= workers; ++r)
    for (int k = 0; k < 2; ++k) send_unit(r);
  int outstanding = 0;
  for (int r = 1; r <= workers; ++r) outstanding += in_flight[static_cast<std::size_t>(r)];

  std::vector<double> buf;
  auto service = [&](bool block) {
    for (;;) {
      int flag = 0;
      MPI_Status st;
      if (block) {
        MPI_Probe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &st);
        flag = 1;
        block = false;
      } else {
        MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &flag, &st);
      }
      if (!flag) return;
      int count = 0;
      MPI_Get_count(&st, MPI_DOUBLE, &count);
      buf.resize(static_cast<std::size_t>(count));
      MPI_Recv(buf.data(), count, MPI_DOUBLE, st.MPI_SOURCE, tag_result, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      --in_flight[static_cast<std::size_t>(st.MPI_SOURCE)];
      --outstanding;
      if (send_unit(st.MPI_SOURCE)) ++outstanding;
      std::size_t unit = static_cast<std::size_t>(buf[0]);
      on_result(unit, std::vector<double>(buf.begin() + 1, buf.end()));
      tick();
    }
  };

  while (!queue.empty() && !stop.load()) {
    service(false);
    if (queue.empty() || stop.load()) break;
    std::size_t u = queue.front();
    queue.pop_front();
    on_result(u, compute(u));
    tick();
  }
  while (outstanding > 0) service(true);
  for (int r = 1; r <= workers; ++r) {
    std::int64_t unit = stop_unit;
    MPI_Send(&unit, 1, MPI_INT64_T, r, tag_work, MPI_COMM_WORLD);
  }
  return !stop.load() || queue.empty();
}

}  // namespace pounding::parallel
