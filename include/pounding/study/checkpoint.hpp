#pragma once
// The run's checkpoint <out>.ckpt: every finished work unit, appended by rank 0, so that a killed or
// failed run continues with --resume and gives bit-identical results ([outputs] per_model = false: one snapshot of
// the rank's reductions instead, format 5 below).
//
// Format 4 (little-endian): header = magic "PNDCKPT4", study hash (u64), unit count (u64), build hash (u64),
// build description length (u64) + bytes; then records = unit (u64), byte count (u64), that many payload
// bytes (a serialised UnitResult, study/unit_result.hpp), checksum (u64) = XXH64 of the payload seeded with XXH64 of
// (unit, count). Formats 1 and 2 (payloads of doubles) and 3 (format 4's layout with an FNV-1a checksum, whose
// byte-wise multiply chain cost the master ~10 us per unit) are recognised and refused as older. A torn last record
// (kill -9 during a write) fails its checksum and is dropped on resume. The file is locked (flock) by the run that
// owns it.
//
// Slices (issue 27.4): under MPI each rank appends the units IT computed to its own file, rank 0 to <out>.ckpt and
// rank r >= 1 to <out>.ckpt.rank<r> (slice_path), each with this header and these records; the master receives only
// unit ids. A checkpoint is the main file plus every slice beside it, whatever rank count wrote them: units are
// identified by id, so a run resumes at any rank count. A checkpoint written before slices (one file) is the same
// thing with no slice. The slices must be visible to rank 0 (a filesystem shared by every node, docs/cluster.md).
//
// Format 5, SNAPSHOTS (issue 27.5, [outputs] per_model = false): a rank's file holds no unit payload but one snapshot
// of what the rank folded: its Reductions' integer counts and order-free summary and the ids of the units folded into
// them (a bit per unit), replaced whole at every flush (written to <file>.tmp<pid> in the same folder, locked,
// fsynced, renamed over the file, the folder fsynced), so counts and ids are always one atomic state; its size is the
// reductions' plus units / 8 bytes, whatever the models per unit. Layout: format 4's header with magic "PNDCKPT5",
// then counts (u64), summary (u64) and done-byte (u64) lengths, the counts (i64), the summary (f64), the done bits
// (bit u % 8 of byte u / 8), and XXH64 of every byte before it. A file whose length or checksum is wrong is DAMAGED
// (a rename never leaves a torn snapshot): refused, never read in part.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace pounding {

// What a checkpoint belongs to: the study (text, records, format), its unit count, and the build of the
// program that wrote it (a different build may change last bits, so its progress is not resumed).
struct CheckpointKey {
  std::uint64_t study_hash = 0, units = 0, build_hash = 0;
  std::string build;  // human-readable description of the build (version, commit, compiler, flags)
};

// One rank's snapshot (format 5): Reductions::counts() and summary(), and the units folded into them.
struct ReductionSnapshot {
  std::vector<std::int64_t> counts;
  std::vector<double> summary;
  std::vector<std::uint8_t> done;  // bit u % 8 of byte u / 8: unit u is in the counts (empty: no unit)
  bool has(std::size_t unit) const { return unit / 8 < done.size() && (done[unit / 8] >> (unit % 8)) & 1; }
  std::uint64_t units_done() const;
};

struct CheckpointScan {
  enum class Kind { empty, ours, other_study, other_build, old_format, not_checkpoint, damaged };
  Kind kind = Kind::empty;
  std::uint64_t units_done = 0;   // valid unit records (ours, other_build)
  std::uint64_t units_total = 0;  // the unit count of the study that wrote it
  std::uint64_t good_bytes = 0;   // file length up to the end of the last valid record
  std::uint64_t file_bytes = 0;   // the file's length: file_bytes - good_bytes are dropped on resume
  std::string stopped_at;         // why the scan stopped before the end ("" at the end): a bad checksum, ...
  std::string build;              // the writer's build description
  int format = 0;                 // the file's format (1, 2, 3: older; 4: unit records; 5: a snapshot), 0 when unknown
  bool same_text = false;         // other_study with the study text, records and format of the key: the unit count differs
};

class Checkpoint {
 public:
  using UnitFn = std::function<void(std::size_t unit, std::vector<std::byte>&& payload)>;

  // Opens `path` (creating it empty if absent) and locks it exclusively for the life of this object or
  // the process. If another process holds it: InputError "<path> is in use by process N". `snapshots`: the file
  // holds format-5 snapshots ([outputs] per_model = false): start() writes an empty one, save() replaces it, and
  // append() is not used.
  explicit Checkpoint(std::string path, bool snapshots = false);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::string& path() const { return path_; }
  bool snapshots() const { return snapshots_; }
  // Reads the file; its valid records go to on_unit only when it belongs to `key` (Kind::ours), and a snapshot
  // (format 5) of `key` to *snapshot when given.
  CheckpointScan scan(const CheckpointKey& key, const UnitFn& on_unit = {}, ReductionSnapshot* snapshot = nullptr);
  // Discards any content and writes the header of `key` (fsynced).
  void start(const CheckpointKey& key);
  // Continues a scanned checkpoint of `key`: drops a torn tail, appends after the last valid record (snapshots:
  // keeps the file until the next save replaces it).
  void resume(const CheckpointScan& scanned, const CheckpointKey& key);
  // Appends one finished unit. A failed write (disk full, EFBIG, EIO) cuts the file back to its last
  // complete record, so it stays resumable, and throws InputError with the OS error and the path.
  void append(std::uint64_t unit, std::span<const std::byte> payload);
  // fsync; throws InputError on failure.
  void sync();
  // Snapshots only: replaces the file by `snap` atomically (see format 5; the new file is locked before the rename,
  // so the lock never lapses). Throws InputError with the OS error; the previous snapshot stays on failure.
  void save(const ReductionSnapshot& snap);
  // The run is complete and its results are written: delete the file.
  void remove();
  // Units appended or resumed so far.
  std::uint64_t units() const { return units_; }
  // Keep the file when this object closes although it was created by this run and holds no unit of it (rank 0's
  // main file when the workers' slices hold the run's units).
  void keep() { created_ = false; }

 private:
  std::string path_;
  int fd_ = -1;
public:
  bool existed() const { return !created_; }  // the file was there before this run opened it

 private:
  bool created_ = false;  // the file did not exist: removed again on close if it never held a unit
  bool snapshots_ = false;
  CheckpointKey key_;     // snapshots: the header of every save (from start or open_for_run)
  std::uint64_t good_ = 0, units_ = 0;
};

// Reads the checkpoint file at `path` without locking it (rank 0 assembling the slices the workers still hold):
// what Checkpoint::scan does.
CheckpointScan scan_checkpoint(const std::string& path, const CheckpointKey& key, const Checkpoint::UnitFn& on_unit = {},
                               ReductionSnapshot* snapshot = nullptr);

// The same scan, telling for each valid unit record of `key` where its payload lies in the file (byte offset and
// length; checksums verified), without keeping the payloads ([outputs] per_model = "stream", study/spill.hpp).
using UnitAtFn = std::function<void(std::size_t unit, std::uint64_t offset, std::uint64_t bytes)>;
CheckpointScan locate_units(const std::string& path, const CheckpointKey& key, const UnitAtFn& on_at);

// Rank r's slice of the checkpoint `main` (r >= 1): "<main>.rank<r>".
std::string slice_path(const std::string& main, int rank);
// The slices that exist beside `main` (any rank, any earlier rank count), in rank order.
std::vector<std::string> slice_paths(const std::string& main);

// The run's policy for the checkpoint of `key`, with the messages a user acts on:
// - resume: load this study's units through on_unit (a snapshot, format 5, through on_snapshot); refuse (InputError)
//   a missing or empty checkpoint, another study's, another build's, a damaged snapshot, or an unreadable file;
//   a snapshot for a Checkpoint without snapshots (per_model = true) is refused as the other kind, while a
//   Checkpoint with snapshots still loads unit records (a per_model = false run of a build before format 5: its
//   units are folded, and the caller's next save replaces the file by a snapshot);
// - fresh: start it, but refuse to discard progress (units of this or another study) unless `force`.
// Returns the number of units loaded. `dropped` (may be null): on resume, what was cut off after the last valid
// record and why, in words ("" when the file ended cleanly) -- the run says it, never drops units silently.
using SnapshotFn = std::function<void(ReductionSnapshot&& snap)>;
std::uint64_t open_for_run(Checkpoint& ckpt, const CheckpointKey& key, bool resume, bool force,
                           const Checkpoint::UnitFn& on_unit, std::string* dropped = nullptr,
                           const SnapshotFn& on_snapshot = {});

// The build of this program: a hash of the executable's bytes (falls back to the description's hash) and
// a description (version, git commit, compiler, vector ISA) for messages and the results' provenance.
CheckpointKey this_build();

}  // namespace pounding
