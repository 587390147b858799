#pragma once
// The study's main job: work units (record, period pair, sample block) -> kernel -> per-model results ->
// checkpoint -> HDF5 results file. Orchestration only; MPI is behind pounding::parallel.
#include <string>

#include "pounding/parallel.hpp"
#include "pounding/study.hpp"

namespace pounding {

struct RunOptions {
  std::string out;      // overrides the study's output path
  bool resume = false;  // continue from <out>.ckpt
  bool progress = true;
};

// Returns the process exit code (0 done, 2 bad input, 130 interrupted). Prints the report on rank 0.
int run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& options);

}  // namespace pounding
