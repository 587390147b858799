#pragma once
// HDF5 infrastructure: RAII handles and a write_dataset(group, name, value) family.
// The only module that includes <hdf5.h>. Files are readable with h5py.
#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <span>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pounding::h5 {

using hid = std::int64_t;  // hid_t without including hdf5.h

// For a program, before its first HDF5 call: HDF5 does not clean up at exit (H5_term_library). The pounding
// executable closes every file through its Handle; a file whose close failed stays in HDF5's tables half torn down,
// and the clean-up at exit crashed on it (SIGSEGV in H5F__close_cb, HDF5 1.10.8) after the failed write had been
// reported. AtomicFile gives a full disk (ENOSPC) room to close; under ulimit -f (EFBIG) or on EIO the close's own
// writes still fail. Not for a library in a host process (the Python module): other HDF5 users there may count on
// that clean-up.
void skip_cleanup_at_exit();

// Owns one HDF5 identifier (file, group, dataset, ...) and closes it.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept;
  ~Handle();
  hid get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  hid release() { return std::exchange(id_, -1); }  // the caller closes it

 private:
  hid id_ = -1;
};

// An HDF5 call that failed: what() is "HDF5 error: <action>[: <OS error>]". action(): what the call was doing
// ("write chunk 3 of peak_u1"); os_error(): the OS error HDF5 reported for the read or write under it (ENOSPC,
// EFBIG, EIO), 0 when it reported none.
class Error : public std::runtime_error {
 public:
  Error(const std::string& what, std::string action, int os_error)
      : std::runtime_error(what), action_(std::move(action)), os_error_(os_error) {}
  const std::string& action() const { return action_; }
  int os_error() const { return os_error_; }

 private:
  std::string action_;
  int os_error_;
};

// A file built in memory and written to path by commit() through a temporary name and a rename
// (files::write_atomically): destroyed without commit(), nothing is written; a failed write (disk full,
// EFBIG) throws InputError with the OS error and leaves neither path nor a temporary.
// Storage::disk builds it instead in an HDF5 file on disk, <path>.tmp<pid> beside path (files::remove_stale_temporaries
// removes one a SIGKILL left), closed, fsynced and renamed on commit(), removed when destroyed without commit(): memory
// stays HDF5's caches, whatever the file's size. An HDF5 error while it is built (a full disk among them) is an
// h5::Error; the temporary goes with the object, and fail() turns such an error into the InputError of a failed write.
class AtomicFile {
 public:
  enum class Storage { memory, disk };
  explicit AtomicFile(std::string path, Storage storage = Storage::memory);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  hid root() const { return file_.get(); }
  void commit();
  // Called with the error that stopped the file being built: Storage::disk closes and removes the temporary at once
  // and throws an h5::Error that carries an OS error as InputError("cannot write <temporary>: <OS error> (the
  // temporary of <path>, removed ...)", path, the fix for that error); any other error is rethrown as it is.
  [[noreturn]] void fail(const std::exception_ptr& error);

 private:
  void abandon() noexcept;
  std::string path_, temporary_;  // temporary_: Storage::disk's file until commit() ("" otherwise)
  Handle file_;
};

// Opens an existing file read-only (error names the path if it cannot).
Handle open_read(const std::string& path);
// Opens an existing file read-write.
Handle open_rw(const std::string& path);

Handle create_group(hid parent, const std::string& name);
Handle open_group(hid parent, const std::string& name);
Handle open_dataset(hid parent, const std::string& name);  // e.g. to give it attributes
bool exists(hid parent, const std::string& name);
bool is_group(hid parent, const std::string& name);  // an existing link that is a group
// The dimensions of a dataset (empty for a scalar).
std::vector<std::size_t> dataset_shape(hid parent, const std::string& name);
bool attribute_exists(hid obj, const std::string& name);

void write_dataset(hid group, const std::string& name, std::span<const double> v);
void write_dataset(hid group, const std::string& name, std::span<const std::int64_t> v);
void write_dataset(hid group, const std::string& name, std::span<const std::int32_t> v);
void write_dataset(hid group, const std::string& name, std::span<const std::uint8_t> v);
// N-D row-major (the last dimension varies fastest); the product of dims must be v.size().
void write_dataset(hid group, const std::string& name, std::span<const double> v, std::span<const std::size_t> dims);
void write_dataset(hid group, const std::string& name, std::span<const std::int64_t> v,
                   std::span<const std::size_t> dims);
void write_dataset(hid group, const std::string& name, std::span<const std::int32_t> v,
                   std::span<const std::size_t> dims);
void write_dataset(hid group, const std::string& name, std::span<const std::uint8_t> v,
                   std::span<const std::size_t> dims);
void write_strings(hid group, const std::string& name, const std::vector<std::string>& v);
// A dataset whose values are not held in memory: fill(first, count, out) writes values [first, first + count) of its
// row-major flattening to out (count values of `type`). It is called for whole rows of the first dimension, from
// several threads at once, a window of chunks at a time (about 64 MiB); an exception it throws is rethrown here. The
// dataset is the one write_dataset gives for the same values and dims: layout, filters and stored bytes.
using Fill = std::function<void(std::size_t first, std::size_t count, void* out)>;
enum class Type { f64, i64, i32, u8 };
void write_dataset(hid group, const std::string& name, Type type, std::span<const std::size_t> dims, const Fill& fill);
// Several datasets that share their first dimension (rows), written together a window of rows at a time from one
// call of fill(first_row, rows, out) per window, which writes rows [first_row, first_row + rows) of dataset k to
// out[k] (row-major, dataset k's type): a caller whose rows are costly to make (the models' table, drawn once per
// model for its 27 datasets) makes each row once. Each dataset is the one write_dataset gives for its values.
struct RowsDataset {
  hid group;
  std::string name;
  Type type;
  std::vector<std::size_t> dims;
};
using RowsFill = std::function<void(std::size_t first_row, std::size_t rows, std::span<void* const> out)>;
void write_datasets(std::span<const RowsDataset> sets, const RowsFill& fill, std::size_t window_rows = 65536);

void write_attribute(hid obj, const std::string& name, const std::string& value);
void write_attribute(hid obj, const std::string& name, double value);
void write_attribute(hid obj, const std::string& name, std::int64_t value);
// 1-D attributes (an empty vector is stored as an empty array).
void write_attribute(hid obj, const std::string& name, std::span<const double> values);
void write_attribute(hid obj, const std::string& name, const std::vector<std::string>& values);

std::vector<double> read_doubles(hid group, const std::string& name);
// A dataset of doubles when every value equals (==) the first, else nullopt (and nothing more read than needed: a
// compressed dataset chunk by chunk, stopping at the first chunk with another value). A reader that only needs to
// know whether a column varies (results::LoadExtent::report) skips inflating it.
std::optional<std::vector<double>> read_doubles_if_constant(hid group, const std::string& name);
std::vector<std::int64_t> read_int64(hid group, const std::string& name);
std::vector<std::int32_t> read_int32(hid group, const std::string& name);
std::vector<std::uint8_t> read_uint8(hid group, const std::string& name);
std::vector<std::string> read_strings(hid group, const std::string& name);
std::string read_string_attribute(hid obj, const std::string& name);
double read_double_attribute(hid obj, const std::string& name);
std::int64_t read_int64_attribute(hid obj, const std::string& name);
std::vector<double> read_doubles_attribute(hid obj, const std::string& name);
std::vector<std::string> read_strings_attribute(hid obj, const std::string& name);

// What an attribute holds, for readers of generic tables (/settings): a scalar or a 1-D array of strings,
// floating-point numbers or integers.
enum class AttributeKind { string, strings, number, numbers, integer, integers, other };
AttributeKind attribute_kind(hid obj, const std::string& name);
// What a dataset holds, for readers of generic groups: strings, 64-bit floats, or integers of 8, 32 or 64 bits.
enum class DatasetKind { strings, f64, i64, i32, u8, other };
DatasetKind dataset_kind(hid group, const std::string& name);
// The attribute names of obj, and the names of the links (groups, datasets) in a group, by name.
std::vector<std::string> attribute_names(hid obj);
std::vector<std::string> member_names(hid group);

}  // namespace pounding::h5
