#pragma once
// The work plan: work units = (record r, period pair p, sample block b), numbered r-major, and the schema of
// what each unit returns (results/schema.hpp). Model m = p * samples + sample, the same on every rank.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pounding/results/results.hpp"
#include "pounding/results/schema.hpp"

namespace pounding {

struct UnitIndex {
  std::size_t record = 0, pair = 0, block = 0;
};

struct WorkPlan {
  std::size_t records = 0, pairs = 0, blocks = 0, batch = 0, samples = 0, gaps = 0;
  // A multiple-stripe study: every unit analyses its block at each of the `stripes` levels (0: no stripes) and
  // returns [stripe][lane] per lane field; the columns hold (stripe, record) analysis records, stripe-major.
  std::size_t stripes = 0;
  std::size_t unit_stripes() const { return std::max<std::size_t>(1, stripes); }
  std::size_t analysis_records() const { return records * unit_stripes(); }
  bool impacts = false;                       // the scene runs coupled analyses per gap
  bool ida = false;                           // the bisection IDA of yielding pairs (study/run.cpp)
  bool per_model = true;                      // [outputs] per_model: false = rank 0 keeps reductions only (Tally)
  bool stream = false;                        // per_model = "stream": rank 0 folds reductions, the columns stay on disk
  // Format 3: the study's System as /system (study/make_results.hpp system_table), empty for the SDOF pair. Set it
  // before `fields`: its extents (floors per building -- the tallest topology of the study --, elements) size the
  // per-floor and per-element rows, and make_results writes it (format 3) when it is not empty.
  results::SystemTable system;
  std::vector<results::FieldSpec> fields;     // what a unit returns (results::unit_schema(impacts, ida, stripes, system.extents()))
  // The format this plan's results file has: 2 for the SDOF pair, 3 with a System.
  std::int64_t format_version() const { return system.empty() ? results::pair_format_version : results::format_version; }

  std::size_t units() const { return records * pairs * blocks; }
  std::size_t models() const { return pairs * samples; }
  UnitIndex decode(std::size_t u) const { return {u / (blocks * pairs), (u / blocks) % pairs, u % blocks}; }
  std::size_t lanes(std::size_t block) const { return std::min(batch, samples - block * batch); }
  // The first model of unit u's block within its record.
  std::size_t first_model(const UnitIndex& i) const { return i.pair * samples + i.block * batch; }
  // Values of a field per lane: 1, the gap count, the floors or elements (format 3), gaps x elements.
  std::size_t per_lane(const results::FieldSpec& f) const { return results::per_lane(f, gaps); }
};

}  // namespace pounding
