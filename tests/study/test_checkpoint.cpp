// The checkpoint (include/pounding/study/checkpoint.hpp) and atomic files (files.hpp): torn records, refusals,
// the lock, write failures that keep the file resumable, atomic replacement.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>

#include "pounding/study/checkpoint.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace pounding;

namespace {

struct TempDir : testdata::TempDir {
  TempDir() : testdata::TempDir("ckpt") {}
};

CheckpointKey key(std::uint64_t study = 11, std::uint64_t units = 100, std::uint64_t build = 5) {
  CheckpointKey k;
  k.study_hash = study, k.units = units, k.build_hash = build, k.build = "test build " + std::to_string(build);
  return k;
}

// 32 bytes of a unit's serialised result (the checkpoint stores them unchanged)
std::vector<std::byte> payload(std::size_t unit) {
  const double v[4] = {double(unit), 0.5 * double(unit), -1.0, 1e-300};
  const auto* p = reinterpret_cast<const std::byte*>(v);
  return {p, p + sizeof v};
}

// Runs `fn` under a file-size limit with SIGXFSZ ignored, restoring both afterwards.
template <class F>
void with_file_size_limit(rlim_t bytes, F&& fn) {
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit lim = old;
  lim.rlim_cur = bytes;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &lim), 0);
  fn();
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
}

}  // namespace

TEST(Checkpoint, RoundTripAndTornLastRecordDropped) {
  TempDir t;
  const std::string p = t.file("r.h5.ckpt");
  {
    Checkpoint c(p);
    open_for_run(c, key(), false, false, {});
    for (std::size_t u : {3, 7, 42}) c.append(u, payload(u));
  }
  const auto full = fs::file_size(p);
  fs::resize_file(p, full - 5);  // kill -9 in the middle of the last record
  std::map<std::size_t, std::vector<std::byte>> got;
  Checkpoint c(p);
  EXPECT_EQ(open_for_run(c, key(), true, false, [&](std::size_t u, std::vector<std::byte>&& d) { got[u] = d; }), 2u);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[3], payload(3));
  EXPECT_EQ(got[7], payload(7));
  EXPECT_EQ(got.count(42), 0u);
  // the torn tail is cut, and appending continues a valid file
  c.append(42, payload(42));
  EXPECT_EQ(fs::file_size(p), full);
}

TEST(Checkpoint, CorruptedRecordEndsTheValidPrefix) {
  TempDir t;
  const std::string p = t.file("c.ckpt");
  {
    Checkpoint c(p);
    open_for_run(c, key(), false, false, {});
    for (std::size_t u = 0; u < 5; ++u) c.append(u, payload(u));
  }
  // flip one byte inside the third record's data
  const std::size_t header = 40 + key().build.size(), rec = 24 + 4 * 8;
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(header + 2 * rec + 20));
  f.put('\x7f');
  f.close();
  Checkpoint c(p);
  const CheckpointScan s = c.scan(key());
  EXPECT_EQ(s.kind, CheckpointScan::Kind::ours);
  EXPECT_EQ(s.units_done, 2u);
}

TEST(Checkpoint, RefusesToDiscardProgressWithoutForce) {
  TempDir t;
  const std::string p = t.file("p.ckpt");
  {
    Checkpoint c(p);
    open_for_run(c, key(11, 3025), false, false, {});
    for (std::size_t u = 0; u < 812; ++u) c.append(u, payload(u));
  }
  const auto size = fs::file_size(p);
  {
    Checkpoint c(p);
    try {
      open_for_run(c, key(11, 3025), false, false, {});
      FAIL() << "a fresh run discarded progress";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("holds 812 of 3,025 units of this study"), std::string::npos) << e.what();
      EXPECT_NE(e.fix().find("--resume to continue or --force to discard it"), std::string::npos) << e.fix();
    }
  }
  EXPECT_EQ(fs::file_size(p), size);
  {
    Checkpoint c(p);
    EXPECT_THROW(open_for_run(c, key(99, 3025), false, false, {}), InputError);  // another study's progress too
  }
  {
    Checkpoint c(p);  // this study cut into other units (another batch, e.g. the impacts scene's default 256 -> 64)
    try {
      open_for_run(c, key(11, 12100), false, false, {});
      FAIL() << "a fresh run discarded another batch's progress";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("holds 812 units of this study cut into 3,025 units, this run into 12,100 "
                                           "(another [analysis] batch)"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(fs::file_size(p), size);
  Checkpoint c(p);
  EXPECT_EQ(open_for_run(c, key(11, 3025), false, true, {}), 0u);  // --force
  EXPECT_EQ(c.scan(key(11, 3025)).units_done, 0u);
}

TEST(Checkpoint, ResumeRefusesOtherStudyOtherBuildNothingAndOldFormat) {
  TempDir t;
  const std::string p = t.file("o.ckpt");
  {
    Checkpoint c(p);
    open_for_run(c, key(), false, false, {});
    c.append(1, payload(1));
  }
  auto message = [&](const CheckpointKey& k) {
    Checkpoint c(p);
    try {
      open_for_run(c, k, true, false, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(key(12)).find("different study"), std::string::npos);
  // the same study text cut into other units: another batch (the impacts scene's default changed from 256 to 64)
  const std::string recut = message(key(11, 101));
  EXPECT_NE(recut.find("cuts this study into 100 work units and this run into 101"), std::string::npos) << recut;
  EXPECT_NE(recut.find("[analysis] batch"), std::string::npos) << recut;
  const std::string other_build = message(key(11, 100, 6));
  EXPECT_NE(other_build.find("different build"), std::string::npos) << other_build;
  EXPECT_NE(other_build.find("test build 5"), std::string::npos) << other_build;  // names the writer's build
  EXPECT_EQ(message(key()), "accepted");
  std::ofstream(p, std::ios::binary) << "PNDCKPT1" << std::string(16, '\0');
  EXPECT_NE(message(key()).find("format 1"), std::string::npos);
  std::ofstream(p, std::ios::binary) << "PNDCKPT2" << std::string(16, '\0');  // payloads of doubles
  EXPECT_NE(message(key()).find("format 2"), std::string::npos);
  std::ofstream(p, std::ios::binary) << "PNDCKPT3" << std::string(16, '\0');  // FNV-1a checksums
  EXPECT_NE(message(key()).find("format 3"), std::string::npos);
  std::ofstream(p, std::ios::binary) << "hello, world";
  EXPECT_NE(message(key()).find("not a pounding checkpoint"), std::string::npos);
  fs::remove(p);
  EXPECT_NE(message(key()).find("no checkpoint to resume from"), std::string::npos);
  EXPECT_FALSE(fs::exists(p)) << "a failed --resume left an empty checkpoint behind";
}

TEST(Checkpoint, ExclusiveLockNamesTheHolder) {
  TempDir t;
  const std::string p = t.file("l.ckpt");
  Checkpoint first(p);
  try {
    Checkpoint second(p);
    FAIL() << "two holders of one checkpoint";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is in use by process " + std::to_string(getpid())), std::string::npos)
        << e.what();
  }
}

TEST(Checkpoint, FailedAppendKeepsTheFileResumable) {
  TempDir t;
  const std::string p = t.file("f.ckpt");
  std::uint64_t appended = 0;
  {
    Checkpoint c(p);
    open_for_run(c, key(), false, false, {});
    with_file_size_limit(1000, [&] {
      try {
        for (std::size_t u = 0; u < 100; ++u, ++appended) c.append(u, payload(u));
        ADD_FAILURE() << "no error at the file-size limit";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("EFBIG"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
      }
    });
  }
  ASSERT_GT(appended, 0u);
  Checkpoint c(p);
  const CheckpointScan s = c.scan(key());
  EXPECT_EQ(s.kind, CheckpointScan::Kind::ours);
  EXPECT_EQ(s.units_done, appended);
  EXPECT_EQ(s.good_bytes, fs::file_size(p)) << "a partial record was left at the end";
}

// Format 5 (issue 27.5, [outputs] per_model = false): one snapshot per file, replaced whole. Its size is the counts'
// and summary's plus a bit per unit, the lock survives every save (the new file is locked before the rename), and a
// resume reads back exactly what was saved.
namespace {
ReductionSnapshot snapshot(std::initializer_list<std::size_t> units, std::size_t total = 100) {
  ReductionSnapshot s;
  s.counts = {7, 0, -3, 1LL << 40};
  s.summary = {1.0, 0.0, 0.01, 0.25};
  s.done.assign((total + 7) / 8, 0);
  for (std::size_t u : units) s.done[u / 8] = static_cast<std::uint8_t>(s.done[u / 8] | (1u << (u % 8)));
  return s;
}
}  // namespace

TEST(CheckpointSnapshot, SavedWholeLockedAndReadBack) {
  TempDir t;
  const std::string p = t.file("s.h5.ckpt");
  const std::size_t header = 40 + key().build.size();
  {
    Checkpoint c(p, true);
    open_for_run(c, key(), false, false, {});  // an empty snapshot: no unit
    EXPECT_EQ(fs::file_size(p), header + 24 + 8);
    c.save(snapshot({3, 7}));
    c.save(snapshot({3, 7, 42, 99}));  // replaced, not appended
    EXPECT_EQ(fs::file_size(p), header + 24 + 4 * 8 + 4 * 8 + 13 + 8);
    try {
      Checkpoint other(p, true);
      ADD_FAILURE() << "the lock lapsed with the rename";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("in use by process"), std::string::npos) << e.what();
    }
    for (const auto& e : fs::directory_iterator(t.dir))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "temporary left: " << e.path();
  }
  {
    ReductionSnapshot got;
    int delivered = 0;
    Checkpoint c(p, true);
    EXPECT_EQ(open_for_run(c, key(), true, false, {}, nullptr,
                           [&](ReductionSnapshot&& s) { got = std::move(s), ++delivered; }),
              4u);
    EXPECT_EQ(delivered, 1);
    EXPECT_EQ(got.counts, snapshot({}).counts);
    EXPECT_EQ(got.summary, snapshot({}).summary);
    EXPECT_EQ(got.done, snapshot({3, 7, 42, 99}).done);
    EXPECT_TRUE(got.has(99) && got.has(3) && !got.has(4));
  }
  // a fresh run refuses to discard the snapshot's progress, as it refuses unit records
  Checkpoint c(p, true);
  EXPECT_THROW(open_for_run(c, key(), false, false, {}), InputError);
}

TEST(CheckpointSnapshot, DamagedIsRefusedNamingTheFile) {
  TempDir t;
  const std::string p = t.file("d.h5.ckpt");
  {
    Checkpoint c(p, true);
    open_for_run(c, key(), false, false, {});
    c.save(snapshot({1, 2, 3}));
  }
  auto resume = [&]() -> std::string {
    Checkpoint c(p, true);
    try {
      open_for_run(c, key(), true, false, {}, nullptr, [](ReductionSnapshot&&) {});
    } catch (const InputError& e) {
      return std::string(e.what()) + " | " + e.fix();
    }
    return "accepted";
  };
  EXPECT_EQ(resume(), "accepted");
  {  // one flipped bit inside the counts
    std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(40 + key().build.size() + 24 + 3));
    f.put('\x01');
  }
  const std::string flipped = resume();
  EXPECT_NE(flipped.find("damaged"), std::string::npos) << flipped;
  EXPECT_NE(flipped.find(p), std::string::npos) << flipped;
  EXPECT_NE(flipped.find("--force"), std::string::npos) << flipped;
  fs::resize_file(p, fs::file_size(p) - 5);  // cut short
  EXPECT_NE(resume().find("damaged"), std::string::npos);
  Checkpoint c(p, true);
  try {  // a fresh run does not overwrite it silently either
    open_for_run(c, key(), false, false, {});
    ADD_FAILURE() << "a damaged snapshot was overwritten without --force";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damaged"), std::string::npos) << e.what();
  }
}

// A snapshot met by a per_model = true run is refused as reductions-only; unit records (a per_model = false run of a
// build before format 5) still resume into a run with snapshots, and its next save turns the file into a snapshot.
TEST(CheckpointSnapshot, KindsMixed) {
  TempDir t;
  const std::string p = t.file("m.h5.ckpt");
  {
    Checkpoint c(p, true);
    open_for_run(c, key(), false, false, {});
    c.save(snapshot({5}));
  }
  {
    Checkpoint c(p);
    try {
      open_for_run(c, key(), true, false, {});
      ADD_FAILURE() << "a snapshot resumed per model";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("reductions only"), std::string::npos) << e.what();
    }
  }
  fs::remove(p);
  {
    Checkpoint c(p);
    open_for_run(c, key(), false, false, {});
    for (std::size_t u : {4, 8}) c.append(u, payload(u));
  }
  std::vector<std::size_t> units;
  Checkpoint c(p, true);
  EXPECT_EQ(open_for_run(c, key(), true, false, [&](std::size_t u, std::vector<std::byte>&&) { units.push_back(u); }),
            2u);
  EXPECT_EQ(units, (std::vector<std::size_t>{4, 8}));
  c.save(snapshot({4, 8}));
  EXPECT_EQ(c.scan(key()).format, 5);
  EXPECT_EQ(c.scan(key()).units_done, 2u);
}

TEST(AtomicFile, ReplacesWholeOrNotAtAll) {
  TempDir t;
  const std::string p = t.file("a.bin");
  std::vector<std::byte> big(64 * 1024, std::byte{1}), small(10, std::byte{2});
  files::write_atomically(p, small);
  EXPECT_EQ(fs::file_size(p), 10u);
  with_file_size_limit(4096, [&] { EXPECT_THROW(files::write_atomically(p, big), InputError); });
  EXPECT_EQ(fs::file_size(p), 10u) << "the old file must survive a failed replacement";
  for (const auto& e : fs::directory_iterator(t.dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "temporary left: " << e.path();
  files::write_atomically(p, big);
  EXPECT_EQ(fs::file_size(p), big.size());
}

TEST(OutputPath, ProblemsFoundBeforeWork) {
  TempDir t;
  EXPECT_THROW(files::check_output_path("", "--out"), InputError);
  EXPECT_THROW(files::check_output_path(t.dir.string() + "/", "--out"), InputError);
  EXPECT_THROW(files::check_output_path(t.dir.string(), "--out"), InputError);
  EXPECT_THROW(files::check_output_path(t.file("missing/r.h5"), "--out"), InputError);
  EXPECT_THROW(files::check_output_path("/dev/null", "--out"), InputError);
  EXPECT_NO_THROW(files::check_output_path(t.file("r.h5"), "--out"));
  EXPECT_FALSE(fs::exists(t.file("r.h5")));
  EXPECT_EQ(std::distance(fs::directory_iterator(t.dir), fs::directory_iterator{}), 0) << "the probe was left";
}

// XXH64 against the reference implementation: xxhsum -H64 0.8.1 (Debian package xxhash) on these bytes.
TEST(Xxh64, ReferenceVectors) {
  EXPECT_EQ(files::xxh64("", 0), 0xef46db3751d8e999ULL);
  EXPECT_EQ(files::xxh64("a", 1), 0xd24ec4f1a98c6e5bULL);
  EXPECT_EQ(files::xxh64("foobar", 6), 0xa2aa05ed9085aaf9ULL);
  EXPECT_EQ(files::xxh64("123456789", 9), 0x8cb841db40e6ae83ULL);
  std::string m37, big;  // 37 bytes: one 32-byte stripe + 4 + 1; 6,403 bytes: stripes + 8 + 3 (a unit's size)
  for (int i = 0; i < 37; ++i) m37.push_back(static_cast<char>((i * 31 + 1) % 256));
  for (int i = 0; i < 6403; ++i) big.push_back(static_cast<char>((i * 131 + 7) % 256));
  EXPECT_EQ(files::xxh64(m37.data(), m37.size()), 0x25f40690a522ac93ULL);
  EXPECT_EQ(files::xxh64(big.data(), big.size()), 0xaf2f37993e7d7128ULL);
  // every single-bit flip of a record changes its checksum (each byte position, stripes and tail)
  for (std::size_t i = 0; i < m37.size(); ++i) {
    std::string c = m37;
    c[i] = static_cast<char>(c[i] ^ (1 << (i % 8)));
    EXPECT_NE(files::xxh64(c.data(), c.size()), files::xxh64(m37.data(), m37.size())) << "byte " << i;
  }
}

TEST(Fnv1a, PublishedTestVectors) {  // Fowler-Noll-Vo reference vectors for 64-bit FNV-1a
  EXPECT_EQ(files::fnv1a("", 0), 0xcbf29ce484222325ULL);
  EXPECT_EQ(files::fnv1a("a", 1), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(files::fnv1a("foobar", 6), 0x85944171f73967e8ULL);
}
