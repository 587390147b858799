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

}  // namespace

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

Checkpoint::Checkpoint(std::string path) : path_(std::move(path)) {
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

CheckpointScan Checkpoint::scan(const CheckpointKey& key, const UnitFn& on_unit) {
  return scan_checkpoint(path_, key, on_unit);
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

CheckpointScan scan_checkpoint(const std::string& path_, const CheckpointKey& key, const Checkpoint::UnitFn& on_unit) {
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
  if (h != key.study_hash || n != key.units) {
    s.kind = CheckpointScan::Kind::other_study;
  } else {
    s.kind = bh == key.build_hash ? CheckpointScan::Kind::ours : CheckpointScan::Kind::other_build;
  }
  s.good_bytes = 40 + blen;
  const bool deliver = s.kind == CheckpointScan::Kind::ours && on_unit;
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
    s.good_bytes += 24 + count;
    ++s.units_done;
    if (deliver) on_unit(static_cast<std::size_t>(unit), std::move(data));
  }
  return s;
}

void Checkpoint::start(const CheckpointKey& key) {
  if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot reset the checkpoint: {}", std::strerror(err)), path_,
                     "check the disk and the path");
  }
  std::string head(magic_v4, 8);
  const std::uint64_t blen = key.build.size();
  for (std::uint64_t v : {key.study_hash, key.units, key.build_hash, blen})
    head.append(reinterpret_cast<const char*>(&v), 8);
  head += key.build;
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

void Checkpoint::resume(const CheckpointScan& scanned) {
  if (::ftruncate(fd_, static_cast<off_t>(scanned.good_bytes)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(scanned.good_bytes), SEEK_SET) < 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot continue the checkpoint: {}", std::strerror(err)), path_,
                     "check the disk and the path");
  }
  good_ = scanned.good_bytes;
  units_ = scanned.units_done;
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

std::uint64_t open_for_run(Checkpoint& ckpt, const CheckpointKey& key, bool resume, bool force,
                           const Checkpoint::UnitFn& on_unit, std::string* dropped) {
  using K = CheckpointScan::Kind;
  const std::string& p = ckpt.path();
  if (resume && force)
    throw InputError("--resume and --force contradict each other", "--resume --force",
                     "give --resume to continue the checkpoint or --force to discard it");
  if (!resume) {
    const CheckpointScan s = ckpt.scan(key);
    if (!force) {
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
          throw InputError(fmt::format("checkpoint {} holds {} units of a different study", p, human(s.units_done)), p,
                           "give another --out, resume that study" + discard);
        case K::old_format:
          throw InputError(fmt::format("checkpoint {} was written by an older pounding (checkpoint format {})", p,
                                       s.format),
                           p,
                           "finish it with that version, or rerun with --force to discard it");
        case K::not_checkpoint:
          throw InputError(fmt::format("{} exists and is not a pounding checkpoint", p), p,
                           "move it away, give another --out, or rerun with --force to overwrite it");
      }
    }
    ckpt.start(key);
    return 0;
  }
  const CheckpointScan s = ckpt.scan(key, on_unit);
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
      throw InputError("the checkpoint belongs to a different study (study text, records or program format changed)", p,
                       "resume with the study file that started the run, or run with --force to start afresh");
    case K::old_format:
      throw InputError(fmt::format("the checkpoint was written by an older pounding (checkpoint format {})", s.format), p,
                       "finish it with that version, or rerun with --force to start afresh");
    case K::not_checkpoint:
      throw InputError("the checkpoint file is not a pounding checkpoint", p, "move it away and run with --force");
  }
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
  ckpt.resume(s);
  return s.units_done;
}

void Checkpoint::remove() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

}  // namespace pounding
