// The run's checkpoint <out>.ckpt: finished units appended by rank 0, read back by --resume.
#include "pounding/study/checkpoint.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/version.hpp"

namespace pounding {

namespace {

// Format 4 (issue 27.4): records checksummed with XXH64 (format 3: the same layout with FNV-1a, ~30x slower per byte).
constexpr char magic_v4[8] = {'P', 'N', 'D', 'C', 'K', 'P', 'T', '4'};
constexpr char magic_v5[8] = {'P', 'N', 'D', 'C', 'K', 'P', 'T', '5'};  // snapshots ([outputs] per_model = false)
constexpr char magic_old[7] = {'P', 'N', 'D', 'C', 'K', 'P', 'T'};  // + '1' or '2': payloads of doubles; '3': FNV-1a
constexpr std::uint64_t max_payload = 1ULL << 31;  // bytes per unit: far above any real unit

// The process holding a flock on (dev, ino), from /proc/locks (Linux); 0 if unknown.
long lock_holder(int fd) {
  struct stat st {};
  if (fstat(fd, &st) != 0) return 0;
  std::ifstream in("/proc/locks");
  const std::string id = fmt::format("{:02x}:{:02x}:{}", major(st.st_dev), minor(st.st_dev), st.st_ino);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream is(line);
    std::string num, type, mode, rw, dev;
    long pid = 0;
    is >> num >> type;
    if (type == "->") is >> type;  // a blocked waiter
    is >> mode >> rw >> pid >> dev;
    if (type == "FLOCK" && dev == id) return pid;
  }
  return 0;
}

std::string human(std::uint64_t n) {  // 3025 -> "3,025"
  const std::string d = std::to_string(n);
  std::string s;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (i > 0 && (d.size() - i) % 3 == 0) s += ',';
    s += d[i];
  }
  return s;
}

std::uint64_t record_checksum(std::uint64_t unit, std::uint64_t count, const std::byte* data) {
  const std::uint64_t head[2] = {unit, count};
  return files::xxh64(data, count, files::xxh64(head, sizeof head));
}

std::string header_bytes(const char (&magic)[8], const CheckpointKey& key) {
  std::string head(magic, 8);
  const std::uint64_t blen = key.build.size();
  for (std::uint64_t v : {key.study_hash, key.units, key.build_hash, blen})
    head.append(reinterpret_cast<const char*>(&v), 8);
  return head + key.build;
}

template <class T>
void put(std::string& out, const std::vector<T>& v) {
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// Format 5: the header, three lengths, the arrays, XXH64 of everything before it.
std::string encode_snapshot(const CheckpointKey& key, const ReductionSnapshot& s) {
  std::string out = header_bytes(magic_v5, key);
  for (std::uint64_t n : {std::uint64_t{s.counts.size()}, std::uint64_t{s.summary.size()}, std::uint64_t{s.done.size()}})
    out.append(reinterpret_cast<const char*>(&n), 8);
  put(out, s.counts), put(out, s.summary), put(out, s.done);
  const std::uint64_t sum = files::xxh64(out.data(), out.size());
  out.append(reinterpret_cast<const char*>(&sum), 8);
  return out;
}

template <class T>
std::uint64_t get(const std::string& b, std::size_t at) {
  T v{};
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

// Reads a whole format-5 file `b` (magic checked): "" and the snapshot, or why it is damaged.
std::string decode_snapshot(const std::string& b, std::uint64_t& study, std::uint64_t& units, std::uint64_t& build_hash,
                            std::string& build, ReductionSnapshot& s) {
  if (b.size() < 40 + 24 + 8) return fmt::format("it is {} bytes long, shorter than any snapshot", b.size());
  if (files::xxh64(b.data(), b.size() - 8) != get<std::uint64_t>(b, b.size() - 8))
    return "its checksum does not match its bytes (damaged or cut short)";
  study = get<std::uint64_t>(b, 8), units = get<std::uint64_t>(b, 16), build_hash = get<std::uint64_t>(b, 24);
  const std::uint64_t blen = get<std::uint64_t>(b, 32);
  if (blen > 4096 || 40 + blen + 24 + 8 > b.size()) return "its header is impossible";
  build = b.substr(40, blen);
  std::size_t at = 40 + blen;
  const std::uint64_t nc = get<std::uint64_t>(b, at), ns = get<std::uint64_t>(b, at + 8), nd = get<std::uint64_t>(b, at + 16);
  at += 24;
  if (nc > b.size() / 8 || ns > b.size() / 8 || at + 8 * nc + 8 * ns + nd + 8 != b.size() ||
      (nd != 0 && nd != (units + 7) / 8))
    return "its lengths do not add up to its size";
  s.counts.resize(nc), s.summary.resize(ns), s.done.resize(nd);
  std::memcpy(s.counts.data(), b.data() + at, 8 * nc);
  std::memcpy(s.summary.data(), b.data() + at + 8 * nc, 8 * ns);
  std::memcpy(s.done.data(), b.data() + at + 8 * nc + 8 * ns, nd);
  if (nd && units % 8 && (s.done.back() >> (units % 8)) != 0) return "it marks units beyond the study's";
  return "";
}

// A format-5 file (magic read): its kind for `key`, and the snapshot when wanted.
CheckpointScan scan_snapshot(const std::string& path, const CheckpointKey& key, CheckpointScan s,
                             ReductionSnapshot* out) {
  s.format = 5;
  const std::string b = files::read_text(path, "the checkpoint", std::size_t{1} << 40);
  ReductionSnapshot snap;
  std::uint64_t h = 0, n = 0, bh = 0;
  s.stopped_at = decode_snapshot(b, h, n, bh, s.build, snap);
  s.good_bytes = s.file_bytes = b.size();
  if (!s.stopped_at.empty()) {
    s.kind = CheckpointScan::Kind::damaged;
    return s;
  }
  s.units_total = n;
  s.units_done = snap.units_done();
  s.same_text = h == key.study_hash;
  s.kind = h != key.study_hash || n != key.units ? CheckpointScan::Kind::other_study
           : bh == key.build_hash               ? CheckpointScan::Kind::ours
                                                : CheckpointScan::Kind::other_build;
  if (out && s.kind == CheckpointScan::Kind::ours) *out = std::move(snap);
  return s;
}

}  // namespace

std::uint64_t ReductionSnapshot::units_done() const {
  std::uint64_t n = 0;
  for (std::uint8_t b : done) n += static_cast<std::uint64_t>(__builtin_popcount(b));
  return n;
}

CheckpointKey this_build() {
  CheckpointKey k;
  k.build = fmt::format("pounding {} (commit {}), {}", program_version, git_commit,
#if defined(__clang__)
                        "clang " __clang_version__
#elif defined(__GNUC__)
                        "GCC " __VERSION__
#else
                        "unknown compiler"
#endif
  );
#if defined(__AVX512F__)
  k.build += ", AVX-512";
#elif defined(__AVX2__)
  k.build += ", AVX2";
#elif defined(__SSE2__)
  k.build += ", SSE2";
#endif
#if defined(__FMA__)
  k.build += "+FMA";
#endif
  // the executable's bytes: any rebuild that can change a result changes them
  std::ifstream exe("/proc/self/exe", std::ios::binary);
  if (exe) {
    std::vector<char> buf(1 << 20);
    std::uint64_t h = 0;  // XXH64 chained over 1 MiB reads (FNV-1a took ~20 ms of every rank's start on 5 MB)
    while (exe.read(buf.data(), static_cast<std::streamsize>(buf.size())) || exe.gcount() > 0)
      h = files::xxh64(buf.data(), static_cast<std::size_t>(exe.gcount()), h);
    k.build_hash = h;
  } else {
    k.build_hash = files::fnv1a(k.build.data(), k.build.size());
  }
  return k;
}

Checkpoint::Checkpoint(std::string path, bool snapshots) : path_(std::move(path)), snapshots_(snapshots) {
  // a checkpoint is read back: a FIFO here (a worker's slice too) would block the first read forever, deaf to
  // SIGTERM; a device would be written to
  files::check_replaceable(path_, path_, "remove it (a checkpoint is a regular file that pounding writes and reads "
                                         "back), or give another --out");
  created_ = ::access(path_.c_str(), F_OK) != 0;
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot open the checkpoint: {}", std::strerror(err)), path_,
                     "check that the output folder exists and is writable");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const long pid = lock_holder(fd_);
    ::close(fd_);
    fd_ = -1;
    created_ = false;
    throw InputError(pid > 0 ? fmt::format("{} is in use by process {}", path_, pid)
                             : fmt::format("{} is in use by another process", path_),
                     path_,
                     "wait for that run to finish, or stop it, or give another --out; two runs must not share "
                     "one output");
  }
}

Checkpoint::~Checkpoint() {
  if (fd_ < 0) return;
  // a checkpoint that never held a unit of this run holds nothing worth keeping
  if (created_ && units_ == 0) ::unlink(path_.c_str());
  ::close(fd_);  // releases the lock
}

CheckpointScan Checkpoint::scan(const CheckpointKey& key, const UnitFn& on_unit, ReductionSnapshot* snapshot) {
  return scan_checkpoint(path_, key, on_unit, snapshot);
}

std::string slice_path(const std::string& main, int rank) { return main + ".rank" + std::to_string(rank); }

std::vector<std::string> slice_paths(const std::string& main) {
  namespace fs = std::filesystem;
  const fs::path p(main);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string stem = p.filename().string() + ".rank";
  std::vector<std::pair<long, std::string>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) continue;
    if (name.find_first_not_of("0123456789", stem.size()) != std::string::npos || name.size() > stem.size() + 9) continue;
    const long r = std::stol(name.substr(stem.size()));
    if (r >= 1) found.emplace_back(r, slice_path(main, static_cast<int>(r)));
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

namespace {
CheckpointScan scan_file(const std::string& path_, const CheckpointKey& key, const Checkpoint::UnitFn& on_unit,
                         ReductionSnapshot* snapshot, const UnitAtFn& on_at) {
  CheckpointScan s;
  std::ifstream in(path_, std::ios::binary);
  {
    struct stat st {};
    if (::stat(path_.c_str(), &st) == 0) s.file_bytes = static_cast<std::uint64_t>(st.st_size);
  }
  char m[8] = {};
  in.read(m, 8);
  if (in.gcount() == 0) return s;  // empty
  if (!in) {
    s.kind = CheckpointScan::Kind::not_checkpoint;
    return s;
  }
  if (std::memcmp(m, magic_old, 7) == 0 && (m[7] == '1' || m[7] == '2' || m[7] == '3')) {
    s.kind = CheckpointScan::Kind::old_format;
    s.format = m[7] - '0';
    return s;
  }
  if (std::memcmp(m, magic_v5, 8) == 0) return scan_snapshot(path_, key, s, snapshot);
  if (std::memcmp(m, magic_v4, 8) != 0) {
    s.kind = CheckpointScan::Kind::not_checkpoint;
    return s;
  }
  std::uint64_t h = 0, n = 0, bh = 0, blen = 0;
  in.read(reinterpret_cast<char*>(&h), 8);
  in.read(reinterpret_cast<char*>(&n), 8);
  in.read(reinterpret_cast<char*>(&bh), 8);
  in.read(reinterpret_cast<char*>(&blen), 8);
  if (!in || blen > 4096) {
    s.kind = CheckpointScan::Kind::not_checkpoint;
    return s;
  }
  s.build.resize(blen);
  in.read(s.build.data(), static_cast<std::streamsize>(blen));
  if (!in) {
    s.kind = CheckpointScan::Kind::not_checkpoint;
    return s;
  }
  s.units_total = n;
  s.format = 4;
  s.same_text = h == key.study_hash;
  if (h != key.study_hash || n != key.units) {
    s.kind = CheckpointScan::Kind::other_study;
  } else {
    s.kind = bh == key.build_hash ? CheckpointScan::Kind::ours : CheckpointScan::Kind::other_build;
  }
  s.good_bytes = 40 + blen;
  const bool deliver = s.kind == CheckpointScan::Kind::ours && on_unit;
  const bool locate = s.kind == CheckpointScan::Kind::ours && on_at;
  std::vector<std::byte> data;
  for (;;) {
    std::uint64_t unit = 0, count = 0, sum = 0;
    in.read(reinterpret_cast<char*>(&unit), 8);
    in.read(reinterpret_cast<char*>(&count), 8);
    if (!in) break;  // the end (or a torn record header)
    if (count > max_payload || unit >= n) {
      s.stopped_at = fmt::format("record {} has an impossible {} (damaged)", s.units_done + 1,
                                 unit >= n ? fmt::format("unit number {}", unit) : fmt::format("length {}", count));
      break;
    }
    data.resize(count);
    in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(count));
    in.read(reinterpret_cast<char*>(&sum), 8);
    if (!in) {
      s.stopped_at = fmt::format("record {} is cut short (a run killed while writing it)", s.units_done + 1);
      break;
    }
    if (record_checksum(unit, count, data.data()) != sum) {
      s.stopped_at = fmt::format("record {} (unit {}) fails its checksum (damaged bytes)", s.units_done + 1, unit);
      break;
    }
    if (locate) on_at(static_cast<std::size_t>(unit), s.good_bytes + 16, count);
    s.good_bytes += 24 + count;
    ++s.units_done;
    if (deliver) on_unit(static_cast<std::size_t>(unit), std::move(data));
  }
  return s;
}
}  // namespace

CheckpointScan scan_checkpoint(const std::string& path, const CheckpointKey& key, const Checkpoint::UnitFn& on_unit,
                               ReductionSnapshot* snapshot) {
  return scan_file(path, key, on_unit, snapshot, {});
}

CheckpointScan locate_units(const std::string& path, const CheckpointKey& key, const UnitAtFn& on_at) {
  return scan_file(path, key, {}, nullptr, on_at);
}

void Checkpoint::start(const CheckpointKey& key) {
  if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot reset the checkpoint: {}", std::strerror(err)), path_,
                     "check the disk and the path");
  }
  key_ = key;
  if (snapshots_) {
    save(ReductionSnapshot{});
    return;
  }
  const std::string head = header_bytes(magic_v4, key);
  good_ = 0;
  try {
    files::write_all(fd_, head.data(), head.size(), path_);
  } catch (const InputError&) {
    if (::ftruncate(fd_, 0) != 0) { /* the header is all there was; an empty file scans as empty */ }
    throw;
  }
  good_ = head.size();
  sync();
}

void Checkpoint::resume(const CheckpointScan& scanned, const CheckpointKey& key) {
  key_ = key;
  units_ = scanned.units_done;
  if (snapshots_) return;  // the caller's next save replaces the file (a snapshot, or unit records of an older build)
  if (::ftruncate(fd_, static_cast<off_t>(scanned.good_bytes)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(scanned.good_bytes), SEEK_SET) < 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot continue the checkpoint: {}", std::strerror(err)), path_,
                     "check the disk and the path");
  }
  good_ = scanned.good_bytes;
}

void Checkpoint::save(const ReductionSnapshot& snap) {
  const std::string bytes = encode_snapshot(key_, snap);
  const std::string tmp = fmt::format("{}.tmp{}", path_, static_cast<long>(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  auto fail = [&](const char* step) {
    const int err = errno;
    if (fd >= 0) ::close(fd), ::unlink(tmp.c_str());
    throw InputError(fmt::format("cannot write the checkpoint snapshot ({}): {}; the previous snapshot stays", step,
                                 std::strerror(err)),
                     path_, "check the disk (space, quota), then rerun with --resume");
  };
  if (fd < 0) fail("create");
  // nobody else knows the temporary yet: locked before the rename, the file at path_ is never unlocked
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) fail("lock");
  try {
    files::write_all(fd, bytes.data(), bytes.size(), tmp);
  } catch (const InputError& e) {
    ::close(fd), ::unlink(tmp.c_str());
    throw InputError(e.what_part() + "; the previous checkpoint snapshot stays", path_, e.fix() + ", then rerun with --resume");
  }
  if (::fsync(fd) != 0) fail("fsync");
  if (::rename(tmp.c_str(), path_.c_str()) != 0) fail("rename");
  const std::filesystem::path dir = std::filesystem::path(path_).parent_path();
  if (const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0)
    ::fsync(dfd), ::close(dfd);  // the rename survives a power cut once the folder is on disk
  if (fd_ >= 0) ::close(fd_);  // the replaced file (unlinked by the rename) and its lock
  fd_ = fd;
  units_ = snap.units_done();
}

void Checkpoint::append(std::uint64_t unit, std::span<const std::byte> payload) {
  const std::uint64_t count = payload.size();
  const std::uint64_t sum = record_checksum(unit, count, payload.data());
  std::string rec;
  rec.reserve(24 + count);
  rec.append(reinterpret_cast<const char*>(&unit), 8);
  rec.append(reinterpret_cast<const char*>(&count), 8);
  rec.append(reinterpret_cast<const char*>(payload.data()), count);
  rec.append(reinterpret_cast<const char*>(&sum), 8);
  try {
    files::write_all(fd_, rec.data(), rec.size(), path_);
  } catch (const InputError& e) {
    // cut back to the last complete record: the file stays a valid, resumable checkpoint
    const bool cut = ::ftruncate(fd_, static_cast<off_t>(good_)) == 0 &&
                     ::lseek(fd_, static_cast<off_t>(good_), SEEK_SET) >= 0 && ::fsync(fd_) == 0;
    throw InputError(fmt::format("{}; the checkpoint keeps {} finished units{}", e.what_part(), human(units_),
                                 cut ? "" : " (its torn last record is dropped on resume)"),
                     path_, e.fix() + " with --resume to continue");
  }
  good_ += rec.size();
  ++units_;
}

void Checkpoint::sync() {
  if (fd_ >= 0 && ::fsync(fd_) != 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot write the checkpoint to disk (fsync): {}", std::strerror(err)), path_,
                     "check the disk, then rerun with --resume");
  }
}

namespace {

// A fresh run (no --resume) that would discard progress, or a file it must not overwrite, without --force.
void refuse_fresh(const CheckpointScan& s, const std::string& p, bool snapshots, std::uint64_t units) {
  using K = CheckpointScan::Kind;
  const std::string discard = " or --force to discard it";
  switch (s.kind) {
    case K::empty: break;
    case K::ours:
      if (s.units_done > 0)
        throw InputError(fmt::format("checkpoint {} holds {} of {} units of this study", p, human(s.units_done),
                                     human(s.units_total)),
                         p, "rerun with --resume to continue" + discard);
      break;
    case K::other_build:
      if (s.units_done > 0)
        throw InputError(fmt::format("checkpoint {} holds {} of {} units of this study, written by another build "
                                     "({})", p, human(s.units_done), human(s.units_total), s.build),
                         p, "rerun with that build and --resume to continue" + discard);
      break;
    case K::other_study:
      if (s.same_text)  // this study cut into other units: another batch (study.hpp default_batch)
        throw InputError(fmt::format("checkpoint {} holds {} units of this study cut into {} units, this run into {} "
                                     "(another [analysis] batch)",
                                     p, human(s.units_done), human(s.units_total), human(units)),
                         p, "give another --out, finish it with the build that started it" + discard);
      throw InputError(fmt::format("checkpoint {} holds {} units of a different study{}", p, human(s.units_done),
                                   s.format == 5 && !snapshots ? " (reductions only: [outputs] per_model = false)" : ""),
                       p, "give another --out, resume that study" + discard);
    case K::old_format:
      throw InputError(fmt::format("checkpoint {} was written by an older pounding (checkpoint format {})", p, s.format),
                       p, "finish it with that version, or rerun with --force to discard it");
    case K::damaged:
      throw InputError(fmt::format("checkpoint {} is damaged: {}", p, s.stopped_at), p,
                       "restore it from a copy and rerun with --resume," + discard);
    case K::not_checkpoint:
      throw InputError(fmt::format("{} exists and is not a pounding checkpoint", p), p,
                       "move it away, give another --out, or rerun with --force to overwrite it");
  }
}

// --resume of a checkpoint that is not this study's, this build's and this kind's.
void refuse_resume(const CheckpointScan& s, const Checkpoint& ckpt, const CheckpointKey& key) {
  using K = CheckpointScan::Kind;
  const std::string& p = ckpt.path();
  if (s.format == 5 && !ckpt.snapshots() && (s.kind == K::ours || s.kind == K::other_study))
    throw InputError("the checkpoint holds reductions only (a run with [outputs] per_model = false) and this study keeps "
                     "per-model outputs",
                     p, "resume with the study file that started the run (per_model = false), or rerun with --force to "
                        "start afresh");
  switch (s.kind) {
    case K::empty:
      if (ckpt.existed())
        throw InputError(fmt::format("checkpoint {} is empty (0 bytes): it holds no finished unit (a run stopped before "
                                     "its first unit, or a truncated file)",
                                     p),
                         p, "run without --resume to start the study afresh (the empty file is replaced)");
      throw InputError(fmt::format("no checkpoint to resume from: {} does not exist", p), p,
                       "run without --resume to start the study");
    case K::ours: break;
    case K::other_build:
      throw InputError(fmt::format("the checkpoint was written by a different build of pounding ({}; this is {}); "
                                   "its units could differ from this build's in the last bits",
                                   s.build, key.build),
                       p, "resume with the build that started the run, or rerun with --force to start afresh");
    case K::other_study:
      if (s.same_text)  // e.g. written before the impacts scene's default batch became 64 (study.hpp default_batch)
        throw InputError(fmt::format("the checkpoint cuts this study into {} work units and this run into {}: it was "
                                     "written with another [analysis] batch (before 2026-11-27 the impacts scene's "
                                     "default was 256, now 64)",
                                     human(s.units_total), human(key.units)),
                         p, "finish it with the build that started the run, or rerun with --force to start afresh");
      throw InputError("the checkpoint belongs to a different study (study text, records or program format changed)", p,
                       "resume with the study file that started the run, or run with --force to start afresh");
    case K::old_format:
      throw InputError(fmt::format("the checkpoint was written by an older pounding (checkpoint format {})", s.format), p,
                       "finish it with that version, or rerun with --force to start afresh");
    case K::damaged:
      throw InputError(fmt::format("the checkpoint snapshot {} is damaged: {}; its units cannot be trusted", p,
                                   s.stopped_at),
                       p, "restore the file from a copy, or rerun with --force to start afresh");
    case K::not_checkpoint:
      throw InputError("the checkpoint file is not a pounding checkpoint", p, "move it away and run with --force");
  }
}

}  // namespace

std::uint64_t open_for_run(Checkpoint& ckpt, const CheckpointKey& key, bool resume, bool force,
                           const Checkpoint::UnitFn& on_unit, std::string* dropped, const SnapshotFn& on_snapshot) {
  const std::string& p = ckpt.path();
  if (resume && force)
    throw InputError("--resume and --force contradict each other", "--resume --force",
                     "give --resume to continue the checkpoint or --force to discard it");
  if (!resume) {
    if (!force) refuse_fresh(ckpt.scan(key), p, ckpt.snapshots(), key.units);
    ckpt.start(key);
    return 0;
  }
  ReductionSnapshot snap;
  const CheckpointScan s = ckpt.scan(key, on_unit, &snap);
  refuse_resume(s, ckpt, key);
  if (s.format == 5 && on_snapshot) on_snapshot(std::move(snap));
  if (dropped && s.file_bytes > s.good_bytes) {
    // the bytes after the last valid record: a torn last record of a killed run, or damage (then whole units go)
    const std::uint64_t per_unit = s.units_done ? (s.good_bytes - 40 - s.build.size()) / s.units_done : 0;
    const std::uint64_t lost = s.file_bytes - s.good_bytes;
    *dropped = fmt::format("{}: the {} bytes after unit record {} are dropped{} and those units are computed again",
                           s.stopped_at.empty() ? "the checkpoint's end is unreadable" : s.stopped_at, human(lost),
                           human(s.units_done),
                           per_unit ? fmt::format(" (about {} units)", human(std::max<std::uint64_t>(1, lost / per_unit)))
                                    : "");
  }
  ckpt.resume(s, key);
  return s.units_done;
}

void Checkpoint::remove() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

}  // namespace pounding
