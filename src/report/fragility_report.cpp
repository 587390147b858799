// The report of a fragility study: the risk-targeted separation first, then the fragility per gap, observed versus
// fitted at each stripe, the hazard and the stripes' scale factors (report/fragility.hpp).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/report/fragility.hpp"
#include "pounding/report/report.hpp"

namespace pounding {

namespace {

using results::Group;
using results::Results;

std::string num(double x, const char* fmt_ = "{:.3g}") { return std::isfinite(x) ? fmt::format(fmt::runtime(fmt_), x) : "n/a"; }
std::string pct(double p) { return std::isfinite(p) ? fmt::format("{:.2f}%", 100 * p) : "n/a"; }
std::string interval(double lo, double hi, const char* f = "{:.3g}") { return fmt::format("[{}, {}]", num(lo, f), num(hi, f)); }

// An attribute that files written before it existed lack: NaN there.
double optional_number(const Group& g, std::string_view key) { return g.attribute(key) ? g.number(key) : NAN; }

struct View {
  const Results& r;
  const Group& in;
  const Group& fr;
  const Group* hz;
  std::vector<double> levels, gaps, gaps_m;
  std::string units;
  bool pair;
  bool metres;  // [gaps] metres: the gaps are metres (/fragility gap_units = "m")
  View(const Results& res)
      : r(res), in(*res.group("intensity")), fr(*res.group("fragility")), hz(res.group("hazard")),
        levels(fr.get<double>("levels")), gaps(fr.get<double>("gaps")), units(in.text("units")),
        pair(fr.find("gaps_m") != nullptr), metres(fr.attribute("gap_units") && fr.text("gap_units") == "m") {
    if (pair) gaps_m = fr.get<double>("gaps_m");
  }
  std::string gap_name(std::size_t k) const {
    if (metres) return fmt::format("{:g} m", gaps[k]);
    return pair ? fmt::format("{:g} d = {:.3f} m", gaps[k], gaps_m[k]) : fmt::format("{:g} d", gaps[k]);
  }
  std::string gap_value(double ratio, double metres_value) const {
    if (metres) return fmt::format("{:.3f} m", metres_value);
    return pair ? fmt::format("{:.3f} m ({:.3g} d)", metres_value, ratio) : fmt::format("{:.3g} d", ratio);
  }
  const char* unit() const { return metres ? "m" : "d"; }
};

std::string overview(const View& v) {
  const Results& r = v.r;
  // every string read from the results file is escaped (report/escape.hpp, issue 44 item 9)
  std::string s = fmt::format("# Pounding fragility study: {}\n\n", report::md_text(r.header.title));
  if (!r.header.exclusion_warning.empty())  // the banner of every report (docs/failure-behaviour.md: exit 3)
    s += fmt::format("> **WARNING — results not trustworthy as they stand:** {}.\n\n",
                     report::md_text(r.header.exclusion_warning));
  s += fmt::format("- results: {} (written {}, commit {}, {} rank(s), wall time {:.2f} s)\n", report::md_code(r.path),
                   report::md_text(r.header.date), report::md_text(r.header.git_commit.substr(0, 12)), r.header.ranks,
                   r.header.wall_time_s);
  s += fmt::format("- machine: {}\n", report::md_text(run_machine(r.header)));
  s += fmt::format("- intensity measure: **{}**{}\n", report::md_text(v.in.text("description")),
                   v.r.settings.find("intensity", "period_pair") && v.r.settings.number("intensity", "period_pair") != 0
                       ? " — period \"pair\": the geometric mean of the two buildings' median periods"
                       : "");
  const std::string method = v.fr.text("method");
  if (method == "msa")
    s += fmt::format("- method: multiple-stripe analysis, {} stripes ({} to {} {}): every record amplitude-scaled to "
                     "each level, the same {} models at every stripe (common random numbers); fit: Baker (2015) "
                     "maximum likelihood over the stripes\n",
                     v.levels.size(), num(v.levels.front()), num(v.levels.back()), v.units, r.model_count());
  else if (v.r.group("ida"))
    s += fmt::format("- method: IDA of yielding buildings: for every record, model and gap the record scale factor at "
                     "first contact, hunted at the stripes' factors (up to max_scale), then bisected to a relative "
                     "width of {:g}, or exact by linear scaling where both buildings were still elastic when they "
                     "touched ({} uncoupled analyses in all); fit: lognormal by moments (censored maximum "
                     "likelihood where no contact occurred up to a record's last factor); {} models diverged in the "
                     "hunt (their records are censored below that factor)\n",
                     v.r.group("ida")->number("tolerance"), v.r.group("ida")->number("analyses_total"),
                     v.r.group("ida")->number("diverged_models"));
  else
    s += "- method: IDA on a linear pair: the peak closing scales exactly with the record, so each model's IM at first "
         "contact is exact from one run (IM x gap / peak closing); fit: lognormal by moments (censored maximum "
         "likelihood where a capacity lies beyond max_scale)\n";
  s += fmt::format("- {} records, {} models per record, seed {}; intervals: percentile bootstrap over records "
                   "({} replicates, {:.0f} %), so they include record-to-record variability\n",
                   r.independent_records(), r.model_count(), r.header.seed, v.fr.number("replicates"),
                   100 * v.fr.number("confidence"));
  s += fmt::format("- record polarity: **{}** — {}\n", r.polarity(),
                   r.polarities() == 2
                       ? "every record applied with both signs, as two analyses of the same record (pounding counts "
                         "when building 1 moves towards building 2, and a ground motion's sign is arbitrary); the "
                         "bootstrap and the jackknife resample records with both signs together"
                       : "every record with its sign as recorded ([records] polarity = \"both\" adds the reversed sign)");
  s += fmt::format("- excluded (diverged or non-finite) analyses: **{}** of {}\n", r.header.excluded_analyses,
                   r.header.total_analyses);
  return s + "\n";
}

// The headline: x*, its bootstrap and jackknife intervals, and the advice (the larger upper end).
std::string target_headline(const View& v, const Group& h) {
  const char* f = v.pair ? "{:.3f}" : "{:.3g}";
  const std::string unit = v.pair ? " m" : " d", m = v.pair ? "_m" : "";
  const double jlo = optional_number(h, "target_gap" + m + "_jack_lo"), jhi = optional_number(h, "target_gap" + m + "_jack_hi");
  double advice = optional_number(h, "target_gap" + m + "_advice");
  if (std::isnan(advice)) advice = h.number("target_gap" + m + "_hi");  // a file written before the jackknife
  std::string s = fmt::format("**{}**, {:.0f} % interval {}{} (bootstrap over records)",
                              v.gap_value(h.number("target_gap"), h.number("target_gap_m")), 100 * v.fr.number("confidence"),
                              interval(h.number("target_gap" + m + "_lo"), h.number("target_gap" + m + "_hi"), f), unit);
  if (!std::isnan(jhi)) s += fmt::format(", {}{} (jackknife over records)", interval(jlo, jhi, f), unit);
  s += fmt::format("; **advice: at least {}{}** ({}).\n\n", num(advice, f), unit,
                   std::isnan(jhi) ? "the upper end" : "the larger upper end");
  if (!std::isnan(jhi))
    s += "With few records the percentile bootstrap runs short for a separation that hangs on the fragility's "
         "dispersion beta; the jackknife (the study without each record in turn, Student t) less so. In simulated "
         "studies with a known answer and 25 records, the bootstrap's 95 % interval held the true separation in "
         "86 % of them, the jackknife's in 92 % (60 records: 91.5 %, 93.5 %), hence the advice.\n\n";
  return s;
}

// A rate that rests on the fitted curve beyond the stripes rests on no analysis: say how much, warn above this.
constexpr double kBeyondStripesWarning = 0.10;

// The share of a rate from beyond the stripes, in words, with a WARNING above kBeyondStripesWarning.
std::string beyond_stripes(const View& v, const std::string& what, double below, double above) {
  if (!std::isfinite(below) || !std::isfinite(above)) return "";
  const double share = below + above;
  const std::string words = fmt::format("{:.1f} % of {} comes from IM beyond the stripes ({:.1f} % below {} {}, {:.1f} % "
                                        "above {} {}), where the fitted fragility is extrapolated",
                                        100 * share, what, 100 * below, num(v.levels.front()), v.units, 100 * above,
                                        num(v.levels.back()), v.units);
  if (share <= kBeyondStripesWarning) return words;
  return fmt::format("**WARNING**: {}; more than {:.0f} % rests on no analysis: add stripes {}", words,
                     100 * kBeyondStripesWarning, above >= below ? "above the highest" : "below the lowest");
}

// The curve point nearest the risk-targeted gap: its shares beyond the stripes (files before them: nothing).
std::string target_beyond_stripes(const View& v, const Group& h) {
  if (!h.find("curve_share_above_stripes") || h.text("target_status") != "ok") return "";
  const auto& g = h.get<double>("curve_gap");
  const double x = h.number("target_gap");
  std::size_t best = 0;
  for (std::size_t i = 1; i < g.size(); ++i)
    if (std::abs(g[i] - x) < std::abs(g[best] - x)) best = i;
  if (g.empty()) return "";
  return beyond_stripes(v, fmt::format("the fitted rate at {:g} {} (the curve's gap nearest the separation)", g[best],
                                       v.unit()),
                        h.get<double>("curve_share_below_stripes")[best], h.get<double>("curve_share_above_stripes")[best]) +
         ".\n\n";
}

std::string target_section(const View& v) {
  if (!v.hz) return "";
  const Group& h = *v.hz;
  const double years = h.number("years"), target = h.number("target_percent");
  std::string s = fmt::format("## Risk-targeted separation: P(pounding in {:g} years) = {:g} %\n\n", years, target);
  const std::string status = h.text("target_status");
  if (status == "ok") {
    s += target_headline(v, h) + target_beyond_stripes(v, h);
  } else {
    s += fmt::format("**not found ({})**: {}\n\n", status, h.text("target_note"));
  }
  if (v.r.group("ida"))
    s += fmt::format("The separation is the gap at which the annual rate of pounding, lambda = integral of P(pound | "
                     "IM = x) |d lambda_IM(x)|, equals {:.4g} per year (1 - exp(-lambda {:g}) = {:g} %), {}.\n\n",
                     h.number("lambda_target"), years, target, h.text("target_note"));
  else
    s += fmt::format("The separation is the gap at which the annual rate of pounding, lambda = integral of P(pound | "
                     "IM = x) |d lambda_IM(x)|, equals {:.4g} per year (1 - exp(-lambda {:g}) = {:g} %), found by "
                     "bisection on the continuum of gaps with the fragility refitted at each; its interval comes from "
                     "the same record bootstrap.\n\n",
                     h.number("lambda_target"), years, target);
  return s;
}

std::string fragility_table(const View& v) {
  std::string s = fmt::format("## Fragility per gap: P(pound | {} = x) = Phi(ln(x / theta) / beta)\n\n",
                              report::md_text(v.in.text("measure")));
  const auto& theta = v.fr.get<double>("theta");
  const auto& beta = v.fr.get<double>("beta");
  const auto& status = v.fr.get<std::string>("status");
  const auto& note = v.fr.get<std::string>("note");
  const bool hz = v.hz != nullptr;
  const double conf = 100 * v.fr.number("confidence");
  const bool jack = hz && v.hz->find("probability_jack_hi");  // files written before the jackknife have none
  s += fmt::format("| gap | theta {} | {:.0f} % interval | beta | {:.0f} % interval | status |{}{}\n", v.units, conf, conf,
                   hz ? fmt::format(" annual rate | P in {:g} years | {:.0f} % interval |", v.hz->number("years"), conf) : "",
                   jack ? " jackknife |" : "");
  s += fmt::format("|---|---|---|---|---|---|{}{}\n", hz ? "---|---|---|" : "", jack ? "---|" : "");
  for (std::size_t k = 0; k < v.gaps.size(); ++k) {
    s += fmt::format("| {} | {} | {} | {} | {} | {} |", v.gap_name(k), num(theta[k], "{:.4g}"),
                     interval(v.fr.get<double>("theta_lo")[k], v.fr.get<double>("theta_hi")[k], "{:.4g}"),
                     num(beta[k], "{:.3f}"),
                     interval(v.fr.get<double>("beta_lo")[k], v.fr.get<double>("beta_hi")[k], "{:.3f}"), status[k]);
    if (hz)
      s += fmt::format(" {} | {} | [{}, {}] |", num(v.hz->get<double>("annual_rate")[k], "{:.3e}"),
                       pct(v.hz->get<double>("probability")[k]), pct(v.hz->get<double>("probability_lo")[k]),
                       pct(v.hz->get<double>("probability_hi")[k]));
    if (jack)
      s += fmt::format(" [{}, {}] |", pct(v.hz->get<double>("probability_jack_lo")[k]),
                       pct(v.hz->get<double>("probability_jack_hi")[k]));
    s += "\n";
  }
  if (jack)
    s += fmt::format("\nIntervals: percentile bootstrap over records; for P in {:g} years also the jackknife over records "
                     "(Student t on ln rate), which runs less short with few records (simulated studies with 25 records: "
                     "the bootstrap's 95 % interval held the true rate in 86 % of them, the jackknife's in 90 %); use the "
                     "larger upper end.\n",
                     v.hz->number("years"));
  std::string notes;
  for (std::size_t k = 0; k < v.gaps.size(); ++k) {
    if (status[k] != "ok" && !note[k].empty()) notes += fmt::format("- {}: {}\n", v.gap_name(k), note[k]);
    if (status[k] == "ok" && note[k].find("held at") != std::string::npos)
      notes += fmt::format("- {}: {}\n", v.gap_name(k), note[k].substr(note[k].find("the fit's own rate")));
    if (hz && v.hz->find("share_above_stripes"))
      if (const double b = v.hz->get<double>("share_below_stripes")[k], a = v.hz->get<double>("share_above_stripes")[k];
          b + a > kBeyondStripesWarning)
        notes += fmt::format("- {}: {}\n", v.gap_name(k), beyond_stripes(v, "the annual rate", b, a));
    if (status[k] == "ok" && (theta[k] > v.levels.back() || theta[k] < v.levels.front()))
      notes += fmt::format("- {}: **the median theta = {:.3g} {} lies {} the stripes**: the fit extrapolates from one "
                           "tail; add levels {} it (Baker 2015: the stripes should bracket the median)\n",
                           v.gap_name(k), theta[k], v.units, theta[k] > v.levels.back() ? "above" : "below",
                           theta[k] > v.levels.back() ? "above" : "below");
  }
  return s + (notes.empty() ? "" : "\n" + notes) + "\n";
}

std::string observed_table(const View& v) {
  const std::size_t S = v.levels.size(), G = v.gaps.size();
  const auto& n = v.fr.get<std::int64_t>("observed_n");
  const auto& z = v.fr.get<std::int64_t>("observed_z");
  const auto& fit = v.fr.get<double>("fitted");
  std::string s = "## Observed versus fitted at each stripe\n\nEach cell: poundings / analyses (observed %) and the "
                  "fitted curve's P.\n\n| " + v.in.text("measure") + " " + v.units + " |";
  for (std::size_t k = 0; k < G; ++k) s += " " + v.gap_name(k) + " |";
  s += "\n|---|";
  for (std::size_t k = 0; k < G; ++k) s += "---|";
  s += "\n";
  for (std::size_t j = 0; j < S; ++j) {
    s += fmt::format("| {} |", num(v.levels[j], "{:.4g}"));
    for (std::size_t k = 0; k < G; ++k) {
      const std::int64_t nn = n[k * S + j], zz = z[k * S + j];
      s += nn ? fmt::format(" {}/{} ({}) fit {} |", zz, nn, pct(static_cast<double>(zz) / static_cast<double>(nn)),
                            pct(fit[k * S + j]))
              : " — |";
    }
    s += "\n";
  }
  return s + "\n";
}

std::string stripes_section(const View& v) {
  const Group& in = v.in;
  if (!in.find("scale")) return "";
  const auto& scale = in.get<double>("scale");
  const auto& dropped = in.get<std::uint8_t>("dropped");
  const std::size_t S = v.levels.size(), R = v.r.record_count(), P = v.r.polarities();  // a record's signs: one
  // records selected to a spectrum ([records] select) carry their selection factor f_i F already: the factor against
  // the recording, which the [0.25, 4] practice is about, is that times the stripe's
  const results::Group* sel_group = v.r.group("selection");
  const std::vector<double>* sel = sel_group && sel_group->find("scale") ? &sel_group->get<double>("scale") : nullptr;
  std::string s = fmt::format("## Stripes and scale factors\n\nEach record is scaled by level / IM; a factor above "
                              "max_scale = {:g} drops the record from that stripe. Factors outside [0.25, 4] distort "
                              "the record's spectral shape relative to its IM (research note 1.5): counted below{}.\n\n"
                              "| level {} | records | dropped | factor min | median | max | outside [0.25, 4] |\n"
                              "|---|---|---|---|---|---|---|\n",
                              in.number("max_scale"),
                              sel ? ", each factor the record's selection factor (f_i F) times the stripe's, its scale "
                                    "against the recording"
                                  : "",
                              v.units);
  for (std::size_t j = 0; j < S; ++j) {
    std::vector<double> f;
    std::size_t drop = 0, outside = 0;
    for (std::size_t k = 0; k < R; k += P) {
      if (dropped[j * R + k]) { ++drop; continue; }
      const double x = scale[j * R + k] * (sel && k / P < sel->size() ? (*sel)[k / P] : 1.0);
      f.push_back(x), outside += x < 0.25 || x > 4;
    }
    std::sort(f.begin(), f.end());
    s += f.empty() ? fmt::format("| {} | 0 | {} | — | — | — | — |\n", num(v.levels[j], "{:.4g}"), drop)
                   : fmt::format("| {} | {} | {} | {:.3g} | {:.3g} | {:.3g} | {} |\n", num(v.levels[j], "{:.4g}"),
                                 f.size(), drop, f.front(), f[f.size() / 2], f.back(), outside);
  }
  return s + "\n";
}

std::string hazard_section(const View& v) {
  if (!v.hz) return "";
  const Group& h = *v.hz;
  std::string s = "## Site hazard\n\n";
  const std::string curve = h.text("curve");
  s += curve.empty() ? fmt::format("- power law lambda(x) = k0 x^-k, k0 = {:.4g} per year, k = {:.3g}\n", h.number("k0"), h.number("k"))
                     : fmt::format("- hazard curve {} ({} points, log-log interpolation; beyond its ends the end "
                                   "slopes are extended and the share of the rate they give is reported)\n",
                                   report::md_code(curve), h.get<double>("im").size());
  if (!h.text("source").empty()) s += fmt::format("- source: {}\n", report::md_text(h.text("source")));
  const auto& tail = h.get<double>("tail_share");
  const double worst = tail.empty() ? 0 : *std::max_element(tail.begin(), tail.end());
  if (worst > 0.01)
    s += fmt::format("- **WARNING**: up to {:.1f} % of a gap's rate comes from beyond the hazard table: extend the table\n", 100 * worst);
  s += "- the hazard's IM must be the fragility's IM (same period and damping; a RotD50 or geometric-mean hazard with "
       "single-component records)\n";
  return s + "\n";
}

}  // namespace

// [gaps] existing (m): the fragility at the as-built gap when it is one of the study's gaps (in metres: a metres axis'
// value, or a pair's x d), else a line that says it is not.
std::string existing_fragility(const View& v) {
  if (!v.r.settings.find("gaps", "existing")) return "";
  const double g = v.r.settings.number("gaps", "existing");
  // one of the gaps within a nanometre: a pair's x d is a product (0.5 x 0.35000000000000003 is not 0.175)
  const auto same = [&](double m) { return std::abs(m - g) <= 1e-9; };
  std::size_t k = 0;
  while (k < v.gaps.size() && !(v.metres ? same(v.gaps[k]) : v.pair && same(v.gaps_m[k]))) ++k;
  std::string s = fmt::format("## At the existing gap\n\nThe as-built gap, [gaps] existing = {:g} m: ", g);
  if (k == v.gaps.size())
    return s + fmt::format("not one of the study's gaps{}, so it has no fragility curve here; give it as one of "
                           "[gaps] metres (or, for a pair, a ratio x with x d = {:g} m) to have its curve.\n\n",
                           v.pair || v.metres ? "" : " (the heights vary, so no ratio is the same metres for every model)",
                           g);
  const auto& theta = v.fr.get<double>("theta");
  const auto& beta = v.fr.get<double>("beta");
  s += fmt::format("its fragility is the row {} below: median theta = {:.4g} {}, beta = {:.3f}", v.gap_name(k), theta[k],
                   v.units, beta[k]);
  if (v.hz)
    s += fmt::format("; annual rate of pounding {:.3e}, P in {:g} years = {}", v.hz->get<double>("annual_rate")[k],
                     v.hz->number("years"), fmt::format("{:.2f}%", 100 * v.hz->get<double>("probability")[k]));
  return s + ".\n\n";
}

std::string fragility_markdown(const Results& r) {
  const View v(r);
  return overview(v) + target_section(v) + existing_fragility(v) + fragility_table(v) + observed_table(v) +
         report_detail::moat_fragility_section(r, v.levels, v.in.text("measure") + " " + v.units) + hazard_section(v) +
         stripes_section(v);
}

std::string fragility_csv(const Results& r) {
  const View v(r);
  const std::size_t S = v.levels.size();
  std::string s = "table,gap_ratio,gap_m,level,theta,beta,lo,hi,n,z,observed,fitted,annual_rate,probability\n";
  const auto& theta = v.fr.get<double>("theta");
  const auto& beta = v.fr.get<double>("beta");
  for (std::size_t k = 0; k < v.gaps.size(); ++k) {
    const double gm = v.pair ? v.gaps_m[k] : NAN;
    s += fmt::format("fragility,{},{},,{},{},{},{},,,,,{},{}\n", v.gaps[k], gm, theta[k], beta[k],
                     v.fr.get<double>("theta_lo")[k], v.fr.get<double>("theta_hi")[k],
                     v.hz ? v.hz->get<double>("annual_rate")[k] : NAN, v.hz ? v.hz->get<double>("probability")[k] : NAN);
    for (std::size_t j = 0; j < S; ++j) {
      const auto n = v.fr.get<std::int64_t>("observed_n")[k * S + j], z = v.fr.get<std::int64_t>("observed_z")[k * S + j];
      s += fmt::format("stripe,{},{},{},,,,,{},{},{},{},,\n", v.gaps[k], gm, v.levels[j], n, z,
                       n ? static_cast<double>(z) / static_cast<double>(n) : NAN, v.fr.get<double>("fitted")[k * S + j]);
    }
  }
  if (v.hz && v.hz->find("curve_gap")) {
    const auto& cg = v.hz->get<double>("curve_gap");
    for (std::size_t k = 0; k < cg.size(); ++k)
      s += fmt::format("rate_curve,{},{},,,,,,,,,,{},{}\n", cg[k],
                       v.metres ? cg[k] : v.pair ? cg[k] * v.r.models.code_gap[0] : NAN,
                       v.hz->get<double>("curve_rate")[k], v.hz->get<double>("curve_probability")[k]);
  }
  if (v.hz) {
    const Group& h = *v.hz;
    s += fmt::format("risk_targeted_gap,{},{},,,,{},{},,,,,{},{}\n", h.number("target_gap"), h.number("target_gap_m"),
                     h.number("target_gap_lo"), h.number("target_gap_hi"), h.number("lambda_target"),
                     h.number("target_percent") / 100);
    s += fmt::format("risk_targeted_gap_jackknife,{},{},,,,{},{},,,,,{},{}\n", h.number("target_gap"),
                     h.number("target_gap_m"), optional_number(h, "target_gap_jack_lo"),
                     optional_number(h, "target_gap_jack_hi"), h.number("lambda_target"), h.number("target_percent") / 100);
    double advice = optional_number(h, "target_gap_advice"), advice_m = optional_number(h, "target_gap_m_advice");
    if (std::isnan(advice)) advice = h.number("target_gap_hi"), advice_m = h.number("target_gap_m_hi");
    s += fmt::format("separation_advice,{},{},,,,,,,,,,{},{}\n", advice, advice_m, h.number("lambda_target"),
                     h.number("target_percent") / 100);
  }
  return s;
}

}  // namespace pounding
