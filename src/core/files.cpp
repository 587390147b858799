// Files never left half-written: atomic replacement, writes that report the OS error, output checks before work.
#include "pounding/core/files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "pounding/core/error.hpp"

namespace pounding::files {

namespace fs = std::filesystem;

std::string os_error(int err) {
  const char* name = err == ENOSPC ? " (ENOSPC)" : err == EFBIG ? " (EFBIG)" : err == EIO ? " (EIO)" : err == EDQUOT ? " (EDQUOT)" : "";
  return fmt::format("{}{}", std::strerror(err), name);
}

std::string fix_for(int err) {
  if (err == ENOSPC || err == EDQUOT) return "free disk space (or choose another folder) and rerun";
  if (err == EFBIG) return "raise the file-size limit (ulimit -f) or choose another file system, and rerun";
  if (err == EACCES || err == EPERM || err == EROFS) return "write to a folder you may write to";
  return "check the disk and the path, and rerun";
}

namespace {

// Holds back SIGINT/SIGTERM/SIGHUP for its lifetime; pending ones are delivered when it ends.
class SignalHold {
 public:
  SignalHold() {
    sigset_t s;
    sigemptyset(&s);
    sigaddset(&s, SIGINT);
    sigaddset(&s, SIGTERM);
    sigaddset(&s, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &s, &old_);
  }
  ~SignalHold() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalHold(const SignalHold&) = delete;
  SignalHold& operator=(const SignalHold&) = delete;

 private:
  sigset_t old_;
};

std::string parent_of(const std::string& path) {
  fs::path p = fs::path(path).parent_path();
  return p.empty() ? std::string(".") : p.string();
}

}  // namespace

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  return h;
}

namespace {
constexpr std::uint64_t xp1 = 0x9E3779B185EBCA87ULL, xp2 = 0xC2B2AE3D27D4EB4FULL, xp3 = 0x165667B19E3779F9ULL,
                        xp4 = 0x85EBCA77C2B2AE63ULL, xp5 = 0x27D4EB2F165667C5ULL;
constexpr std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
std::uint64_t read64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;  // little-endian hosts (x86-64, AArch64 Linux), as the checkpoint's own integers
}
std::uint32_t read32(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
std::uint64_t xround(std::uint64_t acc, std::uint64_t in) { return rotl(acc + in * xp2, 31) * xp1; }
std::uint64_t xmerge(std::uint64_t acc, std::uint64_t v) { return (acc ^ xround(0, v)) * xp1 + xp4; }
}  // namespace

std::uint64_t xxh64(const void* data, std::size_t n, std::uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  const unsigned char* const end = p + n;
  std::uint64_t h;
  if (n >= 32) {
    std::uint64_t v1 = seed + xp1 + xp2, v2 = seed + xp2, v3 = seed, v4 = seed - xp1;
    const unsigned char* const limit = end - 32;
    do {
      v1 = xround(v1, read64(p));
      v2 = xround(v2, read64(p + 8));
      v3 = xround(v3, read64(p + 16));
      v4 = xround(v4, read64(p + 24));
      p += 32;
    } while (p <= limit);
    h = rotl(v1, 1) + rotl(v2, 7) + rotl(v3, 12) + rotl(v4, 18);
    h = xmerge(h, v1), h = xmerge(h, v2), h = xmerge(h, v3), h = xmerge(h, v4);
  } else {
    h = seed + xp5;
  }
  h += static_cast<std::uint64_t>(n);
  for (; p + 8 <= end; p += 8) h = rotl(h ^ xround(0, read64(p)), 27) * xp1 + xp4;
  if (p + 4 <= end) h = rotl(h ^ (static_cast<std::uint64_t>(read32(p)) * xp1), 23) * xp2 + xp3, p += 4;
  for (; p < end; ++p) h = rotl(h ^ (*p * xp5), 11) * xp1;
  h ^= h >> 33, h *= xp2, h ^= h >> 29, h *= xp3, h ^= h >> 32;
  return h;
}

namespace {
// What a path that is not a regular file is, for messages.
const char* kind_of(mode_t mode) {
  return S_ISDIR(mode)    ? "a folder"
         : S_ISFIFO(mode) ? "a FIFO (named pipe)"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a regular file";
}

InputError read_error(const std::string& path, const std::string& what, int err) {
  const char* fix = err == ENOENT || err == ENOTDIR ? "check the path"
                    : err == EISDIR               ? "give a file, not a folder"
                    : err == EACCES || err == EPERM ? "check its permissions"
                                                    : "check the disk and the path";
  return InputError(fmt::format("cannot read {}: {}", what, err == ENOENT ? std::string("not found") : os_error(err)),
                    path, fix);
}

// An input that exists but is not a regular file: a folder, FIFO, socket or device is never read (a FIFO blocks
// until a writer comes, /dev/zero never ends, a folder is a mistake).
// `limit`: the reader's size limit, named in the fix ("16 MiB"), or empty.
InputError not_regular_error(const std::string& path, const std::string& what, mode_t mode, const std::string& limit = "") {
  if (S_ISDIR(mode))
    return InputError(fmt::format("cannot read {}: the path is a folder", what), path, "give a file, not a folder");
  return InputError(fmt::format("cannot read {}: the path is {}, not a regular file", what, kind_of(mode)), path,
                    fmt::format("give the path of an ordinary file{} (pounding reads no FIFO, socket or device: it "
                                "could block or never end)", limit.empty() ? "" : " of at most " + limit));
}
}  // namespace

void check_input_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw read_error(path, what, errno);  // stat never opens: a FIFO cannot block it
  if (!S_ISREG(st.st_mode)) throw not_regular_error(path, what, st.st_mode);
}

std::string read_text(const std::string& path, const std::string& what, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer before we know what the path is
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw read_error(path, what, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw read_error(path, what, err);
  }
  const std::string limit = max_bytes % (1 << 20) == 0 ? fmt::format("{} MiB", max_bytes >> 20) : fmt::format("{} bytes", max_bytes);
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw not_regular_error(path, what, st.st_mode, limit);
  }
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputError(fmt::format("cannot read {}: it holds {} bytes, more than the limit of {}", what,
                                 static_cast<std::uint64_t>(st.st_size), limit),
                     path, "check the path (is it the right file?)");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::string text;
  if (st.st_size > 0) text.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t r = ::read(fd, buf, sizeof buf);
    if (r > 0 && text.size() + static_cast<std::size_t>(r) > max_bytes) {  // a file that grows while it is read
      ::close(fd);
      throw InputError(fmt::format("cannot read {}: more than the limit of {}", what, limit), path,
                       "check the path (is it the right file?)");
    }
    if (r == 0) break;
    if (r < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      throw read_error(path, what, err);
    }
    text.append(buf, static_cast<std::size_t>(r));
  }
  ::close(fd);
  return text;
}

void write_all(int fd, const void* data, std::size_t n, const std::string& path) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      throw InputError(fmt::format("cannot write {}: {}", path, os_error(err)), path, fix_for(err));
    }
    if (w == 0) throw InputError(fmt::format("cannot write {}: no progress", path), path, fix_for(EIO));
    p += w;
    n -= static_cast<std::size_t>(w);
  }
}

void check_replaceable(const std::string& path, const std::string& where, const std::string& fix) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;  // a new file (or a dangling link: the rename replaces the link)
  if (S_ISREG(st.st_mode)) return;
  throw InputError(fmt::format("the output path '{}' exists and is {}; pounding replaces only regular files", path,
                               kind_of(st.st_mode)),
                   where.empty() ? path : where, fix.empty() ? "give the path of a new or ordinary file" : fix);
}

std::string replace_target(const std::string& given) {
  check_replaceable(given, "");
  // a link to a regular file: replace the file it names (beside it), and keep the link
  struct stat lst {};
  if (::lstat(given.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode)) {
    std::error_code ec;
    const fs::path target = fs::canonical(given, ec);
    if (!ec) return target.string();
  }
  return given;
}

namespace {
// fsync and close fd (the temporary `tmp` of `path`), rename it over path, fsync the folder; removes tmp on failure.
void finish_temporary(int fd, const std::string& tmp, const std::string& path) {
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("cannot write {} (fsync): {}", path, os_error(err)), path, fix_for(err));
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("cannot write {} (close): {}", path, os_error(err)), path, fix_for(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("cannot rename {} to {}: {}", tmp, path, os_error(err)), path, fix_for(err));
  }
  // the rename itself survives a power cut only once the directory is on disk
  int dfd = ::open(parent_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}
}  // namespace

void commit_temporary(const std::string& tmp, const std::string& path) {
  SignalHold hold;
  int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("cannot open {}: {}", tmp, os_error(err)), path, fix_for(err));
  }
  finish_temporary(fd, tmp, path);
}

void write_atomically(const std::string& given, std::span<const std::byte> bytes) {
  const std::string path = replace_target(given);
  const std::string tmp = fmt::format("{}.tmp{}", path, static_cast<long>(getpid()));
  SignalHold hold;
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot create {}: {}", tmp, os_error(err)), path, fix_for(err));
  }
  try {
    write_all(fd, bytes.data(), bytes.size(), tmp);
  } catch (const InputError& e) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw InputError(fmt::format("{} (the temporary of {}, removed)", e.what_part(), path), path, e.fix());
  }
  finish_temporary(fd, tmp, path);
}

void write_text_atomically(const std::string& path, std::string_view text) {
  write_atomically(path, std::as_bytes(std::span<const char>(text.data(), text.size())));
}

namespace {
// The fix's example for an output given by `where`: that option when it is one (--html, -o), else --out, with a
// file name of that output's kind.
std::string output_example(const std::string& where, const std::string& folder) {
  const bool option = !where.empty() && where[0] == '-' && where.find(' ') == std::string::npos;
  const std::string name = where == "--html"     ? "report.html"
                           : where == "--output" ? "study-reference.md"
                           : where == "-o"       ? "selection.csv"
                                                 : "results.h5";
  return (option ? where : std::string("--out")) + " " + folder + name;
}
}  // namespace

void check_output_path(const std::string& path, const std::string& where) {
  if (path.empty())
    throw InputError("the output path is empty", where, "give a file name, e.g. " + output_example(where, ""));
  if (path.back() == '/')
    throw InputError(fmt::format("the output path '{}' names a folder, not a file", path), where,
                     "give a file name, e.g. " + output_example(where, path));
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw InputError(fmt::format("the output path '{}' is an existing folder", path), where,
                     "give a file name inside it, e.g. " + output_example(where, path + "/"));
  check_replaceable(path, where);
  const std::string dir = parent_of(path);
  struct stat ds {};
  if (::stat(dir.c_str(), &ds) != 0 || !S_ISDIR(ds.st_mode))
    throw InputError(fmt::format("the folder '{}' of the output path does not exist", dir), where,
                     fmt::format("create it first (mkdir -p {}) or give another path", dir));
  // a real probe, not access(2): it also catches read-only file systems, and ACLs
  const std::string probe = fmt::format("{}.probe{}", path, static_cast<long>(getpid()));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    throw InputError(fmt::format("cannot create files in '{}': {}", dir, os_error(err)), where, fix_for(err));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  // one is not there yet (two outputs of one command): the same path once absolute, links resolved, . and .. gone
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea), cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb ? ca == cb : fs::path(a).lexically_normal() == fs::path(b).lexically_normal();
}

void check_output_not_input(const std::string& output, const std::vector<std::string>& inputs, const std::string& where,
                            std::string_view role, const std::string& fix) {
  if (output.empty()) return;
  for (const std::string& input : inputs) {
    if (input.empty() || !same_file(output, input)) continue;
    throw InputError(fmt::format("the output path '{}' is the same file as {} '{}'; writing it would destroy {}", output,
                                 role, input, role),
                     where.empty() ? output : where,
                     fix.empty() ? fmt::format("give the output a path of its own: pounding never writes over {}", role)
                                 : fix);
  }
}

int remove_stale_temporaries(const std::string& path) {
  const fs::path p(path);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string stem = p.filename().string() + ".tmp";
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) continue;
    if (name.find_first_not_of("0123456789", stem.size()) != std::string::npos) continue;
    if (fs::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

std::string with_extension(const std::string& path, std::string_view ext) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t name = slash == std::string::npos ? 0 : slash + 1;
  const std::size_t dot = path.find_last_of('.');
  const bool has = dot != std::string::npos && dot > name;  // ".hidden" has no extension
  return (has ? path.substr(0, dot) : path) + std::string(ext);
}

}  // namespace pounding::files
