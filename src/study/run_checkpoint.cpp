// The run's checkpoint phase: its key, opening and resuming the main file and the rank slices, the flushes.
#include "run_phases.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <algorithm>
#include <memory>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/core/error.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/core/files.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/sdof.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/histories.hpp"
#include "pounding/study/make_results.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/refine.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/spill.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"

namespace pounding::study_run {

// The study, its records and the build: a checkpoint of anything else is not resumed.
CheckpointKey checkpoint_key(const Inputs& in, const WorkPlan& L) {
  CheckpointKey key = this_build();
  std::uint64_t hash = files::fnv1a(in.study.text.data(), in.study.text.size());
  const std::int64_t version = L.format_version();  // 2 for the SDOF pair: its checkpoints' keys as before
  hash = files::fnv1a(&version, sizeof version, hash);
  for (const auto& rr : in.records) {
    hash = files::fnv1a(rr.record.acc.data(), rr.record.acc.size() * sizeof(double), hash);
    hash = files::fnv1a(&rr.record.dt, sizeof(double), hash);
    for (const Record& m : rr.more_supports)  // a multi-support realisation's other supports (none elsewhere)
      hash = files::fnv1a(m.acc.data(), m.acc.size() * sizeof(double), hash);
  }
  key.study_hash = hash;
  key.units = L.units();
  return key;
}

namespace {

// ---- phase 3: checkpoint and resume (rank 0); every rank learns which units remain ---------------
// [outputs] per_model = false (snapshots): rank 0 adds a rank's snapshot to its tally. The main file is read first;
// a snapshot whose units are all done already was absorbed into rank 0's by a resume that stopped before removing
// it (skipped: its counts are in rank 0's), one sharing only some of them is two runs' files mixed (refused: a unit
// must never count twice).
void absorb_snapshot(Tally& tally, const std::string& path, const ReductionSnapshot& snap) {
  std::size_t n = 0, seen = 0;
  for (std::size_t u = 0; u < tally.units(); ++u)
    if (snap.has(u)) ++n, seen += tally.done(u) ? 1 : 0;
  if (n == 0 || seen == n) return;
  if (seen > 0)
    throw InputError(fmt::format("checkpoint {} shares {} of its {} units with the checkpoint files read before it "
                                 "(files of two runs mixed)",
                                 path, seen, n),
                     path, "move the files of the other run away, or rerun with --force to start afresh");
  try {
    tally.absorb(snap);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("checkpoint {} does not fit this study: {}", path, e.what()), path,
                     "rerun with --force to start afresh");
  }
}

// Rank 0: the slices beside the main file (workers' units, any earlier rank count; study/checkpoint.hpp). A fresh run
// refuses one holding progress (unless --force) as it refuses the main file, then removes it; --resume loads each
// one's units by id and cuts off a torn tail (said, as for the main file). Returns the slices read on --resume.
std::vector<std::string> open_slices(const RunOptions& opt, const Checkpoint& main, const CheckpointKey& key,
                                     Tally& tally, const RunContext& ctx) {
  std::vector<std::string> read;
  for (const std::string& path : slice_paths(main.path())) {
    Checkpoint c(path, main.snapshots());
    files::remove_stale_temporaries(path);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && st.st_size == 0) {  // a rank killed before its header: nothing in it
      c.remove();
      continue;
    }
    if (!opt.resume) {
      open_for_run(c, key, false, opt.force, {});
      c.remove();
      continue;
    }
    std::string dropped;
    open_for_run(
        c, key, true, false,
        [&](std::size_t u, std::vector<std::byte>&& d) {
          if (!tally.done(u)) tally.store(u, d);
        },
        &dropped, [&](ReductionSnapshot&& snap) { absorb_snapshot(tally, path, snap); });
    if (!dropped.empty()) ctx.say(fmt::format("checkpoint {}: {}", path, dropped));
    read.push_back(path);
  }
  return read;
}

// Every worker opens its own slice (continued on --resume, else started; a snapshot slice always starts empty: rank 0
// has absorbed and removed the old one); rank 0 then checks that it sees every worker's slice: the results are
// assembled from them, so the output folder must be shared by every node.
void open_worker_slice(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                       std::optional<Checkpoint>& ckpt, const CheckpointKey& key) {
  session.agree([&] {
    if (session.root()) return;
    ckpt.emplace(slice_path(in.out + ".ckpt", session.rank()), !in.study.per_model);
    files::remove_stale_temporaries(ckpt->path());
    struct stat st {};
    if (!ckpt->snapshots() && opt.resume && ::stat(ckpt->path().c_str(), &st) == 0 && st.st_size > 0)
      ckpt->resume(ckpt->scan(key), key);
    else
      ckpt->start(key);
  });
  session.agree([&] {
    if (!session.root()) return;
    for (int r = 1; r < session.size(); ++r) {
      const std::string path = slice_path(in.out + ".ckpt", r);
      if (::access(path.c_str(), F_OK) != 0)
        throw InputError(fmt::format("rank {}'s checkpoint slice {} is not visible from rank 0 (the results are "
                                     "assembled from the slices)", r, path),
                         in.out_where,
                         "give an output folder on a filesystem shared by every node (docs/cluster.md), e.g. the "
                         "job's working directory on the cluster's shared filesystem");
    }
  });
}

}  // namespace

// Rank 0 loads the main file and the slices. With snapshots (per_model = false) everything loaded is then saved as
// rank 0's one snapshot BEFORE the slices are removed (and before the workers start theirs afresh): a stop between
// the two leaves slices whose units rank 0's snapshot holds, skipped by absorb_snapshot at the next resume.
std::vector<std::size_t> open_checkpoint(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                                         const WorkPlan& L, std::optional<Checkpoint>& ckpt, const CheckpointKey& key,
                                         Tally& tally, const RunContext& ctx) {
  std::string todo_bytes;  // the remaining unit ids as u64, native order
  session.agree([&] {
    if (!session.root()) return;
    std::string dropped;
    open_for_run(
        *ckpt, key, opt.resume, opt.force, [&](std::size_t u, std::vector<std::byte>&& d) { tally.store(u, d); },
        &dropped, [&](ReductionSnapshot&& snap) { absorb_snapshot(tally, ckpt->path(), snap); });
    if (!dropped.empty()) ctx.say(fmt::format("checkpoint {}: {}", ckpt->path(), dropped));
    const std::vector<std::string> read = open_slices(opt, *ckpt, key, tally, ctx);
    if (ckpt->snapshots() && opt.resume) {
      ckpt->save(tally.snapshot());
      for (const std::string& path : read) ::unlink(path.c_str());
    }
    for (std::uint64_t u = 0; u < L.units(); ++u)
      if (!tally.done(u)) todo_bytes.append(reinterpret_cast<const char*>(&u), sizeof u);
    if (opt.resume) ctx.say(fmt::format("resuming: {} of {} units already done", tally.units_done(), L.units()));
  });
  session.broadcast(todo_bytes);
  std::vector<std::size_t> todo(todo_bytes.size() / sizeof(std::uint64_t));
  for (std::size_t k = 0; k < todo.size(); ++k) {
    std::uint64_t u = 0;
    std::memcpy(&u, todo_bytes.data() + k * sizeof u, sizeof u);
    todo[k] = static_cast<std::size_t>(u);
  }
  if (session.size() > 1) open_worker_slice(session, opt, in, ckpt, key);
  return todo;
}

// A flush of a rank's checkpoint: fsync of its appended units, or (snapshots) its reductions saved whole.
void sync_checkpoint(Checkpoint& c, const Tally& tally) {
  if (c.snapshots()) c.save(tally.snapshot());
  else c.sync();
}

// An error during the units (a failed unit or write, on any rank): a snapshot rank saves what it folded so far, so its
// checkpoint keeps every finished unit as unit records do; if that save fails too, the previous snapshot stays.
void save_after_error(Checkpoint* ckpt, const Tally& tally) noexcept {
  if (!ckpt || !ckpt->snapshots()) return;
  try {
    ckpt->save(tally.snapshot());
  } catch (...) {  // the error being thrown is the one to report
  }
}

// Seconds between the periodic flushes: 5 (POUNDING_TEST_CHECKPOINT_S sets another, for tests only).
double checkpoint_interval_s() {
  static const double s = [] {
    const char* v = std::getenv("POUNDING_TEST_CHECKPOINT_S");
    return v ? std::atof(v) : 5.0;
  }();
  return s;
}

}  // namespace pounding::study_run
