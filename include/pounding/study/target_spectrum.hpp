#pragma once
// A study that selects and scales its records to a design spectrum (issue 14 part 4): the [target_spectrum]
// section, [records] select = N, and what the run logs and writes (/selection). The selection itself is
// motion/selection.hpp's select_records, the target motion/target_spectrum.hpp's, shared with
// `pounding records select`.
//
//   [records]          select = N    choose N records (integer >= 1) from the library the section names
//                                    (directory, files or suite); the study uses exactly those, each multiplied
//                                    by its final factor f_i F. Needs [target_spectrum]; not with limit.
//                     max_per_event = 2  (with select) at most this many records of one earthquake (0: no limit;
//                                    FEMA P-695's far-field set takes 2, against event bias)
//                     components = "one" | "both"  (with select) one: one component per station, the better
//                                    match; both: both may be chosen. A second copy of one recording (same event,
//                                    station and axis, motion/library.hpp) is never chosen.
//   [target_spectrum]  code = "ASCE 7-16" | "EC8" | "Standard 2800" | "csv", and the code's parameters:
//                        ASCE 7-16      sds, sd1 (g, the design values), or instead ss, s1 (g, the mapped MCER
//                                       values, (0, 5] and (0, 3]) and site_class = "A" | "B" | "C" | "D" |
//                                       "D-default" | "E" | "F" (Fa, Fv from Tables 11.4-1/11.4-2; F and the
//                                       11.4.8 site-specific cases are refused: motion/asce7_site.hpp);
//                                       tl = 8 (s), mcer = false (true: 1.5 x, the MCER spectrum ASCE 7-16 16.2
//                                       scales to)
//                        EC8            type = 1 | 2, ground = "A".."E" (required), agr (g, required), importance = 1
//                                       (the spectrum at `damping`)
//                        Standard 2800  a (0.35, 0.30, 0.25 or 0.20, required), soil = "I".."IV" (required),
//                                       importance = 1
//                        csv            file = "target.csv" ("period,sa" lines in s, g; relative to the study)
//                      rule = "ASCE 7-16" (default; EC8 for an EC8 target) | "ASCE 7-10" | "EC8" | "none"
//                      t_min, t_max (s): the period range; default [0.2 min(T1, T2), 2.0 max(T1, T2)] (ASCE 7-10:
//                        1.5 max(T1, T2)), T1, T2 the buildings' median periods (median_period(), intensity.hpp:
//                        a distribution's median, a grid's median element -- the middle of the sorted grid, the
//                        geometric mean of the two middle ones for an even count)
//                      points = 30, damping = 0.05, min_scale = 0.25, max_scale = 4
//   [target_spectrum] without select is an error (add select = N): a study either keeps its records as they
//   are or selects them.
#include <cstddef>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "pounding/motion/selection.hpp"
#include "pounding/motion/target_spectrum.hpp"
#include "pounding/results/results.hpp"

namespace pounding {

struct StructureModel;

struct TargetSpectrumSection {
  bool enabled = false;
  TargetSpectrumSpec spec;
  SelectionOptions options;         // count set from [records] select; t_lo/t_hi resolved
  bool range_given = false;         // t_min or t_max in the file
  std::string where;                // "file:line [target_spectrum]" for errors found when the records load
  std::string target_text;          // describe_target()
};

// Null table: absent. Every value is checked here (the spectrum's validate(), the options'); an error names
// file:line, the key and the fix.
TargetSpectrumSection parse_target_spectrum(const toml::table* t, const std::string& path,
                                            const StructureModel& structures);

// The outcome of a study's selection, identical on every rank: what the run log prints and /selection holds.
struct StudySelection {
  Selection selection;
  SelectionOptions options;
  std::string target_text;
  std::vector<std::string> ids, sources;  // per candidate (library order)
  std::vector<std::string> summary() const;  // selection_summary(), one string per line
};

// /selection: the chosen records, their factors and misfits, the target, the scaled mean and spectra.
results::Group selection_group(const StudySelection& s);

}  // namespace pounding
