// libFuzzer target for the record readers (AT2 family, two-column and one-column text). Any input must
// either parse into a finite record with dt > 0 and as many values as NPTS says, or throw InputError;
// anything else (crash, sanitizer report, other exception, non-finite value) is a bug.
// Build: CXX=clang++ cmake -S . -B build-fuzz -DPOUNDING_FUZZ=ON   (POUNDING_FUZZ instruments every target itself)
//        cmake --build build-fuzz --target fuzz_at2 && build-fuzz/fuzz_at2 -max_total_time=300 corpus/
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (double dt : {0.0, 0.01}) {
    pounding::ReadOptions o;
    o.dt = dt;
    try {
      const pounding::Record r = pounding::parse_record(text, "fuzz.AT2", o);
      if (!(r.dt > 0) || !std::isfinite(r.dt) || r.acc.empty()) std::abort();
      for (double a : r.acc)
        if (!std::isfinite(a)) std::abort();
      (void)pounding::measure(r);
    } catch (const pounding::InputError&) {
    }
  }
  return 0;
}
