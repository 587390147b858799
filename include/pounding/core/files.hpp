#pragma once
// Files that must never be left half-written: atomic replacement of a whole file, writes that report the OS
// error, and the checks of an output path made before any work starts.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pounding::files {

// The whole file `path` as bytes (binary-safe: NUL bytes and CRLF kept). `what` names the file in the
// message ("the study file"). Throws InputError naming the path and the OS error when it cannot be read
// (missing, no permission, I/O error), naming what the path is when it is not a regular file (a folder, a FIFO, a
// socket, a device such as /dev/zero: refused before any byte is read, and the open never blocks: O_NONBLOCK, then
// fstat), and naming the limit when it holds more than max_bytes (refused by its size before reading).
inline constexpr std::size_t default_read_limit = std::size_t{256} << 20;  // 256 MiB
std::string read_text(const std::string& path, const std::string& what, std::size_t max_bytes = default_read_limit);

// The same refusals for a reader that opens the file itself (HDF5, record and CSV readers): InputError unless
// `path` is an existing regular file (a link to one is fine). Only stat(2): never blocks, never opens. Call it just
// before the open; `what` as for read_text.
void check_input_file(const std::string& path, const std::string& what);

// An OS error as a message names it: strerror with the name of the common ones ("No space left on device (ENOSPC)"),
// and what to do about it ("free disk space (or choose another folder) and rerun").
std::string os_error(int err);
std::string fix_for(int err);

// Writes all n bytes to fd (retrying short writes and EINTR). Throws InputError naming path and the OS
// error (ENOSPC, EFBIG, EIO, ...) otherwise.
void write_all(int fd, const void* data, std::size_t n, const std::string& path);

// Every file pounding writes goes through write_atomically (HDF5 files too: io/hdf5.hpp AtomicFile builds them in
// memory and commits through it), so no writer can replace a device node, a FIFO, a socket or a folder: the
// path must be new or a regular file (a symbolic link to a regular file replaces that file and keeps the link).
// check_replaceable throws InputError otherwise (the existing-and-not-regular test alone; `where` names the
// option or key, the path itself when empty; `fix` replaces the default fix). check_output_path calls it before
// any work; call it (or check_output_path) at the start of a command so that the refusal comes before the work.
void check_replaceable(const std::string& path, const std::string& where, const std::string& fix = "");

// Replaces `path` by `bytes` atomically (refusing a path that exists and is not a regular file, see above): a temporary `<path>.tmp<pid>` in the same directory is written in
// full, fsynced and renamed over `path`, then the directory is fsynced. SIGINT, SIGTERM and SIGHUP are held
// back meanwhile (delivered afterwards), so an interrupt never leaves the temporary behind. On any failure
// the temporary is removed, `path` is untouched and InputError names the path and the OS error.
void write_atomically(const std::string& path, std::span<const std::byte> bytes);
// The file write_atomically replaces for `path`: path itself, or the regular file a symbolic link names (after
// check_replaceable). A writer that builds its temporary itself (io/hdf5.hpp AtomicFile::Storage::disk) makes
// `<target>.tmp<pid>` and hands it to commit_temporary: fsynced, renamed over target (SIGINT, SIGTERM and SIGHUP held
// meanwhile), the folder fsynced; on failure the temporary is removed and InputError names path and the OS error.
std::string replace_target(const std::string& path);
void commit_temporary(const std::string& temporary, const std::string& target);
// The same for text (CSV, AT2, ...).
void write_text_atomically(const std::string& path, std::string_view text);

// Checks, before any work, that `path` can become the output file: not empty, not a directory name (no
// trailing '/'), not an existing directory or special file, its parent folder exists, and a file can be
// created there (a probe file is created and removed). `where` names the option or key that gave the path.
// Throws InputError with the fix.
void check_output_path(const std::string& path, const std::string& where);

// Whether a and b name the same file: the same device and inode when both exist (so a symbolic or hard link, `./x`
// and `dir/../x` are caught, not only equal strings), else the same absolute path with links and `..` resolved (an
// output not written yet against another output of the same command).
bool same_file(const std::string& a, const std::string& b);

// Refuses, before any work, an output that is the same file (same_file) as one of `inputs`: every command that
// reads files and writes files calls it for each output with every path it reads (and, for outputs that must not
// collide, with its other outputs and role "the results file"). InputError naming both paths, `where` (the option
// or key of the output) and the fix (`fix`, or "give the output a path of its own"); nothing is read or written.
// Empty paths are ignored.
void check_output_not_input(const std::string& output, const std::vector<std::string>& inputs, const std::string& where,
                            std::string_view role = "the input", const std::string& fix = "");

// `path` with its extension (the part after the last '.' of its file name) replaced by `ext` (".html"), or `ext`
// appended when the file name has none: the HTML report written next to a results file ([report] html = true).
std::string with_extension(const std::string& path, std::string_view ext);

// Removes stale temporaries `<path>.tmp<digits>` left by a process killed with SIGKILL while it wrote
// `path`. Call only while holding the output's lock. Returns how many were removed.
int remove_stale_temporaries(const std::string& path);

// 64-bit FNV-1a over bytes (checksums, study hashes).
// (The checkpoint format 1 used a start value one digit short of the offset basis; format 2 uses the
// published one.)
inline constexpr std::uint64_t fnv1a_offset_basis = 0xcbf29ce484222325ULL;  // 14695981039346656037
std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = fnv1a_offset_basis);

// XXH64 (Yann Collet's xxHash, 64-bit, as published; checked against xxhsum 0.8.1): the checksum of checkpoint
// records (format 4). About 0.1 cycle per byte against FNV-1a's ~4 (one multiply chain per byte), which made the
// master's per-unit checksum the largest part of its service time (issue 27.4).
std::uint64_t xxh64(const void* data, std::size_t n, std::uint64_t seed = 0);

}  // namespace pounding::files
