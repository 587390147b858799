// HDF5 handles and writers (datasets with units, chunked rows, the atomic file): the only user of <hdf5.h>.
#include "pounding/io/hdf5.hpp"

#include <hdf5.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <future>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/parallel_for.hpp"

namespace pounding::h5 {
namespace {

// The OS error of the failed read or write on HDF5's error stack ("..., errno = 28, error message = ..." from its
// file drivers), 0 when none is there. Read right after the failed call: the next API call clears the stack.
int stack_os_error() {
  int err = 0;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        const char* at = e->desc ? std::strstr(e->desc, "errno = ") : nullptr;
        if (at && *static_cast<int*>(data) == 0) *static_cast<int*>(data) = std::atoi(at + 8);
        return 0;
      },
      &err);
  return err;
}

[[noreturn]] void fail(const std::string& what) {
  const int err = stack_os_error();
  throw Error(err ? fmt::format("HDF5 error: {}: {}", what, std::strerror(err)) : "HDF5 error: " + what, what, err);
}
void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}
hid checked(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void start_library() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// The filters of a compressed dataset: HDF5's byte shuffle (for elements wider than a byte), then deflate at level 1.
// The shuffle puts byte k of every value together, so the exponent and high mantissa bytes of doubles form long
// runs: on the paper study's results (22 MB of peaks and models) shuffle + level 1 stores 6.3 MB against 7.3 MB for
// level 4 alone (the files before issue 27's write pass), and deflates in 60 % of the time (zlib, measured with
// Python's zlib on the file's values). Any HDF5 reader (h5py included) undoes both filters.
constexpr int deflate_level = 1;
// Values per chunk: 2^14 (128 KiB of doubles), so a dataset of the paper study (25 records x 30,976 models, or the
// models' 30,976 values) has chunks enough for every CPU (the earlier 4 Mi values made each of those one chunk, one
// thread), and a reader of one record decompresses one row, not the whole array.
constexpr hsize_t chunk_values = hsize_t{1} << 14;

// HDF5's shuffle filter over one chunk of `bytes` bytes of `element`-byte values: byte k of value i to k n + i
// (n = bytes / element; no leftover, since a chunk holds whole values).
void shuffle_bytes(const Bytef* src, Bytef* dst, std::size_t bytes, std::size_t element) {
  const std::size_t n = bytes / element;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < element; ++k) dst[k * n + i] = src[i * element + k];
}

// A compressed dataset's chunks (rows [c chunk0, (c + 1) chunk0) of the first dimension, the other dimensions
// whole), shuffled and deflated on every CPU and handed to HDF5 as they are (H5Dwrite_chunk, filter mask 0). HDF5's
// shuffle filter is the transposition above and its deflate filter zlib's compress2 at the filter's level over the
// chunk's bytes, so a reader sees the same stream and the same values as when H5Dwrite ran the filters on one thread
// (tests/results/test_hdf5_chunks.cpp compares the stored chunks with HDF5's own). The last chunk is padded with
// zeros, the default fill value, as HDF5 pads it.
// Chunk bytes [src, src + n) (n <= chunk_bytes: the last chunk is short) padded, shuffled and deflated into `out`;
// returns zlib's status.
int pack_chunk(const Bytef* src, std::size_t n, std::size_t chunk_bytes, std::size_t element, std::vector<Bytef>& padded,
               std::vector<Bytef>& shuffled, std::vector<Bytef>& out) {
  if (n < chunk_bytes) {
    padded.assign(chunk_bytes, 0);
    std::memcpy(padded.data(), src, n);
    src = padded.data();
  }
  if (element > 1) {
    shuffled.resize(chunk_bytes);
    shuffle_bytes(src, shuffled.data(), chunk_bytes, element);
    src = shuffled.data();
  }
  uLongf size = compressBound(static_cast<uLong>(chunk_bytes));
  out.resize(size);
  const int status = compress2(out.data(), &size, src, static_cast<uLong>(chunk_bytes), deflate_level);
  out.resize(size);
  return status;
}

struct ChunkRows {
  std::size_t element, row_bytes, chunk_bytes, chunks, rows, chunk0;
  ChunkRows(hid_t type, const std::string& name, std::span<const hsize_t> dims, hsize_t chunk0_)
      : element(H5Tget_size(type)), rows(static_cast<std::size_t>(dims[0])), chunk0(static_cast<std::size_t>(chunk0_)) {
    if (element == 0) throw std::runtime_error("HDF5 error: type size of " + name);
    row_bytes = element;
    for (std::size_t k = 1; k < dims.size(); ++k) row_bytes *= static_cast<std::size_t>(dims[k]);
    chunk_bytes = chunk0 * row_bytes;
    chunks = (rows + chunk0 - 1) / chunk0;
  }
  std::size_t rows_in(std::size_t c) const { return std::min(chunk0, rows - c * chunk0); }
};

void write_packed(hid_t ds, const std::string& name, std::size_t c, int status, std::size_t ndims, hsize_t chunk0,
                  const std::vector<Bytef>& packed) {
  if (status != Z_OK) throw std::runtime_error(fmt::format("zlib error {} compressing chunk {} of {}", status, c, name));
  std::vector<hsize_t> offset(ndims, 0);
  offset[0] = static_cast<hsize_t>(c) * chunk0;
  check(H5Dwrite_chunk(ds, H5P_DEFAULT, 0, offset.data(), packed.size(), packed.data()),
        fmt::format("write chunk {} of {}", c, name));
}

void write_chunks_deflated(hid_t ds, const std::string& name, const void* data, hid_t type,
                           std::span<const hsize_t> dims, hsize_t chunk0) {
  const ChunkRows g(type, name, dims, chunk0);
  std::vector<std::vector<Bytef>> packed(g.chunks);
  std::vector<int> status(g.chunks, Z_OK);
  parallel_blocks(g.chunks, thread_count(0, g.chunks), [&](std::size_t first, std::size_t last) {
    std::vector<Bytef> padded, shuffled;
    for (std::size_t c = first; c < last; ++c)
      status[c] = pack_chunk(static_cast<const Bytef*>(data) + c * g.chunk_bytes, g.rows_in(c) * g.row_bytes,
                             g.chunk_bytes, g.element, padded, shuffled, packed[c]);
  });
  for (std::size_t c = 0; c < g.chunks; ++c) write_packed(ds, name, c, status[c], dims.size(), chunk0, packed[c]);
}

// The same chunks from a Fill, a window of them at a time (each thread fills, packs and keeps its chunks of the
// window; they are written in chunk order): memory is the window's chunks, not the dataset.
void write_chunks_filled(hid_t ds, const std::string& name, const Fill& fill, hid_t type, std::span<const hsize_t> dims,
                         hsize_t chunk0) {
  const ChunkRows g(type, name, dims, chunk0);
  const std::size_t values_per_row = g.row_bytes / g.element;
  // each thread holds a chunk, its shuffled copy and its deflated copy: at most 512 MiB of them (a chunk of a
  // [records, models] column is a record row, 80 MB at 10^7 models), and 64 MiB of chunks per window
  const std::size_t threads = std::clamp<std::size_t>((std::size_t{512} << 20) / std::max<std::size_t>(1, 3 * g.chunk_bytes), 1,
                                                      static_cast<std::size_t>(thread_count(0, g.chunks)));
  const std::size_t window = std::max<std::size_t>(threads, (std::size_t{64} << 20) / std::max<std::size_t>(1, g.chunk_bytes));
  std::vector<std::vector<Bytef>> packed(std::min(window, g.chunks));
  std::vector<int> status(packed.size(), Z_OK);
  for (std::size_t w0 = 0; w0 < g.chunks; w0 += window) {
    const std::size_t n = std::min(window, g.chunks - w0);
    std::vector<std::exception_ptr> errors(n);
    parallel_blocks(n, thread_count(static_cast<int>(threads), n), [&](std::size_t first, std::size_t last) {
      std::vector<Bytef> raw(g.chunk_bytes), padded, shuffled;
      for (std::size_t k = first; k < last; ++k) {
        const std::size_t c = w0 + k, rows = g.rows_in(c);
        try {
          fill(c * g.chunk0 * values_per_row, rows * values_per_row, raw.data());
        } catch (...) {
          errors[k] = std::current_exception();
          continue;
        }
        status[k] = pack_chunk(raw.data(), rows * g.row_bytes, g.chunk_bytes, g.element, padded, shuffled, packed[k]);
      }
    });
    for (std::size_t k = 0; k < n; ++k) {
      if (errors[k]) std::rethrow_exception(errors[k]);
      write_packed(ds, name, w0 + k, status[k], dims.size(), chunk0, packed[k]);
    }
  }
}

// write_nd's dataset creation: compressed and chunked along the first dimension (chunks of about chunk_values
// values) from 4096 values, else contiguous; returns the dataset and chunk[0] (0: contiguous).
std::pair<Handle, hsize_t> create_nd(hid group, const std::string& name, hid_t type, std::span<const hsize_t> dims) {
  Handle space(checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace " + name));
  Handle plist(checked(H5Pcreate(H5P_DATASET_CREATE), "plist"));
  hsize_t total = 1;
  for (auto d : dims) total *= d;
  std::vector<hsize_t> chunk(dims.begin(), dims.end());
  const bool compressed = total >= 4096;
  if (compressed) {  // compress large datasets; chunk along the first dimension (chunks of about chunk_values)
    const hsize_t rest = std::max<hsize_t>(1, total / dims[0]);
    chunk[0] = std::min<hsize_t>(dims[0], std::max<hsize_t>(1, chunk_values / rest));
    check(H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk");
    if (H5Tget_size(type) > 1) check(H5Pset_shuffle(plist.get()), "shuffle");
    check(H5Pset_deflate(plist.get(), deflate_level), "deflate");
  }
  Handle ds(checked(H5Dcreate2(group, name.c_str(), type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
                    "create dataset " + name));
  return {std::move(ds), compressed ? chunk[0] : 0};
}

template <class T>
void write_nd(hid group, const std::string& name, const T* data, hid_t type, std::span<const hsize_t> dims) {
  const auto [ds, chunk0] = create_nd(group, name, type, dims);
  hsize_t total = 1;
  for (auto d : dims) total *= d;
  if (chunk0) write_chunks_deflated(ds.get(), name, data, type, dims, chunk0);
  else if (total > 0) check(H5Dwrite(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}

// The layout write_nd gives a compressed dataset, as found in a file: chunked along the first dimension only (the
// other dimensions whole), the filters [deflate] (files before 2026-11-27) or [shuffle, deflate], and the stored
// type the memory type. Anything else (contiguous, other chunk shapes or filters, another byte order) is read by
// H5Dread.
struct DeflatedLayout {
  hsize_t chunk0 = 0;
  bool shuffle = false;
};
std::optional<DeflatedLayout> deflated_layout(hid_t ds, hid_t type, std::span<const hsize_t> dims) {
  Handle dcpl(checked(H5Dget_create_plist(ds), "create plist"));
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED || dims.empty()) return std::nullopt;
  Handle ftype(checked(H5Dget_type(ds), "type"));
  if (H5Tequal(ftype.get(), type) <= 0) return std::nullopt;
  std::vector<hsize_t> chunk(dims.size());
  if (H5Pget_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) != static_cast<int>(dims.size()))
    return std::nullopt;
  for (std::size_t k = 1; k < dims.size(); ++k)
    if (chunk[k] != dims[k]) return std::nullopt;
  std::vector<H5Z_filter_t> filters;
  for (int k = 0; k < H5Pget_nfilters(dcpl.get()); ++k) {
    unsigned flags = 0, config = 0;
    std::size_t n = 0;
    filters.push_back(H5Pget_filter2(dcpl.get(), static_cast<unsigned>(k), &flags, &n, nullptr, 0, nullptr, &config));
  }
  const bool shuffle = filters.size() == 2 && filters[0] == H5Z_FILTER_SHUFFLE;
  if (filters.empty() || filters.back() != H5Z_FILTER_DEFLATE || filters.size() > 2 || (filters.size() == 2 && !shuffle))
    return std::nullopt;
  return DeflatedLayout{chunk[0], shuffle};
}

// The inverse of shuffle_bytes, element widths of 2, 4 and 8 bytes with the width fixed at compile time (one write
// of a whole value per i: the generic loop's byte-strided writes were a tenth of a 10^8-analysis report's reading).
template <std::size_t E>
void unshuffle_fixed(const Bytef* src, Bytef* dst, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    Bytef v[E];
    for (std::size_t k = 0; k < E; ++k) v[k] = src[k * n + i];
    std::memcpy(dst + i * E, v, E);
  }
}
void unshuffle_bytes(const Bytef* src, Bytef* dst, std::size_t bytes, std::size_t element) {
  const std::size_t n = bytes / element;
  switch (element) {
    case 2: return unshuffle_fixed<2>(src, dst, n);
    case 4: return unshuffle_fixed<4>(src, dst, n);
    case 8: return unshuffle_fixed<8>(src, dst, n);
    default: break;
  }
  for (std::size_t k = 0; k < element; ++k)
    for (std::size_t i = 0; i < n; ++i) dst[i * element + k] = src[k * n + i];
}

// Where a chunked dataset's chunks go in memory (write_nd's layout: chunks along the first dimension).
struct ChunkGeometry {
  std::size_t element, row_bytes, chunk_bytes, chunks, rows;
  hsize_t chunk0;
  bool shuffle;
  std::size_t ndims;
  ChunkGeometry(std::size_t element_, std::span<const hsize_t> dims, const DeflatedLayout& lay)
      : element(element_), row_bytes(element_), chunk0(lay.chunk0), shuffle(lay.shuffle), ndims(dims.size()) {
    for (std::size_t k = 1; k < dims.size(); ++k) row_bytes *= static_cast<std::size_t>(dims[k]);
    chunk_bytes = static_cast<std::size_t>(lay.chunk0) * row_bytes;
    chunks = static_cast<std::size_t>((dims[0] + lay.chunk0 - 1) / lay.chunk0);
    rows = static_cast<std::size_t>(dims[0]);
  }
  std::size_t rows_in(std::size_t c) const {
    return std::min<std::size_t>(static_cast<std::size_t>(chunk0), rows - c * static_cast<std::size_t>(chunk0));
  }
};

// Chunk c's stored (filtered) bytes into `stored`, on the calling thread; false where the chunk is unallocated or
// was stored with a filter skipped.
bool read_stored_chunk(hid_t ds, const std::string& name, const ChunkGeometry& g, std::size_t c, std::vector<Bytef>& stored) {
  std::vector<hsize_t> offset(g.ndims, 0);
  offset[0] = static_cast<hsize_t>(c) * g.chunk0;
  hsize_t size = 0;
  if (H5Dget_chunk_storage_size(ds, offset.data(), &size) < 0 || size == 0) return false;
  stored.resize(static_cast<std::size_t>(size));
  std::uint32_t mask = 0;
  check(H5Dread_chunk(ds, H5P_DEFAULT, offset.data(), &mask, stored.data()), fmt::format("read chunk {} of {}", c, name));
  return mask == 0;
}

// Chunk c inflated and unshuffled into its rows of `out` (a full chunk straight there, the last one through
// `ordered`); the zlib status. Any thread: no HDF5 call.
int inflate_chunk(const std::vector<Bytef>& stored, const ChunkGeometry& g, std::size_t c, void* out,
                  std::vector<Bytef>& plain, std::vector<Bytef>& ordered) {
  plain.resize(g.chunk_bytes);
  uLongf size = static_cast<uLongf>(g.chunk_bytes);
  int status = uncompress(plain.data(), &size, stored.data(), static_cast<uLong>(stored.size()));
  if (status == Z_OK && size != g.chunk_bytes) status = Z_DATA_ERROR;
  if (status != Z_OK) return status;
  const std::size_t n = g.rows_in(c);
  Bytef* dst = static_cast<Bytef*>(out) + c * static_cast<std::size_t>(g.chunk0) * g.row_bytes;
  if (!g.shuffle) {
    std::memcpy(dst, plain.data(), n * g.row_bytes);
  } else if (n == static_cast<std::size_t>(g.chunk0)) {
    unshuffle_bytes(plain.data(), dst, g.chunk_bytes, g.element);
  } else {  // the padded last chunk: its whole width unshuffled, its rows kept
    ordered.resize(g.chunk_bytes);
    unshuffle_bytes(plain.data(), ordered.data(), g.chunk_bytes, g.element);
    std::memcpy(dst, ordered.data(), n * g.row_bytes);
  }
  return Z_OK;
}

// A stored chunk that zlib cannot inflate (a damaged file): named with its dataset's path in the file.
[[noreturn]] void damaged_chunk(hid_t ds, const std::string& name, std::size_t c, int status) {
  char path[512];
  const ssize_t n = H5Iget_name(ds, path, sizeof path);
  throw std::runtime_error(fmt::format("chunk {} of {} is damaged (zlib error {}: {})", c,
                                       n > 0 && static_cast<std::size_t>(n) < sizeof path ? std::string(path) : name,
                                       status, zError(status)));
}

// Chunks [first, last) read on this thread (HDF5 is not called from other threads) into `stored`; false as
// read_stored_chunk.
bool read_stored_batch(hid_t ds, const std::string& name, const ChunkGeometry& g, std::size_t first, std::size_t last,
                       std::vector<std::vector<Bytef>>& stored) {
  stored.resize(std::max(stored.size(), last - first));
  for (std::size_t c = first; c < last; ++c)
    if (!read_stored_chunk(ds, name, g, c, stored[c - first])) return false;
  return true;
}

// The mirror of write_chunks_deflated: chunks read in batches on this thread while the batch before is inflated and
// unshuffled on every CPU into `out` (two batches of stored bytes in memory, not the whole file's). Returns false
// (nothing usable in `out`) where a chunk is unallocated or was stored with a filter skipped; the caller then reads
// by H5Dread. `pounding report` on a 10^8-analysis file spent 40 % of its time in HDF5's single-threaded inflate.
bool read_chunks_deflated(hid_t ds, const std::string& name, void* out, std::size_t element,
                          std::span<const hsize_t> dims, const DeflatedLayout& lay) {
  const ChunkGeometry g(element, dims, lay);
  constexpr std::size_t batch = 256;  // chunks: about 32 MiB inflated
  std::vector<std::vector<Bytef>> stored[2];
  std::vector<int> status(g.chunks, Z_OK);
  if (!read_stored_batch(ds, name, g, 0, std::min(batch, g.chunks), stored[0])) return false;
  for (std::size_t b0 = 0, side = 0; b0 < g.chunks; b0 += batch, side ^= 1) {
    const std::size_t b1 = std::min(b0 + batch, g.chunks);
    auto inflate = std::async(std::launch::async, [&, b0, b1, side] {
      parallel_blocks(b1 - b0, thread_count(0, b1 - b0), [&](std::size_t first, std::size_t last) {
        std::vector<Bytef> plain, ordered;
        for (std::size_t i = first; i < last; ++i) status[b0 + i] = inflate_chunk(stored[side][i], g, b0 + i, out, plain, ordered);
      });
    });
    bool next = true;
    try {
      if (b1 < g.chunks) next = read_stored_batch(ds, name, g, b1, std::min(b1 + batch, g.chunks), stored[side ^ 1]);
    } catch (...) {
      inflate.get();
      throw;
    }
    inflate.get();
    if (!next) return false;
  }
  for (std::size_t c = 0; c < g.chunks; ++c)
    if (status[c] != Z_OK) damaged_chunk(ds, name, c, status[c]);
  return true;
}

template <class T>
std::vector<T> read_all(hid group, const std::string& name, hid_t type) {
  if (!exists(group, name)) throw std::runtime_error(fmt::format("HDF5: dataset '{}' not found", name));
  Handle ds(checked(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open " + name));
  Handle space(checked(H5Dget_space(ds.get()), "space " + name));
  hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n <= 0) return out;
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(0, H5Sget_simple_extent_ndims(space.get()))));
  if (!dims.empty()) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (const auto lay = deflated_layout(ds.get(), type, dims))
    if (read_chunks_deflated(ds.get(), name, out.data(), sizeof(T), dims, *lay)) return out;
  check(H5Dread(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), "read " + name);
  return out;
}

// read_doubles_if_constant on a compressed dataset: chunk by chunk on this thread, stopping at the first chunk
// with a value unlike the first (`varies`). false: not readable this way (the caller reads it whole).
bool probe_chunks(hid_t ds, const std::string& name, std::span<const hsize_t> dims, const DeflatedLayout& lay,
                  std::vector<double>& out, bool& varies) {
  const ChunkGeometry g(sizeof(double), dims, lay);
  std::vector<Bytef> stored, plain, ordered;
  const std::size_t per_chunk = static_cast<std::size_t>(g.chunk0) * (g.row_bytes / sizeof(double));
  for (std::size_t c = 0; c < g.chunks; ++c) {
    if (!read_stored_chunk(ds, name, g, c, stored)) return false;
    if (const int status = inflate_chunk(stored, g, c, out.data(), plain, ordered); status != Z_OK)
      damaged_chunk(ds, name, c, status);
    const std::size_t first = c * per_chunk, last = std::min(out.size(), first + per_chunk);
    const double v0 = out[0];
    if (!std::all_of(out.begin() + static_cast<std::ptrdiff_t>(first), out.begin() + static_cast<std::ptrdiff_t>(last),
                     [&](double x) { return x == v0; })) {
      varies = true;
      return true;
    }
  }
  varies = false;
  return true;
}

void write_attr_raw(hid obj, const std::string& name, hid_t type, const void* value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle space(checked(H5Screate(H5S_SCALAR), "scalar space"));
  Handle a(checked(H5Acreate2(obj, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT), "attr " + name));
  check(H5Awrite(a.get(), type, value), "write attr " + name);
}

}  // namespace

void skip_cleanup_at_exit() { H5dont_atexit(); }

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    this->~Handle();
    id_ = o.id_;
    o.id_ = -1;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE: H5Fclose(id_); break;
    case H5I_GROUP: H5Gclose(id_); break;
    case H5I_DATASET: H5Dclose(id_); break;
    case H5I_DATASPACE: H5Sclose(id_); break;
    case H5I_DATATYPE: H5Tclose(id_); break;
    case H5I_ATTR: H5Aclose(id_); break;
    case H5I_GENPROP_LST: H5Pclose(id_); break;
    default: break;
  }
  id_ = -1;
}

AtomicFile::AtomicFile(std::string path, Storage storage) : path_(std::move(path)) {
  start_library();
  if (storage == Storage::disk) {
    path_ = files::replace_target(path_);
    temporary_ = fmt::format("{}.tmp{}", path_, static_cast<long>(getpid()));
    hid_t f = H5Fcreate(temporary_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f < 0) {
      ::unlink(temporary_.c_str());
      throw InputError(fmt::format("cannot create the results file's temporary {}", temporary_), path_,
                       "check that the folder is writable and has space");
    }
    file_ = Handle(f);
    return;
  }
  // Built in memory (core driver, no backing store) and written by files::write_atomically on commit():
  // HDF5 never touches the disk, so a full disk is one clean OS error and never a half-closed HDF5 file.
  Handle fapl(checked(H5Pcreate(H5P_FILE_ACCESS), "file access plist"));
  check(H5Pset_fapl_core(fapl.get(), 1 << 20, 0), "core driver");
  hid_t f = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (f < 0) throw std::runtime_error("HDF5 error: cannot create the in-memory file for " + path_);
  file_ = Handle(f);
}

AtomicFile::~AtomicFile() { abandon(); }

// Storage::disk without commit(): the temporary emptied first (truncate), so that on a full disk (ENOSPC) HDF5 has
// the room to write what it still holds and its close succeeds (beyond ulimit -f, EFBIG, it fails again: the
// executable's skip_cleanup_at_exit keeps that from crashing the exit); the objects of the file still open closed,
// the file closed, the temporary removed.
void AtomicFile::abandon() noexcept {
  if (temporary_.empty()) return;
  if (file_.valid()) {
    ::truncate(temporary_.c_str(), 0);
    const unsigned kinds = H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR | H5F_OBJ_LOCAL;
    try {
      std::vector<hid_t> open(static_cast<std::size_t>(std::max<ssize_t>(0, H5Fget_obj_count(file_.get(), kinds))));
      const ssize_t n = open.empty() ? 0 : H5Fget_obj_ids(file_.get(), kinds, open.size(), open.data());
      for (ssize_t k = 0; k < n; ++k) {
        Handle object(open[static_cast<std::size_t>(k)]);  // closed by its type
      }
    } catch (...) {  // no memory for the list: the close below still releases the file
    }
    file_ = Handle();
  }
  ::unlink(std::exchange(temporary_, std::string()).c_str());
}

void AtomicFile::fail(const std::exception_ptr& error) {
  if (temporary_.empty()) std::rethrow_exception(error);
  const std::string tmp = temporary_;
  abandon();
  try {
    std::rethrow_exception(error);
  } catch (const Error& e) {
    if (e.os_error() == 0) throw;
    throw InputError(fmt::format("cannot write {}: {} (the temporary of {}, removed; at HDF5's {})", tmp,
                                 files::os_error(e.os_error()), path_, e.action()),
                     path_, files::fix_for(e.os_error()));
  }
}

void AtomicFile::commit() {
  if (!temporary_.empty()) {  // Storage::disk: HDF5 writes what it cached, then close, fsync, rename
    try {
      check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush " + temporary_);
      check(H5Fclose(file_.release()), "close " + temporary_);  // a failed close: the id is never used again
    } catch (...) {
      fail(std::current_exception());
    }
    const std::string tmp = std::exchange(temporary_, std::string());
    files::commit_temporary(tmp, path_);
    return;
  }
  check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush " + path_);
  const ssize_t n = H5Fget_file_image(file_.get(), nullptr, 0);
  if (n < 0) throw std::runtime_error("HDF5 error: file image size of " + path_);
  std::vector<std::byte> image(static_cast<std::size_t>(n));
  if (H5Fget_file_image(file_.get(), image.data(), image.size()) != n)
    throw std::runtime_error("HDF5 error: file image of " + path_);
  file_ = Handle();
  files::write_atomically(path_, image);
}

Handle open_read(const std::string& path) {
  files::check_input_file(path, "the HDF5 file");  // H5Fopen of a FIFO blocks, of a folder says only "cannot open"
  start_library();
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f >= 0) return Handle(f);
  const std::string fix = "give an existing results file written by pounding";
  if (::access(path.c_str(), R_OK) != 0)
    throw InputError(fmt::format("cannot open HDF5 file: {}", std::strerror(errno)), path, fix);
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError("cannot open HDF5 file: not an HDF5 file", path, fix);
  throw InputError("cannot open HDF5 file", path, fix);
}

Handle open_rw(const std::string& path) {
  files::check_input_file(path, "the HDF5 file");
  start_library();
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (f < 0) throw InputError("cannot open HDF5 file for writing", path, "check the path and permissions");
  return Handle(f);
}

Handle create_group(hid parent, const std::string& name) {
  return Handle(checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group " + name));
}
Handle open_group(hid parent, const std::string& name) {
  return Handle(checked(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "open group " + name));
}
Handle open_dataset(hid parent, const std::string& name) {
  return Handle(checked(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open dataset " + name));
}
bool exists(hid parent, const std::string& name) { return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0; }
bool is_group(hid parent, const std::string& name) {
  if (!exists(parent, name)) return false;
  Handle object(checked(H5Oopen(parent, name.c_str(), H5P_DEFAULT), "open object " + name));
  return H5Iget_type(object.get()) == H5I_GROUP;
}
std::vector<std::size_t> dataset_shape(hid parent, const std::string& name) {
  Handle ds = open_dataset(parent, name);
  Handle space(checked(H5Dget_space(ds.get()), "space " + name));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error("HDF5 error: rank of " + name);
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
  return {d.begin(), d.end()};
}
bool attribute_exists(hid obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

namespace {
hid_t native(Type type) {
  return type == Type::f64 ? H5T_NATIVE_DOUBLE : type == Type::i64 ? H5T_NATIVE_INT64
         : type == Type::i32 ? H5T_NATIVE_INT32 : H5T_NATIVE_UINT8;
}
}  // namespace

void write_dataset(hid g, const std::string& n, Type type, std::span<const std::size_t> dims, const Fill& fill) {
  const hid_t t = native(type);
  if (dims.empty()) throw std::logic_error("write_dataset " + n + ": no dimensions");
  std::vector<hsize_t> d(dims.begin(), dims.end());
  const auto [ds, chunk0] = create_nd(g, n, t, d);
  if (chunk0) return write_chunks_filled(ds.get(), n, fill, t, d, chunk0);
  std::size_t total = 1;
  for (std::size_t x : dims) total *= x;
  if (total == 0) return;
  std::vector<std::byte> all(total * H5Tget_size(t));
  fill(0, total, all.data());
  check(H5Dwrite(ds.get(), t, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), "write " + n);
}

namespace {

// One dataset of write_datasets: its rows not yet written (chunked: fewer than a chunk, or the last short chunk;
// contiguous: every row, written at the end).
struct RowsSink {
  Handle ds;
  hsize_t chunk0 = 0;  // 0: contiguous
  std::size_t row_bytes = 0, next_chunk = 0;
  std::vector<Bytef> pending;
};
}  // namespace

void write_datasets(std::span<const RowsDataset> sets, const RowsFill& fill, std::size_t window_rows) {
  if (sets.empty()) return;
  const std::size_t rows = sets[0].dims.at(0);
  std::vector<RowsSink> sink(sets.size());
  for (std::size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].dims.empty() || sets[k].dims[0] != rows)
      throw std::logic_error("write_datasets: " + sets[k].name + " does not share the first dimension");
    std::vector<hsize_t> d(sets[k].dims.begin(), sets[k].dims.end());
    auto [ds, chunk0] = create_nd(sets[k].group, sets[k].name, native(sets[k].type), d);
    sink[k].ds = std::move(ds), sink[k].chunk0 = chunk0;
    sink[k].row_bytes = H5Tget_size(native(sets[k].type));
    for (std::size_t j = 1; j < d.size(); ++j) sink[k].row_bytes *= static_cast<std::size_t>(d[j]);
  }
  std::vector<std::vector<Bytef>> window(sets.size());
  std::vector<void*> out(sets.size());
  struct Job {
    std::size_t set, chunk, offset, bytes;
    int status = Z_OK;
    std::vector<Bytef> packed;
  };
  for (std::size_t w0 = 0; w0 < rows; w0 += window_rows) {
    const std::size_t n = std::min(window_rows, rows - w0);
    for (std::size_t k = 0; k < sets.size(); ++k) window[k].assign(n * sink[k].row_bytes, 0), out[k] = window[k].data();
    fill(w0, n, out);
    std::vector<Job> jobs;  // the chunks this window completes (the last one, short, at the end of the rows)
    for (std::size_t k = 0; k < sets.size(); ++k) {
      RowsSink& s = sink[k];
      s.pending.insert(s.pending.end(), window[k].begin(), window[k].end());
      if (!s.chunk0) continue;
      const std::size_t chunk_bytes = static_cast<std::size_t>(s.chunk0) * s.row_bytes;
      std::size_t at = 0;
      while (s.pending.size() - at >= chunk_bytes || (w0 + n == rows && s.pending.size() > at)) {
        const std::size_t b = std::min(chunk_bytes, s.pending.size() - at);
        jobs.push_back({k, s.next_chunk++, at, b, Z_OK, {}});
        at += b;
      }
    }
    parallel_blocks(jobs.size(), thread_count(0, jobs.size()), [&](std::size_t first, std::size_t last) {
      std::vector<Bytef> padded, shuffled;
      for (std::size_t j = first; j < last; ++j) {
        Job& b = jobs[j];
        const RowsSink& s = sink[b.set];
        b.status = pack_chunk(s.pending.data() + b.offset, b.bytes, static_cast<std::size_t>(s.chunk0) * s.row_bytes,
                              H5Tget_size(native(sets[b.set].type)), padded, shuffled, b.packed);
      }
    });
    std::vector<std::size_t> used(sets.size(), 0);
    for (const Job& b : jobs) {
      write_packed(sink[b.set].ds.get(), sets[b.set].name, b.chunk, b.status, sets[b.set].dims.size(), sink[b.set].chunk0,
                   b.packed);
      used[b.set] = b.offset + b.bytes;
    }
    for (std::size_t k = 0; k < sets.size(); ++k)
      sink[k].pending.erase(sink[k].pending.begin(), sink[k].pending.begin() + static_cast<std::ptrdiff_t>(used[k]));
  }
  for (std::size_t k = 0; k < sets.size(); ++k)  // the contiguous (small) ones
    if (!sink[k].chunk0 && !sink[k].pending.empty())
      check(H5Dwrite(sink[k].ds.get(), native(sets[k].type), H5S_ALL, H5S_ALL, H5P_DEFAULT, sink[k].pending.data()),
            "write " + sets[k].name);
}

void write_dataset(hid g, const std::string& n, std::span<const double> v) {
  hsize_t d[1] = {v.size()};
  write_nd(g, n, v.data(), H5T_NATIVE_DOUBLE, d);
}
void write_dataset(hid g, const std::string& n, std::span<const std::int64_t> v) {
  hsize_t d[1] = {v.size()};
  write_nd(g, n, v.data(), H5T_NATIVE_INT64, d);
}
void write_dataset(hid g, const std::string& n, std::span<const std::int32_t> v) {
  hsize_t d[1] = {v.size()};
  write_nd(g, n, v.data(), H5T_NATIVE_INT32, d);
}
void write_dataset(hid g, const std::string& n, std::span<const std::uint8_t> v) {
  hsize_t d[1] = {v.size()};
  write_nd(g, n, v.data(), H5T_NATIVE_UINT8, d);
}
namespace {
template <class T>
void write_shaped(hid g, const std::string& n, std::span<const T> v, std::span<const std::size_t> dims, hid_t type) {
  std::vector<hsize_t> d(dims.begin(), dims.end());
  std::size_t total = 1;
  for (std::size_t x : dims) total *= x;
  if (dims.empty() || total != v.size())
    throw std::logic_error(fmt::format("write_dataset {}: {} values do not fill the shape", n, v.size()));
  write_nd(g, n, v.data(), type, d);
}
}  // namespace

void write_dataset(hid g, const std::string& n, std::span<const double> v, std::span<const std::size_t> dims) {
  write_shaped(g, n, v, dims, H5T_NATIVE_DOUBLE);
}
void write_dataset(hid g, const std::string& n, std::span<const std::int64_t> v, std::span<const std::size_t> dims) {
  write_shaped(g, n, v, dims, H5T_NATIVE_INT64);
}
void write_dataset(hid g, const std::string& n, std::span<const std::int32_t> v, std::span<const std::size_t> dims) {
  write_shaped(g, n, v, dims, H5T_NATIVE_INT32);
}
void write_dataset(hid g, const std::string& n, std::span<const std::uint8_t> v, std::span<const std::size_t> dims) {
  write_shaped(g, n, v, dims, H5T_NATIVE_UINT8);
}

void write_strings(hid g, const std::string& n, const std::vector<std::string>& v) {
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  std::vector<const char*> ptrs;
  for (auto& s : v) ptrs.push_back(s.c_str());
  hsize_t d[1] = {v.size()};
  Handle space(checked(H5Screate_simple(1, d, nullptr), "space"));
  Handle ds(checked(H5Dcreate2(g, n.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "dataset " + n));
  if (!v.empty()) check(H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), "write " + n);
}

void write_attribute(hid obj, const std::string& name, const std::string& value) {
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  const char* p = value.c_str();
  write_attr_raw(obj, name, type.get(), &p);
}
void write_attribute(hid obj, const std::string& name, double value) {
  write_attr_raw(obj, name, H5T_NATIVE_DOUBLE, &value);
}
void write_attribute(hid obj, const std::string& name, std::int64_t value) {
  write_attr_raw(obj, name, H5T_NATIVE_INT64, &value);
}

void write_attribute(hid obj, const std::string& name, std::span<const double> values) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  const hsize_t n = values.size();
  Handle space(checked(H5Screate_simple(1, &n, nullptr), "attribute space " + name));
  Handle a(checked(H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   "attr " + name));
  if (n > 0) check(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, values.data()), "write attr " + name);
}
void write_attribute(hid obj, const std::string& name, const std::vector<std::string>& values) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  const hsize_t n = values.size();
  Handle space(checked(H5Screate_simple(1, &n, nullptr), "attribute space " + name));
  Handle a(checked(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), "attr " + name));
  std::vector<const char*> p;
  for (const auto& v : values) p.push_back(v.c_str());
  if (n > 0) check(H5Awrite(a.get(), type.get(), p.data()), "write attr " + name);
}
std::vector<double> read_doubles_attribute(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  Handle space(checked(H5Aget_space(a.get()), "attribute space " + name));
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> v(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (n > 0) check(H5Aread(a.get(), H5T_NATIVE_DOUBLE, v.data()), "read attr " + name);
  return v;
}

std::vector<std::string> read_strings_attribute(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  Handle space(checked(H5Aget_space(a.get()), "attribute space " + name));
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  std::vector<char*> ptrs(static_cast<std::size_t>(std::max<hssize_t>(n, 0)), nullptr);
  if (n > 0) check(H5Aread(a.get(), type.get(), ptrs.data()), "read attr " + name);
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  if (n > 0) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, ptrs.data());
  return out;
}

AttributeKind attribute_kind(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  Handle space(checked(H5Aget_space(a.get()), "attribute space " + name));
  Handle type(checked(H5Aget_type(a.get()), "attribute type " + name));
  const bool scalar = H5Sget_simple_extent_type(space.get()) == H5S_SCALAR;
  if (!scalar && H5Sget_simple_extent_ndims(space.get()) != 1) return AttributeKind::other;
  switch (H5Tget_class(type.get())) {
    case H5T_STRING: return scalar ? AttributeKind::string : AttributeKind::strings;
    case H5T_FLOAT: return scalar ? AttributeKind::number : AttributeKind::numbers;
    case H5T_INTEGER: return scalar ? AttributeKind::integer : AttributeKind::integers;
    default: return AttributeKind::other;
  }
}

DatasetKind dataset_kind(hid group, const std::string& name) {
  Handle d(checked(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "dataset " + name));
  Handle type(checked(H5Dget_type(d.get()), "dataset type " + name));
  const std::size_t size = H5Tget_size(type.get());
  switch (H5Tget_class(type.get())) {
    case H5T_STRING: return DatasetKind::strings;
    case H5T_FLOAT: return size == 8 ? DatasetKind::f64 : DatasetKind::other;
    case H5T_INTEGER: return size == 8 ? DatasetKind::i64 : size == 4 ? DatasetKind::i32 : size == 1 ? DatasetKind::u8 : DatasetKind::other;
    default: return DatasetKind::other;
  }
}

namespace {
herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}
herr_t collect_link(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}
}  // namespace

std::vector<std::string> attribute_names(hid obj) {
  std::vector<std::string> names;
  hsize_t at = 0;
  check(H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, &at, collect_attribute, &names), "list attributes");
  return names;
}

std::vector<std::string> member_names(hid group) {
  std::vector<std::string> names;
  hsize_t at = 0;
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &at, collect_link, &names), "list members");
  return names;
}

std::vector<double> read_doubles(hid g, const std::string& n) { return read_all<double>(g, n, H5T_NATIVE_DOUBLE); }
std::optional<std::vector<double>> read_doubles_if_constant(hid g, const std::string& n) {
  if (!exists(g, n)) throw std::runtime_error(fmt::format("HDF5: dataset '{}' not found", n));
  Handle ds(checked(H5Dopen2(g, n.c_str(), H5P_DEFAULT), "open " + n));
  Handle space(checked(H5Dget_space(ds.get()), "space " + n));
  std::vector<double> out(static_cast<std::size_t>(std::max<hssize_t>(0, H5Sget_simple_extent_npoints(space.get()))));
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(0, H5Sget_simple_extent_ndims(space.get()))));
  if (!dims.empty()) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  bool varies = false;
  const auto lay = out.empty() ? std::nullopt : deflated_layout(ds.get(), H5T_NATIVE_DOUBLE, dims);
  if (!lay || !probe_chunks(ds.get(), n, dims, *lay, out, varies)) {
    out = read_doubles(g, n);
    varies = !out.empty() && !std::all_of(out.begin(), out.end(), [&](double x) { return x == out.front(); });
  }
  if (varies) return std::nullopt;
  return out;
}
std::vector<std::int64_t> read_int64(hid g, const std::string& n) {
  return read_all<std::int64_t>(g, n, H5T_NATIVE_INT64);
}
std::vector<std::int32_t> read_int32(hid g, const std::string& n) {
  return read_all<std::int32_t>(g, n, H5T_NATIVE_INT32);
}
std::vector<std::uint8_t> read_uint8(hid g, const std::string& n) {
  return read_all<std::uint8_t>(g, n, H5T_NATIVE_UINT8);
}

std::vector<std::string> read_strings(hid g, const std::string& n) {
  Handle ds(checked(H5Dopen2(g, n.c_str(), H5P_DEFAULT), "open " + n));
  Handle space(checked(H5Dget_space(ds.get()), "space"));
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  std::vector<char*> ptrs(static_cast<std::size_t>(count), nullptr);
  if (count > 0) check(H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), "read " + n);
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  if (count > 0) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, ptrs.data());
  return out;
}

std::string read_string_attribute(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  Handle type(checked(H5Tcopy(H5T_C_S1), "string type"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "vlen");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "utf8");
  char* p = nullptr;
  check(H5Aread(a.get(), type.get(), &p), "read attr " + name);
  std::string s = p ? p : "";
  H5free_memory(p);
  return s;
}
double read_double_attribute(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  double v = 0;
  check(H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v), "read attr " + name);
  return v;
}
std::int64_t read_int64_attribute(hid obj, const std::string& name) {
  Handle a(checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "attribute " + name));
  std::int64_t v = 0;
  check(H5Aread(a.get(), H5T_NATIVE_INT64, &v), "read attr " + name);
  return v;
}

}  // namespace pounding::h5
