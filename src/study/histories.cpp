// [outputs] histories: see histories.hpp.
#include "pounding/study/histories.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/core/error.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_series.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/system_block.hpp"

namespace pounding {

namespace {

bool named_record(const HistorySpec& h) { return !h.record_name.empty() || h.record_index >= 0; }

// The index of gap ratio x among the study's (-1: none within 1e-9 relative).
std::ptrdiff_t gap_index(const Study& s, double x) {
  for (std::size_t g = 0; g < s.gap_ratios.size(); ++g)
    if (std::abs(s.gap_ratios[g] - x) <= 1e-9 * std::abs(s.gap_ratios[g])) return static_cast<std::ptrdiff_t>(g);
  return -1;
}

// The model keys of an explicit entry: model = row, or pair = [i1, i2] with sample = k, within the study's grid.
void check_model_keys(const Study& s, const HistorySpec& h) {
  const StructureModel& m = s.structures;
  const bool by_pair = h.i1 >= 0 || h.sample >= 0;
  if (h.model < 0 && !by_pair)
    throw InputError("the entry names no model", h.where,
                     "give model = <row of /models>, or pair = [i1, i2] and sample = k (/models/i1, i2, sample)");
  if (h.model >= 0 && by_pair)
    throw InputError("the entry names its model twice (model and pair / sample)", h.where,
                     "give model = <row of /models>, or pair = [i1, i2] and sample = k, not both");
  if (by_pair && (h.i1 < 0 || h.sample < 0))
    throw InputError("pair and sample name a model together", h.where, "give both pair = [i1, i2] and sample = k");
  if (h.model >= m.model_count())
    throw InputError(fmt::format("model = {} is beyond the study's {} models", h.model, m.model_count()), h.where,
                     fmt::format("give a /models row from 0 to {}", m.model_count() - 1));
  if (by_pair && (h.i1 >= static_cast<long>(m.slots(0)) || h.i2 >= static_cast<long>(m.slots(1))))
    throw InputError(fmt::format("pair = [{}, {}] is not a period pair of the study ({} x {} period slots)", h.i1, h.i2,
                                 m.slots(0), m.slots(1)),
                     h.where, fmt::format("give i1 from 0 to {} and i2 from 0 to {}", m.slots(0) - 1, m.slots(1) - 1));
  if (by_pair && h.sample >= m.samples_per_pair)
    throw InputError(fmt::format("sample = {} is beyond the {} samples per pair", h.sample, m.samples_per_pair),
                     h.where, fmt::format("give a sample from 0 to {}", m.samples_per_pair - 1));
}

// The run of an entry: gap = x must be a coupled run of the study.
void check_run_keys(const Study& s, const HistorySpec& h) {
  if (!h.gap_given && h.worst == 0 && s.scene == Scene::impacts)
    throw InputError("an entry of the impacts scene names its run", h.where,
                     fmt::format("give gap = one of [gaps] {} {} for a coupled run, or gap = \"uncoupled\"",
                                 s.gap_metres ? "metres" : "ratios", s.gap_ratios));
  if (!h.gap_given || h.uncoupled) return;
  if (s.scene != Scene::impacts)
    throw InputError(fmt::format("gap = {:g} is a coupled run, and the probability scene runs none", h.gap_ratio),
                     h.where, "write gap = \"uncoupled\" (or delete gap), or scene = \"impacts\"");
  if (gap_index(s, h.gap_ratio) < 0)
    throw InputError(fmt::format("gap = {:g} is not one of the study's gap {}", h.gap_ratio, s.gap_metres ? "metres" : "ratios"),
                     h.where, fmt::format("give one of [gaps] {} {}, or gap = \"uncoupled\"",
                                          s.gap_metres ? "metres" : "ratios", s.gap_ratios));
}

}  // namespace

void check_histories(const Study& s) {
  if (s.histories.empty()) return;
  const std::string& where = s.histories.front().where;
  if (s.intensity.enabled)
    throw InputError("[outputs] histories is not available in a fragility study ([intensity]): its analyses run on "
                     "scaled records (stripes, the IDA's bisection)",
                     where, "delete histories, or name the analyses in the same study without [intensity]");
  if (runs_systems(s.structures) && s.stepper != Stepper::central_difference)
    throw InputError(fmt::format("the time history of a System is recorded by the central-difference stepper, and the "
                                 "study runs {}", to_string(s.stepper)),
                     where, "use [analysis] stepper = \"central-difference\", or delete histories");
  for (const HistorySpec& h : s.histories) {
    check_run_keys(s, h);
    if (h.worst > 0) {
      if (named_record(h) || h.model >= 0 || h.i1 >= 0 || h.sample >= 0)
        throw InputError("worst = N chooses its analyses, and the entry names one too", h.where,
                         "give { worst = N } (with gap: at that gap) or { record, model, gap } as separate entries");
      if (!s.per_model || s.stream)
        throw InputError("worst = N ranks the per-model results, which per_model = false or \"stream\" does not keep",
                         h.where, "set [outputs] per_model = true, or name the analyses: { record, model, gap }");
      continue;
    }
    if (!named_record(h))
      throw InputError("the entry names no record", h.where,
                       "give record = \"<id as in /records/id>\" or its row, or worst = N");
    check_model_keys(s, h);
  }
}

std::vector<HistoryChoice> resolve_histories(const Study& s, const std::vector<StudyRecord>& records) {
  std::vector<HistoryChoice> out;
  for (const HistorySpec& h : s.histories) {
    if (h.worst > 0) continue;
    HistoryChoice c;
    if (!h.record_name.empty()) {
      auto it = std::find_if(records.begin(), records.end(), [&](const StudyRecord& r) { return r.id == h.record_name; });
      if (it == records.end()) {
        std::vector<std::string> ids;
        for (std::size_t r = 0; r < records.size() && ids.size() < 12; ++r)
          if (records[r].polarity > 0) ids.push_back(records[r].id);
        throw InputError(fmt::format("record \"{}\" is not one of the study's {} records", h.record_name, records.size()),
                         h.where, fmt::format("give one of the ids {}{} (or a row from 0 to {})", ids,
                                              records.size() > ids.size() ? " ..." : "", records.size() - 1));
      }
      c.record = static_cast<std::size_t>(it - records.begin());
    } else if (static_cast<std::size_t>(h.record_index) >= records.size()) {
      throw InputError(fmt::format("record = {} is beyond the study's {} records", h.record_index, records.size()),
                       h.where, fmt::format("give a /records row from 0 to {}", records.size() - 1));
    } else {
      c.record = static_cast<std::size_t>(h.record_index);
    }
    const std::int64_t n2 = static_cast<std::int64_t>(s.structures.slots(1));
    c.model = h.model >= 0 ? static_cast<std::size_t>(h.model)
                           : static_cast<std::size_t>((h.i1 * n2 + h.i2) * s.structures.samples_per_pair + h.sample);
    c.gap = h.gap_given && !h.uncoupled ? gap_index(s, h.gap_ratio) : -1;
    c.chosen = "named (" + h.where + ")";
    out.push_back(std::move(c));
  }
  return out;
}

namespace {

// Series per history at most (t, ag, u and a_abs per DOF, force per element): the SDOF pair's 7; a System's from the
// study's tallest topology (table_topology), or for an SDOF facing a shear building its tallest sample.
double series_bound(const Study& s) {
  if (!runs_systems(s.structures)) return 7.0;
  if (const std::optional<LaneTopology> t = table_topology(s.structures, s.seed)) {
    SystemBlock block(s);
    const model::System& sys = block.table_system(*t);
    return 2.0 + 2.0 * sys.ndof() + static_cast<double>(sys.contacts().size());
  }
  const StructureSampler sampler(s.structures, s.seed);
  int dofs = 0;
  for (std::int64_t p = 0; p < s.structures.period_pair_count(); ++p)
    for (std::int64_t k = 0; k < s.structures.samples_per_pair; ++k) {
      const LaneTopology t = lane_topology(s.structures, sampler.sample(s.structures.pair_id(p, k)));
      int n = 0;
      for (std::size_t b = 0; b < t.buildings(); ++b) n += t.storeys[b] + t.isolated[b];
      dofs = std::max(dofs, n);
    }
  return 2.0 + 3.0 * dofs + 2.0;  // elements: at most one per floor, and two moat walls
}

}  // namespace

void check_history_memory(const Study& s, const std::vector<StudyRecord>& records, std::size_t named) {
  std::size_t count = named;
  for (const HistorySpec& h : s.histories) count += static_cast<std::size_t>(h.worst);
  if (count == 0) return;
  double steps = 0;
  for (const StudyRecord& r : records)
    steps = std::max(steps, (r.record.duration() + s.free_vibration) / (r.record.dt / study_substeps(s, r.record.dt)) + 2);
  const double bytes = static_cast<double>(count) * steps * series_bound(s) * sizeof(double);
  // the histories are held in the results and again in the file's image before it is written
  const double avail = available_memory_bytes(), limit = std::isnan(avail) ? 16e9 : avail / 3.0;
  if (bytes <= limit) return;
  throw InputError(fmt::format("the {} time histories need up to {} ({:.0f} steps x {:.0f} series each), more than the "
                               "{} they may use here", count, human_bytes(bytes), steps, series_bound(s),
                               human_bytes(limit)),
                   s.histories.front().where,
                   "choose fewer analyses (a smaller worst = N), or a larger [analysis] max_dt / fewer substeps");
}

namespace {

const results::Field* find_field(const results::Results& res, std::string_view group, std::string_view name) {
  for (const results::Field& f : res.fields)
    if (f.spec.group == group && f.spec.name == name) return &f;
  return nullptr;
}

struct Candidate {
  double value;
  HistoryChoice c;
};

// Every analysis of one worst entry with its ranking value (finite values only: a diverged analysis is left out).
std::vector<Candidate> candidates(const Study& s, const results::Results& res, const HistorySpec& h) {
  const std::size_t R = res.records.size(), M = res.models.size(), G = s.gap_ratios.size();
  std::vector<Candidate> out;
  const bool coupled = s.scene == Scene::impacts && !(h.gap_given && h.uncoupled);
  if (coupled) {
    const results::Field* force = find_field(res, "impacts", "peak_force");
    const results::Field* status = find_field(res, "impacts", "status");
    if (!force || !status) throw std::logic_error("histories: no impacts/peak_force in the results");
    const auto& f = std::get<std::vector<double>>(force->data);
    const auto& st = std::get<std::vector<std::uint8_t>>(status->data);
    const std::ptrdiff_t only = h.gap_given ? gap_index(s, h.gap_ratio) : -1;
    for (std::size_t k = 0; k < R * M * G; ++k) {
      const auto g = static_cast<std::ptrdiff_t>(k % G);
      const bool failed = st[k] == static_cast<std::uint8_t>(LaneStatus::diverged) ||
                          st[k] == static_cast<std::uint8_t>(LaneStatus::non_finite);
      if ((only >= 0 && g != only) || failed || !std::isfinite(f[k])) continue;
      out.push_back({f[k], {k / (M * G), (k / G) % M, g, {}}});
    }
    return out;
  }
  const results::Field* closing = find_field(res, "uncoupled", "peak_closing");
  const results::Field* status = find_field(res, "uncoupled", "status");
  if (!closing || !status) throw std::logic_error("histories: no uncoupled/peak_closing in the results");
  const auto& D = std::get<std::vector<double>>(closing->data);
  const auto& st = std::get<std::vector<std::uint8_t>>(status->data);
  for (std::size_t k = 0; k < R * M; ++k) {
    const double x = D[k] / res.gaps.unit(res.models.code_gap, k % M);  // closing / d, or ([gaps] metres) in metres
    if (st[k] != 0 || !std::isfinite(x)) continue;
    out.push_back({x, {k / M, k % M, -1, {}}});
  }
  return out;
}

}  // namespace

std::vector<HistoryChoice> choose_worst(const Study& s, const results::Results& res,
                                        std::vector<HistoryChoice> out) {
  for (const HistorySpec& h : s.histories) {
    if (h.worst == 0) continue;
    std::vector<Candidate> all = candidates(s, res, h);
    const std::size_t n = std::min(all.size(), static_cast<std::size_t>(h.worst));
    // the largest first; ties in record, model, gap order (the candidates' order)
    std::stable_sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.value > b.value; });
    const bool coupled = all.empty() ? false : all.front().c.gap >= 0;
    for (std::size_t k = 0; k < n; ++k) {
      HistoryChoice c = all[k].c;
      c.chosen = fmt::format("worst {} of {} by {} ({:.6g}{})", k + 1, h.worst,
                             coupled ? "peak impact force" : "peak closing / code gap", all[k].value,
                             coupled ? " N" : "");
      const bool seen = std::any_of(out.begin(), out.end(), [&](const HistoryChoice& o) {
        return o.record == c.record && o.model == c.model && o.gap == c.gap;
      });
      if (!seen) out.push_back(std::move(c));
    }
  }
  return out;
}

namespace {

// One rerun's numbers: the series and the peaks as the study's per-model fields name them.
struct Rerun {
  std::vector<double> t, ag;
  std::vector<std::vector<double>> u, a_abs, force;  // [dof][step], [element][step]
  std::vector<std::string> dofs, elements;
  std::uint8_t status = 0;
  double u1 = 0, u2 = 0, closing = 0, force_peak = 0, t_first = 0;
  std::int32_t count = 0;
};

// Reruns analyses of the study with the recorder, each as its unit ran it (study/run.cpp UnitComputer).
class HistoryRunner {
 public:
  HistoryRunner(const Study& s, const std::vector<StudyRecord>& records, const std::atomic<bool>* stop)
      : s_(s), records_(records), sampler_(s.structures, s.seed) {
    ks_.stop = stop;
    ks_.stepper = s.stepper;
    ks_.displacement_limit = s.displacement_limit;
    uncoupled_ = s.contact;
    uncoupled_.law = ContactLaw::none;
    if (runs_systems(s.structures)) block_.emplace(s);
    if (s.restitution && s.scene == Scene::impacts)
      restitution_ = std::make_unique<physics::HertzdampRestitution>(*s.restitution, s.contact);
  }

  const SampledPair& pair() const { return pair_; }
  // substeps > 0: the analysis's own (impacts/substeps of [analysis] coarse = "refine", study/refine.hpp)
  KernelSettings settings(const Record& rec, int substeps = 0) const {
    KernelSettings ks = ks_;
    ks.substeps = substeps > 0 ? substeps : study_substeps(s_, rec.dt);
    return ks;
  }

  Rerun run(const HistoryChoice& c, int substeps = 0) {
    const std::size_t samples = static_cast<std::size_t>(s_.structures.samples_per_pair);
    pair_ = sampler_.sample(s_.structures.pair_id(static_cast<std::int64_t>(c.model / samples),
                                                  static_cast<std::int64_t>(c.model % samples)));
    const StudyRecord& sr = records_[c.record];
    const GroundMotion gm{sr.record.dt, sr.record.acc, sr.record.duration() + s_.free_vibration};
    KernelSettings ks = settings(sr.record, substeps);
    if (c.gap >= 0 && restitution_) ks.restitution = &restitution_->hook;
    const double ratio = c.gap >= 0 ? s_.gap_ratios[static_cast<std::size_t>(c.gap)] : 0.0;
    return block_ ? system(sr, gm, ks, c.gap >= 0, ratio) : sdof_pair(gm, ks, c.gap >= 0, ratio);
  }

 private:
  // SDOF pair studies: the pair kernel, one lane (UnitComputer's batch_ / coupled())
  Rerun sdof_pair(const GroundMotion& gm, KernelSettings ks, bool coupled, double ratio) {
    PairBatch b;
    b.resize(1);
    PairParams pp = pair_.pair_params(coupled ? ratio : 0.0, s_.e);
    if (coupled) pp.gap = ratio * s_.gap_unit(pair_);  // ratio x d (the same product), or ([gaps] metres) metres
    if (coupled && s_.contact_stiffness > 0) pp.kc = s_.contact_stiffness;
    b.set(0, pp);
    SeriesRecorder rec;
    ks.series = &rec;
    BatchResult r;
    run_batch(b, coupled ? s_.contact : uncoupled_, gm, ks, r);
    Rerun out;
    out.t = std::move(rec.t), out.ag = std::move(rec.ag);
    out.u = {std::move(rec.u1), std::move(rec.u2)}, out.a_abs = {std::move(rec.a1_abs), std::move(rec.a2_abs)};
    out.force = {std::move(rec.force)};
    out.dofs = {"b1_1", "b2_1"}, out.elements = {"pair"};
    out.status = r.status[0], out.u1 = r.peak_u1[0], out.u2 = r.peak_u2[0], out.closing = r.peak_closing[0];
    out.count = r.impact_count[0], out.force_peak = r.peak_force[0], out.t_first = r.t_first_impact[0];
    return out;
  }

  // Systems: SystemBlock::record, the lane as SystemBlock runs it (UnitComputer::systems)
  Rerun system(const StudyRecord& sr, const GroundMotion& gm, const KernelSettings& ks, bool coupled, double ratio) {
    const int channels = s_.structures.bridge ? s_.structures.bridge->spec.channels() : 1;
    channels_.clear();
    for (int c = 0; c < channels && channels > 1; ++c)
      channels_.push_back(c == 0 ? gm
                                 : GroundMotion{sr.record.dt, sr.more_supports[static_cast<std::size_t>(c - 1)].acc,
                                                gm.duration});
    block_->set_channels(channels_);
    physics::SystemSeries series;
    RunPeaks p;
    const std::span<const SampledPair> one(&pair_, 1);
    const model::System& sys =
        coupled ? block_->record(one, ratio, s_.contact, ContactNumbers{s_.e, s_.contact_stiffness}, gm, ks, p, series)
                : block_->record(one, 0.0, uncoupled_, ContactNumbers{}, gm, ks, p, series);
    Rerun out;
    out.t = std::move(series.t), out.ag = std::move(series.ag);
    out.u = std::move(series.u), out.a_abs = std::move(series.a_abs), out.force = std::move(series.force);
    out.dofs.resize(static_cast<std::size_t>(sys.ndof()));
    for (std::size_t b = 0; b < sys.bodies().size(); ++b)
      for (std::size_t k = 0; k < sys.bodies()[b].dofs.size(); ++k)
        out.dofs[static_cast<std::size_t>(sys.bodies()[b].dofs[k])] = fmt::format("b{}_{}", b + 1, k + 1);
    for (const model::ContactElement& ce : sys.contacts()) out.elements.push_back(ce.label);
    out.status = p.status[0], out.u1 = p.u1[0], out.u2 = p.u2[0], out.closing = p.closing[0];
    out.count = p.impact_count[0], out.force_peak = p.peak_force[0], out.t_first = p.t_first_impact[0];
    return out;
  }

  const Study& s_;
  const std::vector<StudyRecord>& records_;
  StructureSampler sampler_;
  KernelSettings ks_;
  ContactModel uncoupled_;
  std::optional<SystemBlock> block_;
  std::unique_ptr<physics::HertzdampRestitution> restitution_;
  std::vector<GroundMotion> channels_;
  SampledPair pair_;
};

bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// The study's per-model values of choice c against the rerun's ("" when equal or not in `res`).
std::string compare(const Study& s, const results::Results& res, const HistoryChoice& c, const Rerun& r) {
  const std::size_t M = res.models.size(), G = s.gap_ratios.size();
  const bool coupled = c.gap >= 0;
  const std::size_t k = coupled ? (c.record * M + c.model) * G + static_cast<std::size_t>(c.gap) : c.record * M + c.model;
  const char* group = coupled ? "impacts" : "uncoupled";
  std::string out;
  auto check = [&](const char* name, double mine) {
    const results::Field* f = find_field(res, group, name);
    if (!f || M == 0) return;
    const double theirs = std::visit([&](const auto& v) { return v.empty() ? mine : static_cast<double>(v[k]); }, f->data);
    if (!same(theirs, mine)) out += fmt::format(" {}/{} {} vs {}", group, name, theirs, mine);
  };
  check("status", r.status);
  check("peak_u1", r.u1), check("peak_u2", r.u2);
  if (coupled) check("impact_count", r.count), check("peak_force", r.force_peak);
  else check("peak_closing", r.closing);
  return out;
}

// The substeps a coupled analysis ran at where the study refined coarse ones (impacts/substeps); 0: the study's.
int analysis_substeps(const Study& s, const results::Results& res, const HistoryChoice& c) {
  const results::Field* f = c.gap >= 0 ? find_field(res, "impacts", "substeps") : nullptr;
  const auto* v = f ? std::get_if<std::vector<std::int32_t>>(&f->data) : nullptr;
  const std::size_t M = res.models.size(), G = s.gap_ratios.size();
  const std::size_t k = (c.record * M + c.model) * G + static_cast<std::size_t>(std::max<std::ptrdiff_t>(c.gap, 0));
  return v && k < v->size() ? (*v)[k] : 0;
}

std::vector<double> flat(const std::vector<std::vector<double>>& rows) {
  std::vector<double> v;
  for (const auto& x : rows) v.insert(v.end(), x.begin(), x.end());
  return v;
}

// /histories/<n>: the series with units, the analysis' identity and its peaks as attributes.
results::Group history_group(const Study& s, const std::vector<StudyRecord>& records, const HistoryChoice& c,
                             const SampledPair& p, const KernelSettings& ks, Rerun&& r, std::size_t n) {
  results::Group g{fmt::format("{}", n), {}, {}};
  const std::size_t steps = r.t.size();
  g.add("t", std::move(r.t), "s", "time of each integration step from t = 0 (the initial state)");
  g.add("ag", std::move(r.ag), "m/s^2", "ground acceleration of support 1 at each step");
  g.add("u", flat(r.u), "m", "displacement of each DOF relative to its support, [dof][step]", {r.u.size(), steps});
  g.add("a_abs", flat(r.a_abs), "m/s^2", "absolute acceleration of each DOF (relative + its support's; / 9.80665 for g), "
        "[dof][step]", {r.a_abs.size(), steps});
  g.add("force", flat(r.force), "N", "contact force of each contact element (0 when open), [element][step]",
        {r.force.size(), steps});
  g.add("dof_names", std::move(r.dofs), "1", "the DOFs: b<building>_<DOF from the bottom> (an isolated base is 1)");
  g.add("element_names", std::move(r.elements), "1", "the contact elements (their /system labels)");
  const StudyRecord& sr = records[c.record];
  const bool coupled = c.gap >= 0;
  g.set("record", sr.id), g.set("record_row", static_cast<std::int64_t>(c.record));
  g.set("record_name", sr.record.name), g.set("record_polarity", static_cast<std::int64_t>(sr.polarity));
  g.set("model", static_cast<std::int64_t>(c.model));
  g.set("i1", static_cast<std::int64_t>(p.id.i1)), g.set("i2", static_cast<std::int64_t>(p.id.i2));
  g.set("sample", static_cast<std::int64_t>(p.id.sample));
  g.set("scene", std::string(to_string(s.scene))), g.set("run", std::string(coupled ? "coupled" : "uncoupled"));
  g.set("chosen", c.chosen);
  g.set("code_gap_m", p.d);
  if (coupled) {
    const double x = s.gap_ratios[static_cast<std::size_t>(c.gap)];
    if (s.gap_metres) g.set("gap_m", x);  // [gaps] metres: the gap itself
    else g.set("gap_ratio", x), g.set("gap_m", x * p.d);
  }
  g.set("dt_s", sr.record.dt / ks.substeps), g.set("substeps", static_cast<std::int64_t>(ks.substeps));
  g.set("status", static_cast<std::int64_t>(r.status));
  g.set("peak_u1", r.u1), g.set("peak_u2", r.u2);
  if (coupled) {
    g.set("peak_force", r.force_peak), g.set("impact_count", static_cast<std::int64_t>(r.count));
    g.set("t_first_impact", r.t_first);
  } else {
    g.set("peak_closing", r.closing);
  }
  g.set("units", std::string("t s; ag, a_abs m/s^2; u m (relative to the DOF's support); force N; peak_u1, peak_u2, "
                             "peak_closing, gap_m, code_gap_m m; peak_force N; t_first_impact s"));
  return g;
}

}  // namespace

results::Group run_histories(const Study& s, const std::vector<StudyRecord>& records,
                             const std::vector<HistoryChoice>& choices, const results::Results& res,
                             const WorkHook* hook, std::string& mismatch) {
  static const std::string phase = "histories: the chosen analyses rerun with the recorder";
  results::Group out{"histories", {}, {}};
  out.set("count", static_cast<std::int64_t>(choices.size()));
  out.set("description", std::string("the time histories of the analyses [outputs] histories chose, one group each "
                                     "(1, 2, ...); each group's attributes name the analysis and its peaks, equal to "
                                     "the study's per-model values"));
  Meter meter(hook, phase, choices.size(), "analyses");
  HistoryRunner runner(s, records, hook ? hook->cancel : nullptr);
  for (std::size_t n = 0; n < choices.size() && !meter.stopped(); ++n) {
    Rerun r;
    const int substeps = analysis_substeps(s, res, choices[n]);
    try {
      r = runner.run(choices[n], substeps);
    } catch (const StopRequested&) {
      throw Cancelled(phase);
    }
    if (const std::string d = compare(s, res, choices[n], r); !d.empty())
      mismatch += fmt::format("{}history {}:{}", mismatch.empty() ? "" : "; ", n + 1, d);
    const KernelSettings ks = runner.settings(records[choices[n].record].record, substeps);
    out.children.push_back(history_group(s, records, choices[n], runner.pair(), ks, std::move(r), n + 1));
    meter.step();
  }
  meter.finish();
  return out;
}

}  // namespace pounding
