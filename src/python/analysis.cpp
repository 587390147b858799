// The analysis layer's statistics on numpy arrays: Baker's MSA fit with its separation and non-identifiability
// statuses, the IDA fits, hazard integration and the risk-targeted separation (analysis/fragility.hpp, hazard.hpp,
// stripes.hpp) -- the code the studies run, not a Python copy.
#include <cmath>
#include <cstdint>
#include <limits>
#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common.hpp"
#include "pounding/analysis/fragility.hpp"
#include "pounding/analysis/hazard.hpp"
#include "pounding/analysis/separation.hpp"
#include "pounding/analysis/stripes.hpp"

namespace pounding::python {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

py::dict fit_dict(const FragilityFit& f) {
  py::dict d;
  d["status"] = std::string(to_string(f.status));
  d["theta"] = f.ok() ? f.fragility.theta : NAN;
  d["beta"] = f.ok() ? f.fragility.beta : NAN;
  d["se_log_theta"] = f.ok() ? f.se_log_theta : NAN;
  d["se_beta"] = f.ok() ? f.se_beta : NAN;
  d["neg_log_likelihood"] = f.ok() ? f.neg_log_likelihood : NAN;
  d["iterations"] = f.iterations;
  d["bracket"] = py::make_tuple(f.bracket.lo, f.bracket.hi);
  d["bound"] = f.bound;
  d["message"] = f.message;
  return d;
}

py::dict fit_msa_py(const py::handle& im, const py::handle& n, const py::handle& z) {
  const auto x = to_vector(im, "im"), nn = to_vector(n, "n"), zz = to_vector(z, "z");
  if (nn.size() != x.size() || zz.size() != x.size())
    throw py::value_error("fragility.fit: im, n and z must have one value per stripe (" + std::to_string(x.size()) +
                          ", " + std::to_string(nn.size()) + ", " + std::to_string(zz.size()) + " given)");
  std::vector<Stripe> stripes(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (nn[j] != std::floor(nn[j]) || zz[j] != std::floor(zz[j]))
      throw py::value_error("fragility.fit: n and z are counts (whole numbers), stripe " + std::to_string(j));
    stripes[j] = {x[j], static_cast<std::int64_t>(nn[j]), static_cast<std::int64_t>(zz[j])};
  }
  return fit_dict(fit_fragility_msa(stripes));  // std::invalid_argument -> ValueError
}

stripes::Settings settings_of(int bootstrap, double confidence, std::uint64_t seed, double years, int threads) {
  check_threads(threads);
  stripes::Settings s;
  s.bootstrap = bootstrap, s.confidence = confidence, s.seed = seed, s.years = years, s.threads = threads;
  return s;
}

std::unique_ptr<HazardCurve> curve_of(const py::object& curve) {
  if (curve.is_none()) return nullptr;
  const char* const need = "curve: (k0, k) of a power law or (im, rate) arrays of a table is needed, got ";
  if (!py::isinstance<py::tuple>(curve) && !py::isinstance<py::list>(curve)) throw py::value_error(need + given(curve));
  const auto t = py::tuple(py::reinterpret_borrow<py::sequence>(curve));
  if (t.size() != 2) throw py::value_error(need + given(curve));
  if (py::isinstance<py::float_>(t[0]) || py::isinstance<py::int_>(t[0]))
    return std::make_unique<HazardCurve>(HazardCurve::power_law(to_number(t[0], "curve k0"), to_number(t[1], "curve k")));
  return std::make_unique<HazardCurve>(
      HazardCurve::from_table(to_vector(t[0], "curve im"), to_vector(t[1], "curve rate")));
}

py::dict gap_fragility_dict(const stripes::GapFragility& g) {
  py::dict d = fit_dict(g.fit);
  d["gap"] = g.gap;
  d["theta_ci"] = py::make_tuple(g.theta_ci.lo, g.theta_ci.hi);
  d["beta_ci"] = py::make_tuple(g.beta_ci.lo, g.beta_ci.hi);
  d["replicates"] = g.replicates, d["replicates_failed"] = g.replicates_failed;
  d["annual_rate"] = g.annual_rate, d["rate_ci"] = py::make_tuple(g.rate_lo, g.rate_hi);
  d["probability"] = g.probability, d["probability_ci"] = py::make_tuple(g.probability_lo, g.probability_hi);
  d["tail_share"] = g.tail_share, d["note"] = g.note;
  return d;
}

// IDA capacities, one per record (+inf or above censored_at: no pounding up to censored_at). Without censoring the
// method of moments (Baker eqs. 2-3), with it the censored lognormal MLE (stripes.hpp fit_ida).
py::dict fit_ida_py(const py::handle& capacities, std::optional<double> censored_at, int bootstrap, double confidence,
                    std::uint64_t seed, const py::object& curve, double years) {
  stripes::Capacities c;
  c.capacity = to_vector(capacities, "capacities");
  c.records = c.capacity.size(), c.models = 1;
  double top = 0;
  for (double v : c.capacity)
    if (std::isfinite(v)) top = std::max(top, v);
  const double cap = censored_at ? *censored_at : top;
  if (!(cap > 0) || !std::isfinite(cap)) throw py::value_error("fit_ida: censored_at must be finite and > 0");
  c.cap.assign(c.records, cap);
  const auto hazard = curve_of(curve);
  stripes::GapFragility g;
  run_interruptible([&](const std::atomic<bool>& stop) {  // Ctrl-C ends the bootstrap within one replicate
    const WorkHook hook{{}, &stop};
    auto s = settings_of(bootstrap, confidence, seed, years, 1);
    s.hook = &hook;
    g = stripes::fit_ida(c, {}, s, hazard.get(), 0.0);
  });
  return gap_fragility_dict(g);
}

py::dict rate_py(double theta, double beta, const py::object& curve, double years) {
  const auto hazard = curve_of(curve);
  if (!hazard) throw py::value_error("hazard.rate: a curve is needed");
  if (!(theta > 0) || !std::isfinite(theta) || !(beta >= 0) || !std::isfinite(beta))
    throw py::value_error("hazard.rate: theta must be finite and > 0, beta finite and >= 0");
  const PoundingRate r = pounding_rate(*hazard, LognormalFragility{theta, beta});
  py::dict d;
  d["rate"] = r.rate, d["tail_share"] = r.tail_share, d["probability"] = probability_in_years(r.rate, years);
  d["years"] = years;
  return d;
}

// demands[s, r, m] (peak closing over each model's gap unit), levels[s]: Baker MLE per gap and the risk-targeted gap.
stripes::Demands demands_of(const py::handle& demands, const py::handle& levels) {
  const Array a = checked_array(demands, "demands");
  if (a.ndim() != 3)
    throw py::value_error("demands: a 3-D array [stripe, record, model] is needed, got " + given(demands));
  stripes::Demands d;
  d.levels = to_vector(levels, "levels");
  if (d.levels.size() != static_cast<std::size_t>(a.shape(0)))
    throw py::value_error("levels: one IM level per stripe of demands (axis 0) is needed");
  d.records = static_cast<std::size_t>(a.shape(1)), d.models = static_cast<std::size_t>(a.shape(2));
  d.demand.assign(a.data(), a.data() + a.size());
  return d;
}

py::list fit_stripes_py(const py::handle& demands, const py::handle& levels, const py::handle& gaps, int bootstrap,
                        double confidence, std::uint64_t seed, const py::object& curve, double years, int threads) {
  const auto d = demands_of(demands, levels);
  const auto x = to_vector(gaps, "gaps");
  const auto hazard = curve_of(curve);
  std::vector<stripes::GapFragility> fits;
  auto s = settings_of(bootstrap, confidence, seed, years, threads);
  run_interruptible([&](const std::atomic<bool>& stop) {  // Ctrl-C ends the bootstrap within one replicate
    const WorkHook hook{{}, &stop};
    s.hook = &hook;
    fits = stripes::fit_msa(d, x, s, hazard.get());
  });
  py::list out;
  for (const auto& g : fits) out.append(gap_fragility_dict(g));
  return out;
}

py::dict target_gap_py(const py::handle& demands, const py::handle& levels, const py::object& curve,
                       double lambda_target, int bootstrap, double confidence, std::uint64_t seed, double years,
                       int threads) {
  const auto d = demands_of(demands, levels);
  const auto hazard = curve_of(curve);
  if (!hazard) throw py::value_error("risk_targeted_gap: a hazard curve is needed");
  stripes::TargetGap t;
  auto s = settings_of(bootstrap, confidence, seed, years, threads);
  run_interruptible([&](const std::atomic<bool>& stop) {  // Ctrl-C ends the replicates within one replicate
    const WorkHook hook{{}, &stop};
    s.hook = &hook;
    t = stripes::risk_targeted_gap(d, *hazard, lambda_target, s);
  });
  py::dict r;
  r["gap"] = t.gap, r["ci"] = py::make_tuple(t.lo, t.hi), r["lambda_target"] = t.lambda_target, r["rate"] = t.rate;
  r["range"] = py::make_tuple(t.range_lo, t.range_hi), r["replicates"] = t.replicates;
  r["replicates_below"] = t.replicates_below, r["replicates_above"] = t.replicates_above;
  r["jackknife_se"] = t.jack_se, r["jackknife_ci"] = py::make_tuple(t.jack_lo, t.jack_hi);
  r["advice"] = t.advice, r["status"] = t.status, r["note"] = t.note;
  return r;
}

}  // namespace

void bind_analysis(py::module_& m) {
  py::module_ a = m.def_submodule("analysis", "the statistics and code rules of the analysis layer");
  a.def("ddc_rho", &separation::ddc_rho, py::arg("T1"), py::arg("T2"), py::arg("zeta1"), py::arg("zeta2"),
        "CQC correlation of two oscillators (Der Kiureghian 1981) that the DDC code rule uses; periods in s, damping "
        "ratios as fractions.");
  a.def("fit_msa", &fit_msa_py, py::arg("im"), py::arg("n"), py::arg("z"));
  a.def("fit_moments", [](const py::handle& c) {
    const auto f = fit_fragility_moments(to_vector(c, "capacities"));
    return py::make_tuple(f.theta, f.beta);
  }, py::arg("capacities"));
  a.def("fit_ida", &fit_ida_py, py::arg("capacities"), py::arg("censored_at"), py::arg("bootstrap"),
        py::arg("confidence"), py::arg("seed"), py::arg("curve"), py::arg("years"));
  a.def("fit_stripes", &fit_stripes_py, py::arg("demands"), py::arg("levels"), py::arg("gaps"), py::arg("bootstrap"),
        py::arg("confidence"), py::arg("seed"), py::arg("curve"), py::arg("years"), py::arg("threads"));
  a.def("rate", &rate_py, py::arg("theta"), py::arg("beta"), py::arg("curve"), py::arg("years"));
  a.def("rate_closed_form", [](double k0, double k, double theta, double beta) {
    return pounding_rate_closed_form(k0, k, LognormalFragility{theta, beta});
  }, py::arg("k0"), py::arg("k"), py::arg("theta"), py::arg("beta"));
  a.def("probability_in_years", &probability_in_years, py::arg("rate"), py::arg("years"));
  a.def("rate_for_probability", &rate_for_probability, py::arg("p"), py::arg("years"));
  a.def("risk_targeted_gap", &target_gap_py, py::arg("demands"), py::arg("levels"), py::arg("curve"),
        py::arg("lambda_target"), py::arg("bootstrap"), py::arg("confidence"), py::arg("seed"), py::arg("years"),
        py::arg("threads"));
  a.attr("inf") = kInf;
}

}  // namespace pounding::python
