// A fragility study's analysis and report: fragility curves per gap, hazard integration, risk-targeted gap.
#include "pounding/report/fragility.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "pounding/analysis/hazard.hpp"
#include "pounding/analysis/stripes.hpp"
#include "pounding/report/report.hpp"

namespace pounding {

namespace {

using results::Group;
using results::Results;

bool setting_is(const Results& r, std::string_view section, std::string_view key, std::string_view value) {
  const results::SettingValue* v = r.settings.find(section, key);
  const auto* s = v ? std::get_if<std::string>(v) : nullptr;
  return s && *s == value;
}

bool pair_study(const Results& r) {
  const results::SettingValue* v = r.settings.find("structures", "heights_specified");
  const auto* i = v ? std::get_if<std::int64_t>(v) : nullptr;
  return i && *i != 0 && !r.models.code_gap.empty();
}

std::optional<HazardCurve> hazard_of(const Results& r) {
  if (!r.settings.find("hazard", "years")) return std::nullopt;
  const std::vector<double> im = r.settings.numbers("hazard", "im");
  if (!im.empty()) return HazardCurve::from_table(im, r.settings.numbers("hazard", "rate"));
  return HazardCurve::power_law(r.settings.number("hazard", "k0"), r.settings.number("hazard", "k"));
}

stripes::Settings stripe_settings(const Results& r) {
  stripes::Settings s;
  s.bootstrap = static_cast<int>(r.settings.number("report", "bootstrap"));
  s.confidence = r.settings.number("report", "confidence");
  s.seed = static_cast<std::uint64_t>(r.header.seed) ^ 0x66726167696c6974ULL;  // "fragilit": its own stream
  s.years = r.settings.find("hazard", "years") ? r.settings.number("hazard", "years") : 50.0;
  return s;
}

// The demands of every (stripe or run, record, model) in gap units: peak closing / d (d the model's code gap; on a
// metres axis, [gaps] metres, 1: the closing in metres);
// NaN for an analysis left out (diverged, non-finite, coarse unless kept, or a record dropped from the stripe).
std::vector<double> demand_ratios(const Results& r) {
  const auto& pc = r.column<double>("uncoupled", "peak_closing");
  const auto& st = r.column<std::uint8_t>("uncoupled", "status");
  const bool keep = setting_is(r, "analysis", "coarse", "keep");
  const std::size_t M = r.model_count();
  std::vector<double> d(pc.size(), NAN);
  for (std::size_t i = 0; i < pc.size(); ++i)
    if (st[i] == 0 || (keep && st[i] == 3)) d[i] = pc[i] / r.gaps.unit(r.models.code_gap, i % M);
  return d;
}

// lambda_P cannot rise with the gap (every analysis that exceeds a gap exceeds every smaller one), but each gap has its
// own fit, and two fitted curves can cross (issue 23, item 3): the study's gaps and the curve's are held on one
// non-increasing curve (stripes::non_increasing), and a study gap whose own rate was lowered says so.
void hold_non_increasing(std::vector<stripes::GapFragility>& fits, stripes::RateCurve& curve, double years) {
  std::vector<double> x, v;
  for (const auto& f : fits) x.push_back(f.gap), v.push_back(f.annual_rate);
  x.insert(x.end(), curve.gap.begin(), curve.gap.end());
  v.insert(v.end(), curve.rate_fitted.begin(), curve.rate_fitted.end());
  const std::vector<double> held = stripes::non_increasing(x, v);
  for (std::size_t k = 0; k < fits.size(); ++k) {
    auto& f = fits[k];
    if (!(held[k] < f.annual_rate)) continue;
    f.note += fmt::format("; the fit's own rate here, {:.4g} per year, exceeds the rate at a smaller gap: held at {:.4g} "
                          "(lambda cannot rise with the gap)",
                          f.annual_rate, held[k]);
    f.annual_rate = held[k], f.probability = probability_in_years(held[k], years);
  }
  for (std::size_t i = 0; i < curve.gap.size(); ++i) {
    curve.rate[i] = held[fits.size() + i];
    curve.probability[i] = std::isnan(curve.rate[i]) ? NAN : probability_in_years(curve.rate[i], years);
  }
}

// The rate-versus-separation curve's gaps: curve_step, 2 curve_step, ... up to curve_max.
std::vector<double> curve_grid(const Results& r) {
  std::vector<double> grid;
  const double step = r.settings.number("gaps", "curve_step"), max = r.settings.number("gaps", "curve_max");
  for (double x = step; x <= max + 1e-12; x += step) grid.push_back(x);
  return grid;
}

// The bisection IDA's curve: its fits at the study's gaps.
stripes::RateCurve curve_of_fits(const std::vector<stripes::GapFragility>& fits) {
  stripes::RateCurve c;
  for (const auto& f : fits) {
    c.gap.push_back(f.gap), c.rate.push_back(f.annual_rate), c.probability.push_back(f.probability);
    c.rate_fitted.push_back(f.annual_rate), c.share_below.push_back(f.share_below), c.share_above.push_back(f.share_above);
  }
  return c;
}

bool any_positive(const std::vector<double>& demand) {
  return std::any_of(demand.begin(), demand.end(), [](double v) { return std::isfinite(v) && v > 0; });
}

// Every analysis excluded (diverged, non-finite) or none closing at all: there are no gaps to search. The run still
// writes its results (and exits 3 when the exclusions are too many, with the banner), so this is a status, not an
// error after the work is done (issue 24, item 4).
stripes::TargetGap no_target(double lambda_target) {
  stripes::TargetGap t;
  t.lambda_target = lambda_target;
  t.status = "not found";
  t.note = "no counted analysis has a positive peak closing (every one excluded, or the buildings never approach): "
           "there is no gap to search; see the excluded analyses above";
  return t;
}

void add_fit_rows(Group& g, const std::vector<stripes::GapFragility>& fits, std::size_t S, const std::string& units) {
  const std::size_t G = fits.size();
  std::vector<double> theta(G), beta(G), tlo(G), thi(G), blo(G), bhi(G), fitted(G * S, NAN);
  std::vector<std::int64_t> n(G * S, 0), z(G * S, 0), failed(G);
  std::vector<std::string> status(G), note(G);
  for (std::size_t k = 0; k < G; ++k) {
    const auto& f = fits[k];
    const bool ok = f.fit.ok();
    theta[k] = ok ? f.fit.fragility.theta : NAN, beta[k] = ok ? f.fit.fragility.beta : NAN;
    tlo[k] = f.theta_ci.lo, thi[k] = f.theta_ci.hi, blo[k] = f.beta_ci.lo, bhi[k] = f.beta_ci.hi;
    status[k] = to_string(f.fit.status), note[k] = f.note.empty() ? f.fit.message : f.note;
    failed[k] = f.replicates_failed;
    for (std::size_t s = 0; s < S && s < f.observed.size(); ++s) n[k * S + s] = f.observed[s].n, z[k * S + s] = f.observed[s].z;
    for (std::size_t s = 0; s < S && s < f.fitted.size(); ++s) fitted[k * S + s] = f.fitted[s];
  }
  g.add("theta", theta, units, "median of the lognormal fragility P(pound | IM = x) = Phi(ln(x / theta) / beta); NaN: no fit (see status)");
  g.add("beta", beta, "1", "log standard deviation of the fragility");
  g.add("theta_lo", tlo, units, "lower end of theta's bootstrap interval (records resampled)");
  g.add("theta_hi", thi, units, "upper end of theta's bootstrap interval");
  g.add("beta_lo", blo, "1", "lower end of beta's bootstrap interval");
  g.add("beta_hi", bhi, "1", "upper end of beta's bootstrap interval");
  g.add("replicates_failed", failed, "1", "bootstrap replicates whose fit was not ok (treated as in status/note)");
  g.add("status", status, "1", "ok, no_pounding, all_pounded, separated, decreasing or not_converged");
  g.add("note", note, "1", "what the fit did at this gap, in words");
  g.add("observed_n", n, "1", "analyses counted at each stripe; [gaps, stripes]", {G, S});
  g.add("observed_z", z, "1", "analyses that pounded (peak closing > gap) at each stripe; [gaps, stripes]", {G, S});
  g.add("fitted", fitted, "1", "fitted P(pound) at each stripe level; [gaps, stripes]", {G, S});
}

void add_hazard_group(Results& r, const HazardCurve& hz, const std::vector<stripes::GapFragility>& fits,
                      const stripes::Settings& st, const std::vector<double>& demand, const std::vector<double>& levels) {
  Group& h = r.group_for("hazard");
  const std::string units = r.settings.text("intensity", "units");
  const double years = st.years, target = r.settings.number("hazard", "target");
  const double lambda_target = rate_for_probability(target / 100.0, years);
  h.set("years", years), h.set("target_percent", target), h.set("lambda_target", lambda_target);
  h.set("source", r.settings.text("hazard", "source"));
  h.set("curve", r.settings.text("hazard", "curve"));
  h.set("k0", r.settings.number("hazard", "k0")), h.set("k", r.settings.number("hazard", "k"));
  std::vector<double> im = r.settings.numbers("hazard", "im"), rate = r.settings.numbers("hazard", "rate");
  if (im.empty())  // a power law: tabulate it over the stripes' range and a decade either side, for plots
    for (int i = 0; i <= 40; ++i) {
      const double x = levels.front() / 10 * std::pow(100 * levels.back() / levels.front(), i / 40.0);
      im.push_back(x), rate.push_back(hz.rate(x));
    }
  h.add("im", im, units, "the hazard curve used: IM levels");
  h.add("rate", rate, "1/year", "the hazard curve used: annual rate of exceedance of each IM level");
  const std::size_t G = fits.size();
  std::vector<double> lam(G), llo(G), lhi(G), p(G), plo(G), phi(G), tail(G);
  for (std::size_t k = 0; k < G; ++k) {
    const auto& f = fits[k];
    lam[k] = f.annual_rate, llo[k] = f.rate_lo, lhi[k] = f.rate_hi;
    p[k] = f.probability, plo[k] = f.probability_lo, phi[k] = f.probability_hi, tail[k] = f.tail_share;
  }
  h.add("annual_rate", lam, "1/year", "annual rate of pounding at each gap: integral of P(pound | x) |d lambda_IM(x)|");
  h.add("rate_lo", llo, "1/year", "lower end of the annual rate's bootstrap interval");
  h.add("rate_hi", lhi, "1/year", "upper end of the annual rate's bootstrap interval");
  h.add("probability", p, "1", "probability of at least one pounding in `years`: 1 - exp(-rate years)");
  h.add("probability_lo", plo, "1", "lower end of the probability's bootstrap interval");
  h.add("probability_hi", phi, "1", "upper end of the probability's bootstrap interval");
  h.add("tail_share", tail, "1", "share of the rate from IM beyond the hazard table (its end slopes extended)");
  std::vector<double> below(G), above(G);
  for (std::size_t k = 0; k < G; ++k) below[k] = fits[k].share_below, above[k] = fits[k].share_above;
  h.add("share_below_stripes", below, "1",
        "share of the gap's fitted rate from IM below the lowest stripe (the fragility extrapolated, no data there)");
  h.add("share_above_stripes", above, "1",
        "share of the gap's fitted rate from IM above the highest stripe (the fragility extrapolated, or a bound's "
        "P = 1 there)");
  std::vector<double> jlo(G), jhi(G), pjlo(G), pjhi(G);
  for (std::size_t k = 0; k < G; ++k)
    jlo[k] = fits[k].rate_jack_lo, jhi[k] = fits[k].rate_jack_hi, pjlo[k] = fits[k].probability_jack_lo,
    pjhi[k] = fits[k].probability_jack_hi;
  h.add("rate_jack_lo", jlo, "1/year", "lower end of the annual rate's jackknife interval over records (NaN: none)");
  h.add("rate_jack_hi", jhi, "1/year", "upper end of the annual rate's jackknife interval over records (NaN: none)");
  h.add("probability_jack_lo", pjlo, "1", "lower end of the probability's jackknife interval over records");
  h.add("probability_jack_hi", pjhi, "1", "upper end of the probability's jackknife interval over records");
  (void)demand;
}

// The risk-targeted separation's attributes of /hazard (docs/results-format.md); d: the pair's code gap in m (NaN
// for a grid study).
void set_target_attributes(Group& h, const stripes::TargetGap& t, double d) {
  h.set("target_gap", t.gap), h.set("target_gap_lo", t.lo), h.set("target_gap_hi", t.hi);
  h.set("target_gap_m", t.gap * d), h.set("target_gap_m_lo", t.lo * d), h.set("target_gap_m_hi", t.hi * d);
  h.set("target_gap_jack_se", t.jack_se);
  h.set("target_gap_jack_lo", t.jack_lo), h.set("target_gap_jack_hi", t.jack_hi);
  h.set("target_gap_m_jack_lo", t.jack_lo * d), h.set("target_gap_m_jack_hi", t.jack_hi * d);
  h.set("target_gap_advice", t.advice), h.set("target_gap_m_advice", t.advice * d);
  h.set("target_status", t.status), h.set("target_note", t.note);
}

// the rate-versus-separation curve of /hazard (MSA and bisection IDA; none for a linear IDA)
void add_rate_curve(Group& h, const stripes::RateCurve& curve, bool metres) {
  if (curve.gap.empty()) return;
  if (metres) h.add("curve_gap", curve.gap, "m", "gaps (m, [gaps] metres) of the rate-versus-separation curve");
  else h.add("curve_gap", curve.gap, "1", "gaps (ratios of d) of the rate-versus-separation curve");
  h.add("curve_rate", curve.rate, "1/year", "annual rate of pounding at each curve gap (point estimate)");
  h.add("curve_probability", curve.probability, "1", "probability of pounding in `years` at each curve gap");
  h.add("curve_rate_fitted", curve.rate_fitted, "1/year",
        "each curve gap's own fitted rate, before curve_rate holds it non-increasing (fits at two gaps can cross)");
  h.add("curve_share_below_stripes", curve.share_below, "1",
        "share of curve_rate_fitted from IM below the lowest stripe (extrapolated)");
  h.add("curve_share_above_stripes", curve.share_above, "1",
        "share of curve_rate_fitted from IM above the highest stripe (extrapolated, or a bound's P = 1)");
}

}  // namespace

namespace {
// /fragility's gaps: ratios of each model's d (a pair's also in metres, gaps_m), or ([gaps] metres) metres.
void add_gap_axis(Group& g, const Results& r, const std::vector<double>& gaps) {
  if (r.gaps.in_metres) {  // [gaps] metres: the gaps are metres, every model's
    g.set("gap_units", std::string("m"));
    g.add("gaps", gaps, "m", "the gaps in metres ([gaps] metres: every model's gap)");
    g.add("gaps_m", gaps, "m", "the gaps in metres (= gaps)");
    return;
  }
  g.set("gap_units", std::string("ratio of the code gap d"));
  g.add("gaps", gaps, "1", "the gaps, as ratios of each model's code gap d");
  if (pair_study(r)) {
    std::vector<double> m;
    for (double x : gaps) m.push_back(x * r.models.code_gap[0]);
    g.add("gaps_m", m, "m", "the gaps in metres (this pair's d times the ratio)");
  }
}
}  // namespace

bool is_fragility_study(const Results& r) { return r.group("intensity") != nullptr; }

void analyse_fragility(Results& r, const WorkHook* hook) {
  if (!is_fragility_study(r) || r.group("fragility")) return;
  const Group& in = *r.group("intensity");
  const std::vector<double> levels = in.get<double>("levels");
  const std::string units = in.text("units"), method = in.text("method");
  const std::optional<HazardCurve> hz = hazard_of(r);
  stripes::Settings st = stripe_settings(r);
  st.hook = hook;
  const std::vector<double>& gaps = r.gaps.ratios;
  std::vector<double> demand = demand_ratios(r);
  std::vector<stripes::GapFragility> fits;
  stripes::TargetGap target;
  stripes::RateCurve curve;
  const double lambda_target =
      hz ? rate_for_probability(r.settings.number("hazard", "target") / 100.0, st.years) : 0.0;
  // [records] polarity "both": record k's two signs (rows 2k, 2k + 1) are one record of 2 x models analyses, so
  // the bootstrap and the jackknife over records keep them together (the flat order is the same)
  const std::size_t P = r.polarities(), R = r.independent_records(), M = P * r.model_count();
  if (method == "msa") {
    const stripes::Demands D{levels, R, M, demand};
    fits = stripes::fit_msa(D, gaps, st, hz ? &*hz : nullptr);
    if (hz) {
      target = any_positive(demand) ? stripes::risk_targeted_gap(D, *hz, lambda_target, st) : no_target(lambda_target);
      curve = stripes::rate_curve(D, *hz, curve_grid(r), st.years);
      hold_non_increasing(fits, curve, st.years);
    }
  } else if (const Group* ida = r.group("ida")) {  // ida on yielding pairs: the capacities of the bisection
    const std::vector<double>& row_cap = ida->get<double>("cap");
    std::vector<double> cap(R, INFINITY);  // a record's censoring point: the smaller of its two signs'
    for (std::size_t q = 0; q < row_cap.size(); ++q) cap[q / P] = std::min(cap[q / P], row_cap[q]);
    const std::vector<double>& capacity = ida->get<double>("capacity");
    const std::size_t RM = R * M, G = gaps.size();
    for (std::size_t k = 0; k < G; ++k) {
      stripes::Capacities C{R, M, std::vector<double>(RM), cap};
      for (std::size_t q = 0; q < RM; ++q) C.capacity[q] = capacity[q * G + k];
      fits.push_back(stripes::fit_ida(C, levels, st, hz ? &*hz : nullptr, gaps[k]));
    }
    if (hz) {
      target = stripes::risk_targeted_gap_at_gaps(fits, lambda_target, st.confidence);
      curve = curve_of_fits(fits);
      hold_non_increasing(fits, curve, st.years);
    }
  } else {  // ida on a linear pair: every capacity exact from the run at the records' own intensity
    std::vector<double> im;  // a record's two signs have one IM (negation is exact)
    for (std::size_t q = 0; q < R; ++q) im.push_back(in.get<double>("im")[q * P]);
    const double max_scale = in.number("max_scale");
    std::vector<double> cap(im.size());
    for (std::size_t k = 0; k < im.size(); ++k) cap[k] = im[k] * max_scale;
    for (double x : gaps) {
      const stripes::Capacities C = stripes::linear_capacities(im, demand, M, x, cap);
      fits.push_back(stripes::fit_ida(C, levels, st, hz ? &*hz : nullptr, x));
    }
    if (hz) target = stripes::risk_targeted_gap_linear_ida(im, demand, M, cap, *hz, lambda_target, st);
  }
  Group& g = r.group_for("fragility");
  g.set("method", method);
  if (method == "ida") g.set("ida", std::string(r.group("ida") ? "bisection" : "linear"));
  g.set("confidence", st.confidence);
  g.set("replicates", static_cast<std::int64_t>(st.bootstrap));
  g.set("im_units", units);
  add_gap_axis(g, r, gaps);
  g.add("levels", levels, units, "the stripes' IM levels (the observed and fitted columns)");
  add_fit_rows(g, fits, levels.size(), units);
  if (!hz) return;
  add_hazard_group(r, *hz, fits, st, demand, levels);
  Group& h = *const_cast<Group*>(r.group("hazard"));
  const double d = r.gaps.in_metres ? 1.0 : pair_study(r) ? r.models.code_gap[0] : NAN;  // the axis' metres per unit
  set_target_attributes(h, target, d);
  add_rate_curve(h, curve, r.gaps.in_metres);
}

}  // namespace pounding
