#pragma once
// Files that must never be left half-written: atomic replacement of a whole file, writes that report the OS
// error, and the checks of an output path made before any work starts.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace pounding::files {

// The whole file `path` as bytes (binary-safe: NUL bytes and CRLF kept). `what` names the file in the
// message ("the study file"). Throws InputError naming the path and the OS error when it cannot be read
// (missing, a folder, no permission, I/O error).
std::string read_text(const std::string& path, const std::string& what);

// Writes all n bytes to fd (retrying short writes and EINTR). Throws InputError naming path and the OS
// error (ENOSPC, EFBIG, EIO, ...) otherwise.
void write_all(int fd, const void* data, std::size_t n, const std::string& path);

// Replaces `path` by `bytes` atomically: a temporary `<path>.tmp<pid>` in the same directory is written in
// full, fsynced and renamed over `path`, then the directory is fsynced. SIGINT, SIGTERM and SIGHUP are held
// back meanwhile (delivered afterwards), so an interrupt never leaves the temporary behind. On any failure
// the temporary is removed, `path` is untouched and InputError names the path and the OS error.
void write_atomically(const std::string& path, std::span<const std::byte> bytes);
// The same for text (CSV, AT2, ...).
void write_text_atomically(const std::string& path, std::string_view text);

// Checks, before any work, that `path` can become the output file: not empty, not a directory name (no
// trailing '/'), not an existing directory or special file, its parent folder exists, and a file can be
// created there (a probe file is created and removed). `where` names the option or key that gave the path.
// Throws InputError with the fix.
void check_output_path(const std::string& path, const std::string& where);

// Removes stale temporaries `<path>.tmp<digits>` left by a process killed with SIGKILL while it wrote
// `path`. Call only while holding the output's lock. Returns how many were removed.
int remove_stale_temporaries(const std::string& path);

// 64-bit FNV-1a over bytes (checksums, study hashes).
// (The checkpoint format 1 used a start value one digit short of the offset basis; format 2 uses the
// published one.)
inline constexpr std::uint64_t fnv1a_offset_basis = 0xcbf29ce484222325ULL;  // 14695981039346656037
std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = fnv1a_offset_basis);

}  // namespace pounding::files
