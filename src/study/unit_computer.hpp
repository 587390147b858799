// The per-unit computer of a study run (unit_computer.cpp), private to run.cpp: made and called through these.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

#include "pounding/study/intensity.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/unit_result.hpp"

namespace pounding {
class StructureSampler;
}

namespace pounding::study_run {

// One work unit: the block sampled, its runs, a UnitResult. One per worker thread (it holds every buffer it writes);
// what it shares with the others is read only except `computed`, the rank's count of units started.
class UnitComputer;
struct UnitComputerDelete {
  void operator()(UnitComputer* c) const noexcept;
};
using UnitComputerPtr = std::unique_ptr<UnitComputer, UnitComputerDelete>;

// `stop`: a stop reaches the steppers inside a unit (may be null).
UnitComputerPtr make_unit_computer(const Study& s, const std::vector<StudyRecord>& records, const StripePlan& stripes,
                                   const StructureSampler& sampler, const WorkPlan& plan, int rank,
                                   std::atomic<int>& computed, const std::atomic<bool>* stop);
// Unit `unit` (the plan's id) computed.
UnitResult compute_unit(UnitComputer& computer, std::size_t unit);

}  // namespace pounding::study_run
