#pragma once
// Distribution of work units over MPI ranks: the only module that knows about MPI (src/parallel/mpi_executor.cpp).
// Without mpirun the program runs as one rank and MPI is never initialised.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pounding::parallel {

class Session {
 public:
  Session(int& argc, char**& argv);  // initialises MPI only when launched by mpirun/srun
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool mpi() const { return mpi_; }
  void barrier() const;
  // rank 0's value is sent to every rank
  void broadcast(std::string& s) const;
  void broadcast(int& v) const;
  // every rank's `mine`, in rank order, on every rank (collective: every rank calls it)
  std::vector<std::string> allgather(const std::string& mine) const;
  // element-wise maximum over the ranks, on rank 0 (the other ranks' v is left as it was)
  void max_to_root(std::vector<double>& v) const;
  // element-wise sum over the ranks, on rank 0 (collective; the other ranks' v is left as it was)
  void sum_to_root(std::vector<std::int64_t>& v) const;
  // every rank's `mine` (the same length on every rank), concatenated in rank order, on rank 0 (empty elsewhere)
  std::vector<double> gather_to_root(const std::vector<double>& mine) const;
  [[noreturn]] void abort(int code) const;
  // Runs `phase` on this rank. If it throws on any rank, every rank throws the error of the lowest failing
  // rank (as an InputError with the same what/where/fix), so the whole job stops together, promptly, and
  // rank 0 prints one message. `phase` must not itself communicate.
  // The other ranks wait (without spinning: agree polls and sleeps) while rank 0 works.
  void agree(const std::function<void()>& phase) const;
  // Collective, before a phase only rank 0 works in (the report and the results write after the units): the ranks on
  // rank 0's node lend it their CPUs -- their affinity masks joined into the mask of rank 0's calling thread, which
  // the threads it starts inherit -- since they only wait until the next agree() returns. Under mpirun's default
  // binding rank 0 is otherwise held to one core for its threaded report and deflate while the others idle. The
  // kernel keeps the mask within the job's cpuset; a failure to widen it changes nothing.
  void lend_cpus_to_root() const;

 private:
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

// A unit's result as bytes (the study serialises its typed fields, study/unit_result.hpp): the executor
// moves them between ranks unchanged.
using Payload = std::vector<std::byte>;
// Computes a unit and returns its payload.
using ComputeFn = std::function<Payload(std::size_t unit)>;
// Receives a finished unit's payload ON THE RANK THAT COMPUTED IT (every rank), in completion order, on the calling
// thread: the payload never crosses ranks (issue 27.4: the master only schedules; the study appends it to that
// rank's own checkpoint slice, study/checkpoint.hpp).
using ResultFn = std::function<void(std::size_t unit, Payload&& payload)>;
// Rank 0 only: unit `unit` was computed and stored (its on_result returned) on worker rank `rank`. The worker's
// message to the master is the unit id alone (8 bytes).
using DoneFn = std::function<void(std::size_t unit, int rank)>;
// Called on every rank after each unit it stores, and on rank 0 after each unit a worker reports (progress,
// checkpoint flushes).
using TickFn = std::function<void()>;

// Rank 0's work for the workers' units (issue 27.4, README "Speed"): per unit a worker reports, the 8-byte receive,
// the worker's next unit sent, and on_done; `service_s` sums their wall time (steady clock). Filled by the overload
// with threads (any thread count) when given.
struct MasterStats {
  std::size_t worker_units = 0;
  double service_s = 0;
};

// Dynamic master/worker scheduling of `todo` (unit ids, handed out in this order). Rank 0 hands units to
// workers (two in flight per worker so none waits for the master) and computes units itself between
// messages, so with 2 ranks both cores compute. A worker stores its own results (on_result on the worker) and sends
// rank 0 only the unit's id, after on_result returned (on_done on rank 0). Returns false on every rank if `stop` was
// raised on rank 0 (it stops handing out work, collects what is in flight and returns; workers are released).
// If compute or on_result throws on any rank, or on_done/tick throw on rank 0, rank 0 stops handing out work, waits
// only for the units in flight on healthy workers, releases every worker, and the error is thrown on every
// rank (InputError with the failing rank's what/where/fix).
bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ComputeFn& compute,
               const ResultFn& on_result, const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop);

// Computes a unit on worker thread `thread` of this rank (0 <= thread < threads): each thread must use its own
// computing state (the study gives each its own UnitComputer); it runs concurrently with the other threads.
using ThreadComputeFn = std::function<Payload(std::size_t unit, int thread)>;

// run_units with `threads` worker threads on every rank (the same count on every rank; threads <= 1: the
// calling thread computes, as above, except on rank 0 of several ranks, which computes its units on one pool thread
// so that the calling thread serves the workers at least every 1 ms). Each rank keeps 2 threads units in flight: rank 0 hands a worker
// rank 2 threads units and computes on its own pool between messages; on_result, tick and every MPI call stay on
// the calling thread. Results reach on_result in completion order, which varies with the thread count: the
// caller stores them by unit id. A stop or an error drops the units queued on the threads and waits for the
// running ones (within a unit's time); after an error nothing more is stored.
bool run_units(const Session& s, const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
               const ResultFn& on_result, const DoneFn& on_done, const TickFn& tick, const std::atomic<bool>& stop,
               MasterStats* stats = nullptr);

}  // namespace pounding::parallel
