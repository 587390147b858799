// The results file's compressed datasets (src/io/hdf5.cpp write_chunks_deflated): the chunks are deflated on
// every CPU and handed to HDF5 with H5Dwrite_chunk. Checked against HDF5 itself, which the engine did not write:
//  - every stored chunk is byte for byte the chunk HDF5's own deflate filter stores when H5Dwrite gets the same
//    values through the same dataset creation properties (so any reader, h5py included, decompresses it): the
//    engine's own byte shuffle and deflate must match HDF5's filters byte for byte;
//  - the values read back through HDF5 equal the values written, for 1-D and 2-D datasets of every numeric type,
//    at the sizes around the compression threshold (4096 values) and the chunk length (65536 rows), with a
//    partial last chunk;
//  - the engine's reader (h5::read_*, which inflates the chunks on every CPU) returns the values from the engine's
//    chunks, from HDF5's own, and from the layout of files before 2026-11-27 (deflate level 4 alone, large chunks);
//  - the dataset declares the deflate filter (and, for values wider than a byte, the shuffle filter before it), so
//    the chunks are not raw bytes by accident;
//  - a dataset written from an h5::Fill ([outputs] per_model = "stream", study/spill.hpp) is the same dataset: its
//    stored chunks equal the in-memory write's, byte for byte, and every call asks for whole rows; an on-disk
//    AtomicFile (Storage::disk) leaves nothing but the committed file, and nothing at all when a Fill throws;
//  - datasets written together by rows (h5::write_datasets: the streamed models' table) are the same datasets too,
//    with windows shorter and longer than their chunks, and each row is asked for once, in order.
#include <hdf5.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <type_traits>
#include <numeric>
#include <string>
#include <vector>

#include "pounding/io/hdf5.hpp"
#include "temp_dir.hpp"

namespace {

using namespace pounding;

template <class T>
std::vector<T> ramp(std::size_t n) {  // compressible but not constant: a slow ramp with a wobble
  std::vector<T> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<T>((i / 7) % 251 + (i % 3));
  return v;
}

template <class T>
std::vector<T> read_back(hid_t file, const std::string& name);  // the engine's reader
template <>
std::vector<double> read_back<double>(hid_t f, const std::string& n) { return h5::read_doubles(f, n); }
template <>
std::vector<std::int64_t> read_back<std::int64_t>(hid_t f, const std::string& n) { return h5::read_int64(f, n); }
template <>
std::vector<std::int32_t> read_back<std::int32_t>(hid_t f, const std::string& n) { return h5::read_int32(f, n); }
template <>
std::vector<std::uint8_t> read_back<std::uint8_t>(hid_t f, const std::string& n) { return h5::read_uint8(f, n); }

template <class T>
constexpr h5::Type engine_type() {
  return std::is_same_v<T, double> ? h5::Type::f64 : std::is_same_v<T, std::int64_t> ? h5::Type::i64
         : std::is_same_v<T, std::int32_t> ? h5::Type::i32 : h5::Type::u8;
}

template <class T>
hid_t native_type();
template <>
hid_t native_type<double>() { return H5T_NATIVE_DOUBLE; }
template <>
hid_t native_type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <>
hid_t native_type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <>
hid_t native_type<std::uint8_t>() { return H5T_NATIVE_UINT8; }

// The stored (filtered) bytes of every chunk of dataset name, in chunk order.
std::vector<std::vector<unsigned char>> stored_chunks(hid_t file, const std::string& name) {
  h5::Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT));
  h5::Handle space(H5Dget_space(ds.get()));
  hsize_t count = 0;
  EXPECT_GE(H5Dget_num_chunks(ds.get(), space.get(), &count), 0);
  std::vector<std::vector<unsigned char>> out;
  for (hsize_t c = 0; c < count; ++c) {
    std::vector<hsize_t> offset(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.get())));
    unsigned mask = 0;
    haddr_t addr = 0;
    hsize_t size = 0;
    EXPECT_GE(H5Dget_chunk_info(ds.get(), space.get(), c, offset.data(), &mask, &addr, &size), 0);
    std::vector<unsigned char> bytes(size);
    std::uint32_t filters = 0;
    EXPECT_GE(H5Dread_chunk(ds.get(), H5P_DEFAULT, offset.data(), &filters, bytes.data()), 0);
    EXPECT_EQ(filters, 0u) << name << " chunk " << c << ": a filter was skipped";
    out.push_back(std::move(bytes));
  }
  return out;
}

template <class T>
void check_shape(std::vector<std::size_t> dims) {
  std::size_t total = 1;
  for (std::size_t d : dims) total *= d;
  const std::vector<T> values = ramp<T>(total);
  testdata::TempDir tmp("hdf5-chunks");
  const std::string path = tmp.file("chunks.h5");
  const std::string label = std::to_string(total) + " values of " + std::to_string(sizeof(T)) + " bytes";
  {
    h5::AtomicFile f(path);
    h5::write_dataset(f.root(), "engine", std::span<const T>(values), std::span<const std::size_t>(dims));
    // the same values from a Fill, which must be asked for whole rows only
    const std::size_t row = total && dims[0] ? total / dims[0] : 1;
    std::atomic<bool> cut{false};
    h5::write_dataset(f.root(), "filled", engine_type<T>(), std::span<const std::size_t>(dims),
                      [&](std::size_t first, std::size_t n, void* out) {
                        if (first % row || n % row || first + n > total) cut = true;
                        std::memcpy(out, values.data() + first, std::min(n, total - std::min(first, total)) * sizeof(T));
                      });
    EXPECT_FALSE(cut) << label << ": a Fill asked for part of a row";
    // the reference: the same creation properties, the values through HDF5's own filter pipeline
    h5::Handle engine(H5Dopen2(f.root(), "engine", H5P_DEFAULT));
    h5::Handle dcpl(H5Dget_create_plist(engine.get()));
    h5::Handle space(H5Dget_space(engine.get()));
    h5::Handle ref(H5Dcreate2(f.root(), "reference", native_type<T>(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
    ASSERT_GE(ref.get(), 0);
    // the layout of files before 2026-11-27: deflate at level 4 alone, chunks of up to 4 Mi values
    h5::Handle old_dcpl(H5Pcreate(H5P_DATASET_CREATE));
    if (total >= 4096) {
      std::vector<hsize_t> chunk(dims.begin(), dims.end());
      chunk[0] = std::min<hsize_t>({chunk[0], 65536, std::max<hsize_t>(1, (hsize_t{1} << 22) / (total / dims[0]))});
      ASSERT_GE(H5Pset_chunk(old_dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), 0);
      ASSERT_GE(H5Pset_deflate(old_dcpl.get(), 4), 0);
    }
    h5::Handle old(H5Dcreate2(f.root(), "old", native_type<T>(), space.get(), H5P_DEFAULT, old_dcpl.get(), H5P_DEFAULT));
    ASSERT_GE(old.get(), 0);
    if (total > 0) {
      ASSERT_GE(H5Dwrite(ref.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
      ASSERT_GE(H5Dwrite(old.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    }
    f.commit();
  }
  h5::Handle file = h5::open_read(path);
  for (const char* name : {"engine", "reference", "old", "filled"})
    EXPECT_EQ(read_back<T>(file.get(), name), values) << label << ": the engine's reader on '" << name << "'";

  std::vector<T> back(total);
  {
    h5::Handle ds(H5Dopen2(file.get(), "engine", H5P_DEFAULT));
    if (total > 0) {
      ASSERT_GE(H5Dread(ds.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()), 0);
    }
    EXPECT_EQ(back, values) << label << ": the values read back differ";
    h5::Handle dcpl(H5Dget_create_plist(ds.get()));
    const bool chunked = H5Pget_layout(dcpl.get()) == H5D_CHUNKED;
    EXPECT_EQ(chunked, total >= 4096) << label << ": compressed from 4096 values on";
    if (!chunked) return;
    std::vector<H5Z_filter_t> filters;
    for (int k = 0; k < H5Pget_nfilters(dcpl.get()); ++k) {
      unsigned flags = 0, config = 0;
      std::size_t n = 0;
      filters.push_back(H5Pget_filter2(dcpl.get(), static_cast<unsigned>(k), &flags, &n, nullptr, 0, nullptr, &config));
    }
    const std::vector<H5Z_filter_t> expected =
        sizeof(T) > 1 ? std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE} : std::vector<H5Z_filter_t>{H5Z_FILTER_DEFLATE};
    EXPECT_EQ(filters, expected) << label << ": the filter pipeline (shuffle for values wider than a byte, then deflate)";
  }
  const auto ours = stored_chunks(file.get(), "engine"), theirs = stored_chunks(file.get(), "reference");
  ASSERT_EQ(ours.size(), theirs.size()) << label;
  EXPECT_EQ(stored_chunks(file.get(), "filled"), ours) << label << ": the Fill's stored chunks differ from the in-memory write's";
  // chunks of about 2^14 values, so a large dataset is deflated on several CPUs
  EXPECT_GE(ours.size(), total > 32768 ? 2u : 1u) << label << ": one chunk only";
  for (std::size_t c = 0; c < ours.size(); ++c)
    EXPECT_EQ(ours[c], theirs[c]) << label << ": chunk " << c << " differs from HDF5's own deflate filter's";
}

TEST(Hdf5Chunks, OneDimensionalAroundTheThresholdAndTheChunkLength) {
  for (std::size_t n : {0u, 1u, 4095u, 4096u, 65536u, 65537u, 200003u}) {
    check_shape<double>({n});
    check_shape<std::int64_t>({n});
    check_shape<std::int32_t>({n});
    check_shape<std::uint8_t>({n});
  }
}

TEST(Hdf5Chunks, TwoDimensionalWithAPartialLastChunk) {
  check_shape<double>({70001, 3});
  check_shape<std::uint8_t>({131075, 7});
  check_shape<std::int32_t>({5, 1000});
  check_shape<std::uint8_t>({1100, 4000});  // 4.4 Mi values: chunks of 4 rows
  check_shape<double>({25, 30976});          // the paper study's peaks: a chunk per record row
  check_shape<double>({30976, 6});           // its gaps in metres: chunks of 2730 rows, the last one partial
}

// The reader takes the chunks in batches of 256 (read on one thread while the batch before is inflated): several
// batches, the last one partial and ending in a partial chunk.
TEST(Hdf5Chunks, ManyBatchesOfChunks) {
  check_shape<std::uint8_t>({16384 * 530 + 11});
  check_shape<double>({16384 * 260 + 5});
}

// Storage::disk: the file is built in <path>.tmp<pid> and renamed by commit(); destroyed without commit(), or after a
// Fill threw half-way through a dataset of several windows, nothing is left in the folder.
TEST(Hdf5Chunks, OnDiskFileLeavesNothingButTheCommittedFile) {
  namespace fs = std::filesystem;
  testdata::TempDir tmp("hdf5-disk");
  const std::string path = tmp.file("disk.h5");
  const auto files = [&] {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(fs::path(path).parent_path())) names.push_back(e.path().filename().string());
    return names;
  };
  const std::vector<double> v = ramp<double>(16384 * 1100);  // 1100 chunks of 128 KiB: three windows of 64 MiB
  const std::size_t dims[] = {1100, 16384};
  {
    h5::AtomicFile f(path, h5::AtomicFile::Storage::disk);
    EXPECT_EQ(files().size(), 1u);
    EXPECT_NE(files().at(0).find("disk.h5.tmp"), std::string::npos) << files().at(0);
    std::size_t calls = 0;
    EXPECT_THROW(h5::write_dataset(f.root(), "x", h5::Type::f64, dims,
                                   [&](std::size_t first, std::size_t n, void* out) {
                                     if (first >= 16384 * 700) throw std::runtime_error("fill failed");
                                     ++calls;
                                     std::memcpy(out, v.data() + first, n * sizeof(double));
                                   }),
                 std::runtime_error);
    EXPECT_GE(calls, 512u) << "the failure came before the second window";
  }
  EXPECT_TRUE(files().empty()) << "left after a failed Fill: " << files().at(0);
  {
    h5::AtomicFile f(path, h5::AtomicFile::Storage::disk);
    h5::write_dataset(f.root(), "x", h5::Type::f64, dims,
                      [&](std::size_t first, std::size_t n, void* out) { std::memcpy(out, v.data() + first, n * sizeof(double)); });
    f.commit();
  }
  ASSERT_EQ(files(), std::vector<std::string>{"disk.h5"});
  h5::Handle file = h5::open_read(path);
  EXPECT_EQ(h5::read_doubles(file.get(), "x"), v);
}

// h5::write_datasets: four datasets of 70,001 rows (chunks of 16,384, 2,340, 5,461 and 70,001 rows) written in
// windows of 1,000 rows (a chunk spans many windows) and of 65,536 rows (a window holds many chunks), and a set of
// 500 rows whose first three datasets are contiguous (under 4096 values): each equals write_dataset's, stored chunks included.
TEST(Hdf5Chunks, SeveralDatasetsWrittenByRows) {
  testdata::TempDir tmp("hdf5-rows");
  const std::string path = tmp.file("rows.h5");
  for (const std::size_t rows : {std::size_t{70001}, std::size_t{500}}) {
    const std::vector<double> a = ramp<double>(rows);
    const std::vector<std::uint8_t> b = ramp<std::uint8_t>(rows * 7);
    const std::vector<std::int32_t> c = ramp<std::int32_t>(rows * 3);
    const std::vector<std::int64_t> d = ramp<std::int64_t>(rows * 9);
    for (const std::size_t window : {std::size_t{1000}, std::size_t{65536}}) {
      {
        h5::AtomicFile f(path, h5::AtomicFile::Storage::disk);
        const std::size_t da[] = {rows}, db[] = {rows, 7}, dc[] = {rows, 3}, dd[] = {rows, 9};
        h5::write_dataset(f.root(), "a", std::span<const double>(a), da);
        h5::write_dataset(f.root(), "b", std::span<const std::uint8_t>(b), db);
        h5::write_dataset(f.root(), "c", std::span<const std::int32_t>(c), dc);
        h5::write_dataset(f.root(), "d", std::span<const std::int64_t>(d), dd);
        const std::vector<h5::RowsDataset> sets{{f.root(), "ra", h5::Type::f64, {rows}},
                                                {f.root(), "rb", h5::Type::u8, {rows, 7}},
                                                {f.root(), "rc", h5::Type::i32, {rows, 3}},
                                                {f.root(), "rd", h5::Type::i64, {rows, 9}}};
        std::size_t next = 0;
        h5::write_datasets(
            sets,
            [&](std::size_t first, std::size_t n, std::span<void* const> out) {
              EXPECT_EQ(first, next) << "rows asked out of order or twice";
              next = first + n;
              std::memcpy(out[0], a.data() + first, n * sizeof(double));
              std::memcpy(out[1], b.data() + first * 7, n * 7);
              std::memcpy(out[2], c.data() + first * 3, n * 3 * sizeof(std::int32_t));
              std::memcpy(out[3], d.data() + first * 9, n * 9 * sizeof(std::int64_t));
            },
            window);
        EXPECT_EQ(next, rows);
        f.commit();
      }
      h5::Handle file = h5::open_read(path);
      const std::string label = std::to_string(rows) + " rows, windows of " + std::to_string(window);
      EXPECT_EQ(h5::read_doubles(file.get(), "ra"), a) << label;
      EXPECT_EQ(h5::read_uint8(file.get(), "rb"), b) << label;
      EXPECT_EQ(h5::read_int32(file.get(), "rc"), c) << label;
      EXPECT_EQ(h5::read_int64(file.get(), "rd"), d) << label;
      for (const char* name : {"a", "b", "c", "d"}) {
        EXPECT_EQ(h5::dataset_shape(file.get(), std::string("r") + name), h5::dataset_shape(file.get(), name)) << label;
        h5::Handle ds(H5Dopen2(file.get(), name, H5P_DEFAULT));
        h5::Handle dcpl(H5Dget_create_plist(ds.get()));
        if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED) {  // under 4096 values: a, b, c at 500 rows
          EXPECT_TRUE(rows == 500 && std::string(name) != "d") << label << ": " << name << " is contiguous";
          continue;
        }
        EXPECT_EQ(stored_chunks(file.get(), std::string("r") + name), stored_chunks(file.get(), name)) << label << " " << name;
      }
    }
  }
}

// h5::read_doubles_if_constant: the values when all equal the first (a compressed column read whole, a small one
// contiguous), nullopt when one differs -- in the first chunk, the last chunk's last value, a NaN anywhere.
TEST(Hdf5Chunks, ReadDoublesIfConstant) {
  testdata::TempDir tmp("hdf5-constant");
  const std::string path = tmp.file("constant.h5");
  const std::size_t n = 16384 * 5 + 7;
  const std::vector<double> same(n, 2.5);
  std::vector<double> first = same, last = same, nan = same;
  first[3] = 2.0, last.back() = 2.5000000000000004, nan[n / 2] = NAN;
  const std::vector<double> small(100, -1.0);
  {
    h5::AtomicFile f(path);
    for (const auto& [name, v] : {std::pair{"same", &same}, {"first", &first}, {"last", &last}, {"nan", &nan}, {"small", &small}})
      h5::write_dataset(f.root(), name, std::span<const double>(*v));
    f.commit();
  }
  h5::Handle file = h5::open_read(path);
  const auto got = h5::read_doubles_if_constant(file.get(), "same");
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(*got, same);
  for (const char* name : {"first", "last", "nan"}) EXPECT_FALSE(h5::read_doubles_if_constant(file.get(), name).has_value()) << name;
  const auto s = h5::read_doubles_if_constant(file.get(), "small");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(*s, small);
}

}  // namespace
