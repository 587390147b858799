// The end of a run: excluded analyses, and the Results of a finished study (provenance, settings, models, fields).
#include "pounding/study/make_results.hpp"

#include "pounding/sampling/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/core/type_list.hpp"
#include "pounding/core/version.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/settings.hpp"
#include "pounding/study/spill.hpp"

namespace pounding {

namespace {

std::string now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

results::Header make_header(const Study& study, const Exclusions& ex, const RunFacts& facts) {
  results::Header h;
  h.program_version = program_version;
  h.git_commit = git_commit;
  h.date = now_iso();
  h.seed = static_cast<std::int64_t>(study.seed);
  h.study_text = study.text, h.study_path = study.path, h.title = study.title;
  h.scene = to_string(study.scene), h.scene_reason = study.scene_reason;
  h.contact_law = to_string(study.contact.law), h.damping_law = to_string(study.contact.damping);
  h.restitution = study.e;
  h.stepper = to_string(study.stepper);
  h.substeps = study.substeps, h.max_dt = study.max_dt;
  h.ranks = facts.ranks, h.build = facts.build;
  const Machine m = this_machine();  // rank 0's: the one that writes the results
  h.host = m.host, h.cpu_model = m.cpu_model, h.cpu_cores = m.cpu_cores;
  h.excluded_analyses = ex.excluded, h.total_analyses = ex.total;
  h.max_excluded_fraction = study.max_excluded_fraction, h.exclusion_warning = ex.verdict;
  h.wall_time_s = facts.wall_time_s;
  return h;
}

results::RecordTable record_table(const std::vector<StudyRecord>& records) {
  results::RecordTable t;
  for (const auto& rr : records) {
    t.id.push_back(rr.id), t.name.push_back(rr.record.name), t.source.push_back(rr.record.source);
    t.note.push_back(rr.note), t.synthetic.push_back(rr.synthetic ? 1 : 0);
    t.dt.push_back(rr.record.dt), t.duration.push_back(rr.record.duration());
    t.pga_g.push_back(rr.record.pga() / g_accel);
    t.npts.push_back(static_cast<std::int64_t>(rr.record.acc.size()));
    t.polarity.push_back(rr.polarity);
  }
  return t;
}

// Models [first, first + n) of the table's per-model columns (each sized n), drawn on every CPU: a sample depends
// only on its pair and index, so no rank ships them, and any window draws the same values.
void draw_models(const Study& study, const WorkPlan& plan, const StructureSampler& sampler, std::size_t first,
                 std::size_t n, results::ModelTable& t) {
  for (const auto& [name, member] : results::model_doubles) (t.*member).resize(n);
  t.i1.resize(n), t.i2.resize(n), t.sample.resize(n);
  const std::size_t parts = std::max<std::size_t>(1, n / 4096);
  parallel_blocks(parts, thread_count(0, parts), [&](std::size_t p0, std::size_t p1) {
    std::vector<SampledPair> sp;
    for (std::size_t i = p0 * n / parts; i < p1 * n / parts;) {
      const std::size_t m = first + i, p = m / plan.samples, s0 = m % plan.samples;
      const std::size_t count = std::min(plan.samples - s0, p1 * n / parts - i);
      const SampleId pair = study.structures.pair_id(static_cast<std::int64_t>(p));
      sp.resize(count);
      sampler.sample_block(pair.i1, pair.i2, static_cast<std::int64_t>(s0), sp);
      for (std::size_t j = 0; j < count; ++j, ++i) {
        const auto& q = sp[j];
        t.T1[i] = q.s1.T, t.T2[i] = q.s2.T, t.h1[i] = q.s1.h, t.h2[i] = q.s2.h, t.m1[i] = q.s1.m, t.m2[i] = q.s2.m;
        t.k1[i] = q.s1.k, t.k2[i] = q.s2.k, t.fy1[i] = q.s1.fy, t.fy2[i] = q.s2.fy, t.code_gap[i] = q.d;
        t.kh[i] = q.kh, t.i1[i] = q.id.i1, t.i2[i] = q.id.i2, t.sample[i] = q.id.sample;
        t.aspect1[i] = q.s1.aspect, t.aspect2[i] = q.s2.aspect, t.rho1[i] = q.s1.rho, t.rho2[i] = q.s2.rho;
        t.mbar1[i] = q.s1.mbar, t.mbar2[i] = q.s2.mbar, t.c1[i] = q.s1.c, t.c2[i] = q.s2.c;
        t.zeta1[i] = q.s1.zeta, t.zeta2[i] = q.s2.zeta, t.alpha1[i] = q.s1.alpha, t.alpha2[i] = q.s2.alpha;
      }
    }
  });
}

results::ModelTable model_table(const Study& study, const WorkPlan& plan) {
  const StructureSampler sampler(study.structures, study.seed);
  const std::size_t M = plan.models();
  results::ModelTable t;
  draw_models(study, plan, sampler, 0, M, t);
  std::vector<SampledPair> sp(plan.samples);
  // a row's buildings 3..n (a bridge's frames 3..n)
  t.row.resize(study.structures.bridge ? study.structures.bridge->frames() - 2 : study.structures.more.size());
  for (auto& b : t.row)
    for (const auto& [prefix, member] : results::row_model_doubles) (b.*member).resize(M);
  for (std::size_t p = 0; p < plan.pairs && !t.row.empty(); ++p) {
    const SampleId pair = study.structures.pair_id(static_cast<std::int64_t>(p));
    sampler.sample_block(pair.i1, pair.i2, 0, sp);
    for (std::size_t s = 0; s < plan.samples; ++s)
      for (std::size_t b = 0; b < t.row.size(); ++b) {
        const std::size_t m = p * plan.samples + s;
        const SampledStructure& x = sp[s].more[b];
        t.row[b].T[m] = x.T, t.row[b].h[m] = x.h, t.row[b].m[m] = x.m, t.row[b].k[m] = x.k, t.row[b].fy[m] = x.fy;
        t.row[b].zeta[m] = x.zeta;
      }
  }
  t.periods1 = sampler.building(0).periods, t.periods2 = sampler.building(1).periods;
  t.periods = t.periods1;  // building 1's grid, for readers of the one-grid files
  t.zeta = study.structures.zeta;
  return t;
}

}  // namespace

physics::CoarseSummary coarse_summary(const Study& study, const WorkPlan& L, const Tally& t,
                                      const std::vector<StudyRecord>& records) {
  constexpr std::size_t imp_status = results::unit_field("impacts", "status");
  constexpr std::size_t imp_h_omega = results::unit_field("impacts", "h_omega_contact");
  physics::CoarseSummary c;
  c.limit = physics::resolution_limit(study.stepper, false, study.contact.law);
  c.kept = study.coarse == CoarsePolicy::keep;
  c.refine = study.coarse == CoarsePolicy::refine;
  const std::size_t MG = L.models() * L.gaps;
  const auto& st = t.values<std::uint8_t>(imp_status);
  const auto& hw = t.values<double>(imp_h_omega);
  const std::vector<std::int32_t>* used =  // impacts/substeps: coarse = "refine" only
      c.refine ? &t.values<std::int32_t>(results::field_index(L.fields, "impacts", "substeps")) : nullptr;
  for (std::size_t r = 0; r < L.records; ++r) {
    const double dt = records[r % records.size()].record.dt;
    const int n = study_substeps(study, dt);
    for (std::size_t i = r * MG; i < (r + 1) * MG; ++i) c.add(hw[i], st[i], used ? (*used)[i] : n, n, dt);
  }
  return c;
}

namespace {
// The verdict's share and advice, the same for per-model results and reductions: more than max_excluded_fraction
// excluded, and what to check when anything was said.
void close_verdict(const Study& study, double frac, Exclusions& ex) {
  if (frac > study.max_excluded_fraction)
    ex.verdict += fmt::format("{}{} of {} analyses ({:.3g} %) were excluded, more than [analysis] "
                              "max_excluded_fraction = {:.3g} %",
                              ex.verdict.empty() ? "" : "; ", ex.excluded, ex.total, 100.0 * frac,
                              100.0 * study.max_excluded_fraction);
  if (!ex.verdict.empty())
    ex.verdict += "; the probabilities may be biased: check the record units and scale, the contact stiffness "
                  "and the step (substeps, max_dt)";
}

// [outputs] per_model = false: the reductions' per-record counts (probability scene of an SDOF pair only).
Exclusions reduced_exclusions(const Study& study, const WorkPlan& L, const Reductions& red,
                              const std::vector<StudyRecord>& records) {
  Exclusions ex;
  std::vector<std::string> lost;
  for (std::size_t r = 0; r < L.records; ++r) {
    ex.excluded += red.excluded(r), ex.total += red.analysed(r);
    const std::string& id = records[r % records.size()].id;
    if (L.models() > 0 && red.excluded(r) == red.analysed(r) && std::find(lost.begin(), lost.end(), id) == lost.end())
      lost.push_back(id);
  }
  const double frac = ex.total ? static_cast<double>(ex.excluded) / static_cast<double>(ex.total) : 0.0;
  if (!lost.empty()) ex.verdict = fmt::format("every analysis of record(s) {} diverged or was non-finite", fmt::join(lost, ", "));
  close_verdict(study, frac, ex);
  return ex;
}
}  // namespace

Exclusions count_exclusions(const Study& study, const WorkPlan& L, const Tally& t,
                            const std::vector<StudyRecord>& records) {
  if (const Reductions* red = t.reductions()) return reduced_exclusions(study, L, *red, records);
  constexpr std::size_t unc_status = results::unit_field("uncoupled", "status");
  constexpr std::size_t imp_status = results::unit_field("impacts", "status");
  Exclusions ex;
  const std::size_t M = L.models(), G = L.gaps;
  const auto& us = t.values<std::uint8_t>(unc_status);
  const bool keep = study.coarse == CoarsePolicy::keep;
  const auto bad = [keep](std::uint8_t s) {
    return s != 0 && s != results::dropped_status && !(keep && s == static_cast<std::uint8_t>(LaneStatus::coarse));
  };
  if (L.impacts) ex.coarse = coarse_summary(study, L, t, records);
  std::vector<std::string> lost;  // each record once, in order
  std::vector<int> lost_at;       // ... and at how many stripes (1 without stripes)
  for (std::size_t r = 0; r < L.analysis_records(); ++r) {  // (stripe, record) in a multiple-stripe study
    std::int64_t bad_unc = 0, bad_cpl = 0;
    std::int64_t dropped = 0;
    for (std::size_t m = 0; m < M; ++m) bad_unc += bad(us[r * M + m]), dropped += us[r * M + m] == results::dropped_status;
    if (dropped) continue;  // a record dropped from a stripe: nothing analysed, nothing excluded
    if (L.impacts)
      for (std::size_t i = r * M * G; i < (r + 1) * M * G; ++i) bad_cpl += bad(t.values<std::uint8_t>(imp_status)[i]);
    ex.excluded += bad_unc + bad_cpl;
    ex.total += static_cast<std::int64_t>(M + (L.impacts ? M * G : 0));
    if (M > 0 && (bad_unc == static_cast<std::int64_t>(M) || (L.impacts && bad_cpl == static_cast<std::int64_t>(M * G)))) {
      const std::string& id = records[r % records.size()].id;
      const auto it = std::find(lost.begin(), lost.end(), id);
      if (it == lost.end()) lost.push_back(id), lost_at.push_back(1);
      else ++lost_at[static_cast<std::size_t>(it - lost.begin())];
    }
  }
  const std::size_t stripes = records.empty() ? 1 : L.analysis_records() / records.size();
  if (stripes > 1)  // a multiple-stripe study: say at how many of the stripes, not the name once per stripe
    for (std::size_t i = 0; i < lost.size(); ++i) lost[i] += fmt::format(" ({} of {} stripes)", lost_at[i], stripes);
  const double frac = ex.total ? static_cast<double>(ex.excluded) / static_cast<double>(ex.total) : 0.0;
  if (!lost.empty())
    ex.verdict = fmt::format("every {}analysis of record(s) {} diverged or was non-finite",
                             L.impacts ? "uncoupled or every coupled " : "", fmt::join(lost, ", "));
  close_verdict(study, frac, ex);
  return ex;
}

results::Settings settings_of(const Study& study) {
  results::Settings s;
  visit_settings(study, [&](const std::string& section, const std::string& key, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, bool>) s.add(section, key, static_cast<std::int64_t>(value));
    else s.add(section, key, value);
  });
  return s;
}

namespace {

// The name of hysteresis model `law` (its index in model::Hystereses).
std::string_view hysteresis_name(int law) {
  const std::string_view out = model::hysteresis_name(law);
  if (out.empty()) throw std::logic_error(fmt::format("system_table: no hysteresis model {}", law));
  return out;
}

constexpr std::string_view role_name(model::SpringRole r) {
  switch (r) {
    case model::SpringRole::storey: return "storey";
    case model::SpringRole::isolator: return "isolator";
    case model::SpringRole::link: return "link";
  }
  return "";
}

constexpr std::string_view side_name(model::SideKind k) {
  switch (k) {
    case model::SideKind::point: return "point";
    case model::SideKind::interpolated: return "interpolated";
    case model::SideKind::wall: return "wall";
  }
  return "";
}

}  // namespace

results::Extents extents_of(const model::System& system) {
  results::Extents x;
  if (system.ndof() == 0 || system.is_sdof_pair()) return x;
  for (const model::Body& b : system.bodies()) x.floors.push_back(b.dofs.size());
  x.elements = system.contacts().size();
  return x;
}

results::SystemTable system_table(const model::System& system, std::span<const ContactModel> groups,
                                  std::span<const double> gap_offsets) {
  results::SystemTable t;
  if (system.ndof() == 0 || system.is_sdof_pair()) return t;
  const auto& elements = system.contacts();
  if (groups.size() != system.groups().size() || (!gap_offsets.empty() && gap_offsets.size() != elements.size()))
    throw std::logic_error(fmt::format("system_table: {} contact models for {} groups, {} gap offsets for {} elements",
                                       groups.size(), system.groups().size(), gap_offsets.size(), elements.size()));
  const std::size_t D = static_cast<std::size_t>(system.ndof());
  t.dof_building.resize(D), t.dof_floor.resize(D), t.dof_height.resize(D);
  for (std::size_t b = 0; b < system.bodies().size(); ++b) {
    const model::Body& body = system.bodies()[b];
    t.building_label.push_back(body.label);
    t.building_floors.push_back(static_cast<std::int32_t>(body.dofs.size()));
    t.building_isolated.push_back(body.isolated ? 1 : 0);
    for (std::size_t k = 0; k < body.dofs.size(); ++k) {
      const auto d = static_cast<std::size_t>(body.dofs[k]);
      t.dof_building[d] = static_cast<std::int32_t>(b);
      t.dof_floor[d] = static_cast<std::int32_t>(body.isolated ? k : k + 1);
      t.dof_height[d] = body.heights[k];
    }
  }
  for (const model::Spring& s : system.springs()) {
    t.spring_i.push_back(s.i), t.spring_j.push_back(s.j);
    t.spring_building.push_back(s.body), t.spring_storey.push_back(s.role == model::SpringRole::storey ? s.storey : 0);
    t.spring_role.emplace_back(role_name(s.role));
    t.spring_law.emplace_back(hysteresis_name(s.law));
  }
  const auto height = [&](int dof) { return t.dof_height[static_cast<std::size_t>(dof)]; };
  t.group_elements.assign(system.groups().size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const model::ContactElement& c = elements[e];
    // where it acts: the height of a point side (the left one first), else the lower DOF of an interpolated side
    const model::Side& at = c.left.kind == model::SideKind::point     ? c.left
                            : c.right.kind == model::SideKind::point  ? c.right
                            : c.left.kind != model::SideKind::wall    ? c.left
                                                                      : c.right;
    const double level = at.kind == model::SideKind::wall ? 0.0 : at.p < 0 ? c.xi * height(at.q) : height(at.p);
    const auto side = [&](const model::Side& s, std::vector<std::string>& kind, std::vector<std::int32_t>& dof,
                          std::vector<std::int32_t>& dof2, std::vector<double>& xi) {
      kind.emplace_back(side_name(s.kind));
      const bool wall = s.kind == model::SideKind::wall, interp = s.kind == model::SideKind::interpolated;
      dof.push_back(wall ? -1 : s.p);
      dof2.push_back(interp ? s.q : -1);
      xi.push_back(interp ? c.xi : 0.0);
    };
    side(c.left, t.element_left_kind, t.element_left_dof, t.element_left_dof2, t.element_left_xi);
    side(c.right, t.element_right_kind, t.element_right_dof, t.element_right_dof2, t.element_right_xi);
    t.element_level.push_back(c.level), t.element_level_height.push_back(level);
    t.element_group.push_back(c.group), t.element_label.push_back(c.label);
    t.element_gap_offset.push_back(gap_offsets.empty() ? 0.0 : gap_offsets[e]);
    ++t.group_elements.at(static_cast<std::size_t>(c.group));
  }
  for (std::size_t g = 0; g < system.groups().size(); ++g) {
    t.group_name.push_back(system.groups()[g].name);
    t.group_law.emplace_back(to_string(groups[g].law));
    t.group_damping_law.emplace_back(to_string(groups[g].damping));
    t.group_study_gap.push_back(system.groups()[g].study_gap ? 1 : 0);
  }
  if (const std::string p = t.check(); !p.empty()) throw std::logic_error("system_table: " + p);
  return t;
}

results::Group intensity_group(const Study& study, const StripePlan& p) {
  const IntensitySpec& x = study.intensity;
  const std::string units(im_units(x.im.measure));
  results::Group g{"intensity", {}, {}};
  g.set("measure", std::string(to_string(x.im.measure)));
  g.set("units", units);
  g.set("description", describe(x.im));
  g.set("method", std::string(to_string(x.method)));
  g.set("periods", x.im.periods);
  g.set("damping", x.im.damping);
  g.set("period_pair", static_cast<std::int64_t>(x.period_pair));
  g.set("max_scale", x.max_scale);
  g.add("levels", x.levels, units, "the stripes' intensity levels (" + describe(x.im) + ")");
  g.add("im", p.im, units, "the intensity measure of each record as loaded (before any stripe scaling)");
  if (p.stripes) {
    g.add("scale", p.scale, "1", "amplitude factor of each record at each stripe: level / im; [stripes, records]",
          {p.stripes, p.records});
    g.add("dropped", p.dropped, "1",
          "1: the record is not in this stripe (its factor exceeds max_scale); [stripes, records]", {p.stripes, p.records});
  }
  return g;
}

namespace {

// The bisection IDA's unit rows (results::ida_fields) as the module group /ida, with the capacities in IM units
// and each record's censoring point: im times the smallest scale_limit of its models (a model whose analysis
// diverged in the hunt censors the record just below; one that diverged at the first factor is excluded instead).
results::Group ida_group(const Study& study, const WorkPlan& plan, const StripePlan& p, std::vector<results::Field>& fields) {
  const IntensitySpec& x = study.intensity;
  const std::string units(im_units(x.im.measure));
  const std::size_t R = plan.records, M = plan.models(), G = plan.gaps;
  results::Group g{"ida", {}, {}};
  g.set("method", std::string("hunt at the stripes' factors (up to max_scale), then bisection on ln(scale)"));
  g.set("tolerance", x.tolerance);
  g.set("max_scale", x.max_scale);
  std::vector<double> lo, hi, limit;
  std::vector<std::int64_t> analyses;
  for (auto it = fields.begin(); it != fields.end();) {
    if (it->spec.group != "ida") {
      ++it;
      continue;
    }
    if (it->spec.name == "analyses")
      for (std::int32_t a : std::get<std::vector<std::int32_t>>(it->data)) analyses.push_back(a);
    else if (it->spec.name == "scale_limit") limit = std::move(std::get<std::vector<double>>(it->data));
    else (it->spec.name == "scale_lo" ? lo : hi) = std::move(std::get<std::vector<double>>(it->data));
    it = fields.erase(it);
  }
  std::vector<double> cap(R);
  std::int64_t diverged = 0, total = 0;
  for (std::size_t r = 0; r < R; ++r) {
    const std::vector<double> hunt = ida_hunt_factors(x, p.im[r]);
    double f = hunt.back();
    for (std::size_t m = 0; m < M; ++m) {
      const double l = limit[r * M + m];
      diverged += l < hunt.back();
      if (l > 0) f = std::min(f, l);
    }
    cap[r] = p.im[r] * f;
  }
  std::vector<double> capacity(lo.size());
  for (std::size_t k = 0; k < lo.size(); ++k) {
    const double im = p.im[k / (M * G)];
    capacity[k] = std::isnan(lo[k]) ? NAN : std::isinf(hi[k]) ? INFINITY : im * std::sqrt(lo[k] * hi[k]);
  }
  for (std::int64_t a : analyses) total += a;
  g.set("analyses_total", total);
  g.set("diverged_models", diverged);
  if (study.gap_metres) g.add("gaps", study.gap_ratios, "m", "the gap axis in metres ([gaps] metres): every model's gap");
  else g.add("gaps", study.gap_ratios, "1", "the gap axis: ratios of each model's code gap d");
  g.add("cap", cap, units,
        "each record's censoring point: its IM times the smallest scale_limit of its models; a capacity above it "
        "counts as censored there");
  g.add("analyses", analyses, "1", std::string(results::ida_fields[0].description), {R, M});
  g.add("scale_limit", limit, "1", std::string(results::ida_fields[1].description), {R, M});
  g.add("scale_lo", lo, "1", std::string(results::ida_fields[2].description), {R, M, G});
  g.add("scale_hi", hi, "1", std::string(results::ida_fields[3].description), {R, M, G});
  g.add("capacity", capacity, units,
        "IM at first contact: the record's IM times the geometric mean of the final bracket (within tolerance); "
        "+inf: no contact up to the last factor analysed (censored); NaN: excluded; [records, models, gaps]",
        {R, M, G});
  return g;
}

}  // namespace

results::Results make_results(const Study& study, const std::vector<StudyRecord>& records, const WorkPlan& plan,
                              Tally& tally, const Exclusions& ex, const RunFacts& facts, const StripePlan& stripes,
                              const std::shared_ptr<const SpilledColumns>& spilled) {
  results::Results r;
  r.header = make_header(study, ex, facts);
  r.settings = settings_of(study);
  r.records = record_table(records);
  if (const Reductions* red = tally.reductions(); red) {  // per_model = false (and "stream"): the period grids
    auto sampler = std::make_shared<const StructureSampler>(study.structures, study.seed);
    r.models.periods1 = sampler->building(0).periods, r.models.periods2 = sampler->building(1).periods;
    r.models.periods = r.models.periods1;
    r.models.zeta = study.structures.zeta;
    r.gaps.ratios = study.gap_ratios;
    r.gaps.in_metres = study.gap_metres;
    if (!spilled) {
      r.groups.push_back(red->group());
      return r;
    }
    // "stream": the models' table drawn window by window as the file is written (results::Results::model_rows)
    r.streamed_models = plan.models();
    r.model_rows = [&study, plan, sampler](std::size_t first, std::size_t n, results::ModelTable& t) {
      draw_models(study, plan, *sampler, first, n, t);
    };
  } else {
    r.models = model_table(study, plan);
    r.gaps = results::gap_table(study.gap_ratios, r.models.code_gap, study.gap_metres);  // every scene
  }
  if (plan.impacts) r.gap_ratios = study.gap_ratios;
  r.fields = spilled ? SpilledColumns::fields(spilled) : tally.take_fields();
  r.stripes = stripes.stripes;
  r.system = plan.system;  // empty for the SDOF pair: format 2
  results::add_derived_fields(r);
  if (study.intensity.enabled) r.groups.push_back(intensity_group(study, stripes));
  if (plan.ida) r.groups.push_back(ida_group(study, plan, stripes, r.fields));
  return r;
}

}  // namespace pounding
