// The multiple-stripe scene and peaks_at, the analysis at one factor the IDA's hunt shares (scene.hpp).
#include "pounding/results/schema.hpp"

#include "scene.hpp"

namespace pounding::study_run {

std::span<const double> scaled(Scratch& scratch, const Record& rec, double f) {
  scratch.scaled.resize(rec.acc.size());
  for (std::size_t t = 0; t < scratch.scaled.size(); ++t) scratch.scaled[t] = f * rec.acc[t];
  return scratch.scaled;
}

// With fa == 0 the anchor run of every lane (scratch.anchor; fa becomes f); at a higher factor f the lanes that
// scale linearly over f / fa (Runner::scales_linearly, the model trait; [analysis] scale_elastic) take the anchor's
// peaks times f / fa, the others (scratch.lanes) run on the scaled record (a lane's bits do not depend on the lanes
// run beside it).
void peaks_at(UnitContext& c, double f, double& fa) {
  const Record& rec = c.record.record;
  Scratch& x = c.scratch;
  const std::size_t n = c.block.size();
  const UnitMotion m{GroundMotion{rec.dt, scaled(x, rec, f), rec.duration() + c.s.free_vibration}, {}};
  const bool anchor = fa == 0;
  if (anchor) fa = f;
  const double ratio = anchor ? 1.0 : f / fa;
  x.lanes.clear();
  if (anchor) {
    c.runner.uncoupled(m, c.ks, x.anchor);
  } else {
    for (std::size_t i = 0; i < n; ++i)
      if (!(c.s.scale_elastic && c.runner.scales_linearly(x.anchor, i, ratio, c.ks.displacement_limit))) x.lanes.push_back(i);
    if (!x.lanes.empty()) c.runner.rerun_uncoupled(x.lanes, m, c.ks, x.sub);
  }
  x.cur.resize(n, x.anchor.buildings, c.runner.layout());
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    if (j < x.lanes.size() && x.lanes[j] == i) x.cur.set_scaled(i, x.sub, j++, 1.0);
    else x.cur.set_scaled(i, x.anchor, i, ratio);
  }
}

// A multiple-stripe unit: the block of models under record r scaled to every stripe's level, lowest first. A
// record dropped from a stripe (factor above max_scale) is not analysed there (status dropped_status). The first
// stripe analysed runs every model (the anchor, factor fa). At a higher stripe with factor f a model whose
// buildings stayed elastic in the anchor run and stay so at f -- ratio f / fa times each anchor peak |u| below
// (1 - 1e-9) fy / k, and ratio times (peak |u1| + peak |u2|) within the displacement limit -- is not rerun: an
// elastic response scales exactly with the record, so its peaks are the anchor's times the ratio
// ([analysis] scale_elastic; tests/cli/fragility_scale_elastic.sh compares it with every model run). The others
// (and all of them with scale_elastic = false) are run on the scaled record.
void stripes(UnitContext& c, UnitResult& out) {
  const std::size_t n = c.block.size(), R = c.stripes.records;
  const std::size_t unc_status = results::unit_field("uncoupled", "status");
  double fa = 0;
  for (std::size_t s = 0; s < c.plan.stripes; ++s) {
    const std::size_t k = s * R + c.r, at = s * n;
    if (c.stripes.dropped[k]) {
      for (std::size_t i = 0; i < n; ++i) out.values<std::uint8_t>(unc_status)[at + i] = results::dropped_status;
      continue;
    }
    const bool anchor = fa == 0;
    peaks_at(c, c.stripes.scale[k], fa);
    for (std::size_t i = 0; i < n; ++i) put_uncoupled(out, at + i, c.scratch.cur, i);
    for (std::size_t i = 0; i < n; ++i) put_uncoupled_rows(c, out, i, c.scratch.cur, s);
    if (anchor) continue;
    auto scaled_flag = out.values<std::uint8_t>(c.fields.stripe_scaled);
    for (std::size_t i = 0; i < n; ++i) scaled_flag[at + i] = 1;
    for (std::size_t i : c.scratch.lanes) scaled_flag[at + i] = 0;
  }
}

}  // namespace pounding::study_run
