// The IDA scene: per lane and gap the record factor of first contact, a hunt through peaks_at, then bisection (scene.hpp).
#include <algorithm>
#include <cmath>

#include "scene.hpp"

namespace pounding::study_run {

namespace {

enum : std::uint8_t { open, found, excluded };  // the IDA's (lane, gap) states

// The bisection (see ida()): every found (lane, gap) bracket narrowed to the tolerance, each step's open brackets at
// their midpoints through Runner::at_factors (the pair: one kernel lane per bracket, each spring its unscaled
// equivalent at the factor, the identity R(f w; fy) = f R(w; fy / f) checked in tests/study; a System: the record
// scaled, one run per (lane, factor)).
void bisect(UnitContext& c, std::vector<std::uint8_t>& state, std::vector<double>& lo, std::vector<double>& hi,
            std::span<std::int32_t> analyses) {
  const std::size_t G = c.plan.gaps;
  Scratch& x = c.scratch;
  for (int step = 0; step < 200; ++step) {
    x.todo.clear();
    for (std::size_t k = 0; k < state.size(); ++k)
      if (state[k] == found && !(hi[k] <= lo[k] * (1.0 + c.s.intensity.tolerance))) x.todo.push_back(k);
    if (x.todo.empty()) break;
    x.mids.resize(x.todo.size());
    for (std::size_t j = 0; j < x.todo.size(); ++j) {
      const std::size_t k = x.todo[j];
      x.mids[j] = LaneFactor{k / G, lo[k] > 0 ? std::sqrt(lo[k] * hi[k]) : 0.5 * hi[k]};
    }
    c.runner.at_factors(x.mids, c.record.record, c.s.free_vibration, c.ks, x.factors);
    for (std::size_t j = 0; j < x.todo.size(); ++j) {
      const std::size_t k = x.todo[j], i = k / G, g = k % G;
      const double f = x.mids[j].f;
      if (x.factors.ran[j]) ++analyses[i];
      if (x.factors.excluded[j]) state[k] = excluded;
      else if (x.factors.closing[j] > c.s.gap_at(g, c.block[i])) hi[k] = f;
      else lo[k] = f;
    }
  }
}

}  // namespace

// The bisection IDA of yielding pairs (method = "ida"): for every lane and gap ratio x, the record scale factor
// at which the pair first touches, i.e. the smallest f with peak closing D(f) > x d.
//  1. Hunt: the record scaled (like a stripe, bit-identical to MSA's analysis at that factor) to each factor of
//     ida_hunt_factors -- the stripes' levels below max_scale, then max_scale. The first factor whose run
//     touches brackets f* between it and the factor before (0 before the first); no touch up to the last factor:
//     censored. A diverged analysis ends the lane's hunt: its open gaps are censored at the factor before (the
//     record's cap comes down to it in make_results), or excluded when that was the first factor.
//  2. Bisection on ln f (halving from 0 while the bracket starts there) until hi <= lo (1 + tolerance): bisect().
//  A lane whose buildings are still elastic at the factor that closed its bracket needs no bisection: its first
//  contact is the anchor's linear extrapolation, exact (scale_lo = scale_hi).
// With several crossings of D(f) = x d (a "resurrection"), the hunt's first bracket is kept: f* is the first
// crossing to the resolution of the hunt.
void ida(UnitContext& c, UnitResult& out) {
  const std::size_t n = c.block.size(), G = c.plan.gaps;
  const RunPeaks &cur = c.scratch.cur, &anchor = c.scratch.anchor;
  const std::vector<double> hunt = ida_hunt_factors(c.s.intensity, c.stripes.im[c.r]);
  std::vector<std::uint8_t> state(n * G, open);
  std::vector<double> lo(n * G, 0.0), hi(n * G, INFINITY);
  auto analyses = out.values<std::int32_t>(c.fields.ida_analyses);
  auto limit = out.values<double>(c.fields.ida_limit);
  for (std::size_t i = 0; i < n; ++i) analyses[i] = 1, limit[i] = hunt.back();  // 1: the record as it is
  std::vector<std::uint8_t> diverged(n, 0);
  double fa = 0;
  for (std::size_t h = 0; h < hunt.size(); ++h) {
    const double f = hunt[h];
    peaks_at(c, f, fa);
    if (h == 0)
      for (std::size_t i = 0; i < n; ++i) ++analyses[i];
    else
      for (std::size_t i : c.scratch.lanes) ++analyses[i];  // the lanes run, not scaled from the anchor
    for (std::size_t i = 0; i < n; ++i) {
      if (diverged[i]) continue;
      if (cur.status[i] != 0) {
        // no contact known up to the factor before: censored there (the record's cap goes down to it, make_results);
        // at the first factor nothing is known: excluded
        diverged[i] = 1, limit[i] = h ? hunt[h - 1] : 0.0;
        for (std::size_t g = 0; g < G; ++g)
          if (state[i * G + g] == open && h == 0) state[i * G + g] = excluded;
        continue;
      }
      for (std::size_t g = 0; g < G; ++g) {
        const std::size_t k = i * G + g;
        if (state[k] != open) continue;
        if (cur.closing[i] > c.s.gap_at(g, c.block[i])) state[k] = found, hi[k] = f;
        else lo[k] = f;
      }
    }
  }
  // A lane still elastic where it first touched is linear on [0, hi]: D(f) = (f / fa) D(fa), so its first contact
  // is exactly at fa x d / D(fa), no bisection needed ([analysis] scale_elastic; the bracket closes on it)
  if (c.s.scale_elastic)
    for (std::size_t k = 0; k < n * G; ++k) {
      const std::size_t i = k / G;
      if (state[k] != found || !c.runner.scales_linearly(anchor, i, hi[k] / fa, c.ks.displacement_limit)) continue;
      const double D = anchor.closing[i];
      const double f = fa * c.s.gap_ratios[k % G] * c.s.gap_unit(c.block[i]) / D;  // (fa x) d / D in this order: ratio studies' bits
      lo[k] = hi[k] = std::clamp(f, lo[k], hi[k]);
    }
  bisect(c, state, lo, hi, analyses);
  auto slo = out.values<double>(c.fields.ida_lo), shi = out.values<double>(c.fields.ida_hi);
  for (std::size_t k = 0; k < n * G; ++k) {
    const bool ok = state[k] != excluded;
    slo[k] = ok ? lo[k] : NAN, shi[k] = ok ? hi[k] : NAN;  // open: censored, [last factor analysed, inf)
  }
}

}  // namespace pounding::study_run
