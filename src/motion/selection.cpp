// Record selection and amplitude scaling to a design spectrum (see selection.hpp).
#include "pounding/motion/selection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "pounding/core/error.hpp"
#include "pounding/motion/spectrum.hpp"

namespace pounding {

ScalingRule parse_scaling_rule(const std::string& name) {
  if (auto r = parse_enum(scaling_rule_names, name)) return *r;
  throw InputError(fmt::format("unknown scaling rule '{}'", escaped_excerpt(name)), "--rule",
                   "use " + enum_name_list(scaling_rule_names, " or ", "\""));
}

double rule_fraction(ScalingRule rule) {
  switch (rule) {
    case ScalingRule::asce7_16: return 0.9;  // ASCE 7-16 16.2.3: 90 % of the MCER target
    case ScalingRule::asce7_10: return 1.0;  // ASCE 7-10 16.1.3.1: not less than the design spectrum
    case ScalingRule::ec8: return 0.9;       // EN 1998-1 3.2.3.1.2(4): no value below 90 % of Se
    case ScalingRule::none: return 0.0;
  }
  return 0.0;
}

ComponentRule parse_component_rule(const std::string& name) {
  if (auto r = parse_enum(component_rule_names, name)) return *r;
  throw InputError(fmt::format("unknown components rule '{}'", escaped_excerpt(name)), "--components",
                   "use " + enum_name_list(component_rule_names, " or ", "\""));
}

void validate(const SelectionOptions& o) {
  if (o.count < 1) throw InputError("count 0", "--count", "choose at least 1 record");
  if (!(o.t_lo > 0) || !std::isfinite(o.t_lo) || !(o.t_hi > o.t_lo) || !std::isfinite(o.t_hi))
    throw InputError(fmt::format("period range {}-{} s is not 0 < t_lo < t_hi", o.t_lo, o.t_hi), "--range",
                     "give a range such as 0.2,2.0 (multiples of --period, which must be > 0)");
  if (o.t_lo < selection_period_min || o.t_hi > selection_period_max)
    throw InputError(fmt::format("period range {:g}-{:g} s is outside the spectra's [{:g}, {:g}] s", o.t_lo, o.t_hi,
                                 selection_period_min, selection_period_max),
                     "--range", "give periods of a building (the range is 0.2 T to 2 T by default)");
  if (o.points < 2 || o.points > selection_points_max)
    throw InputError(fmt::format("{} periods is outside [2, {}]", o.points, selection_points_max), "--points",
                     "give 2 to 1000 periods (30 is usual)");
  if (!(o.min_scale >= selection_scale_min) || !(o.max_scale >= o.min_scale) || !(o.max_scale <= selection_scale_max))
    throw InputError(fmt::format("scale limits [{}, {}] are not {:g} <= min <= max <= {:g}", o.min_scale, o.max_scale,
                                 selection_scale_min, selection_scale_max),
                     "--min-scale/--max-scale", "give e.g. --min-scale 0.25 --max-scale 4");
  if (!(o.damping >= 0 && o.damping <= selection_damping_max))
    throw InputError(fmt::format("damping ratio {} is outside [0, {:g}]", o.damping, selection_damping_max), "--damping",
                     "give e.g. 0.05");
  if (static_cast<std::size_t>(o.rule) >= std::size(scaling_rule_names))
    throw InputError("scaling rule out of range", "--rule", "use " + enum_name_list(scaling_rule_names, " or "));
  if (static_cast<std::size_t>(o.components) >= std::size(component_rule_names))
    throw InputError("components rule out of range", "--components", "use one or both");
}

std::vector<double> log_spaced(double t_lo, double t_hi, int points) {
  std::vector<double> p;
  for (int i = 0; i < points; ++i)
    p.push_back(i + 1 == points ? t_hi : t_lo * std::pow(t_hi / t_lo, static_cast<double>(i) / (points - 1)));
  return p;
}

LogFit log_least_squares_scale(std::span<const double> target, std::span<const double> record) {
  if (target.empty() || target.size() != record.size())
    throw InputError(fmt::format("{} target values and {} record values", target.size(), record.size()),
                     "log_least_squares_scale", "give one record value per target period");
  double sum = 0;
  for (std::size_t j = 0; j < target.size(); ++j) {
    if (!(target[j] > 0) || !(record[j] > 0) || !std::isfinite(target[j]) || !std::isfinite(record[j]))
      throw InputError(fmt::format("Sa {} (target) and {} (record) at point {}: both must be > 0", target[j],
                                   record[j], j), "log_least_squares_scale", "the log fit needs positive spectra");
    sum += std::log(target[j] / record[j]);
  }
  const double n = static_cast<double>(target.size());
  const double ln_f = sum / n;  // PEER (2010): the weighted mean of ln(S_T / S_r), weights equal here
  double sq = 0;
  for (std::size_t j = 0; j < target.size(); ++j) {
    const double e = std::log(target[j]) - (ln_f + std::log(record[j]));
    sq += e * e;
  }
  return {std::exp(ln_f), sq / n};
}

double suite_factor(std::span<const double> target, std::span<const std::vector<double>> scaled_spectra,
                    double fraction) {
  if (scaled_spectra.empty()) throw InputError("no spectra", "suite_factor", "give at least one scaled spectrum");
  double f = 1.0;
  for (std::size_t j = 0; j < target.size(); ++j) {
    double m = 0;
    for (const auto& s : scaled_spectra) {
      if (s.size() != target.size())
        throw InputError(fmt::format("a spectrum of {} values against {} target values", s.size(), target.size()),
                         "suite_factor", "give every spectrum at the target's periods");
      m += s[j];
    }
    m /= static_cast<double>(scaled_spectra.size());
    f = std::max(f, fraction * target[j] / m);  // m = 0 under a positive target: F = inf, no factor helps
  }
  return f;
}

namespace {

struct Candidate {
  std::vector<double> spectrum;  // g at the check periods
  double scale = 0, mse = std::numeric_limits<double>::infinity();
  bool fitted = false;  // false: a zero Sa somewhere in the range, the log fit is undefined
};

std::vector<double> target_values(const DesignSpectrum& target, const std::vector<double>& periods) {
  std::vector<double> t;
  for (double p : periods) {
    const double v = target.sa(p);
    if (!(v > 0))
      throw InputError(fmt::format("the target Sa at {:.3g} s is {} g", p, v), target.describe(),
                       "give a target spectrum that is > 0 over the period range");
    t.push_back(v);
  }
  return t;
}

Candidate fit_candidate(const SelectionCandidate& c, const std::vector<double>& periods,
                        const std::vector<double>& target, double damping) {
  if (c.record == nullptr || c.record->acc.empty() || !(c.record->dt > 0))
    throw InputError("empty record", c.id, "give every candidate a record");
  Candidate out;
  const Spectrum s = response_spectrum(*c.record, periods, damping);
  for (double psa : s.psa) out.spectrum.push_back(psa / g_accel);
  out.fitted = std::all_of(out.spectrum.begin(), out.spectrum.end(), [](double v) { return v > 0; });
  if (out.fitted) {
    const LogFit fit = log_least_squares_scale(target, out.spectrum);
    out.scale = fit.scale, out.mse = fit.mse;
  }
  return out;
}

bool within(const Candidate& c, const SelectionOptions& o) {
  return c.fitted && c.scale >= o.min_scale && c.scale <= o.max_scale;
}

[[noreturn]] void too_few_eligible(const std::vector<Candidate>& all, std::size_t eligible, const SelectionOptions& o) {
  std::size_t below = 0, above = 0, zero = 0;
  double lowest = std::numeric_limits<double>::infinity(), highest = 0;
  for (const auto& c : all) {
    if (!c.fitted) ++zero;
    else if (c.scale < o.min_scale) ++below, lowest = std::min(lowest, c.scale);
    else if (c.scale > o.max_scale) ++above, highest = std::max(highest, c.scale);
  }
  std::string fix = "relax";
  if (above > 0) fix += fmt::format(" --max-scale {:g} ({} need more, up to {:.3g})", o.max_scale, above, highest);
  if (below > 0) fix += fmt::format("{} --min-scale {:g} ({} need less, down to {:.3g})", above > 0 ? " or" : "",
                                    o.min_scale, below, lowest);
  if (above == 0 && below == 0) fix = "add";
  fix += fmt::format(", lower --count, or add records{}",
                     zero > 0 ? fmt::format(" ({} have Sa = 0 in the range)", zero) : std::string());
  throw InputError(fmt::format("only {} of {} candidate records have a least-squares scale factor within [{:g}, {:g}], "
                               "{} needed", eligible, all.size(), o.min_scale, o.max_scale, o.count),
                   "--count/--min-scale/--max-scale", fix);
}

std::string rule_text(const SelectionOptions& o) {
  const std::string range = fmt::format("{:.2f}-{:.2f} s", o.t_lo, o.t_hi);
  switch (o.rule) {
    case ScalingRule::asce7_16:
      return "ASCE 7-16 16.2.3: mean of the scaled spectra >= 90 % of the target over " + range;
    case ScalingRule::asce7_10:
      return "ASCE 7-10 16.1.3.1: mean of the scaled spectra >= 100 % of the design spectrum over " + range +
             " (the code's range is 0.2T-1.5T)";
    case ScalingRule::ec8:
      return "EN 1998-1 3.2.3.1.2: mean of the scaled spectra >= 90 % of the elastic spectrum over " + range +
             " (the code's range is 0.2T1-2T1) and mean PGA >= the spectrum at T = 0 (ag S)";
    case ScalingRule::none: return "none: no code condition, the records keep their least-squares factors";
  }
  return "";
}

double target_pga(const DesignSpectrum& target) {
  try {
    return target.sa(0.0);
  } catch (const InputError& e) {
    throw InputError("the EC8 rule needs the target at T = 0 (ag S): " + e.what_part(), target.describe(),
                     "give a target spectrum that starts at T = 0, or another --rule");
  }
}

// F, the scaled mean, the ratios and `meets` for the chosen records (research note 3.5).
void apply_rule(Selection& s, const std::vector<double>& pgas, const DesignSpectrum& target, const SelectionOptions& o) {
  const double alpha = rule_fraction(o.rule);
  std::vector<std::vector<double>> scaled;
  for (std::size_t i = 0; i < s.spectra.size(); ++i) {
    scaled.push_back(s.spectra[i]);
    for (double& v : scaled.back()) v *= s.individual_scale[i];
  }
  double mean_pga = 0;
  for (std::size_t i = 0; i < pgas.size(); ++i) mean_pga += s.individual_scale[i] * pgas[i];
  mean_pga /= static_cast<double>(pgas.size());
  const double pga_target = o.rule == ScalingRule::ec8 ? target_pga(target) : 0.0;
  s.suite_factor = o.rule == ScalingRule::none ? 1.0 : suite_factor(s.target, scaled, alpha);
  if (o.rule == ScalingRule::ec8) s.suite_factor = std::max(s.suite_factor, pga_target / mean_pga);
  s.mean.assign(s.periods.size(), 0.0);
  for (std::size_t i = 0; i < s.chosen.size(); ++i) {
    s.scale.push_back(s.individual_scale[i] * s.suite_factor);
    for (std::size_t j = 0; j < s.periods.size(); ++j) s.mean[j] += s.scale[i] * s.spectra[i][j];
  }
  s.min_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < s.periods.size(); ++j) {
    s.mean[j] /= static_cast<double>(s.chosen.size());
    s.min_ratio = std::min(s.min_ratio, s.mean[j] / s.target[j]);
  }
  s.meets = s.min_ratio >= alpha - 1e-9;
  if (o.rule == ScalingRule::ec8) {
    s.pga_ratio = s.suite_factor * mean_pga / pga_target;
    s.meets = s.meets && s.pga_ratio >= 1 - 1e-9;
    s.min_ratio = std::min(s.min_ratio, s.pga_ratio);
  }
}

void add_warnings(Selection& s, const SelectionOptions& o, std::span<const SelectionCandidate> candidates) {
  for (std::size_t i = 0; i < s.chosen.size(); ++i)
    if (s.scale[i] < o.min_scale || s.scale[i] > o.max_scale)
      s.warnings.push_back(fmt::format("{}: final scale {:.3f} (f {:.3f} x suite factor {:.3f}) is outside "
                                       "[{:g}, {:g}]", candidates[s.chosen[i]].id, s.scale[i], s.individual_scale[i], s.suite_factor,
                                       o.min_scale, o.max_scale));
  const std::size_t n = s.chosen.size();
  if (o.rule == ScalingRule::asce7_16) {
    if (n < 11) s.warnings.push_back(fmt::format("ASCE 7-16 16.2.2 asks for at least 11 records, {} chosen", n));
    s.warnings.push_back(
        o.mcer_target
            ? "ASCE 7-16 16.2 scales maximum-direction (RotD100) spectra to the MCER target; these are "
              "single-component spectra against that target, so the factors are conservative (larger)"
            : "ASCE 7-16 16.2 scales records to the MCER spectrum (1.5 x the design spectrum); this target is the "
              "design-level spectrum, so the records are scaled to a design-level demand (give mcer = true, or "
              "--mcer, for the code's target); single-component spectra against its maximum-direction (RotD100) "
              "rule make the factors conservative (larger)");
  }
  if (o.rule == ScalingRule::asce7_10 && n < 7)
    s.warnings.push_back(fmt::format("ASCE 7-10 16.1.4 uses the mean response only with at least 7 records ({} "
                                     "chosen; with 3-6 use the maximum)", n));
  if (o.rule == ScalingRule::ec8 && n < 7)
    s.warnings.push_back(fmt::format("EC8 4.3.3.4.3 uses the mean response only with at least 7 records ({} chosen; "
                                     "with fewer use the most unfavourable)", n));
  if ((o.rule == ScalingRule::asce7_10 || o.rule == ScalingRule::ec8) && n < 3)
    s.warnings.push_back(fmt::format("{} asks for at least 3 records, {} chosen", to_string(o.rule), n));
  if (!s.meets) s.warnings.push_back("the code condition does not hold: " + s.rule_text);
}

std::string component_text(const RecordIdentity& id) { return id.component.empty() ? "?" : id.component; }

// Why candidate c may not join `chosen` (empty: it may): one recording twice, a station's second component, an
// event's quota.
std::string refusal(std::size_t c, const std::vector<std::size_t>& chosen, const std::vector<RecordIdentity>& ids,
                    std::span<const SelectionCandidate> cands, const SelectionOptions& o) {
  const RecordIdentity& me = ids[c];
  if (!me.known()) return "";
  std::vector<std::string> same_event_ids;
  for (std::size_t k : chosen) {
    const RecordIdentity& other = ids[k];
    if (same_recording(me, other))
      return fmt::format("the same recording as {} ({}, {}, component {} ~ {}: one motion, two files)", cands[k].id,
                         me.event_text(), me.station, component_text(me), component_text(other));
    if (o.components == ComponentRule::one && same_station(me, other))
      return fmt::format("the other component of station {} ({}), already chosen as {} (components = one)",
                         me.station, me.event_text(), cands[k].id);
    if (same_event(me, other)) same_event_ids.push_back(cands[k].id);
  }
  if (o.max_per_event > 0 && same_event_ids.size() >= o.max_per_event) {
    std::string list;
    for (const auto& x : same_event_ids) list += (list.empty() ? "" : ", ") + x;
    return fmt::format("{} already has {} record{} chosen ({}; max_per_event = {})", me.event_text(),
                       same_event_ids.size(), same_event_ids.size() == 1 ? "" : "s", list, o.max_per_event);
  }
  return "";
}

}  // namespace

std::vector<std::size_t> apply_recording_rules(Selection& s, std::span<const SelectionCandidate> candidates,
                                               const std::vector<std::size_t>& ranked, const SelectionOptions& o) {
  std::vector<RecordIdentity> ids;
  ids.reserve(candidates.size());
  for (const auto& c : candidates) {
    ids.push_back(c.record ? identity_of(*c.record) : RecordIdentity{});
    s.unidentified += !ids.back().known();
  }
  std::vector<std::size_t> chosen;
  std::vector<RefusedCandidate> refused;
  for (std::size_t c : ranked) {
    if (chosen.size() == o.count) break;
    std::string why = refusal(c, chosen, ids, candidates, o);
    if (why.empty()) chosen.push_back(c);
    else refused.push_back({c, std::move(why)});
  }
  if (chosen.size() < o.count) {
    std::size_t dup = 0, comp = 0, event = 0;
    for (const auto& r : refused) {
      if (r.reason.rfind("the same recording", 0) == 0) ++dup;
      else if (r.reason.rfind("the other component", 0) == 0) ++comp;
      else ++event;
    }
    std::string fix;
    if (event > 0) fix += fmt::format("raise --max-per-event (now {}; {} passed over for it)", o.max_per_event, event);
    if (comp > 0) fix += fmt::format("{}allow both components of a station (--components both; {} passed over)",
                                     fix.empty() ? "" : ", ", comp);
    fix += fmt::format("{}lower the count, or add records of other events and stations", fix.empty() ? "" : ", ");
    throw InputError(fmt::format("only {} of the {} eligible records are distinct recordings within the event and "
                                 "component rules ({} second copies of one recording, {} second components, {} over "
                                 "an event's quota), {} needed",
                                 chosen.size(), ranked.size(), dup, comp, event, o.count),
                     "--max-per-event/--components", fix);
  }
  s.refused = std::move(refused);
  return chosen;
}

Selection select_records(std::span<const SelectionCandidate> candidates, const DesignSpectrum& target,
                         const SelectionOptions& options) {
  validate(options);
  Selection s;
  s.periods = log_spaced(options.t_lo, options.t_hi, options.points);
  s.target = target_values(target, s.periods);
  s.rule_text = rule_text(options);
  std::vector<Candidate> all;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    all.push_back(fit_candidate(candidates[i], s.periods, s.target, options.damping));
    if (within(all.back(), options)) order.push_back(i);
  }
  s.eligible = order.size();
  if (s.eligible < options.count) too_few_eligible(all, s.eligible, options);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a].mse < all[b].mse; });
  order = apply_recording_rules(s, candidates, order, options);
  std::vector<double> pgas;
  for (std::size_t i : order) {
    s.chosen.push_back(i);
    s.individual_scale.push_back(all[i].scale);
    s.mse.push_back(all[i].mse);
    s.identity.push_back(identity_of(*candidates[i].record));
    s.spectra.push_back(all[i].spectrum);
    pgas.push_back(candidates[i].record->pga() / g_accel);
  }
  apply_rule(s, pgas, target, options);
  add_warnings(s, options, candidates);
  return s;
}

}  // namespace pounding
