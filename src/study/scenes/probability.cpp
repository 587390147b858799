// The probability scene: every lane uncoupled, its peaks and D (the largest study-gap closing) per lane (scene.hpp).
#include "scene.hpp"

namespace pounding::study_run {

// The uncoupled runs give status, the buildings' largest floor displacements and D = the largest peak closing over
// the study-gap contacts (system_block.hpp; the pair's peak closing), so the scene answers every gap exactly; the
// per-floor rows and a row's buildings 3..n where the plan's schema has them.
void probability(UnitContext& c, const UnitMotion& m, UnitResult& out) {
  RunPeaks& peaks = c.scratch.peaks;
  c.runner.uncoupled(m, c.ks, peaks);
  for (std::size_t i = 0; i < c.block.size(); ++i) {
    put_uncoupled(out, i, peaks, i);
    put_uncoupled_rows(c, out, i, peaks, 0);
  }
}

}  // namespace pounding::study_run
