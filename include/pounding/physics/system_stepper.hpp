#pragma once
// The system stepper's entry points besides physics::run_system (physics/system_batch.hpp): the checks that are
// the stepper's own (which stepper, laws and sides it runs), and a test-only entry that runs any system --
// System::sdof_pair() included -- through the dynamic layout (physics/steppers/system_central_difference.hpp).
#include <cstddef>
#include <span>
#include <vector>

#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/validate.hpp"

namespace pounding::physics {

// What the dynamic layout cannot run beyond physics::validate's refusals: a stepper other than central difference,
// a hysteresis law outside the registry, more than
// one ground-motion channel, the stereomechanical law at a side that is not a point, a series recorder.
std::vector<Problem> system_stepper_problems(const SystemBatch& batch, std::span<const ContactModel> groups,
                                             const KernelSettings& settings);

// Lanes per tile of the dynamic layout: simd::W (one chunk per tile). Central difference runs each chunk through
// the whole record, so a wider tile only batches the fill and the collection; and a chunk of a wide tile reads
// its rows `tile` x 8 bytes apart (512 B at 64 lanes), which maps every row into 8 of the L1's 64 sets, where
// at tile = W the chunk's rows are contiguous (bench: `pounding bench --storeys`).
std::size_t default_system_tile(std::size_t width);

namespace testing {
// Validation, then the dynamic layout whatever the topology (run_system sends the SDOF pair to the pair kernel).
// `tile`: lanes per tile, a multiple of simd::W (0: default_system_tile).
void run_system_dynamic(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                        const KernelSettings& settings, SystemResult& out, std::size_t tile = 0);
// The dynamic layout's generic path even where the stick path (Layout::stick) would run: the reference its bits are
// compared with (test_system_stick.cpp). Central difference only.
void run_system_generic(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                        const KernelSettings& settings, SystemResult& out);
// Whether the stick path runs `system` (an impulsive contact law aside).
bool stick_path(const model::System& system);
}  // namespace testing

}  // namespace pounding::physics
