// [outputs] per_model = false: the reductions folded in on rank 0 instead of every model's peaks.
#include "pounding/study/reductions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/kernel/batch.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

std::vector<double> histogram_edges() {
  const int decades = static_cast<int>(std::lround(std::log10(histogram_hi / histogram_lo)));
  std::vector<double> e;
  for (int b = 0; b <= decades * histogram_per_decade; ++b)
    e.push_back(histogram_lo * std::pow(10.0, static_cast<double>(b) / histogram_per_decade));
  e.back() = histogram_hi;
  return e;
}

double reduction_bytes(std::size_t rows, std::size_t pairs, std::size_t gaps, std::size_t curve_points) {
  const double bins = static_cast<double>(histogram_edges().size() + 1);
  return 8.0 * static_cast<double>(rows) *
         (3.0 + static_cast<double>(gaps) + static_cast<double>(pairs) * (1.0 + static_cast<double>(gaps)) +
          static_cast<double>(curve_points) + bins);
}

Reductions::~Reductions() = default;
Reductions::Reductions(Reductions&&) noexcept = default;
Reductions& Reductions::operator=(Reductions&&) noexcept = default;

Reductions::Reductions(const Study& study, const WorkPlan& plan)
    : study_(&study), plan_(plan), sampler_(std::make_unique<StructureSampler>(study.structures, study.seed)),
      edges_(histogram_edges()) {
  const int points = static_cast<int>(std::floor(study.curve_max / study.curve_step + 1e-9));  // as the report's curve
  for (int i = 1; i <= points; ++i) curve_x_.push_back(study.curve_step * i);
  const std::size_t R = plan.records, P = plan.pairs, G = study.gap_ratios.size();
  n_.assign(R, 0), excluded_.assign(R, 0), gap_hits_.assign(R * G, 0);
  pair_n_.assign(R * P, 0), pair_hits_.assign(R * P * G, 0);
  curve_hits_.assign(R * curve_x_.size(), 0), histogram_.assign(R * (edges_.size() + 1), 0);
  for (std::size_t p = 0; p < P; ++p) {
    const SampleId id = study.structures.pair_id(static_cast<std::int64_t>(p));
    pair_i1_.push_back(id.i1), pair_i2_.push_back(id.i2);
  }
}

bool Reductions::ok(std::uint8_t s) const {
  return s == 0 || (study_->coarse == CoarsePolicy::keep && s == static_cast<std::uint8_t>(LaneStatus::coarse));
}

void Reductions::fold(const UnitIndex& u, std::span<const std::uint8_t> status, std::span<const double> closing) {
  const std::size_t lanes = status.size(), row = u.record;
  const std::size_t block = u.pair * plan_.blocks + u.block, m0 = plan_.first_model(u);
  if (plan_.stream && drawn_.empty()) drawn_.assign(plan_.pairs * plan_.blocks, 0), gap_of_.assign(plan_.models(), 0.0);
  if (!plan_.stream || !drawn_[block]) {  // draw the models (once per model with "stream"): the summary and each d
    std::vector<SampledPair> sp(lanes);
    const SampleId pair = study_->structures.pair_id(static_cast<std::int64_t>(u.pair));
    sampler_->sample_block(pair.i1, pair.i2, static_cast<std::int64_t>(u.block * plan_.batch), sp);
    if (plan_.stream) drawn_[block] = 1;
    for (std::size_t j = 0; j < lanes; ++j) {
      const SampledPair& q = sp[j];
      const std::array<double, 15> key{q.s1.T, q.s2.T, q.s1.h, q.s2.h, q.s1.m, q.s2.m, q.s1.k, q.s2.k,
                                       q.s1.fy, q.s2.fy, q.s1.c, q.s2.c, q.d, q.s1.alpha, q.s2.alpha};
      if (!seen_) first_ = key, seen_ = true, gap_min_ = gap_max_ = q.d;
      else if (key != first_) varied_ = true;
      gap_min_ = std::min(gap_min_, q.d), gap_max_ = std::max(gap_max_, q.d);
      if (plan_.stream) gap_of_[m0 + j] = study_->gap_unit(q);
      else fold_one(row, u.pair, status[j], closing[j], study_->gap_unit(q));
    }
    if (!plan_.stream) return;
  }
  for (std::size_t j = 0; j < lanes; ++j) fold_one(row, u.pair, status[j], closing[j], gap_of_[m0 + j]);
}

// One analysis (record row, period pair) with its status, peak closing and gap unit d (its code gap d, or 1 m with
// [gaps] metres: Study::gap_unit).
void Reductions::fold_one(std::size_t row, std::size_t pair, std::uint8_t status, double c, double d) {
  const std::size_t G = study_->gap_ratios.size(), C = curve_x_.size(), B = edges_.size() + 1;
  if (!ok(status)) {
    ++excluded_[row];
    return;
  }
  ++n_[row], ++pair_n_[row * plan_.pairs + pair];
  for (std::size_t g = 0; g < G; ++g)
    if (c > study_->gap_ratios[g] * d) ++gap_hits_[row * G + g], ++pair_hits_[(row * plan_.pairs + pair) * G + g];
  const double z = c / d;  // the report's curve: z > x (strict, like delta > 0)
  for (std::size_t i = 0; i < C && z > curve_x_[i]; ++i) ++curve_hits_[row * C + i];
  // bin b: e_{b-1} < z <= e_b; 0 below e_0 (and NaN-free: ok analyses are finite), B - 1 above the last edge
  const std::size_t b = static_cast<std::size_t>(std::lower_bound(edges_.begin(), edges_.end(), z) - edges_.begin());
  ++histogram_[row * B + b];
}

std::vector<std::int64_t> Reductions::counts() const {
  std::vector<std::int64_t> v;
  for (const auto* a : {&n_, &excluded_, &gap_hits_, &pair_n_, &pair_hits_, &curve_hits_, &histogram_})
    v.insert(v.end(), a->begin(), a->end());
  return v;
}

void Reductions::set_counts(std::span<const std::int64_t> summed) {
  std::size_t at = 0;
  for (auto* a : {&n_, &excluded_, &gap_hits_, &pair_n_, &pair_hits_, &curve_hits_, &histogram_}) {
    if (at + a->size() > summed.size()) throw std::logic_error("Reductions::set_counts: too few counts");
    std::copy(summed.begin() + static_cast<std::ptrdiff_t>(at),
              summed.begin() + static_cast<std::ptrdiff_t>(at + a->size()), a->begin());
    at += a->size();
  }
  if (at != summed.size()) throw std::logic_error("Reductions::set_counts: too many counts");
}

void Reductions::add_counts(std::span<const std::int64_t> more) {
  std::vector<std::int64_t> c = counts();
  if (more.size() != c.size())
    throw std::invalid_argument(fmt::format("{} counts, this study's reductions have {}", more.size(), c.size()));
  for (std::size_t k = 0; k < c.size(); ++k) c[k] += more[k];
  set_counts(c);
}

// [seen, varied, gap_min, gap_max, first_ (15)]
std::vector<double> Reductions::summary() const {
  std::vector<double> v = {seen_ ? 1.0 : 0.0, varied_ ? 1.0 : 0.0, gap_min_, gap_max_};
  v.insert(v.end(), first_.begin(), first_.end());
  return v;
}

void Reductions::merge_summary(std::span<const double> o) {
  if (o.size() != 4 + first_.size()) throw std::invalid_argument("Reductions::merge_summary: wrong length");
  if (o[0] == 0.0) return;  // that rank folded no model
  std::array<double, 15> first{};
  std::copy(o.begin() + 4, o.end(), first.begin());
  if (!seen_) {
    seen_ = true, varied_ = o[1] != 0.0, gap_min_ = o[2], gap_max_ = o[3], first_ = first;
    return;
  }
  if (o[1] != 0.0 || first != first_) varied_ = true;
  gap_min_ = std::min(gap_min_, o[2]), gap_max_ = std::max(gap_max_, o[3]);
}

results::Group Reductions::group() const {
  const std::size_t R = plan_.records, P = plan_.pairs, G = study_->gap_ratios.size();
  results::Group g{"reductions", {}, {}};
  g.set("models", static_cast<std::int64_t>(plan_.models()));
  g.set("fixed_pair", static_cast<std::int64_t>(seen_ && !varied_));
  g.set("code_gap_min", gap_min_);
  g.set("code_gap_max", gap_max_);
  g.set("histogram_per_decade", static_cast<std::int64_t>(histogram_per_decade));
  const bool m = study_->gap_metres;  // [gaps] metres: every x below is metres and z the closing in metres
  if (m) g.set("gap_unit", std::string("m"));
  const char* x_unit = m ? "m" : "1";
  if (m)
    g.set("description",
          std::string("[outputs] per_model = false: counts over the ok analyses (status 0, or coarse with [analysis] "
                      "coarse = \"keep\") per record row, instead of per-model arrays; [gaps] metres: z = uncoupled "
                      "peak closing in metres, every gap x in metres. Every value is an integer count: independent of "
                      "ranks, threads, batch width and order"));
  else g.set("description",
        std::string("[outputs] per_model = false: counts over the ok analyses (status 0, or coarse with [analysis] "
                    "coarse = \"keep\") per record row, instead of per-model arrays; z = uncoupled peak closing / code "
                    "gap d. Every value is an integer count: independent of ranks, threads, batch width and order"));
  g.add("gap_ratios", study_->gap_ratios, x_unit,
        m ? "the gaps x (m, [gaps] metres) of gap_hits and pair_hits" : "the gap ratios x of gap_hits and pair_hits (gap = x d)");
  g.add("n", n_, "1", "ok analyses per record row [records]");
  g.add("excluded", excluded_, "1", "analyses with status != ok per record row (diverged, non-finite) [records]");
  g.add("gap_hits", gap_hits_, "1",
        m ? "ok analyses with peak closing > x (m) per record row and gap [records, gaps]"
          : "ok analyses with peak closing > x d per record row and gap ratio [records, gaps]",
        {R, G});
  std::vector<std::int64_t> i1(pair_i1_.begin(), pair_i1_.end()), i2(pair_i2_.begin(), pair_i2_.end());
  g.add("pair_i1", i1, "1", "period pair p's index in building 1's period grid (/models/periods1) [pairs]");
  g.add("pair_i2", i2, "1", "period pair p's index in building 2's period grid (/models/periods2) [pairs]");
  g.add("pair_n", pair_n_, "1", "ok analyses per record row and period pair [records, pairs]", {R, P});
  g.add("pair_hits", pair_hits_, "1",
        m ? "ok analyses with peak closing > x (m) per record row, period pair and gap [records, pairs, gaps]"
          : "ok analyses with peak closing > x d per record row, period pair and gap ratio [records, pairs, gaps]",
        {R, P, G});
  g.add("curve_x", curve_x_, x_unit,
        m ? "the gap curve's gaps x (m) = curve_step c, c = 1..floor(curve_max / curve_step)"
          : "the gap curve's ratios x = curve_step c, c = 1..floor(curve_max / curve_step)");
  g.add("curve_hits", curve_hits_, "1", "ok analyses with z > x per record row and curve ratio [records, curve]",
        {R, curve_x_.size()});
  g.add("histogram_edges", edges_, x_unit,
        fmt::format("edges e_0..e_B of z's log grid, {} bins per decade from {:g} to {:g}", histogram_per_decade,
                    histogram_lo, histogram_hi));
  g.add("histogram", histogram_, "1",
        "ok analyses per record row and bin of z: bin 0 is z <= e_0 (never closing included), bin b is "
        "(e_{b-1}, e_b], the last bin z > e_B [records, B + 2]",
        {R, edges_.size() + 1});
  return g;
}

}  // namespace pounding
