#pragma once
// Writes a Results to an HDF5 file (docs/results-format.md): format 3 with /system when Results::system is not
// empty, else format 2 exactly as before (schema.hpp pair_format_version; whatever the Header says). Built in
// memory and renamed into place (h5::AtomicFile), so a failure leaves neither a partial file nor a temporary.
// Errors: InputError (the OS error, e.g. a full disk), std::runtime_error (HDF5), std::logic_error (a dataset
// without units and description, a field that does not fill its shape, an inconsistent SystemTable, per-floor or
// per-element fields without a SystemTable or whose floors or elements differ from it -- refused before any file).
#include <memory>
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::h5 {
class AtomicFile;
}

namespace pounding::results {

void write(const std::string& path, const Results& r);

// The same file in two parts, so a caller can render its report while the bulk is written (study/run.cpp: the report
// on another thread; HDF5 is called from the writer's thread only). The constructor builds in memory everything of
// `r` but its header's closing attributes (wall time, exclusions) and its extra groups (/timing, analyses,
// selection); finish() adds those from `r` -- the Results given to the constructor, completed, not another one --
// and renames the file into place. A Writer destroyed without finish() leaves nothing on disk.
class Writer {
 public:
  // on_disk: built in an on-disk temporary instead of memory (h5::AtomicFile::Storage::disk), for files larger than
  // memory ([outputs] per_model = "stream": fields with a source).
  Writer(const std::string& path, const Results& r, bool on_disk = false);
  ~Writer();
  Writer(Writer&&) noexcept;
  Writer& operator=(Writer&&) noexcept;
  void finish(const Results& r);

 private:
  std::unique_ptr<h5::AtomicFile> file_;
};

}  // namespace pounding::results
