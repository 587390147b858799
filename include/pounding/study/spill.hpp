#pragma once
// [outputs] per_model = "stream" (issue 27, item 5): studies whose per-model columns do not fit in memory. While the
// units run, rank 0 keeps only the Reductions (for the run's report) and which units are done; every unit's payload
// is where it already goes, in the checkpoint (rank 0's <out>.ckpt and the workers' slices, study/checkpoint.hpp).
// After the units SpilledColumns indexes those files once (unit -> file, offset; checksums verified) and serves each
// per-model field of the results file as an h5::Fill: the writer asks for whole rows of a chunk and gets them read
// with pread from the unit records. The results file is built on disk (h5::AtomicFile::Storage::disk), so rank 0's
// memory is the index (12 bytes per unit), the Reductions, the models' table and a window of chunks, not
// records x models x 25 bytes. The datasets equal those of per_model = true bit for bit, layout and compressed
// bytes included (tests/cli/test_stream.sh compares the two files with compare_results.py).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pounding/results/results.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/plan.hpp"

namespace pounding {

class SpilledColumns {
 public:
  // Indexes every unit record of `key` in the checkpoint `main` and its slices (the first record of a unit wins: a
  // unit found twice, after a resume, holds the same bits). Throws InputError naming the checkpoint when a unit is
  // missing (nothing is written then).
  SpilledColumns(const WorkPlan& plan, const std::string& main, const CheckpointKey& key);
  ~SpilledColumns();
  SpilledColumns(const SpilledColumns&) = delete;
  SpilledColumns& operator=(const SpilledColumns&) = delete;

  // Values [first, first + count) of field `field`'s row-major [records, models(, per lane)] column into out (whole
  // lanes: first and count multiples of the field's values per lane). Thread-safe (pread). Throws InputError on a
  // read error or a record shorter than the plan says.
  void fill(std::size_t field, std::size_t first, std::size_t count, void* out) const;
  // The plan's fields, each with `source` reading through this object (kept alive by the sources).
  static std::vector<results::Field> fields(const std::shared_ptr<const SpilledColumns>& self);

 private:
  WorkPlan plan_;
  struct At {
    std::uint64_t offset = 0;
    std::uint32_t file = UINT32_MAX;  // index in paths_, fds_; UINT32_MAX: not found
  };
  std::vector<At> at_;  // per unit
  std::vector<std::string> paths_;
  std::vector<int> fds_;
  std::vector<std::size_t> field_offset_;  // per field: its bytes before it in a unit's payload, per lane
  std::vector<std::size_t> field_width_;   // per field: bytes per lane
};

}  // namespace pounding
