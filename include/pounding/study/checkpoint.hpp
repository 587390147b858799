#pragma once
// The run's checkpoint <out>.ckpt: every finished work unit, appended by rank 0, so that a killed or
// failed run continues with --resume and gives bit-identical results.
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

struct CheckpointScan {
  enum class Kind { empty, ours, other_study, other_build, old_format, not_checkpoint };
  Kind kind = Kind::empty;
  std::uint64_t units_done = 0;   // valid unit records (ours, other_build)
  std::uint64_t units_total = 0;  // the unit count of the study that wrote it
  std::uint64_t good_bytes = 0;   // file length up to the end of the last valid record
  std::uint64_t file_bytes = 0;   // the file's length: file_bytes - good_bytes are dropped on resume
  std::string stopped_at;         // why the scan stopped before the end ("" at the end): a bad checksum, ...
  std::string build;              // the writer's build description
  int format = 0;                 // the file's format (1, 2: older; 3: this one), 0 when unknown
};

class Checkpoint {
 public:
  using UnitFn = std::function<void(std::size_t unit, std::vector<std::byte>&& payload)>;

  // Opens `path` (creating it empty if absent) and locks it exclusively for the life of this object or
  // the process. If another process holds it: InputError "<path> is in use by process N".
  explicit Checkpoint(std::string path);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::string& path() const { return path_; }
  // Reads the file; its valid records go to on_unit only when it belongs to `key` (Kind::ours).
  CheckpointScan scan(const CheckpointKey& key, const UnitFn& on_unit = {});
  // Discards any content and writes the header of `key` (fsynced).
  void start(const CheckpointKey& key);
  // Continues a scanned checkpoint of this key: drops a torn tail, appends after the last valid record.
  void resume(const CheckpointScan& scanned);
  // Appends one finished unit. A failed write (disk full, EFBIG, EIO) cuts the file back to its last
  // complete record, so it stays resumable, and throws InputError with the OS error and the path.
  void append(std::uint64_t unit, std::span<const std::byte> payload);
  // fsync; throws InputError on failure.
  void sync();
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
  std::uint64_t good_ = 0, units_ = 0;
};

// Reads the checkpoint file at `path` without locking it (rank 0 assembling the slices the workers still hold):
// what Checkpoint::scan does.
CheckpointScan scan_checkpoint(const std::string& path, const CheckpointKey& key, const Checkpoint::UnitFn& on_unit = {});

// Rank r's slice of the checkpoint `main` (r >= 1): "<main>.rank<r>".
std::string slice_path(const std::string& main, int rank);
// The slices that exist beside `main` (any rank, any earlier rank count), in rank order.
std::vector<std::string> slice_paths(const std::string& main);

// The run's policy for the checkpoint of `key`, with the messages a user acts on:
// - resume: load this study's units through on_unit; refuse (InputError) a missing or empty checkpoint,
//   another study's, another build's, or an unreadable file;
// - fresh: start it, but refuse to discard progress (units of this or another study) unless `force`.
// Returns the number of units loaded. `dropped` (may be null): on resume, what was cut off after the last valid
// record and why, in words ("" when the file ended cleanly) -- the run says it, never drops units silently.
std::uint64_t open_for_run(Checkpoint& ckpt, const CheckpointKey& key, bool resume, bool force,
                           const Checkpoint::UnitFn& on_unit, std::string* dropped = nullptr);

// The build of this program: a hash of the executable's bytes (falls back to the description's hash) and
// a description (version, git commit, compiler, vector ISA) for messages and the results' provenance.
CheckpointKey this_build();

}  // namespace pounding
