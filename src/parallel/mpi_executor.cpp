// The MPI executor (POUNDING_WITH_MPI=ON): MPI lives here and nowhere else. A serial build compiles
// src/parallel/serial_executor.cpp instead, with the semantics of the one-rank paths below.
#include "pounding/parallel/executor.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <deque>
#include <list>
#include <string>

#include "pounding/core/error.hpp"
#include "unit_pool.hpp"

namespace pounding::parallel {

namespace {
constexpr int tag_work = 1, tag_result = 2, tag_error = 3;
constexpr std::int64_t stop_unit = -1;
constexpr char sep = '\x1f';  // separates what, where and fix in an error message

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

// A result message: the unit id (8 bytes, native order) followed by the payload bytes.
void pack_result(std::vector<std::byte>& msg, std::int64_t unit, const Payload& payload) {
  msg.resize(sizeof unit + payload.size());
  std::memcpy(msg.data(), &unit, sizeof unit);
  if (!payload.empty()) std::memcpy(msg.data() + sizeof unit, payload.data(), payload.size());
}

bool worker_loop(const ComputeFn& compute) {
  // Results go out with MPI_Isend from two alternating buffers: a result larger than the eager limit
  // waits for the master to post its receive (it may be busy computing a unit), and the worker goes on
  // computing its next unit meanwhile instead of blocking in MPI_Send. After a failure the worker sends
  // the error once and only drains unit messages until the master's stop.
  std::vector<std::byte> msg[2];
  MPI_Request req[2] = {MPI_REQUEST_NULL, MPI_REQUEST_NULL};
  Failure failed;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (int k = 0;; k ^= 1) {
    std::int64_t unit = stop_unit;
    MPI_Recv(&unit, 1, MPI_INT64_T, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (unit == stop_unit) break;
    if (failed.set) continue;
    Payload payload;
    try {
      payload = compute(static_cast<std::size_t>(unit));
    } catch (...) {
      failed.capture(rank);
      std::string text = failed.pack();
      MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_error, MPI_COMM_WORLD);
      continue;
    }
    MPI_Wait(&req[k], MPI_STATUS_IGNORE);
    pack_result(msg[k], unit, payload);
    MPI_Isend(msg[k].data(), static_cast<int>(msg[k].size()), MPI_BYTE, 0, tag_result, MPI_COMM_WORLD, &req[k]);
  }
  MPI_Waitall(2, req, MPI_STATUSES_IGNORE);
  Failure outcome;
  return finish(outcome, false);
}

// A worker rank with `threads` threads (threads > 1): the master keeps 2 threads units in flight here; units are
// received without blocking while the pool computes, and each result goes out with MPI_Isend as it finishes. Every
// MPI call stays on this thread (MPI_THREAD_FUNNELED). After a failure the error is sent once, the queued units are
// dropped, the running ones' results discarded, and unit messages are only drained until the master's stop.
bool worker_loop_threaded(const ThreadComputeFn& compute, int threads) {
  struct Send {
    MPI_Request request = MPI_REQUEST_NULL;
    std::vector<std::byte> bytes;
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
      if (d->error) {
        try {
          std::rethrow_exception(d->error);
        } catch (...) {
          failed.capture(rank);
        }
        pool.drop_queued();
        std::string text = failed.pack();
        MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, tag_error, MPI_COMM_WORLD);
      } else {
        Send& out = sends.emplace_back();
        pack_result(out.bytes, static_cast<std::int64_t>(d->unit), d->payload);
        MPI_Isend(out.bytes.data(), static_cast<int>(out.bytes.size()), MPI_BYTE, 0, tag_result, MPI_COMM_WORLD,
                  &out.request);
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
// messages, stores results in completion order, and stops every worker at the end.
// Results are received without blocking: a probed result gets an MPI_Irecv and its worker its next unit at once, and
// the master goes on computing while the data arrives. With a transport whose large messages advance only inside MPI
// calls on both sides (shared memory without single-copy, measured: README "Speed"), a blocking receive made the
// master wait for each busy worker instead of computing (rank 0 computed no unit; 2 ranks were slower than 1).
class Master {
 public:
  // threads > 1: `threaded` computes rank 0's units on a pool of that many threads, and every worker has 2 threads
  // units in flight (each worker rank runs as many threads).
  Master(const Session& s, const std::vector<std::size_t>& todo, const ComputeFn& compute, const ResultFn& on_result,
         const TickFn& tick, const std::atomic<bool>& stop, const ThreadComputeFn* threaded = nullptr, int threads = 1)
      : size_(s.size()), queue_(todo.begin(), todo.end()), compute_(compute), on_result_(on_result), tick_(tick),
        stop_(stop), in_flight_(static_cast<std::size_t>(size_), 0), dead_(static_cast<std::size_t>(size_), 0),
        threaded_(threaded), threads_(threaded ? threads : 1) {}

  bool run() {
    for (int r = 1; r < size_; ++r)
      for (int k = 0; k < 2 * threads_; ++k) outstanding_ += send_unit(r);
    if (threaded_) compute_on_pool();
    while (!queue_.empty() && !halted() && !threaded_) {
      service(false);
      if (queue_.empty() || halted()) break;
      const std::size_t u = queue_.front();
      queue_.pop_front();
      deliver([&] { on_result_(u, compute_(u)); });
    }
    while (outstanding_ > 0) service(true);
    for (int r = 1; r < size_; ++r) {
      std::int64_t unit = stop_unit;
      MPI_Send(&unit, 1, MPI_INT64_T, r, tag_work, MPI_COMM_WORLD);
    }
    return finish(failed_, stop_.load() && !queue_.empty());
  }

 private:
  struct Pending {  // a result whose receive is posted and not yet complete
    MPI_Request request = MPI_REQUEST_NULL;
    std::vector<std::byte> bytes;
  };

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

  // on_result and tick: a throw stops the run (the error goes to every rank at the end)
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

  // A probed result: post its receive, hand its worker the next unit (the worker's slot is free once its result
  // is on its way), and complete the receive later (complete_results).
  void post_result(const MPI_Status& st) {
    int count = 0;
    MPI_Get_count(&st, MPI_BYTE, &count);
    Pending p;
    if (!spare_.empty()) p.bytes = std::move(spare_.back()), spare_.pop_back();
    p.bytes.resize(static_cast<std::size_t>(count));
    MPI_Irecv(p.bytes.data(), count, MPI_BYTE, st.MPI_SOURCE, tag_result, MPI_COMM_WORLD, &p.request);
    pending_.push_back(std::move(p));
    --in_flight_[static_cast<std::size_t>(st.MPI_SOURCE)];
    if (send_unit(st.MPI_SOURCE)) ++outstanding_;
  }

  // Stores every result whose data has arrived; returns how many.
  std::size_t complete_results() {
    std::size_t done = 0;
    for (std::size_t i = 0; i < pending_.size();) {
      int flag = 0;
      MPI_Test(&pending_[i].request, &flag, MPI_STATUS_IGNORE);  // a completed (null) request tests true
      if (!flag) {
        ++i;
        continue;
      }
      Pending p = std::move(pending_[i]);
      pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(i));
      --outstanding_;
      ++done;
      if (!failed_.set) {  // nothing more is stored after a failure
        std::int64_t unit = 0;
        std::memcpy(&unit, p.bytes.data(), sizeof unit);
        deliver([&] { on_result_(static_cast<std::size_t>(unit), Payload(p.bytes.begin() + sizeof unit, p.bytes.end())); });
      }
      spare_.push_back(std::move(p.bytes));
    }
    return done;
  }

  // Posts the receives of every waiting message and stores the results that have arrived. With `block`, returns
  // only after at least one message was taken or one result stored.
  void service(bool block) {
    for (;;) {
      bool progressed = complete_results() > 0;
      for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) break;
        progressed = true;
        if (st.MPI_TAG == tag_error) receive_error(st);
        else post_result(st);
      }
      if (complete_results() > 0) progressed = true;
      if (!block || progressed) return;
      // nothing yet: wait for the oldest posted result if there is one, else for the next message
      if (!pending_.empty()) {
        MPI_Wait(&pending_.front().request, MPI_STATUS_IGNORE);  // now null: stored by the next pass
      } else {
        MPI_Status st;
        MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
      }
    }
  }

  int size_;
  std::deque<std::size_t> queue_;
  const ComputeFn& compute_;
  const ResultFn& on_result_;
  const TickFn& tick_;
  const std::atomic<bool>& stop_;
  Failure failed_;
  std::vector<int> in_flight_;
  std::vector<char> dead_;
  int outstanding_ = 0;
  std::vector<Pending> pending_;
  std::vector<std::vector<std::byte>> spare_;  // result buffers to reuse
  std::string text_;
  const ThreadComputeFn* threaded_;
  int threads_;
};
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

void Session::abort(int code) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
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
  int mine = f.set ? rank_ : size_, first = size_;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size_) return;
  std::string msg = f.pack();
  broadcast_from(msg, first);
  f.unpack(msg);
  f.raise();
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
  if (!s.root()) return worker_loop(compute);
  return Master(s, todo, compute, on_result, tick, stop).run();
}

bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
               const ResultFn& on_result, const TickFn& tick, const std::atomic<bool>& stop) {
  const ComputeFn one = [&](std::size_t u) { return compute(u, 0); };
  if (threads <= 1) return run_units(s, todo, one, on_result, tick, stop);
  if (s.size() == 1) return run_units_threaded(todo, compute, threads, on_result, tick, stop);
  if (!s.root()) return worker_loop_threaded(compute, threads);
  return Master(s, todo, one, on_result, tick, stop, &compute, threads).run();
}

}  // namespace pounding::parallel
