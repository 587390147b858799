// The MPI executor (POUNDING_WITH_MPI=ON): MPI lives here and nowhere else. A serial build compiles
// src/parallel/serial_executor.cpp instead, with the semantics of the one-rank paths below.
#include "pounding/parallel/executor.hpp"

#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <deque>
#include <list>
#include <new>
#include <string>
#include <thread>

#include "pounding/core/error.hpp"
#include "unit_pool.hpp"

namespace pounding::parallel {

namespace {
constexpr int tag_work = 1, tag_result = 2, tag_error = 3;
constexpr std::int64_t stop_unit = -1;
constexpr char sep = '\x1f';  // separates what, where and fix in an error message

// A worker's report of a unit it was stopped inside (StopRequested): -2 - unit (stop_unit is -1), so the master
// puts the unit back among those still to do and the run ends as stopped.
std::int64_t abandoned(std::int64_t unit) { return -2 - unit; }

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "SLURM_STEP_NUM_TASKS", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

// An error crossing ranks: InputError's parts, or a plain exception's text with the rank as its place.
struct Failure {
  bool set = false;
  std::string what, where, fix;
  void capture(int rank) {
    if (set) return;
    set = true;
    try {
      throw;
    } catch (const InputError& e) {
      what = e.what_part(), where = e.where(), fix = e.fix();
    } catch (const std::bad_alloc&) {
      what = "out of memory", where = "rank " + std::to_string(rank);
      fix = "give the study fewer records, period pairs or samples_per_pair, or [outputs] per_model = false or "
            "\"stream\" (docs/studies.md), or run fewer ranks per node";
    } catch (const std::exception& e) {
      what = e.what(), where = "rank " + std::to_string(rank), fix = "rerun; if the run had started, --resume continues from its checkpoint";
    } catch (...) {
      what = "unknown error", where = "rank " + std::to_string(rank), fix = "rerun; if the run had started, --resume continues from its checkpoint";
    }
  }
  std::string pack() const { return what + sep + where + sep + fix; }
  void unpack(const std::string& s) {
    set = true;
    const auto a = s.find(sep), b = s.find(sep, a + 1);
    what = s.substr(0, a), where = s.substr(a + 1, b - a - 1), fix = s.substr(b + 1);
  }
  [[noreturn]] void raise() const { throw InputError(what, where, fix); }
};

// rank `from`'s string to every rank
void broadcast_from(std::string& s, int from) {
  long long n = static_cast<long long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, from, MPI_COMM_WORLD);
  s.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, from, MPI_COMM_WORLD);
}

// After the work loop: rank 0's outcome (0 done, 1 stopped, 2 failed + message) to every rank.
bool finish(Failure& f, bool stopped) {
  int code = f.set ? 2 : stopped ? 1 : 0;
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (code == 2) {
    std::string msg = f.pack();
    broadcast_from(msg, 0);
    f.unpack(msg);
    f.raise();
  }
  return code == 0;
}

// A worker's report of a stored unit: its id alone (8 bytes, native order; issue 27.4). The payload stays on the
// worker, which stored it through on_result (the study appends it to the rank's own checkpoint slice).
bool worker_loop(const ComputeFn& compute, const ResultFn& on_result, const TickFn& tick) {
  // Reports go out with MPI_Isend from two alternating slots, so the worker never waits for a busy master.
  // After a failure the worker sends the error once and only drains unit messages until the master's stop.
  std::int64_t done[2] = {0, 0};
  MPI_Request req[2] = {MPI_REQUEST_NULL, MPI_REQUEST_NULL};
  Failure failed;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (int k = 0;; k ^= 1) {
    std::int64_t unit = stop_unit;
    MPI_Recv(&unit, 1, MPI_INT64_T, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (unit == stop_unit) break;
    if (failed.set) continue;
    try {
      on_result(static_cast<std::size_t>(unit), compute(static_cast<std::size_t>(unit)));
      tick();
    } catch (const StopRequested&) {  // stopped inside the unit: tell the master it is still to do
      MPI_Wait(&req[k], MPI_STATUS_IGNORE);
      done[k] = abandoned(unit);
      MPI_Isend(&done[k], 1, MPI_INT64_T, 0, tag_result, MPI_COMM_WORLD, &req[k]);
      continue;
    } catch (...) {
      failed.capture(rank);
      std::string text = failed.pack();
      MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_error, MPI_COMM_WORLD);
      continue;
    }
    MPI_Wait(&req[k], MPI_STATUS_IGNORE);
    done[k] = unit;
    MPI_Isend(&done[k], 1, MPI_INT64_T, 0, tag_result, MPI_COMM_WORLD, &req[k]);
  }
  MPI_Waitall(2, req, MPI_STATUSES_IGNORE);
  Failure outcome;
  return finish(outcome, false);
}

// A worker rank with `threads` threads (threads > 1): the master keeps 2 threads units in flight here; units are
// received without blocking while the pool computes, and each finished unit is stored here (on_result) and reported
// with MPI_Isend. Every MPI call stays on this thread (MPI_THREAD_FUNNELED). After a failure the error is sent once,
// the queued units are dropped, the running ones' results discarded, and unit messages are only drained until the
// master's stop.
bool worker_loop_threaded(const ThreadComputeFn& compute, int threads, const ResultFn& on_result, const TickFn& tick) {
  struct Send {
    MPI_Request request = MPI_REQUEST_NULL;
    std::int64_t unit = 0;
  };
  std::list<Send> sends;
  Failure failed;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  UnitPool pool(compute, threads);
  bool stopping = false;
  const auto receive = [&] {  // one work message (probed or about to arrive)
    std::int64_t unit = stop_unit;
    MPI_Recv(&unit, 1, MPI_INT64_T, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (unit == stop_unit) stopping = true;
    else if (!failed.set) pool.submit(static_cast<std::size_t>(unit));
  };
  const auto fail = [&] {  // inside a catch
    failed.capture(rank);
    pool.drop_queued();
    std::string text = failed.pack();
    MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_error, MPI_COMM_WORLD);
  };
  for (;;) {
    for (int flag = 1; flag && !stopping;) {
      MPI_Iprobe(0, tag_work, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
      if (flag) receive();
    }
    if (pool.in_flight() == 0) {
      if (stopping) break;
      receive();  // nothing to compute: wait for the master (our sends progress inside MPI meanwhile)
      continue;
    }
    if (std::optional<UnitPool::Done> d = pool.take(std::chrono::milliseconds(1)); d && !failed.set) {
      try {
        const bool stopped = is_stop(d->error);  // stopped inside the unit: the master puts it back
        if (d->error && !stopped) std::rethrow_exception(d->error);
        if (!stopped) {
          on_result(d->unit, std::move(d->payload));
          tick();
        }
        Send& out = sends.emplace_back();
        out.unit = stopped ? abandoned(static_cast<std::int64_t>(d->unit)) : static_cast<std::int64_t>(d->unit);
        MPI_Isend(&out.unit, 1, MPI_INT64_T, 0, tag_result, MPI_COMM_WORLD, &out.request);
      } catch (...) {
        fail();
      }
    }
    for (auto it = sends.begin(); it != sends.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      it = done ? sends.erase(it) : std::next(it);
    }
  }
  for (Send& x : sends) MPI_Wait(&x.request, MPI_STATUS_IGNORE);
  Failure outcome;
  return finish(outcome, false);
}

// Rank 0 of a multi-rank run: hands out units (two in flight per worker), computes units itself between
// messages, stores its own results, counts the workers' (on_done), and stops every worker at the end.
// A worker's message is 8 bytes (the unit id): it arrives eagerly, so the master receives it at once and hands that
// worker its next unit; the master's time per worker unit is a probe, an 8-byte receive and an 8-byte send
// (issue 27.4; before, it received, copied and checkpointed each unit's payload, 6.4-75 KB).
class Master {
 public:
  // threads > 1: `threaded` computes rank 0's units on a pool of that many threads, and every worker has 2 threads
  // units in flight (each worker rank runs as many threads).
  Master(const Session& s, const std::vector<std::size_t>& todo, const ComputeFn& compute, const ResultFn& on_result,
         const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop,
         const ThreadComputeFn* threaded = nullptr, int threads = 1, MasterStats* stats = nullptr)
      : stats_(stats), size_(s.size()), queue_(todo.begin(), todo.end()), compute_(compute), on_result_(on_result),
        on_done_(on_done), tick_(tick), stop_(stop), in_flight_(static_cast<std::size_t>(size_), 0),
        dead_(static_cast<std::size_t>(size_), 0), threaded_(threaded), threads_(threaded ? threads : 1) {}

  bool run() {
    for (int r = 1; r < size_; ++r)
      for (int k = 0; k < 2 * threads_; ++k) outstanding_ += send_unit(r);
    if (threaded_) compute_on_pool();
    while (!queue_.empty() && !halted() && !threaded_) {
      service(false);
      if (queue_.empty() || halted()) break;
      const std::size_t u = queue_.front();
      queue_.pop_front();
      Payload d;
      try {
        d = compute_(u);
      } catch (const StopRequested&) {
        queue_.push_front(u);  // stopped inside the unit: still to do
        break;
      } catch (...) {
        failed_.capture(0);
        break;
      }
      deliver([&] { on_result_(u, std::move(d)); });
    }
    while (outstanding_ > 0) service(true);
    for (int r = 1; r < size_; ++r) {
      std::int64_t unit = stop_unit;
      MPI_Send(&unit, 1, MPI_INT64_T, r, tag_work, MPI_COMM_WORLD);
    }
    return finish(failed_, stop_.load() && !queue_.empty());
  }

 private:
  bool halted() const { return failed_.set || stop_.load(); }

  // Rank 0's own units on its threads, between servicing the workers' messages (every 1 ms at least).
  void compute_on_pool() {
    UnitPool pool(*threaded_, threads_);
    const std::size_t window = 2 * static_cast<std::size_t>(threads_);
    for (;;) {
      if (halted()) {
        const std::vector<std::size_t> back = pool.drop_queued();  // not started: still to do
        queue_.insert(queue_.begin(), back.begin(), back.end());
      } else
        while (!queue_.empty() && pool.in_flight() < window) {
          pool.submit(queue_.front());
          queue_.pop_front();
        }
      if (pool.in_flight() == 0) return;
      service(false);
      std::optional<UnitPool::Done> d = pool.take(std::chrono::milliseconds(1));
      if (!d || failed_.set) continue;
      if (is_stop(d->error)) {
        queue_.push_front(d->unit);  // stopped inside the unit: still to do
        continue;
      }
      if (d->error) {
        try {
          std::rethrow_exception(d->error);
        } catch (...) {
          failed_.capture(0);
        }
        continue;
      }
      deliver([&] { on_result_(d->unit, std::move(d->payload)); });
    }
  }

  bool send_unit(int rank) {
    if (queue_.empty() || halted() || dead_[static_cast<std::size_t>(rank)]) return false;
    std::int64_t unit = static_cast<std::int64_t>(queue_.front());
    queue_.pop_front();
    ++in_flight_[static_cast<std::size_t>(rank)];
    MPI_Send(&unit, 1, MPI_INT64_T, rank, tag_work, MPI_COMM_WORLD);
    return true;
  }

  // on_result, on_done and tick: a throw stops the run (the error goes to every rank at the end)
  template <class F>
  void deliver(F&& store) {
    try {
      store();
      tick_();
    } catch (...) {
      failed_.capture(0);
    }
  }

  void receive_error(const MPI_Status& st) {  // the worker computes nothing more; its units in flight are lost
    const auto src = static_cast<std::size_t>(st.MPI_SOURCE);
    int count = 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    text_.resize(static_cast<std::size_t>(count));
    MPI_Recv(text_.data(), count, MPI_CHAR, st.MPI_SOURCE, tag_error, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!failed_.set) failed_.unpack(text_);
    outstanding_ -= in_flight_[src];
    in_flight_[src] = 0;
    dead_[src] = 1;
  }

  // A worker stored a unit: hand it its next one at once, then count the stored one.
  void receive_done(const MPI_Status& st) {
    const auto t0 = std::chrono::steady_clock::now();
    std::int64_t unit = 0;
    MPI_Recv(&unit, 1, MPI_INT64_T, st.MPI_SOURCE, tag_result, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    --in_flight_[static_cast<std::size_t>(st.MPI_SOURCE)];
    --outstanding_;
    if (unit < 0) {  // the worker was stopped inside it: still to do, and that worker gets no more units
      queue_.push_front(static_cast<std::size_t>(-2 - unit));
      dead_[static_cast<std::size_t>(st.MPI_SOURCE)] = 1;
      return;
    }
    if (send_unit(st.MPI_SOURCE)) ++outstanding_;
    if (!failed_.set) deliver([&] { on_done_(static_cast<std::size_t>(unit), st.MPI_SOURCE); });
    if (stats_) {
      ++stats_->worker_units;
      stats_->service_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  }

  // Takes every waiting message. With `block`, returns only after at least one message was taken.
  void service(bool block) {
    for (bool progressed = false;;) {
      for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) break;
        progressed = true;
        if (st.MPI_TAG == tag_error) receive_error(st);
        else receive_done(st);
      }
      if (!block || progressed) return;
      MPI_Status st;
      MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);  // nothing yet: wait for the next message
    }
  }

  MasterStats* stats_;
  int size_;
  std::deque<std::size_t> queue_;
  const ComputeFn& compute_;
  const ResultFn& on_result_;
  const DoneFn& on_done_;
  const TickFn& tick_;
  const std::atomic<bool>& stop_;
  Failure failed_;
  std::vector<int> in_flight_;
  std::vector<char> dead_;
  int outstanding_ = 0;
  std::string text_;
  const ThreadComputeFn* threaded_;
  int threads_;
};
}  // namespace

// Open MPI probes its network transports in MPI_Init even when every rank is on one node: initialising the `cm`
// messaging layer (its MTLs: libfabric, PSM, PSM2) took about 0.2 s of a 0.3 s MPI_Init on the 2-core VM, and ob1 over
// shared memory (vader) is what it then selects anyway. When Open MPI's launcher says every rank runs on this node
// (OMPI_COMM_WORLD_LOCAL_SIZE equals OMPI_COMM_WORLD_SIZE: the same on every rank, so every rank decides alike) and
// the user has chosen no messaging layer (no OMPI_MCA_pml or OMPI_MCA_mtl in the environment, which `mpirun --mca`
// also sets), cm is excluded before MPI_Init. POUNDING_MPI_TRANSPORTS=all keeps Open MPI's own choice (docs/cluster.md).
namespace {
void skip_network_layers_on_one_node() {
  const char* keep = std::getenv("POUNDING_MPI_TRANSPORTS");
  if (keep != nullptr && std::strcmp(keep, "all") == 0) return;
  const char* n = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (n == nullptr || local == nullptr || std::strcmp(n, local) != 0) return;
  if (std::getenv("OMPI_MCA_pml") != nullptr || std::getenv("OMPI_MCA_mtl") != nullptr) return;
  setenv("OMPI_MCA_pml", "^cm", 0);
}
}  // namespace

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  skip_network_layers_on_one_node();
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

std::vector<std::string> Session::allgather(const std::string& mine) const {
  if (!mpi_ || size_ == 1) return {mine};
  const long long n = static_cast<long long>(mine.size());
  std::vector<long long> sizes(static_cast<std::size_t>(size_));
  MPI_Allgather(&n, 1, MPI_LONG_LONG, sizes.data(), 1, MPI_LONG_LONG, MPI_COMM_WORLD);
  std::vector<std::string> all(static_cast<std::size_t>(size_));
  // one rank's bytes at a time (a count is an int): each rank broadcasts its own
  for (int r = 0; r < size_; ++r) {
    std::string& s = all[static_cast<std::size_t>(r)];
    s = r == rank_ ? mine : std::string(static_cast<std::size_t>(sizes[static_cast<std::size_t>(r)]), '\0');
    for (std::size_t at = 0; at < s.size();) {
      const int chunk = static_cast<int>(std::min<std::size_t>(s.size() - at, std::size_t{1} << 30));
      MPI_Bcast(s.data() + at, chunk, MPI_CHAR, r, MPI_COMM_WORLD);
      at += static_cast<std::size_t>(chunk);
    }
  }
  return all;
}

void Session::broadcast(int& v) const {
  if (mpi_) MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

void Session::max_to_root(std::vector<double>& v) const {
  if (!mpi_ || size_ == 1 || v.empty()) return;
  std::vector<double> out(v.size());
  MPI_Reduce(v.data(), out.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  if (rank_ == 0) v = std::move(out);
}

void Session::sum_to_root(std::vector<std::int64_t>& v) const {
  if (!mpi_ || size_ == 1 || v.empty()) return;
  std::vector<std::int64_t> out(rank_ == 0 ? v.size() : 0);
  for (std::size_t at = 0; at < v.size();) {  // a count is an int
    const int n = static_cast<int>(std::min<std::size_t>(v.size() - at, std::size_t{1} << 28));
    MPI_Reduce(v.data() + at, rank_ == 0 ? out.data() + at : nullptr, n, MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    at += static_cast<std::size_t>(n);
  }
  if (rank_ == 0) v = std::move(out);
}

std::vector<double> Session::gather_to_root(const std::vector<double>& mine) const {
  if (!mpi_ || size_ == 1) return mine;
  std::vector<double> all(rank_ == 0 ? mine.size() * static_cast<std::size_t>(size_) : 0);
  MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, rank_ == 0 ? all.data() : nullptr,
             static_cast<int>(mine.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return all;
}

void Session::abort(int code) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

void Session::lend_cpus_to_root() const {
  if (!mpi_ || size_ == 1) return;
  MPI_Comm node = MPI_COMM_NULL;  // the ranks sharing rank 0's memory (its node), rank 0 first (key = world rank)
  if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node) != MPI_SUCCESS) return;
  cpu_set_t mine;
  CPU_ZERO(&mine);
  if (sched_getaffinity(0, sizeof mine, &mine) != 0) CPU_ZERO(&mine);
  int local = 0, n = 1;
  MPI_Comm_rank(node, &local), MPI_Comm_size(node, &n);
  std::vector<cpu_set_t> all(rank_ == 0 ? static_cast<std::size_t>(n) : 0);
  MPI_Gather(&mine, static_cast<int>(sizeof mine), MPI_BYTE, all.data(), static_cast<int>(sizeof mine), MPI_BYTE, 0, node);
  MPI_Comm_free(&node);
  if (rank_ != 0 || local != 0) return;
  cpu_set_t joined = mine;
  for (cpu_set_t& s : all) CPU_OR(&joined, &joined, &s);
  if (CPU_COUNT(&joined) > CPU_COUNT(&mine)) sched_setaffinity(0, sizeof joined, &joined);
}

// MPI_Allreduce of `mine` (MPI_MIN) that waits by polling with short sleeps: a blocking collective spins a core on
// every waiting rank, the cores rank 0 borrows for its report and write (lend_cpus_to_root).
static int min_over_ranks_politely(int mine) {
  int first = mine;
  MPI_Request req = MPI_REQUEST_NULL;
  MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &req);
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return first;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

void Session::agree(const std::function<void()>& phase) const {
  if (!mpi_ || size_ == 1) {
    phase();
    return;
  }
  Failure f;
  try {
    phase();
  } catch (...) {
    f.capture(rank_);
  }
  const int first = min_over_ranks_politely(f.set ? rank_ : size_);
  if (first == size_) return;
  std::string msg = f.pack();
  broadcast_from(msg, first);
  f.unpack(msg);
  f.raise();
}

bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ComputeFn& compute,
               const ResultFn& on_result, const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop) {
  if (s.size() == 1) {
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
  if (!s.root()) return worker_loop(compute, on_result, tick);
  return Master(s, todo, compute, on_result, on_done, tick, stop).run();
}

bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
               const ResultFn& on_result, const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop,
               MasterStats* stats) {
  const ComputeFn one = [&](std::size_t u) { return compute(u, 0); };
  if (threads <= 1) {
    // rank 0 computes its own units on one pool thread, so this thread answers the workers at least every 1 ms
    // instead of once per unit it computes (measured on the loaded 2-core VM, 2 ranks, quick.toml at 256 samples,
    // interleaved: units phase 3.4-3.8 s against 8.1-9.2 s, where the worker waited for work 65 % of the phase)
    if (s.size() > 1 && s.root()) return Master(s, todo, one, on_result, on_done, tick, stop, &compute, 1, stats).run();
    return run_units(s, todo, one, on_result, on_done, tick, stop);
  }
  if (s.size() == 1) return run_units_threaded(todo, compute, threads, on_result, tick, stop);
  if (!s.root()) return worker_loop_threaded(compute, threads, on_result, tick);
  return Master(s, todo, one, on_result, on_done, tick, stop, &compute, threads, stats).run();
}

}  // namespace pounding::parallel
