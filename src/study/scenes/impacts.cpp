// The impacts scene: per gap the lanes that touch run coupled, the others take their uncoupled peaks (scene.hpp).
#include "scene.hpp"

namespace pounding::study_run {

// A lane whose uncoupled peak closing stays <= g never touches at gap g, and its coupled run is bit-identical to the
// uncoupled one (the first-passage property, tested): only the lanes that touch (D > gap) or failed are run with
// contact (all with skip_untouched = false); the others take the uncoupled results.
void impacts(UnitContext& c, std::size_t g, const UnitMotion& m, UnitResult& out) {
  const RunPeaks& peaks = c.scratch.peaks;
  std::vector<std::size_t>& lanes = c.scratch.lanes;
  KernelSettings kc = c.ks;  // e(v0) at every study-gap impact ([contact] restitution)
  if (c.restitution) kc.restitution = &c.restitution->hook;
  lanes.clear();
  for (std::size_t i = 0; i < c.block.size(); ++i) {
    const bool untouched = peaks.status[i] == 0 && !(peaks.closing[i] > c.s.gap_at(g, c.block[i]));
    if (!c.s.skip_untouched || !untouched) lanes.push_back(i);
  }
  c.runner.coupled(lanes, c.s.gap_ratios[g], m, kc, c.scratch.coupled);
  for (std::size_t i = 0, j = 0; i < c.block.size(); ++i)
    put_coupled(c, out, i, g, j < lanes.size() && lanes[j] == i ? j++ : std::string::npos);
}

}  // namespace pounding::study_run
