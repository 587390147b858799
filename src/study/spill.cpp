// [outputs] per_model = "stream": per-model columns written from the checkpoint in bounded memory.
#include "pounding/study/spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/core/error.hpp"

namespace pounding {

namespace {
constexpr std::uint32_t missing = std::numeric_limits<std::uint32_t>::max();
}

SpilledColumns::SpilledColumns(const WorkPlan& plan, const std::string& main, const CheckpointKey& key)
    : plan_(plan), at_(plan.units()) {
  if (plan.unit_stripes() != 1) throw std::logic_error("SpilledColumns: stripes are not streamed");
  std::size_t before = 0;
  for (const results::FieldSpec& f : plan.fields) {
    field_offset_.push_back(before);
    field_width_.push_back(plan.per_lane(f) * results::dtype_size(f.dtype));
    before += field_width_.back();
  }
  std::vector<std::string> paths{main};
  for (std::string& p : slice_paths(main)) paths.push_back(std::move(p));
  std::size_t found = 0;
  for (const std::string& path : paths) {
    const auto file = static_cast<std::uint32_t>(paths_.size());  // this file's index once it is kept
    bool used = false;
    locate_units(path, key, [&](std::size_t u, std::uint64_t offset, std::uint64_t bytes) {
      if (at_[u].file != missing) return;
      if (bytes != before * plan_.lanes(plan_.decode(u).block))
        throw InputError(fmt::format("checkpoint {}: unit {} holds {} bytes, this study's unit {}", path, u, bytes,
                                     before * plan_.lanes(plan_.decode(u).block)),
                         path, "rerun with --force to start afresh");
      at_[u] = {offset, file}, ++found, used = true;
    });
    if (!used) continue;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
      throw InputError(fmt::format("cannot reopen checkpoint {}: {}", path, std::strerror(errno)), path,
                       "check the output folder; --resume writes the results without recomputing");
    paths_.push_back(path), fds_.push_back(fd);
  }
  if (found != at_.size())
    throw InputError(fmt::format("{} of {} units are missing from the checkpoint files after the run",
                                 at_.size() - found, at_.size()),
                     main, "check that every rank writes to the same shared output folder, then rerun with --resume "
                           "(the missing units are computed again)");
}

SpilledColumns::~SpilledColumns() {
  for (int fd : fds_) ::close(fd);
}

void SpilledColumns::fill(std::size_t field, std::size_t first, std::size_t count, void* out) const {
  const std::size_t per = plan_.per_lane(plan_.fields[field]), width = field_width_[field];
  const std::size_t M = plan_.models();
  if (first % per != 0 || count % per != 0)
    throw std::logic_error("SpilledColumns::fill: a range that cuts a lane's values");
  std::size_t r = first / (M * per), m = (first % (M * per)) / per, left = count / per;
  auto* to = static_cast<char*>(out);
  while (left > 0) {
    const std::size_t p = m / plan_.samples, s = m % plan_.samples, b = s / plan_.batch, lane0 = s % plan_.batch;
    const std::size_t lanes = plan_.lanes(b), take = std::min(lanes - lane0, left);
    const std::size_t u = (r * plan_.pairs + p) * plan_.blocks + b;
    const At& at = at_[u];
    std::size_t want = take * width;
    auto offset = static_cast<off_t>(at.offset + field_offset_[field] * lanes + lane0 * width);
    while (want > 0) {
      const ssize_t got = ::pread(fds_[at.file], to, want, offset);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        const int err = errno;
        throw InputError(fmt::format("cannot read unit {} from checkpoint {}: {}", u, paths_[at.file],
                                     got == 0 ? "the file ends early" : std::strerror(err)),
                         paths_[at.file], "check the disk; --resume writes the results without recomputing");
      }
      to += got, offset += got, want -= static_cast<std::size_t>(got);
    }
    left -= take, m += take;
    if (m == M) m = 0, ++r;
  }
}

std::vector<results::Field> SpilledColumns::fields(const std::shared_ptr<const SpilledColumns>& self) {
  std::vector<results::Field> out;
  for (std::size_t k = 0; k < self->plan_.fields.size(); ++k) {
    results::Field f{self->plan_.fields[k], results::make_column(self->plan_.fields[k], 0), {}};
    f.source = [self, k](std::size_t first, std::size_t count, void* to) { self->fill(k, first, count, to); };
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace pounding
