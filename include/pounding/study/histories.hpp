#pragma once
// [outputs] histories (issue 45 item 5): the full time histories of chosen analyses of a study, rerun after the units
// with the series recorder (the pair kernel's SeriesRecorder, physics::run_system_recorded for Systems) and stored in
// the results file as /histories/<n> (docs/results-format.md).
//
// The selection is a list of entries (docs/studies.md, "Time histories of chosen analyses"):
//   { record = "EQ3" | 2, model = 17 | pair = [i1, i2], sample = k, gap = 0.5 | "uncoupled" }   one analysis
//   { worst = N (, gap = x) }   the N analyses of the largest peak impact force (impacts scene, coupled runs, over
//                              every gap or at gap x) or of the largest peak closing / code gap (probability scene)
// An explicit entry is resolved against the records and models before the first unit (InputError naming the entry);
// "worst" after the units, from the per-model results. A history is the same analysis as the study's: the same
// sampled structure, record (and its other supports), step and substeps, contact model, e, kc and gap, through the
// same code (SystemBlock, run_batch), so its peaks equal the study's per-model values bit for bit.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pounding/core/progress.hpp"
#include "pounding/results/results.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

// One resolved analysis: record row, model row (p x samples + sample), gap index (-1: the uncoupled run).
struct HistoryChoice {
  std::size_t record = 0, model = 0;
  std::ptrdiff_t gap = -1;
  std::string chosen;  // "explicit (file:line)" or "worst 2 of 3 by peak force"
};

// While the study is parsed: the entries against the scene, the structures' grid, the stepper and per_model
// (InputError at the entry's file:line).
void check_histories(const Study& study);

// Before the first unit: every explicit entry of study.histories against the records (name as in /records/id, the
// first row of that id, or a row index) and the models (a /models row, or pair [i1, i2] and sample), and its gap
// (one of the study's gap ratios; "uncoupled"). InputError at the entry's file:line with the fix.
std::vector<HistoryChoice> resolve_histories(const Study& study, const std::vector<StudyRecord>& records);

// Before the first unit: the memory the histories will hold (the named ones and worst N each, at the longest record,
// the study's largest System) against the memory available (a third of it: the results and the file's image hold
// them). InputError at the first entry with the fix.
void check_history_memory(const Study& study, const std::vector<StudyRecord>& records, std::size_t named);

// After the units: study.histories' "worst" entries resolved from the per-model results `res` (its uncoupled /
// impacts fields and /models code_gap), appended to `explicit_choices` in the entries' order (an analysis chosen
// twice is kept once).
std::vector<HistoryChoice> choose_worst(const Study& study, const results::Results& res,
                                        std::vector<HistoryChoice> explicit_choices);

// Reruns each choice with the recorder and returns /histories (one child group per choice, named 1, 2, ...). `res`
// (may hold no per-model fields: per_model = false) gives the study's per-model values to compare with: a history
// whose peaks differ is named in `mismatch` (empty when every history agrees, or nothing to compare). Progress and
// stop through `hook` (Cancelled when stopped).
results::Group run_histories(const Study& study, const std::vector<StudyRecord>& records,
                             const std::vector<HistoryChoice>& choices, const results::Results& res,
                             const WorkHook* hook, std::string& mismatch);

}  // namespace pounding
