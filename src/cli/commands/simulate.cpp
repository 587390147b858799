// `pounding simulate`: one pair through one record -> observers (and optionally the time series).
#include <optional>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <array>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <span>
#include <string>
#include <vector>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/commands.hpp"
#include "cli/commands/bridge_file.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/contact/registry.hpp"
#include "cli/commands/restitution_options.hpp"
#include "pounding/core/error.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/report/json.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/io/hdf5.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/bridge.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/system_series.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/validate.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/report/summary.hpp"
#include "pounding/sampling/isolation_check.hpp"
#include "pounding/workloads/workloads.hpp"

namespace pounding::cli {

namespace {

// Default masses from the heights: the paper's mass model m = mbar rho r^2 h with r = h / aspect (eq. 7,
// stochastic-pounding-monte-carlo.txt) at its mean values (sampling/sampler.hpp's defaults, aspect the middle
// of 1, 2, 3): h = 30 m gives 7.29e6 kg, 45 m 2.46e7 kg.
constexpr double default_mbar = 0.6, default_rho = 1800.0, default_aspect = 2.0;
constexpr const char* mass_model_text = "m = mbar rho r^2 h, r = h / aspect, mbar 0.6, rho 1800 kg/m^3, aspect 2";
double mass_from_height(double h) {
  const double r = h / default_aspect;
  return default_mbar * default_rho * r * r * h;
}

struct SimulateOptions {
  std::string record, units = "g", series;
  double dt_record = 0.0;
  double m1 = 0, T1 = 1.0, k1 = 0, h1 = 30.0, fy1 = 0;  // m = 0: from the height (mass_from_height)
  double m2 = 0, T2 = 1.5, k2 = 0, h2 = 45.0, fy2 = 0;
  double alpha = 0.05, zeta = 0.05, gap = 0.1;
  std::vector<double> modal_zeta;  // multi-storey buildings: classical modal damping, per mode from 1 (empty: Rayleigh)
  bool elastic = false;
  std::string contact = "hertzdamp", damping_law = "lankarani-nikravesh", stepper = "central-difference";
  double e = 0.65, kh = 0, n = 1.5, density = 2400.0, youngs = 24.86e9, poisson = 0.15;
  double dt = 0, duration = 0, u_limit = 10.0;
  bool locate = false;
  bool k1_given = false, k2_given = false, fy1_given = false, fy2_given = false, dt_given = false, kh_given = false;
  bool duration_given = false, m1_given = false, m2_given = false, h1_given = false, h2_given = false;
  bool json = false;
  // initial displacement / velocity of buildings 1 and 2 relative to the ground (m, m/s): one value (the SDOF, or
  // every floor) or one per floor from the bottom (an isolated building may lead with its base): pull-back and
  // free-vibration tests; empty: at rest
  std::vector<double> initial_u[2], initial_v[2];
  double scale = 1.0;  // --scale: a factor on the record (as a study's [records] scale)
  double cy[2] = {0, 0};  // --yield-coefficientK: buildings 1 and 2 yield at a base shear Cy M g (0: not given)
  bool scale_given = false, cy_given[2] = {false, false};
  RestitutionOpts rest;                              // e(v0) (issue 26 §3): --restitution-*
  std::optional<contact::RestitutionCurve> curve;    // parsed in the callback
  // multi-storey buildings (issue 25 §4): any of these options makes both buildings shear buildings
  struct Storeys {
    int storeys = 1;
    // one value (every floor / storey) or one per floor / storey, bottom first (--storey-massK 2e5,2e5,1.5e5)
    std::vector<double> mass, stiffness, height{3.2}, yield;
    bool storeys_given = false, mass_given = false, stiffness_given = false, height_given = false, yield_given = false;
    std::vector<double> rayleigh_modes;  // --rayleigh-modesK i,j: Rayleigh's two modes (default 1, 2)
    bool rayleigh_given = false;
    std::string rayleigh_option;  // the option that gave them (building K >= 3 may inherit building 1's or 2's)
    bool any() const {
      return storeys_given || mass_given || stiffness_given || height_given || yield_given || rayleigh_given;
    }
  };
  Storeys b[2];
  // base isolation (issue 25 §2): bearing, base mass, bearing numbers, moat walls; any of these makes building i
  // an isolated shear building
  using Isolation = sampling::IsolationInput;  // sampling/isolation_check.hpp: one check for simulate and Python
  Isolation iso[2];
  // which floors pound (issue 25 §3): common levels or the lower roof only, the level tolerance, gap offsets per level
  std::string contact_levels = "common";
  double level_tolerance = 0.05;
  std::string shape_functions = "linear";  // a floor against a column: linear or cubic (model::ShapeFunctions)
  std::vector<double> gap_offsets;
  bool levels_given = false;
  // a row of buildings (issue 25 step 8, docs/rows.md): --buildings N, buildings 3..N by --TK, --mK, --kK, --hK,
  // --fyK and the storey options --storeysK ...; an option not given takes building 1's value for odd K and building
  // 2's for even K
  static constexpr int max_buildings = 8;
  int buildings = 2;
  struct RowBuilding {
    double m = 0, T = 1.0, k = 0, h = 30.0, fy = 0;
    bool m_given = false, T_given = false, k_given = false, h_given = false, fy_given = false;
    bool m_user = false, k_user = false, fy_user = false;  // given for this building (not inherited)
    Storeys st;
  };
  RowBuilding more[max_buildings - 2];
  // a bridge (issue 26 §1): the chain of frames, joints and abutments in a TOML file (bridge_file.hpp); multi-support
  // input (§2): one record per support, or --record delayed by k * wave_delay at support k + 1
  std::string bridge;
  std::vector<std::string> support_records;
  double wave_delay = 0.0;
  bool wave_delay_given = false;
  bool storey_mode() const {
    return b[0].any() || b[1].any() || levels_given || iso[0].any() || iso[1].any() || buildings > 2;
  }
};

// One building's options, whichever way they were given (--m1 ... or --mK of a row).
struct Side {
  std::string k;  // "1", "2", ...
  SimulateOptions::Storeys st;
  double m = 0, T = 0, kk = 0, h = 0, fy = 0;
  bool m_given = false, k_given = false, fy_given = false, h_given = false;
};

// --m1/--m2, or the mass model's value at --h1/--h2.
void resolve_masses(SimulateOptions& o) {
  for (auto [m, h, given, i] : {std::tuple{&o.m1, o.h1, o.m1_given, "1"}, {&o.m2, o.h2, o.m2_given, "2"}}) {
    if (given) continue;
    if (!(std::isfinite(h) && h > 0))
      throw InputError(fmt::format("--h{} = {} must be a height > 0 (m)", i, h), std::string("--h") + i,
                       fmt::format("give the height in m (the default mass comes from it), or give --m{}", i));
    *m = mass_from_height(h);
  }
  // --yield-coefficientK of an SDOF (a one-storey building): fy = Cy m g, the mass resolved above
  if (o.cy_given[0]) o.fy1 = o.cy[0] * o.m1 * physics::standard_gravity, o.fy1_given = true;
  if (o.cy_given[1]) o.fy2 = o.cy[1] * o.m2 * physics::standard_gravity, o.fy2_given = true;
}

// What the pair and the analysis are beyond the summary: the masses and where they came from, and the analysis
// length against the record's.
std::string describe_duration(double record_length, double analysis_length) {
  std::string t = fmt::format("analysis_duration_s: {:.6g}\n", analysis_length);
  if (analysis_length < record_length - 1e-12)
    t += fmt::format("analysis_note: --duration shortened the analysis to the first {:.6g} s of the record's {:.6g} s\n",
                     analysis_length, record_length);
  else if (analysis_length > record_length + 1e-12)
    t += fmt::format("analysis_note: --duration runs {:.6g} s: the record's {:.6g} s, then free vibration\n",
                     analysis_length, record_length);
  return t;
}
std::string describe_run(const SimulateOptions& o, double record_length, double analysis_length) {
  std::string t;
  for (const auto& [name, m, given, h] : {std::tuple{"m1", o.m1, o.m1_given, o.h1}, {"m2", o.m2, o.m2_given, o.h2}})
    t += fmt::format("{}_kg: {:.6g} ({})\n", name, m,
                     given ? std::string("--") + name : fmt::format("from h = {:g} m: {}", h, mass_model_text));
  return t + describe_duration(record_length, analysis_length);
}

// --duration shorter than the record keeps its first duration / dt steps (rounded to a whole step); longer, the
// kernel continues in free vibration. Returns the analysis length.
double cut_to_duration(const SimulateOptions& o, Record& rec) {
  const double own = rec.duration();
  if (!o.duration_given) return own;
  if (o.duration >= own) return o.duration;
  const auto steps = std::max<long>(1, std::lround(o.duration / rec.dt));
  rec.acc.resize(static_cast<std::size_t>(steps) + 1);
  return rec.duration();
}

// Builds one structure from the options of side `i` ("1" or "2").
Structure make_structure(double m, double T, double k, double h, double fy, double alpha, double zeta, bool elastic,
                         const std::string& i, bool k_given, bool fy_given) {
  require_positive(m, "--m" + i);
  if (k_given) require_positive(k, "--k" + i);
  if (fy_given) {
    require_positive(fy, "--fy" + i);
    // the yield coefficient Cy = fy / (m g) a study's building may have
    const config::StudyKey& cy = config::study_key("structures.buildingN", "yield_coefficient");
    const double w = m * g_accel;
    if (!(fy >= cy.lo * w && fy <= cy.hi * w))
      throw InputError(fmt::format("--fy{} = {} N is {:.3g} times the weight m g = {:.6g} N", i, fy, fy / w, w), "--fy" + i,
                       fmt::format("give a yield force of {} times m g, [{:.6g}, {:.6g}] N (as yield_coefficient in a "
                                   "study's [structures.buildingK])",
                                   cy.range, cy.lo * w, cy.hi * w));
  }
  Structure s;
  if (k_given) {
    s.m = m, s.k = k, s.c = 2.0 * zeta * std::sqrt(k * m);
  } else {
    require_positive(T, "--T" + i);
    s = Structure::from_period(m, T, zeta);
  }
  s.alpha = alpha;
  if (elastic) {
    s.fy = std::numeric_limits<double>::infinity();
  } else if (fy_given) {
    s.fy = fy;
  } else {
    require_positive(h, "--h" + i);
    s.fy = s.k * 0.02 * h / 6.0;  // ductility 6 at 2 % drift (stochastic-pounding-monte-carlo.txt, sec. 2)
  }
  return s;
}

void write_series_csv(const std::string& path, const SeriesRecorder& r) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "t_s,ag_m_s2,u1_m,u2_m,v1_m_s,v2_m_s,a1_abs_m_s2,a2_abs_m_s2,fs1_N,fs2_N,contact_force_N\n");
  for (std::size_t j = 0; j < r.t.size(); ++j)
    fmt::format_to(std::back_inserter(out), "{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                   r.t[j], r.ag[j], r.u1[j], r.u2[j], r.v1[j], r.v2[j], r.a1_abs[j], r.a2_abs[j], r.fs1[j], r.fs2[j],
                   r.force[j]);
  files::write_text_atomically(path, std::string_view(out.data(), out.size()));
}

void write_series_h5(const std::string& path, const SeriesRecorder& r, const std::string& summary) {
  h5::AtomicFile f(path);
  auto g = h5::create_group(f.root(), "series");
  using S = SeriesRecorder;
  for (const auto& [name, values] : {std::pair{"t", &S::t}, {"ag", &S::ag}, {"u1", &S::u1}, {"u2", &S::u2},
                                     {"v1", &S::v1}, {"v2", &S::v2}, {"a1_abs", &S::a1_abs}, {"a2_abs", &S::a2_abs},
                                     {"fs1", &S::fs1}, {"fs2", &S::fs2}, {"contact_force", &S::force}})
    h5::write_dataset(g.get(), name, r.*values);
  h5::write_attribute(g.get(), "units", std::string("SI: s, m, m/s, m/s^2, N"));
  h5::write_attribute(f.root(), "summary", summary);
  f.commit();
}

// A system's series (physics/system_series.hpp): columns t, ag, then per DOF u and a_abs, per contact element F,
// named by body (b1, b2, ...; an isolated body's DOF 1 is its base) and element label.
std::vector<std::string> series_dof_names(const model::System& sys) {
  std::vector<std::string> names(static_cast<std::size_t>(sys.ndof()));
  for (std::size_t b = 0; b < sys.bodies().size(); ++b)
    for (std::size_t k = 0; k < sys.bodies()[b].dofs.size(); ++k)
      names[static_cast<std::size_t>(sys.bodies()[b].dofs[k])] = fmt::format("b{}_{}", b + 1, k + 1);
  return names;
}
std::string series_element_name(const model::ContactElement& ce) {
  std::string n = ce.label;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

void write_system_series_csv(const std::string& path, const physics::SystemSeries& r, const model::System& sys) {
  fmt::memory_buffer out;
  auto put = [&]<class... A>(fmt::format_string<A...> f, A&&... a) {
    fmt::format_to(std::back_inserter(out), f, std::forward<A>(a)...);
  };
  const std::vector<std::string> dofs = series_dof_names(sys);
  put("t_s,ag_m_s2");
  for (const std::string& d : dofs) put(",u_{}_m", d);
  for (const std::string& d : dofs) put(",a_abs_{}_m_s2", d);
  for (const model::ContactElement& ce : sys.contacts()) put(",F_{}_N", series_element_name(ce));
  put("\n");
  for (std::size_t j = 0; j < r.t.size(); ++j) {
    put("{:.17g},{:.17g}", r.t[j], r.ag[j]);
    for (const auto& v : r.u) put(",{:.17g}", v[j]);
    for (const auto& v : r.a_abs) put(",{:.17g}", v[j]);
    for (const auto& v : r.force) put(",{:.17g}", v[j]);
    put("\n");
  }
  files::write_text_atomically(path, std::string_view(out.data(), out.size()));
}

void write_system_series_h5(const std::string& path, const physics::SystemSeries& r, const model::System& sys,
                            const std::string& summary) {
  h5::AtomicFile f(path);
  auto g = h5::create_group(f.root(), "series");
  auto flat = [](const std::vector<std::vector<double>>& rows) {
    std::vector<double> v;
    for (const auto& x : rows) v.insert(v.end(), x.begin(), x.end());
    return v;
  };
  const std::size_t steps = r.t.size();
  auto units = [&](const char* name, const char* unit) {
    h5::write_attribute(h5::open_dataset(g.get(), name).get(), "units", std::string(unit));
  };
  h5::write_dataset(g.get(), "t", r.t), units("t", "s");
  h5::write_dataset(g.get(), "ag", r.ag), units("ag", "m/s^2");
  for (const auto& [name, rows, unit] : {std::tuple{"u", &r.u, "m"}, {"a_abs", &r.a_abs, "m/s^2"}, {"force", &r.force, "N"}}) {
    const std::size_t dims[] = {rows->size(), steps};
    h5::write_dataset(g.get(), name, flat(*rows), dims), units(name, unit);
  }
  std::vector<std::string> elements;
  for (const model::ContactElement& ce : sys.contacts()) elements.push_back(ce.label);
  h5::write_strings(g.get(), "dof_names", series_dof_names(sys));
  h5::write_strings(g.get(), "element_names", elements);
  h5::write_attribute(g.get(), "units", std::string("SI: t s, ag and a_abs m/s^2 (support 1's ag; a_abs absolute), u m "
                                                    "(relative to the DOF's support), force N; u, a_abs [dof][step], "
                                                    "force [element][step]"));
  h5::write_attribute(f.root(), "summary", summary);
  f.commit();
}

// The coupled run of a system, recording its series when --series is given (the same numbers either way).
const physics::SystemResult& run_coupled(const SimulateOptions& o, const physics::SystemBatch& batch,
                                         std::span<const ContactModel> groups, std::span<const GroundMotion> gm,
                                         const KernelSettings& ks, physics::SystemResult& r,
                                         physics::SystemSeries& series) {
  if (o.series.empty())
    physics::run_system(batch, groups, gm, ks, r);
  else
    physics::run_system_recorded(batch, groups, gm, ks, r, series);
  return r;
}

void write_system_series(const SimulateOptions& o, const physics::SystemSeries& series, const model::System& sys,
                         const std::string& summary) {
  if (o.series.empty()) return;
  if (std::filesystem::path(o.series).extension() == ".csv")
    write_system_series_csv(o.series, series, sys);
  else
    write_system_series_h5(o.series, series, sys, summary);
}

// The scalar options, checked before any work or output. A quantity a study also sets is checked against that
// study key's range (config::require_key_range: one range per quantity for simulate, Python and the studies).
void validate_scalars(const SimulateOptions& o) {
  using config::require_key_range;
  if (o.scale_given) require_key_range(o.scale, "records", "scale", "--scale");
  if (o.scale_given && !o.support_records.empty())  // it scales --record, not the supports' own records
    throw InputError("--scale with --support-record", "--scale", "scale the support records' files, or drop --scale");
  for (int i = 0; i < 2 && !o.bridge.empty(); ++i)  // a bridge's frames take their numbers from its file
    for (const auto& [given, name] : {std::pair{!o.initial_u[i].empty(), "--initial-u"},
                                      {!o.initial_v[i].empty(), "--initial-v"}, {o.cy_given[i], "--yield-coefficient"}})
      if (given)
        throw InputError(fmt::format("{}{} describes building {} and this run is a --bridge", name, i + 1, i + 1),
                         name + std::to_string(i + 1), "drop it: the bridge file gives its frames' numbers");
  for (int i = 0; i < 2; ++i) {
    if (!o.cy_given[i]) continue;
    const std::string k = std::to_string(i + 1);
    require_key_range(o.cy[i], "structures.buildingN", "yield_coefficient", "--yield-coefficient" + k);
    if ((i == 0 ? o.fy1_given : o.fy2_given) || o.b[i].yield_given)
      throw InputError(fmt::format("--yield-coefficient{0} with --{1}{0}: two strengths for building {0}", k,
                                   o.b[i].yield_given ? "storey-yield" : "fy"),
                       "--yield-coefficient" + k, "give one of them");
  }
  require_key_range(o.zeta, "structures", "zeta", "--zeta");
  for (double z : o.modal_zeta) require_key_range(z, "structures", "modal_zeta", "--modal-zeta", "each; ");
  require_key_range(o.alpha, "structures", "alpha", "--alpha");
  if (!std::isfinite(o.gap) || o.gap < 0)
    throw InputError(fmt::format("--gap = {} must be >= 0", o.gap), "--gap", "give the at-rest separation in m");
  require_key_range(o.e, "contact", "e", "--e");
  if (o.dt_given) require_positive(o.dt, "--dt");
  if (o.duration_given) require_positive(o.duration, "--duration");
  if (o.kh_given) require_positive(o.kh, "--kh"), require_key_range(o.kh, "contact", "stiffness", "--kh");
  require_key_range(o.u_limit, "analysis", "displacement_limit", "--u-limit");
  require_key_range(o.density, "structures", "contact_density", "--density");
  require_key_range(o.youngs, "structures", "contact_youngs_modulus", "--E");
  require_key_range(o.poisson, "structures", "contact_poisson", "--nu");
}

// A building's options as given (not inherited), against the study keys of a building: --mK its mass, --TK its
// period, --hK its height, --kK its stiffness (an SDOF is a one-storey shear building: storey_stiffness),
// --storey-massK, --storey-stiffnessK, --storey-heightK the shear model's floor_mass, storey_stiffness,
// storey_height. A storey mass of 1e300 kg ran to "status: ok" with infinite energies; --T1 1e9 ran.
struct GivenBuilding {
  std::string k;
  double m, T, kk, h;
  bool m_given, T_given, k_given, h_given;
  const SimulateOptions::Storeys& st;
};
void validate_building(const GivenBuilding& b) {
  using config::require_key_range;
  constexpr std::string_view B = "structures.buildingN";
  if (b.m_given) require_key_range(b.m, B, "mass", "--m" + b.k);
  if (b.T_given) require_key_range(b.T, B, "period", "--T" + b.k);
  if (b.k_given) require_key_range(b.kk, B, "storey_stiffness", "--k" + b.k, "an SDOF is a one-storey building; ");
  if (b.h_given) require_key_range(b.h, B, "height", "--h" + b.k, "the default mass m = mbar rho r^2 h comes from it; ");
  // a list: every value in the key's range
  for (double v : b.st.mass) require_key_range(v, B, "floor_mass", "--storey-mass" + b.k, "each; ");
  for (double v : b.st.stiffness) require_key_range(v, B, "storey_stiffness", "--storey-stiffness" + b.k, "each; ");
  for (double v : b.st.height) require_key_range(v, B, "storey_height", "--storey-height" + b.k, "each; ");
  // (a study's shear building has no storey_yield key: the bridge frame's, the same quantity)
  for (double v : b.st.yield) require_key_range(v, "bridge.frame", "storey_yield", "--storey-yield" + b.k, "each; ");
}
void validate_buildings(const SimulateOptions& o) {
  // --T1, --T2 and --h1, --h2 have defaults in range: checked whether given or not
  validate_building({"1", o.m1, o.T1, o.k1, o.h1, o.m1_given, true, o.k1_given, true, o.b[0]});
  validate_building({"2", o.m2, o.T2, o.k2, o.h2, o.m2_given, true, o.k2_given, true, o.b[1]});
  for (int K = 3; K <= std::min(o.buildings, SimulateOptions::max_buildings); ++K) {
    const SimulateOptions::RowBuilding& x = o.more[K - 3];
    validate_building({std::to_string(K), x.m, x.T, x.k, x.h, x.m_given, x.T_given, x.k_given, x.h_given, x.st});
  }
}

ContactModel contact_model(const SimulateOptions& o) {
  ContactModel cm;
  cm.law = as_option("--contact", [&] { return parse_contact_law(o.contact); });
  cm.damping = as_option("--damping-law", [&] { return parse_damping_law(o.damping_law); });
  config::require_key_range(o.n, "contact", "n", "--n");
  cm.n = o.n;
  return cm;
}

KernelSettings kernel_settings(const SimulateOptions& o) {
  KernelSettings ks;
  ks.stepper = as_option("--stepper", [&] { return parse_stepper(o.stepper); });
  ks.displacement_limit = o.u_limit;
  ks.energy = true;
  ks.locate_contact = o.locate;
  if (o.locate && ks.stepper != Stepper::rk4)
    throw InputError("--locate-contact needs --stepper rk4", "--locate-contact", "add --stepper rk4 or drop the option");
  return ks;
}

// --record, or the built-in sweep.
Record ground_motion(const SimulateOptions& o) {
  Record rec;
  if (o.record.empty()) {
    rec.name = "builtin-sweep";
    rec.source = "built-in example: 0.4 g sine sweep 0.3-3 Hz, 40 s";
    rec.dt = 0.005;
    rec.acc = builtin_motion(rec.dt, 40.0);
  } else {
    ReadOptions ro;
    ro.units = as_option("--units", [&] { return parse_units(o.units); });
    ro.dt = o.dt_record;
    rec = read_record(o.record, ro);
  }
  if (o.scale_given) {  // as a study's [records] scale: every sample times the factor, then the checks
    for (double& a : rec.acc) a *= o.scale;
    rec.source += fmt::format(", scaled by {:g}", o.scale);
  }
  if (!o.record.empty()) require_analysable(rec, {1.0, "", "add --units cm/s2"});  // 2 s long, PGA <= 5 g (records.hpp)
  return rec;
}

// Substeps per record step for --dt, which must divide it.
int substeps_for(const SimulateOptions& o, double record_dt) {
  const double q = record_dt / o.dt;
  const config::StudyKey& most = config::study_key("analysis", "substeps");  // 1e-9 s: 5e6 substeps, std::bad_alloc
  if (!(q <= most.hi + 0.5))
    throw InputError(fmt::format("--dt = {} s is {:.4g} integration steps per record step of {} s, more than the {:g} a "
                                 "study allows",
                                 o.dt, q, record_dt, most.hi),
                     "--dt",
                     fmt::format("give --dt >= {:.6g} s (the record step / {:g}, as [analysis] substeps)",
                                 record_dt / most.hi, most.hi));
  const int substeps = static_cast<int>(std::lround(q));
  if (substeps < 1 || std::abs(q - substeps) > 1e-9 * q)
    throw InputError(fmt::format("--dt = {} does not divide the record step {}", o.dt, record_dt), "--dt",
                     "give the record step divided by a whole number");
  return substeps;
}

// The sizes the options set, checked before any record is copied or padded and before the time loop (issue 44 item 8:
// --duration 1e12 and --dt 1e-9 ended in std::bad_alloc, --wave-delay 1e300 in vector::_M_fill_insert): free
// vibration after the record at most a study's [analysis] free_vibration, and the memory of the run -- every support's
// record (`samples` each, padded), and per integration step the time loop's schedule (physics::make_schedule: ag; with
// several supports each channel's ag, vg, ug) and --series' 11 columns -- within the memory available
// (available_memory_bytes, core/machine.hpp; the measure of a study's memory check).
void check_sizes(const SimulateOptions& o, double record_dt, std::size_t samples, int channels) {
  const double record_length = record_dt * static_cast<double>(samples > 0 ? samples - 1 : 0);
  const config::StudyKey& fv = config::study_key("analysis", "free_vibration");
  if (o.duration_given && o.duration - record_length > fv.hi)
    throw InputError(fmt::format("--duration = {} s is the record's {:.6g} s and {:.6g} s of free vibration, more than "
                                 "the {:g} s a study allows",
                                 o.duration, record_length, o.duration - record_length, fv.hi),
                     "--duration",
                     fmt::format("give --duration <= {:.6g} s (the record and at most {:g} s of free vibration, as "
                                 "[analysis] free_vibration)",
                                 record_length + fv.hi, fv.hi));
  const int substeps = o.dt_given ? substeps_for(o, record_dt) : 1;
  const double length = o.duration_given ? o.duration : record_length;
  const double steps = std::ceil(length / record_dt) * substeps;
  const double per_step = 1.0 + (channels > 1 ? 3.0 * channels : 0.0) + (o.series.empty() ? 0.0 : 11.0);
  const double need = 8.0 * (2.0 * channels * static_cast<double>(samples) + per_step * (steps + 1.0));
  const double avail = available_memory_bytes();
  if (!(std::isfinite(avail) && need > avail)) return;
  const double fit = std::floor((avail / 8.0 - 2.0 * channels * static_cast<double>(samples)) / per_step);
  const std::string where = o.wave_delay_given ? "--wave-delay" : o.duration_given ? "--duration" : o.dt_given ? "--dt" : "--record";
  throw InputError(
      fmt::format("the run needs {} ({:.4g} s in {:.4g} integration steps of {:.4g} s{}{}), more than the {} of memory "
                  "available on this machine (MemAvailable)",
                  human_bytes(need), length, steps, record_dt / substeps,
                  channels > 1 ? fmt::format(", {} supports of {} samples each", channels, samples) : std::string(),
                  o.series.empty() ? "" : ", every step kept for --series", human_bytes(avail)),
      where,
      fit >= 1 ? fmt::format("give a shorter --duration, a longer --dt{} (at most {:.4g} steps fit)",
                             o.wave_delay_given ? " or a shorter --wave-delay" : "", fit)
               : std::string("give a shorter record or fewer supports"));
}

// The most substeps the step chooser may take (physics::choose_step): [analysis] substeps' range, and the memory of
// the time loop's schedule (and --series) at that step -- check_sizes' formula, so a refined step cannot run out of
// memory after the first run.
int most_substeps(const SimulateOptions& o, double record_dt, std::size_t samples, int channels) {
  const double key_hi = config::study_key("analysis", "substeps").hi;
  const double record_length = record_dt * static_cast<double>(samples > 0 ? samples - 1 : 0);
  const double length = o.duration_given ? o.duration : record_length;
  const double per_step = 1.0 + (channels > 1 ? 3.0 * channels : 0.0) + (o.series.empty() ? 0.0 : 11.0);
  const double avail = available_memory_bytes();
  if (!std::isfinite(avail)) return static_cast<int>(key_hi);
  const double fit = (avail / 8.0 - 2.0 * channels * static_cast<double>(samples)) / per_step;
  return static_cast<int>(std::clamp(std::floor(fit / (std::ceil(length / record_dt) + 1.0)), 1.0, key_hi));
}

void set_pair_initial(const SimulateOptions& o, PairParams& p);

PairParams pair_params(const SimulateOptions& o, const ContactModel& cm, const Structure& s1, const Structure& s2) {
  PairParams p;
  set_pair_initial(o, p);  // --initial-u1/v1/u2/v2
  p.s1 = s1, p.s2 = s2, p.gap = o.gap, p.e = o.e;
  if (contact::traits(cm.law).explicit_stiffness) {
    if (!o.kh_given) require_positive(0.0, fmt::format("--kh ({} stiffness, N/m)", to_string(cm.law)));
    p.kc = o.kh;
  } else {
    p.kc = o.kh_given ? o.kh : hertz_stiffness_spheres(s1.m, s2.m, o.density, o.youngs, o.poisson);
  }
  return p;
}

// --initial-uK / --initial-vK: one finite value per DOF within --u-limit (m) / any finite velocity (m/s); `dofs` the
// counts a list may have (1 always).
void check_initial(const SimulateOptions& o, int i, std::initializer_list<std::size_t> dofs, const std::string& what) {
  const std::string k = std::to_string(i + 1);
  for (const auto& [v, name] : {std::pair{&o.initial_u[i], "--initial-u"}, {&o.initial_v[i], "--initial-v"}}) {
    if (v->empty()) continue;
    if (std::find(dofs.begin(), dofs.end(), v->size()) == dofs.end())
      throw InputError(fmt::format("{}{} has {} values and building {} {}", name, k, v->size(), k, what), name + k,
                       fmt::format("give one value (every floor) or one per floor from the bottom ({})",
                                   fmt::join(dofs, " or ")));
    const bool u = std::string_view(name) == "--initial-u";
    for (double x : *v)
      if (!std::isfinite(x) || (u && !(std::abs(x) < o.u_limit)))
        throw InputError(fmt::format("{}{} = {} is out of range", name, k, x), name + k,
                         u ? fmt::format("give displacements (m) below --u-limit {:g} m in magnitude", o.u_limit)
                           : std::string("give finite velocities (m/s)"));
  }
}

// The SDOF pair's initial state (PairParams u1, v1, u2, v2).
void set_pair_initial(const SimulateOptions& o, PairParams& p) {
  for (int i = 0; i < 2; ++i) check_initial(o, i, {1}, "is an SDOF (one value)");
  if (!o.initial_u[0].empty()) p.u1 = o.initial_u[0][0];
  if (!o.initial_v[0].empty()) p.v1 = o.initial_v[0][0];
  if (!o.initial_u[1].empty()) p.u2 = o.initial_u[1][0];
  if (!o.initial_v[1].empty()) p.v2 = o.initial_v[1][0];
}

// ---- multi-storey buildings (issue 25 §4; docs/architecture.md §2.7.3) ----

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using sampling::bearing_of;

// Building i's isolation options (issue 25 §2), checked before any work by sampling::validate_isolation, named as
// the options are.
void validate_isolation(const SimulateOptions& o, int i) {
  const std::string k = std::to_string(i + 1);
  sampling::validate_isolation(o.iso[i], [&k](std::string_view key) -> std::string {
    static const std::pair<std::string_view, std::string_view> options[] = {
        {"bearing", "--isolation"},    {"base_mass", "--base-mass"},     {"k_eff", "--bearing-keff"},
        {"zeta_eff", "--bearing-zeta"}, {"k1", "--bearing-k1-"},          {"k2", "--bearing-k2-"},
        {"qd", "--bearing-qd"},         {"radius", "--bearing-radius"},   {"mu_slow", "--bearing-mu-slow"},
        {"mu_fast", "--bearing-mu-fast"}, {"rate", "--bearing-rate"},     {"u_y", "--bearing-uy"},
        {"a", "--bearing-a"},           {"beta", "--bearing-beta"},       {"gamma", "--bearing-gamma"},
        {"eta", "--bearing-eta"},       {"moat.gap", "--moat-gap"},       {"moat.law", "--moat-law"},
        {"moat.stiffness", "--moat-stiffness"}, {"moat.e", "--moat-e"}};
    static const std::pair<std::string_view, std::string_view> groups[] = {
        {"friction-pendulum keys", "--bearing-radius/mu-slow/mu-fast/rate/uy"},
        {"bouc-wen keys", "--bearing-a/beta/gamma/eta"},
        {"non-pendulum keys", "--bearing-keff/zeta/k1/k2/qd"},
        {"lead-rubber keys", "--bearing-k1/k2/qd"},
        {"linear keys", "--bearing-keff/--bearing-zeta"}};
    for (const auto& [name, option] : options)
      if (name == key) return std::string(option) + k;
    for (const auto& [name, text] : groups)
      if (name == key) return std::string(text);
    if (key == "building") return "building " + k;
    throw std::logic_error("simulate: no option for isolation input " + std::string(key));
  });
}

// A storey list of building k: one value (every floor or storey) or one per floor / storey, bottom first.
void check_storey_counts(const SimulateOptions::Storeys& b, const std::string& k) {
  const std::pair<const std::vector<double>*, const char*> lists[] = {
      {&b.mass, "--storey-mass"}, {&b.stiffness, "--storey-stiffness"}, {&b.height, "--storey-height"},
      {&b.yield, "--storey-yield"}};
  for (const auto& [v, name] : lists) {
    const std::size_t n = v->size();
    if (n <= 1 || n == static_cast<std::size_t>(b.storeys)) continue;  // 0: not given
    throw InputError(fmt::format("{}{} has {} values and building {} has {} storeys", name, k, n, k, b.storeys),
                     name + k,
                     fmt::format("give one value (every storey) or {} values, one per storey from the bottom, "
                                 "comma-separated (or --storeys{} {})",
                                 b.storeys, k, n));
  }
}

// The storey options, checked before any work: counts, heights, masses and stiffnesses, and the SDOF options that
// mean nothing for a building of several storeys.
void validate_storeys(const SimulateOptions& o) {
  for (int i = 0; i < 2; ++i) {
    const SimulateOptions::Storeys& b = o.b[i];
    const std::string k = std::to_string(i + 1);
    if (b.storeys < 1 || b.storeys > model::max_storeys)
      throw InputError(fmt::format("--storeys{} = {} is out of range", k, b.storeys), "--storeys" + k,
                       fmt::format("give a number of storeys in [1, {}]", model::max_storeys));
    check_storey_counts(b, k);
    if (b.storeys == 1) continue;
    const bool given[] = {i == 0 ? o.m1_given : o.m2_given, i == 0 ? o.k1_given : o.k2_given,
                          i == 0 ? o.fy1_given : o.fy2_given, i == 0 ? o.h1_given : o.h2_given};
    const char* name[] = {"--m", "--k", "--fy", "--h"};
    const std::string fix[] = {"give the mass of each floor with --storey-mass" + k,
                               "give --storey-stiffness" + k + " (or --T" + k + ")",
                               "give each storey's yield force with --storey-yield" + k + " (default: a drift of 0.02 h / 6)",
                               "give each storey's height with --storey-height" + k};
    for (int j = 0; j < 4; ++j)
      if (given[j])
        throw InputError(fmt::format("{}{} describes an SDOF, and building {} has {} storeys", name[j], k, k, b.storeys),
                         name[j] + k, fix[j]);
  }
  for (int i = 0; i < 2; ++i) validate_isolation(o, i);
  if (o.contact_levels != "common" && o.contact_levels != "top")
    throw unknown_key_error(o.contact_levels, "--contact-levels", "--contact-levels", "common, top", "argument");
  config::require_key_range(o.level_tolerance, "contact", "level_tolerance", "--level-tolerance");
  if (!parse_enum(model::shape_functions_names, o.shape_functions))
    throw unknown_key_error(o.shape_functions, "--shape-functions", "--shape-functions", "linear, cubic", "argument");
  for (double off : o.gap_offsets) config::require_key_range(off, "contact", "gap_offsets", "--gap-offsets", "each; ");
}

// Building i's numbers. One storey: the SDOF options unchanged (make_structure), so two one-storey buildings of
// equal storey heights are today's pair bit for bit; several: uniform floors and storeys, the storeys from
// --storey-stiffness or scaled to --T, yield drift 0.02/6 (the SDOF's yield displacement 0.02 h / 6 per storey),
// Rayleigh --zeta on modes 1 and 2 (--rayleigh-modesK i,j).
physics::ShearSpec shear_spec(const SimulateOptions& o, const Side& side, const Structure& sdof) {
  const SimulateOptions::Storeys& b = side.st;
  physics::ShearSpec spec;
  spec.alpha = o.alpha;
  spec.zeta = o.zeta;
  if (b.storeys > 1 && !o.modal_zeta.empty()) spec.modal = true, spec.modal_zeta = o.modal_zeta;
  if (b.rayleigh_given)  // checked by check_rayleigh_modes: two different modes in [1, storeys]
    spec.mode_i = static_cast<int>(std::min(b.rayleigh_modes[0], b.rayleigh_modes[1])),
    spec.mode_j = static_cast<int>(std::max(b.rayleigh_modes[0], b.rayleigh_modes[1]));
  if (b.storeys == 1) {
    spec.floor_mass = {sdof.m}, spec.storey_stiffness = {sdof.k}, spec.storey_yield = {sdof.fy};
    return spec;
  }
  // the default mass: the mass model's at the building's height (storeys x storey height, or the storeys' sum)
  const double height = b.height.size() == 1 ? b.storeys * b.height[0]
                                             : std::accumulate(b.height.begin(), b.height.end(), 0.0);
  spec.floor_mass = b.mass_given ? b.mass : std::vector<double>{mass_from_height(height) / b.storeys};
  if (b.stiffness_given) spec.storey_stiffness = b.stiffness;
  else spec.period = side.T;
  if (spec.storey_stiffness.empty()) require_positive(spec.period, "--T" + side.k);
  if (o.elastic) return spec;  // fy = inf, as an SDOF's --elastic wins over --fy
  const int i = std::stoi(side.k) - 1;  // --yield-coefficientK: buildings 1 and 2
  if (b.yield_given) spec.storey_yield = b.yield;
  else if (i < 2 && o.cy_given[i]) spec.yield_coefficient = o.cy[i];  // base shear Cy M g, upper storeys by the profile
  else spec.yield_drift = 0.02 / 6.0;
  return spec;
}

// --rayleigh-modesK i,j of each building (given, or inherited by a row's building K >= 3 from building 1 or 2): two
// different whole mode numbers in [1, storeys] of a multi-storey building damped by Rayleigh (not --modal-zeta).
void check_rayleigh_modes(const SimulateOptions& o, const std::vector<Side>& sides) {
  for (const Side& x : sides) {
    const SimulateOptions::Storeys& b = x.st;
    if (!b.rayleigh_given) continue;
    const std::string& opt = b.rayleigh_option;
    const std::string who = opt == "--rayleigh-modes" + x.k ? "" : fmt::format(" (building {} takes it)", x.k);
    if (!o.modal_zeta.empty())
      throw InputError(opt + " with --modal-zeta", opt,
                       "give either --modal-zeta z1,z2,... (classical damping) or --rayleigh-modesK i,j (Rayleigh)");
    if (b.storeys == 1)
      throw InputError(fmt::format("{} for a one-storey building{}", opt, who), opt,
                       "give --storeys" + x.k + " > 1, or drop it: one storey has one mode, damped by c = 2 zeta sqrt(k m)");
    const std::vector<double>& v = b.rayleigh_modes;
    bool ok = v.size() == 2 && v[0] != v[1];
    for (double m : v) ok = ok && m == std::floor(m) && m >= 1 && m <= b.storeys;
    if (!ok)
      throw InputError(fmt::format("{} '{}' is not two different modes of building {}'s {} storeys", opt,
                                   fmt::join(v, ","), x.k, b.storeys),
                       opt, fmt::format("give two mode numbers in [1, {}], e.g. 1,{}{}", b.storeys, b.storeys,
                                        who.empty() ? "" : "; or give --rayleigh-modes" + x.k + " for it"));
  }
}

// The buildings' longest stable step (physics::structure_step_max: highest frequency and damping, the bound
// physics::validate checks in substeps) as a --dt error: a stiff storey over a light floor is far above T1, and the
// storey dashpots of Rayleigh damping on short storeys shorten it further, invisible to the user.
void check_step(const SimulateOptions& o, const physics::SystemBatch& batch, const KernelSettings& ks, double record_dt) {
  const physics::StructureStep s = physics::structure_step_max(batch, 0, ks.stepper);
  const double h = record_dt / ks.substeps;
  if (h < s.h_max) return;
  const double need = s.substeps(record_dt);
  const std::string rule = ks.stepper == Stepper::central_difference
                               ? std::string("h^2 omega^2 + 4 h (2 zeta omega) < 4")
                               : fmt::format("h omega < {}", physics::structure_step_limit(ks.stepper));
  throw InputError(fmt::format("the integration step {} s is too long for the buildings' highest frequency and damping "
                               "(h <= {:.4g} s needed: {} with omega_max <= {:.6g} rad/s and 2 zeta omega <= {:.4g} 1/s "
                               "by Gershgorin's bounds)",
                               h, s.h_max, rule, s.omega_max, s.damping),
                   o.dt_given ? "--dt" : "--dt (default: the record step)",
                   fmt::format("give --dt <= {:.6g} s (the record step {} s / {})", record_dt / need, record_dt, need));
}

// The step of a system run (multi-storey, isolated, bridge): --dt checked against the structures' stability, or,
// without --dt, the fewest substeps that are stable and then resolve the contact (physics::choose_step; `run` runs
// the coupled analysis at ks.substeps). The step's story goes to the output ("step: ..."); a run still coarse
// prints what would resolve it on stderr too (the JSON output has it as "step_advice").
physics::StepChoice choose_system_step(const SimulateOptions& o, const physics::SystemBatch& batch,
                                       std::span<const ContactModel> groups, KernelSettings& ks, const Record& rec,
                                       int channels, const std::function<const physics::SystemResult&()>& run) {
  double h_stability = physics::no_limit;
  if (o.dt_given) {
    ks.substeps = substeps_for(o, rec.dt);
    check_step(o, batch, ks, rec.dt);
  } else {
    const physics::StructureStep st = physics::structure_step_max(batch, 0, ks.stepper);
    h_stability = st.h_max;
    if (rec.dt / ks.substeps >= st.h_max) ks.substeps = static_cast<int>(st.substeps(rec.dt));
  }
  const int most = std::max(ks.substeps, most_substeps(o, rec.dt, rec.acc.size(), channels));
  const physics::StepChoice c =
      physics::choose_step(o.dt_given, ks.substeps, rec.dt, h_stability, most, [&](int n) {
        ks.substeps = n;
        return physics::worst_element(*batch.system, groups, ks, run());
      });
  ks.substeps = c.substeps;
  return c;
}

// "step: ..." for the text output, the JSON members step / step_runs / step_advice, and the advice on stderr.
std::string step_text(const physics::StepChoice& c) {
  std::string s = fmt::format("step: {}\n", physics::describe(c));
  if (const std::string a = physics::coarse_advice(c); !a.empty()) s += fmt::format("step_advice: {}\n", a);
  return s;
}
std::string with_step_json(std::string json, const physics::StepChoice& c) {
  const std::size_t end = json.rfind('}');
  if (end == std::string::npos) return json;
  report::JsonWriter w;
  w.begin_object().member("step", physics::describe(c)).member("step_runs", c.runs).member("step_substeps", c.substeps);
  if (const std::string a = physics::coarse_advice(c); !a.empty()) w.member("step_advice", a);
  const std::string add = w.end_object().str();
  json.insert(end, "," + add.substr(1, add.rfind('}') - 1));
  return json;
}
void warn_coarse(const physics::StepChoice& c) {
  if (const std::string a = physics::coarse_advice(c); !a.empty()) fmt::print(stderr, "warning: {}\n", a);
}

// The contact elements' numbers: gap = --gap (+ --gap-offsets per level), kc = --kh or the equivalent-sphere Hertz
// stiffness of the element's two floor masses, e = --e. Checked before the run.
void set_storey_contacts(const SimulateOptions& o, const ContactModel& cm, physics::SystemBatch& batch,
                         SystemRunReport& run) {
  const model::System& sys = *batch.system;
  const bool needs_kh = cm.law == ContactLaw::linear || cm.law == ContactLaw::kelvin;
  if (needs_kh && !o.kh_given) require_positive(0.0, "--kh (linear/Kelvin stiffness, N/m)");
  int top = 0;
  for (const model::ContactElement& ce : sys.contacts()) top = std::max(top, ce.level);
  if (!o.gap_offsets.empty() && static_cast<int>(o.gap_offsets.size()) != top)  // more: they were silently ignored
    throw InputError(fmt::format("--gap-offsets has {} values and the buildings pound at levels 1 to {}",
                                 o.gap_offsets.size(), top),
                     "--gap-offsets", fmt::format("give one offset (m) per level from level 1 to {}", top));
  physics::set_contacts(batch, 0, o.gap, o.kh_given ? o.kh : 0.0, o.e, o.gap_offsets,
                        *parse_enum(model::shape_functions_names, o.shape_functions));
  // no --kh: equivalent spheres of the floor masses each element joins (a column: its nearer floor)
  if (!o.kh_given) physics::set_sphere_stiffness(batch, 0, o.density, o.youngs, o.poisson);
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    const model::ContactElement& ce = sys.contacts()[e];
    if (!sys.groups()[static_cast<std::size_t>(ce.group)].study_gap) {  // a moat: set_moat's numbers
      run.contact_stiffness.push_back(0.0), run.contact_gap.push_back(0.0);
      continue;
    }
    run.contact_stiffness.push_back(batch.kc[e]);
    run.contact_gap.push_back(batch.gap[e]);
  }
}

// The buildings' numbers (shear or isolated) in lane 0 and their report lines.
void set_buildings(const SimulateOptions& o, const std::vector<Side>& sides, const std::vector<Structure>& sdof,
                   const std::vector<model::StickTopology>& sticks, physics::SystemBatch& batch, SystemRunReport& run) {
  const model::System& sys = *batch.system;
  for (int i = 0; i < static_cast<int>(sticks.size()); ++i) {
    const std::string label = sys.bodies()[static_cast<std::size_t>(i)].label;
    const physics::ShearSpec spec = shear_spec(o, sides[i], sdof[i]);
    // Rayleigh's two modes, where a multi-storey building has them
    const std::vector<int> modes = spec.modal || sides[i].st.storeys == 1 ? std::vector<int>{}
                                                                            : std::vector<int>{spec.mode_i, spec.mode_j};
    if (!sticks[i].isolated) {
      const physics::ShearNumbers num = physics::set_shear_building(batch, 0, i, spec);
      run.buildings.push_back({label, model::floor_levels(sticks[i]), num.m, num.k, num.fy, num.modes.period,
                               num.zeta_modes, {}, modes});
      continue;
    }
    const SimulateOptions::Isolation& s = o.iso[i];
    const physics::IsolationSpec iso = sampling::isolation_spec(s, spec.floor_mass[0]);
    const physics::IsolationNumbers num = physics::set_isolated_building(batch, 0, i, spec, iso);
    const bool smooth = iso.bearing == physics::Bearing::friction_pendulum || iso.bearing == physics::Bearing::bouc_wen;
    // the periods on the isolator's initial stiffness (linear, lead-rubber, Bouc-Wen) or, for the friction
    // pendulum, on its pendulum stiffness W/R alone (sliding; T -> 2 pi sqrt(R/g) for a rigid superstructure)
    const double k_chain = iso.bearing == physics::Bearing::friction_pendulum ? model::FrictionPendulum::params(model::FrictionPendulum::unpack(num.isolator)).k : num.isolator.k;
    std::vector<double> chain_m{num.m_base}, chain_k{k_chain};
    chain_m.insert(chain_m.end(), num.super.m.begin(), num.super.m.end());
    chain_k.insert(chain_k.end(), num.super.k.begin(), num.super.k.end());
    BuildingReport br{label, model::floor_levels(sticks[i]), num.super.m, num.super.k, num.super.fy,
                      num.super.modes.period, num.super.zeta_modes, {}, modes};
    br.isolation = IsolationReport{s.bearing, num.m_base, num.isolator.k, smooth ? kNaN : num.isolator.fy,
                                   smooth ? kNaN : num.isolator.alpha, num.c_base,
                                   model::shear_stick_modes(chain_m, chain_k).period, {}};
    if (iso.bearing == physics::Bearing::friction_pendulum)
      br.isolation->law_numbers = {{"weight_N", num.weight}, {"radius_m", iso.radius}, {"mu_slow", iso.mu_slow},
                                   {"mu_fast", iso.mu_fast}, {"rate_s_m", iso.rate}, {"uy_m", iso.uy},
                                   {"pendulum_k_N_m", model::FrictionPendulum::params(model::FrictionPendulum::unpack(num.isolator)).k}};
    else if (iso.bearing == physics::Bearing::bouc_wen)
      br.isolation->law_numbers = {{"alpha", iso.k2 / iso.k1}, {"uy_m", iso.qd / (iso.k1 - iso.k2)},
                                   {"qd_N", iso.qd}, {"A", iso.bw_a}, {"beta", iso.bw_beta}, {"gamma", iso.bw_gamma},
                                   {"eta", static_cast<double>(iso.bw_eta)}};
    run.buildings.push_back(std::move(br));
  }
}

// The moat walls' numbers (--moat-*: gap each side, stiffness, e) and the contact models per group: group 0 the
// pounding between the buildings, then one per moat.
std::vector<ContactModel> set_moats(const SimulateOptions& o, const ContactModel& cm, physics::SystemBatch& batch) {
  const model::System& sys = *batch.system;
  std::vector<ContactModel> groups{cm};
  for (int i = 0; i < 2; ++i) {
    const SimulateOptions::Isolation& s = o.iso[i];
    if (!s.moat_given) continue;
    ContactModel moat = cm;
    moat.law = parse_contact_law(s.moat_law);
    groups.push_back(moat);
    const double m_base = batch.m[static_cast<std::size_t>(sys.bodies()[static_cast<std::size_t>(i)].dofs[0])];
    const double kc = s.moat_stiffness > 0 ? s.moat_stiffness  // 0 or not given: the default, as in a study
                                             : hertz_stiffness_spheres(m_base, m_base, o.density, o.youngs, o.poisson);
    physics::set_moat(batch, 0, i, s.moat_gap, s.moat_gap, kc, s.moat_e_given ? s.moat_e : o.e);
  }
  return groups;
}

// Buildings 3..N of a row (--buildings N): every option not given from building 1 (odd K) or 2 (even K), checked
// as buildings 1 and 2 are.
void resolve_row(SimulateOptions& o) {
  for (int K = 3; K <= o.buildings; ++K) {
    SimulateOptions::RowBuilding& x = o.more[K - 3];
    const bool odd = K % 2 == 1;
    const std::string k = std::to_string(K);
    if (!x.T_given) x.T = odd ? o.T1 : o.T2;
    if (!x.h_given) x.h = odd ? o.h1 : o.h2, x.h_given = odd ? o.h1_given : o.h2_given;
    if (!x.m_given) x.m = odd ? o.m1 : o.m2, x.m_given = odd ? o.m1_given : o.m2_given;
    if (!x.k_given) x.k = odd ? o.k1 : o.k2, x.k_given = odd ? o.k1_given : o.k2_given;
    if (!x.fy_given) x.fy = odd ? o.fy1 : o.fy2, x.fy_given = odd ? o.fy1_given : o.fy2_given;
    const SimulateOptions::Storeys& t = o.b[odd ? 0 : 1];
    if (!x.st.storeys_given) x.st.storeys = t.storeys, x.st.storeys_given = t.storeys_given;
    if (!x.st.mass_given) x.st.mass = t.mass, x.st.mass_given = t.mass_given;
    if (!x.st.stiffness_given) x.st.stiffness = t.stiffness, x.st.stiffness_given = t.stiffness_given;
    if (!x.st.height_given) x.st.height = t.height, x.st.height_given = t.height_given;
    if (!x.st.yield_given) x.st.yield = t.yield, x.st.yield_given = t.yield_given;
    if (!x.st.rayleigh_given)
      x.st.rayleigh_modes = t.rayleigh_modes, x.st.rayleigh_given = t.rayleigh_given, x.st.rayleigh_option = t.rayleigh_option;
    if (x.st.storeys < 1 || x.st.storeys > model::max_storeys)
      throw InputError(fmt::format("--storeys{} = {} is out of range", k, x.st.storeys), "--storeys" + k,
                       fmt::format("give a number of storeys in [1, {}]", model::max_storeys));
    check_storey_counts(x.st, k);
    if (x.st.storeys > 1)
      for (auto [user, name] : {std::pair{x.m_user, "--m"}, {x.k_user, "--k"}, {x.fy_user, "--fy"}})
        if (user)
          throw InputError(fmt::format("{}{} describes an SDOF, and building {} has {} storeys", name, k, k, x.st.storeys),
                           name + k, "give the storey options --storey-mass" + k + " / --storey-stiffness" + k);
    // the values given for building K were checked by validate_buildings, those it inherits as building 1's or 2's
  }
}

// Every building's options, left to right.
std::vector<Side> sides_of(const SimulateOptions& o) {
  std::vector<Side> out;
  out.push_back({"1", o.b[0], o.m1, o.T1, o.k1, o.h1, o.fy1, o.m1_given, o.k1_given, o.fy1_given, o.h1_given});
  out.push_back({"2", o.b[1], o.m2, o.T2, o.k2, o.h2, o.fy2, o.m2_given, o.k2_given, o.fy2_given, o.h2_given});
  for (int K = 3; K <= o.buildings; ++K) {
    const SimulateOptions::RowBuilding& x = o.more[K - 3];
    out.push_back({std::to_string(K), x.st, x.m, x.T, x.k, x.h, x.fy, x.m_given, x.k_given, x.fy_given, x.h_given});
  }
  return out;
}

// Floor-to-column elements: the struck column's fixed-end shears at the element's peak force (physics::
// column_shear_per_force; F is >= 0 and xi fixed, so the peak shears are the peak force's), the Karayannis-Favvata
// criterion -- the extra shear the impact puts into the column below and above the contact point, not added to the
// storey shear of the drift (their peaks need not coincide; the storey springs report theirs).
struct ColumnShearRow {
  std::string label;
  double xi, below, above;
};
std::vector<ColumnShearRow> column_shears(const model::System& sys, const physics::SystemResult& r) {
  std::vector<ColumnShearRow> out;
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    const model::ContactElement& ce = sys.contacts()[e];
    if (ce.left.kind != model::SideKind::interpolated && ce.right.kind != model::SideKind::interpolated) continue;
    const physics::ColumnShear v = physics::column_shear_per_force(ce.xi);
    const double F = r.peak_force[physics::SystemBatch::at(static_cast<int>(e), 0, r.width)];
    out.push_back({ce.label, ce.xi, v.below * F, v.above * F});
  }
  return out;
}
std::string column_shears_text(const model::System& sys, const physics::SystemResult& r) {
  std::string s;
  for (const ColumnShearRow& c : column_shears(sys, r))
    s += fmt::format("{} column_shear: xi {:.6g}, below_N {:.6g}, above_N {:.6g}\n", c.label, c.xi, c.below, c.above);
  return s;
}
// The JSON object with "column_shears": [{label, xi, below, above}] (N; null when not finite) before its closing brace.
std::string with_column_shears_json(std::string json, const model::System& sys, const physics::SystemResult& r) {
  const std::vector<ColumnShearRow> rows = column_shears(sys, r);
  const std::size_t end = json.rfind('}');
  if (end == std::string::npos) return json;
  auto num = [](double x) { return std::isfinite(x) ? fmt::format("{:.17g}", x) : std::string("null"); };
  std::string a = ",\"column_shears\":[";
  for (std::size_t k = 0; k < rows.size(); ++k)
    a += fmt::format("{}{{\"label\":\"{}\",\"xi\":{},\"below\":{},\"above\":{}}}", k ? "," : "", rows[k].label,
                     num(rows[k].xi), num(rows[k].below), num(rows[k].above));
  a += "]";
  json.insert(end, a);
  return json;
}

// Buildings 1 and 2's initial state in lane 0 (batch.u0, v0 by DOF): one value on every floor, one per floor, or for
// an isolated building one per DOF, its base first.
void set_system_initial(const SimulateOptions& o, const model::System& sys, const std::vector<model::StickTopology>& sticks,
                        physics::SystemBatch& batch) {
  for (int i = 0; i < 2; ++i) {
    const auto n = static_cast<std::size_t>(sticks[i].storeys);
    check_initial(o, i, sticks[i].isolated ? std::initializer_list<std::size_t>{1, n, n + 1}
                                           : std::initializer_list<std::size_t>{1, n},
                  fmt::format("has {} floors{}", n, sticks[i].isolated ? " on its base" : ""));
    const std::vector<int>& dofs = sys.bodies()[static_cast<std::size_t>(i)].dofs;  // an isolated body: base first
    for (auto [v, field] : {std::pair{&o.initial_u[i], &batch.u0}, {&o.initial_v[i], &batch.v0}}) {
      if (v->empty()) continue;
      const std::size_t skip = sticks[i].isolated && v->size() != n + 1 ? 1 : 0;  // floors only: the base at rest
      for (std::size_t d = skip; d < dofs.size(); ++d)
        (*field)[physics::SystemBatch::at(dofs[d], 0, batch.width)] = v->size() == 1 ? v->front() : (*v)[d - skip];
    }
  }
}

// The one-storey buildings 1 and 2: their storey options as the SDOF's numbers (checked as the SDOF's).
void one_storey_sdof_numbers(SimulateOptions& o) {
  for (int i = 0; i < 2; ++i) {
    const SimulateOptions::Storeys& b = o.b[i];
    if (b.storeys != 1) continue;
    if (b.mass_given) (i == 0 ? o.m1 : o.m2) = b.mass[0], (i == 0 ? o.m1_given : o.m2_given) = true;
    if (b.stiffness_given) (i == 0 ? o.k1 : o.k2) = b.stiffness[0], (i == 0 ? o.k1_given : o.k2_given) = true;
    if (b.yield_given) (i == 0 ? o.fy1 : o.fy2) = b.yield[0], (i == 0 ? o.fy1_given : o.fy2_given) = true;
  }
}

int run_storeys(SimulateOptions& o, const ContactModel& cm, KernelSettings& ks) {
  validate_storeys(o);
  resolve_row(o);
  one_storey_sdof_numbers(o);
  resolve_masses(o);
  std::vector<Side> sides = sides_of(o);
  std::vector<Structure> sdof;
  for (Side& x : sides) {
    if (x.st.storeys == 1 && x.st.mass_given) x.m = x.st.mass[0], x.m_given = true;
    if (x.st.storeys == 1 && x.st.stiffness_given) x.kk = x.st.stiffness[0], x.k_given = true;
    if (x.st.storeys == 1 && x.st.yield_given) x.fy = x.st.yield[0], x.fy_given = true;
    if (!x.m_given) x.m = mass_from_height(x.h);  // buildings 3..N (1 and 2: resolve_masses)
    sdof.push_back(make_structure(x.m, x.T, x.kk, x.h, x.fy, o.alpha, o.zeta, o.elastic, x.k, x.k_given, x.fy_given));
  }
  check_rayleigh_modes(o, sides);
  std::vector<model::StickTopology> sticks(sides.size());
  for (std::size_t i = 0; i < sides.size(); ++i) {
    sticks[i].storeys = sides[i].st.storeys, sticks[i].storey_heights = sides[i].st.height;
    if (!o.modal_zeta.empty() && sticks[i].storeys > 1) sticks[i].damping = model::DampingForm::dense;
    if (i >= 2) continue;  // isolation: buildings 1 and 2
    sticks[i].isolated = !o.iso[i].bearing.empty(), sticks[i].moat = o.iso[i].moat_given;
    if (sticks[i].isolated) sticks[i].isolator_law = physics::isolator_law(bearing_of(o.iso[i].bearing));
  }
  if (!o.modal_zeta.empty() &&
      std::none_of(sticks.begin(), sticks.end(), [](const model::StickTopology& t) { return t.storeys > 1; }))
    throw InputError("--modal-zeta damps multi-storey buildings and every building of this run has one storey",
                     "--modal-zeta", "give --storeys1/--storeys2 > 1 (a one-storey building's damping is --zeta), or "
                                     "drop --modal-zeta");
  // a floor meets at most one floor of its neighbour: the tolerance below half the smallest storey height
  double h_min = std::numeric_limits<double>::infinity();
  for (const model::StickTopology& st : sticks)
    h_min = std::min(h_min, *std::min_element(st.storey_heights.begin(), st.storey_heights.end()));
  if (!(o.level_tolerance < 0.5 * h_min))
    throw InputError(fmt::format("--level-tolerance {:g} m is not below half the smallest storey height ({:g} m): a "
                                 "floor could meet two floors of its neighbour",
                                 o.level_tolerance, h_min),
                     "--level-tolerance", fmt::format("give --level-tolerance < {:g} m (default 0.05)", 0.5 * h_min));
  const model::ContactLevels levels =
      o.contact_levels == "top" ? model::ContactLevels::top : model::ContactLevels::common;
  const model::System sys = model::shear_buildings(sticks, o.level_tolerance, levels);
  physics::SystemBatch batch;
  batch.resize(sys, 1);
  SystemRunReport run;
  set_buildings(o, sides, sdof, sticks, batch, run);
  set_system_initial(o, sys, sticks, batch);
  set_storey_contacts(o, cm, batch, run);
  const std::vector<ContactModel> groups = set_moats(o, cm, batch);
  // the moat elements' stiffness and gap in the report (set_storey_contacts wrote the floor elements')
  for (std::size_t e = 0; e < sys.contacts().size(); ++e)
    run.contact_stiffness[e] = batch.kc[e], run.contact_gap[e] = batch.gap[e];
  Record rec = ground_motion(o);
  check_sizes(o, rec.dt, rec.acc.size(), 1);
  const double record_length = rec.duration();
  const double analysis_length = cut_to_duration(o, rec);
  GroundMotion gm{rec.dt, rec.acc, analysis_length > record_length ? analysis_length : 0.0};
  physics::SystemResult r;
  physics::SystemSeries series;  // --series: the coupled run's (the final one of the step choice)
  const physics::StepChoice step = choose_system_step(o, batch, groups, ks, rec, 1, [&]() -> const physics::SystemResult& {
    return run_coupled(o, batch, groups, std::span<const GroundMotion>(&gm, 1), ks, r, series);
  });
  // the uncoupled run (no pounding between the buildings; moats stay, architecture §2.6.2) for the amplification
  std::vector<ContactModel> free_groups = groups;
  free_groups[0].law = ContactLaw::none;
  physics::SystemResult free;
  physics::run_system(batch, free_groups, gm, ks, free);
  run.uncoupled = &free;

  run.system = &sys, run.result = &r, run.record = &rec, run.settings = &ks, run.contact = &cm;
  run.e_target = o.e, run.gap = o.gap, run.analysis_duration = analysis_length;
  if (o.json) {
    fmt::print("{}", with_step_json(with_column_shears_json(format_system_json(run), sys, r), step));
  } else {
    fmt::print("{}{}{}{}", describe_duration(record_length, analysis_length), step_text(step),
               format_system_summary(run), column_shears_text(sys, r));
  }
  warn_coarse(step);
  write_system_series(o, series, sys, format_system_summary(run));
  return r.status[0] != 0 ? 3 : 0;
}

// The pair's observers as one JSON object (--json without storey options): the same run as the text output.
std::string pair_json(const SimulateOptions& o, const PairBatch& b, const BatchResult& r, const ContactModel& cm,
                      const PairParams& p, const Record& rec, const KernelSettings& ks, const GroundMotion& gm,
                      double analysis_length) {
  static const model::System pair = model::System::sdof_pair();
  const physics::SystemResult sr = physics::from_pair_result(r);
  // the same pair without pounding, for the amplifications (no series: that is the coupled run's)
  KernelSettings free_settings = ks;
  free_settings.series = nullptr;
  free_settings.restitution = nullptr;
  ContactModel none;
  none.law = ContactLaw::none;
  BatchResult free;
  run_batch(b, none, gm, free_settings, free);
  const physics::SystemResult sf = physics::from_pair_result(free);
  SystemRunReport run;
  run.system = &pair, run.result = &sr, run.uncoupled = &sf, run.record = &rec, run.settings = &ks, run.contact = &cm;
  run.e_target = p.e, run.gap = p.gap, run.analysis_duration = analysis_length, run.contact_stiffness = {p.kc};
  for (const auto& [s, h, label] : {std::tuple{p.s1, o.h1, "building1"}, {p.s2, o.h2, "building2"}})
    run.buildings.push_back({label, {h}, {s.m}, {s.k}, {s.fy}, {2 * std::numbers::pi * std::sqrt(s.m / s.k)},
                             {s.c / (2.0 * std::sqrt(s.k * s.m))}, {}, {}});
  return format_system_json(run);
}

// What a bridge run reports about its frames (one "building" per frame) and links.
void bridge_report(const physics::BridgeSpec& spec, const physics::SystemBatch& batch, SystemRunReport& run) {
  const physics::BridgeIndex x = physics::bridge_index(spec);
  for (std::size_t k = 0; k < spec.frames.size(); ++k) {
    const physics::BridgeFrame& f = spec.frames[k];
    if (f.storeys > 1) {  // a stick frame: per level, its modes and their damping ratios (as a shear building's)
      const physics::ShearNumbers num = physics::frame_numbers(f);
      const model::Body& b = batch.system->bodies()[k];
      run.buildings.push_back(
          {x.frame_label[k], b.heights, num.m, num.k, num.fy, num.modes.period, num.zeta_modes, {}, {}});
      continue;
    }
    const double kf = physics::frame_stiffness(f), c = batch.c_floor[static_cast<std::size_t>(x.frame_dof[k])];
    run.buildings.push_back({x.frame_label[k], {f.height}, {f.mass}, {kf}, {f.fy},
                             {2 * std::numbers::pi * std::sqrt(f.mass / kf)}, {c / (2.0 * std::sqrt(kf * f.mass))}, {}, {}});
  }
  run.spring_labels = x.spring_label;
  for (std::size_t e = 0; e < spec.joints.size(); ++e)
    run.contact_stiffness.push_back(batch.kc[e]), run.contact_gap.push_back(batch.gap[e]);
  run.gap = spec.joints.empty() ? 0.0 : spec.joints[0].gap;
}

// --wave-delay: the delay between neighbouring supports a study's support motions can have, at most the largest
// [records.motions] spacing over the smallest velocity (10000 m / 50 m/s = 200 s). 1e300 s ended in
// vector::_M_fill_insert, 1e6 s took 3.1 GB.
void check_wave_delay(const SimulateOptions& o) {
  const double most = config::study_key("records.motions", "spacing").hi / config::study_key("records.motions", "velocity").lo;
  if (!(std::isfinite(o.wave_delay) && o.wave_delay >= 0 && o.wave_delay <= most))
    throw InputError(fmt::format("--wave-delay = {} s is out of range", o.wave_delay), "--wave-delay",
                     fmt::format("give the delay between neighbouring supports in [0, {:g}] s (a study's support motions: "
                                 "[records.motions] spacing <= {:g} m over velocity >= {:g} m/s)",
                                 most, config::study_key("records.motions", "spacing").hi,
                                 config::study_key("records.motions", "velocity").lo));
}

// The ground motion of every support of a bridge: --support-record files (one per support, the same step; a shorter
// one padded with zeros), or --record (or the built-in sweep) delayed by k * --wave-delay at support k + 1 (a whole
// number of record steps), or the one record for every support of a one-channel bridge.
std::vector<Record> support_motions(const SimulateOptions& o, int channels) {
  std::vector<Record> recs;
  if (!o.support_records.empty()) {
    if (o.wave_delay_given || !o.record.empty())
      throw InputError("--support-record gives every support its record", "--support-record",
                       "drop --record and --wave-delay, or drop --support-record");
    if (static_cast<int>(o.support_records.size()) != channels)
      throw InputError(fmt::format("{} --support-record files for a bridge of {} supports", o.support_records.size(), channels),
                       "--support-record", "give one --support-record per support, in support order");
    for (const std::string& f : o.support_records) {
      SimulateOptions one = o;
      one.record = f;
      recs.push_back(ground_motion(one));
      if (recs.back().dt != recs.front().dt)
        throw InputError(fmt::format("{} has step {} s, {} has {} s", f, recs.back().dt, o.support_records[0], recs.front().dt),
                         "--support-record", "resample the records to one time step");
    }
    std::size_t longest = 0;
    for (const Record& r : recs) longest = std::max(longest, r.acc.size());
    check_sizes(o, recs.front().dt, longest, channels);
  } else {
    const Record base = ground_motion(o);
    if (o.wave_delay_given) {
      check_wave_delay(o);
      const double q = o.wave_delay / base.dt;
      if (std::abs(q - std::round(q)) > 1e-9 * std::max(1.0, q))
        throw InputError(fmt::format("--wave-delay = {} s is not a whole number of record steps ({} s)", o.wave_delay, base.dt),
                         "--wave-delay", fmt::format("give a multiple of {} s", base.dt));
    } else if (channels > 1) {
      throw InputError(fmt::format("the bridge has {} supports and one record", channels), "--bridge",
                       "give --support-record per support, or --wave-delay S to delay --record from support to support");
    }
    const auto shift = static_cast<std::size_t>(std::llround(o.wave_delay_given ? o.wave_delay / base.dt : 0.0));
    check_sizes(o, base.dt, base.acc.size() + shift * static_cast<std::size_t>(channels - 1), channels);
    for (int k = 0; k < channels; ++k) {
      Record r = base;
      r.acc.insert(r.acc.begin(), shift * static_cast<std::size_t>(k), 0.0);
      if (channels > 1) r.name = fmt::format("{} (delayed {:.6g} s)", base.name, base.dt * static_cast<double>(shift) * k);
      recs.push_back(std::move(r));
    }
  }
  std::size_t n = 0;
  for (const Record& r : recs) n = std::max(n, r.acc.size());
  for (Record& r : recs) r.acc.resize(n, 0.0);
  return recs;
}

// simulate --bridge FILE: the chain through the record, the text or JSON summary (per frame, per joint, per link).
int run_bridge(SimulateOptions& o, const ContactModel& cm, KernelSettings& ks) {
  if (o.storey_mode())
    throw InputError("--bridge describes the whole structure; the building options do not apply", "--bridge",
                     "drop --storeys*/--isolation*/--contact-levels, or drop --bridge");
  for (const auto& [opt, given] : {std::pair{"--m1", o.m1_given}, {"--m2", o.m2_given}, {"--k1", o.k1_given},
                                    {"--k2", o.k2_given}, {"--fy1", o.fy1_given}, {"--fy2", o.fy2_given},
                                    {"--h1", o.h1_given}, {"--h2", o.h2_given}})
    if (given)
      throw InputError(fmt::format("{} describes a building of the pair, not a bridge frame", opt), opt,
                       "give the frames' numbers in the --bridge file");
  const physics::BridgeSpec spec =
      read_bridge_file(o.bridge, o.kh_given ? o.kh : std::numeric_limits<double>::quiet_NaN(), o.e,
                       o.curve ? o.rest.option() : std::string());
  const model::System sys = physics::bridge_system(spec);
  physics::SystemBatch batch;
  batch.resize(sys, 1);
  physics::set_bridge(batch, 0, spec);
  std::vector<Record> recs = support_motions(o, spec.channels());
  Record& rec = recs[0];
  const double record_length = rec.duration();
  double analysis_length = 0.0;
  for (Record& x : recs) analysis_length = cut_to_duration(o, x);
  const std::vector<ContactModel> groups(sys.groups().size(), cm);
  std::vector<GroundMotion> gm;
  for (const Record& x : recs) gm.push_back({x.dt, x.acc, analysis_length > record_length ? analysis_length : 0.0});
  physics::SystemResult r, free;
  std::optional<physics::HertzdampRestitution> rest;  // e(v0) at every joint impact (--restitution-*)
  if (o.curve) ks.restitution = &rest.emplace(*o.curve, cm).hook;
  physics::SystemSeries series;  // --series: the coupled run's (the final one of the step choice)
  const physics::StepChoice step =
      choose_system_step(o, batch, groups, ks, rec, static_cast<int>(recs.size()), [&]() -> const physics::SystemResult& {
        return run_coupled(o, batch, groups, std::span<const GroundMotion>(gm), ks, r, series);
      });
  KernelSettings free_ks = ks;  // open joints: no impact, no curve
  free_ks.restitution = nullptr;
  std::vector<ContactModel> free_groups = groups;  // the same chain with open joints: the amplification
  for (ContactModel& g : free_groups) g.law = ContactLaw::none;
  physics::run_system(batch, free_groups, std::span<const GroundMotion>(gm), free_ks, free);
  SystemRunReport run;
  bridge_report(spec, batch, run);
  run.system = &sys, run.result = &r, run.uncoupled = &free, run.record = &rec, run.settings = &ks, run.contact = &cm;
  run.e_target = o.e, run.analysis_duration = analysis_length;
  std::string supports = fmt::format("supports: {}\n", recs.size());
  for (std::size_t k = 0; k < recs.size() && recs.size() > 1; ++k)
    supports += fmt::format("support{}_record: {}\nsupport{}_pga_g: {:.6g}\n", k + 1, recs[k].name, k + 1, recs[k].pga() / g_accel);
  std::int64_t outside = 0, impacts = 0;
  for (std::size_t e = 0; e < r.restitution_outside.size(); ++e)
    outside += std::max(0, r.restitution_outside[e]), impacts += std::max(0, r.impact_count[e]);
  if (o.json) {
    std::string json = format_system_json(run);
    if (o.curve) {  // the curve and the joints' impacts outside its valid range (per joint: levels' restitution_outside)
      report::JsonWriter w;
      w.begin_object().member("restitution", o.curve->describe()).member("restitution_outside_valid", outside);
      const std::string add = w.end_object().str();
      const std::size_t close = json.rfind('}');
      json = json.substr(0, close) + "," + add.substr(1, add.rfind('}') - 1) + json.substr(close);
    }
    fmt::print("{}", with_step_json(json, step));
  } else {
    fmt::print("{}{}{}{}", describe_duration(record_length, analysis_length), supports, step_text(step),
               format_system_summary(run));
    if (o.curve)
      fmt::print("restitution: {}\nrestitution_outside_valid: {} of {} impacts\n", o.curve->describe(), outside, impacts);
  }
  warn_coarse(step);
  write_system_series(o, series, sys, format_system_summary(run));
  return r.status[0] != 0 ? 3 : 0;
}

// The pair's JSON with the e(v0) curve and its count of impacts outside the valid range (when a curve is given).
std::string with_restitution(std::string json, const SimulateOptions& o, const BatchResult& r) {
  if (!o.curve) return json;
  report::JsonWriter w;
  w.begin_object();
  w.member("restitution", o.curve->describe());
  w.member("restitution_outside_valid", static_cast<std::int64_t>(r.restitution_outside[0]));
  w.member("restitution_note", "each impact took e(v0) at its latched approach velocity; e_target and xibar are "
                               "--e's, not used");
  std::string add = w.end_object().str();  // {"restitution":...}\n
  const std::size_t close = json.rfind('}');
  return json.substr(0, close) + "," + add.substr(1, add.rfind('}') - 1) + json.substr(close);
}

// Runs the pair, prints the summary and writes --series; returns the exit code (3: diverged, the numbers
// printed are not results).
// The SDOF pair's step: --dt, or the record step refined until the contact is resolved (physics::choose_step); the
// series (when recorded) holds the final run only.
physics::StepChoice choose_pair_step(bool given, int most, const PairBatch& b, const ContactModel& cm,
                                     const GroundMotion& gm, KernelSettings& ks, SeriesRecorder& series,
                                     BatchResult& r) {
  const physics::StepChoice step =
      physics::choose_step(given, ks.substeps, gm.dt, physics::no_limit, most, [&](int n) {
        ks.substeps = n;
        series.clear();
        run_batch(b, cm, gm, ks, r);
        return physics::lane_resolution(r, 0, ks, cm.law);
      });
  ks.substeps = step.substeps;
  return step;
}

int run_simulate(SimulateOptions& o) {
  if (!o.series.empty()) {  // never over the record, a support's record or the bridge file; never a device or FIFO
    std::vector<std::string> inputs = o.support_records;
    inputs.push_back(o.record);
    inputs.push_back(o.bridge);
    files::check_output_not_input(o.series, inputs, "--series");
    files::check_output_path(o.series, "--series");
    const std::string ext = std::filesystem::path(o.series).extension().string();
    if (ext != ".csv" && ext != ".h5")
      throw InputError(fmt::format("unknown series format '{}'", ext), "--series", "use a .csv or .h5 file name");
  }
  validate_scalars(o);  // everything is validated before any work or output
  validate_buildings(o);
  const ContactModel cm = contact_model(o);
  KernelSettings ks = kernel_settings(o);
  if (o.curve && (o.storey_mode() || cm.law != ContactLaw::hertzdamp || ks.stepper != Stepper::central_difference))
    throw InputError("a velocity-dependent restitution runs an SDOF pair or a --bridge with --contact hertzdamp and "
                     "--stepper central-difference only (not yet multi-storey, isolated or other laws/steppers)",
                     o.rest.option(), "drop the --restitution-* options, or simulate that pair or bridge");
  if (!o.modal_zeta.empty() && (!o.bridge.empty() || !o.storey_mode()))
    throw InputError("--modal-zeta damps multi-storey buildings; this run has none", "--modal-zeta",
                     "give --storeys1/--storeys2 > 1 (an SDOF's damping is --zeta), or drop --modal-zeta");
  if (!o.bridge.empty()) return run_bridge(o, cm, ks);
  if (!o.support_records.empty() || o.wave_delay_given)
    throw InputError("--support-record and --wave-delay give a bridge's supports their records", "--support-record",
                     "add --bridge FILE.toml, or drop them");
  if (o.storey_mode()) return run_storeys(o, cm, ks);
  resolve_masses(o);
  Structure s1 = make_structure(o.m1, o.T1, o.k1, o.h1, o.fy1, o.alpha, o.zeta, o.elastic, "1", o.k1_given, o.fy1_given);
  Structure s2 = make_structure(o.m2, o.T2, o.k2, o.h2, o.fy2, o.alpha, o.zeta, o.elastic, "2", o.k2_given, o.fy2_given);
  Record rec = ground_motion(o);
  check_sizes(o, rec.dt, rec.acc.size(), 1);
  const double record_length = rec.duration();
  const double analysis_length = cut_to_duration(o, rec);
  if (o.dt_given) ks.substeps = substeps_for(o, rec.dt);
  const int most = std::max(ks.substeps, most_substeps(o, rec.dt, rec.acc.size(), 1));
  const PairParams p = pair_params(o, cm, s1, s2);

  SeriesRecorder series;
  if (!o.series.empty()) ks.series = &series;
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  GroundMotion gm{rec.dt, rec.acc, analysis_length > record_length ? analysis_length : 0.0};
  BatchResult r;
  std::optional<physics::HertzdampRestitution> rest;
  if (o.curve) ks.restitution = &rest.emplace(*o.curve, cm).hook;
  const physics::StepChoice step = choose_pair_step(o.dt_given, most, b, cm, gm, ks, series, r);

  std::string text = describe_run(o, record_length, analysis_length) + step_text(step) +
                     format_summary(r, 0, cm, p, rec, ks);
  if (o.curve)
    text += fmt::format("restitution: {}\nrestitution_outside_valid: {} of {} impacts\nrestitution_note: each impact "
                        "took e(v0) at its latched approach velocity; e_target and xibar above are --e's, not used\n",
                        o.curve->describe(), r.restitution_outside[0], r.impact_count[0]);
  fmt::print("{}", o.json ? with_step_json(with_restitution(pair_json(o, b, r, cm, p, rec, ks, gm, analysis_length), o, r), step)
                          : text);
  warn_coarse(step);
  if (!o.series.empty()) {
    if (std::filesystem::path(o.series).extension() == ".csv")
      write_series_csv(o.series, series);
    else
      write_series_h5(o.series, series, text);
  }
  return r.status[0] != 0 ? 3 : 0;
}

// Whether any of `names` was given.
bool any_given(CLI::App* c, std::initializer_list<const char*> names) {
  for (const char* k : names)
    if (c->count(k) > 0) return true;
  return false;
}

// Which floors pound and how (issue 25 §3; docs/floor-contact.md): --contact-levels, --level-tolerance, --gap-offsets,
// --shape-functions.
void add_contact_level_options(CLI::App* c, SimulateOptions* o) {
  c->add_option("--contact-levels", o->contact_levels,
                "which floors pound (multi-storey): common (every pair of floors at the same level) or top (the lower "
                "roof only)")
      ->capture_default_str();
  c->add_option("--level-tolerance", o->level_tolerance, "floors whose levels differ by at most this (m) pound")
      ->capture_default_str();
  add_number_list(c, "--gap-offsets", o->gap_offsets, "per contact level from level 1, added to --gap (m), comma-separated");
  c->add_option("--shape-functions", o->shape_functions,
                "a floor striking a column between two floors: linear (N2 = xi) or cubic (the fixed-fixed column, "
                "N2 = 3 xi^2 - 2 xi^3) weights of the two floors")
      ->capture_default_str();
}

void add_row_options(CLI::App* c, SimulateOptions& opts);

// The multi-storey options (issue 25 §4): storeys, floors, levels.
void add_storey_options(CLI::App* c, SimulateOptions& opts) {
  SimulateOptions* o = &opts;
  for (int i = 0; i < 2; ++i) {
    const std::string k = std::to_string(i + 1);
    c->add_option("--storeys" + k, o->b[i].storeys,
                  "storeys of building " + k + " (a shear building; any storey option makes both buildings shear "
                  "buildings, a one-storey one keeps the SDOF options)")
        ->capture_default_str();
    // one value: every floor / storey; one per floor / storey: bottom first
    add_number_list(c, "--storey-mass" + k, o->b[i].mass,
                    "mass of each floor of building " + k + " (kg; one value, or one per floor from the bottom: "
                    "2e5,2e5,1.5e5); default: the mass model's at storeys x storey height, split equally");
    add_number_list(c, "--storey-stiffness" + k, o->b[i].stiffness,
                    "stiffness of each storey of building " + k + " (N/m; one value or one per storey); default: "
                    "uniform storeys scaled to --T" + k);
    add_number_list(c, "--storey-height" + k, o->b[i].height,
                    "height of each storey of building " + k + " (m; one value or one per storey, default 3.2); "
                    "floors at levels within 0.05 m pound");
    add_number_list(c, "--storey-yield" + k, o->b[i].yield,
                    "yield force (storey shear) of each storey of building " + k + " (N; one value or one per "
                    "storey); default: a drift of 0.02 h / 6 (--elastic: none)");
    add_number_list(c, "--rayleigh-modes" + k, o->b[i].rayleigh_modes,
                    "the two modes i,j of building " + k + " that get --zeta exactly (Rayleigh; default 1,2)");
  }
  for (int i = 0; i < 2; ++i) {
    const std::string k = std::to_string(i + 1);
    SimulateOptions::Isolation& s = o->iso[i];
    c->add_option("--isolation" + k, s.bearing,
                  "base-isolate building " + k + ": linear (--bearing-keff, --bearing-zeta), lead-rubber (bilinear: "
                  "--bearing-k1-, --bearing-k2-, --bearing-qd), friction-pendulum (--bearing-radius, --bearing-mu-slow, "
                  "--bearing-mu-fast, --bearing-rate, --bearing-uy) or bouc-wen (--bearing-k1-, -k2-, -qd and "
                  "--bearing-a, -beta, -gamma, -eta); a base mass at level 0 under the storeys");
    c->add_option("--base-mass" + k, s.base_mass, "mass of building " + k + "'s base (kg); default: one floor's mass");
    c->add_option("--bearing-keff" + k, s.k_eff, "linear bearing: effective stiffness of all isolators (N/m)");
    c->add_option("--bearing-zeta" + k, s.zeta_eff,
                  fmt::format("linear bearing: damping ratio, c_b = 2 zeta sqrt(k_eff M_total) (default {:g}); "
                              "lead-rubber: the rubber's dashpot c_b = 2 zeta sqrt(k2 M_total) (default none)",
                              physics::default_bearing_zeta));
    c->add_option("--bearing-k1-" + k, s.k1, "lead-rubber: elastic stiffness k1 (N/m)");
    c->add_option("--bearing-k2-" + k, s.k2, "lead-rubber: post-yield stiffness k2 < k1 (N/m)");
    c->add_option("--bearing-qd" + k, s.qd, "lead-rubber: characteristic strength Qd (N; Fy = Qd k1/(k1 - k2))");
    c->add_option("--bearing-radius" + k, s.radius, "friction pendulum: effective radius R (m)");
    c->add_option("--bearing-mu-slow" + k, s.mu_slow, "friction pendulum: friction coefficient at rest, mu_slow");
    c->add_option("--bearing-mu-fast" + k, s.mu_fast,
                  "friction pendulum: friction at high speed (default mu_slow: constant friction)");
    c->add_option("--bearing-rate" + k, s.rate,
                  "friction pendulum: a in mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|) (s/m, default 0)");
    c->add_option("--bearing-uy" + k, s.uy,
                  "friction pendulum: yield displacement of the smoothed stick-slip (m, default 0.00025)");
    c->add_option("--bearing-a" + k, s.bw_a, "Bouc-Wen: A (default 1)");
    c->add_option("--bearing-beta" + k, s.bw_beta, "Bouc-Wen: beta, the |du| term (default 0.5)");
    c->add_option("--bearing-gamma" + k, s.bw_gamma, "Bouc-Wen: gamma, the du term, |gamma| <= beta (default 0.5)");
    c->add_option("--bearing-eta" + k, s.bw_eta, "Bouc-Wen: the integer exponent eta in [1, 8] (default 1)");
    c->add_option("--moat-gap" + k, s.moat_gap, "moat walls left and right of building " + k + "'s base, this far (m)");
    c->add_option("--moat-law" + k, s.moat_law, "contact law at the moat walls (default hertzdamp)");
    c->add_option("--moat-stiffness" + k, s.moat_stiffness,
                  "moat contact stiffness (N/m^n; 0 or not given: equivalent-sphere Hertz of two base masses)");
    c->add_option("--moat-e" + k, s.moat_e, "moat coefficient of restitution (default: --e)");
  }
  add_contact_level_options(c, o);
  c->add_option("--buildings", o->buildings,
                "a row of N buildings side by side, each pounding its neighbours (2..8; buildings 3..N by --T3, --m3, "
                "--k3, --h3, --fy3, --storeys3, --storey-mass3, --storey-stiffness3, --storey-height3 ...; an option "
                "not given: building 1's for odd K, building 2's for even K)")
      ->capture_default_str();
  add_row_options(c, opts);
}

// The options of a row's buildings 3..8 (--buildings N, docs/rows.md).
void add_row_options(CLI::App* c, SimulateOptions& opts) {
  for (int K = 3; K <= SimulateOptions::max_buildings; ++K) {
    const std::string k = std::to_string(K);
    SimulateOptions::RowBuilding& x = opts.more[K - 3];
    const std::string group = "Row (--buildings N >= 3)";
    c->add_option("--T" + k, x.T, "period of building " + k + " (s)")->group(group);
    c->add_option("--m" + k, x.m, "mass of building " + k + " (kg)")->group(group);
    c->add_option("--k" + k, x.k, "initial stiffness of building " + k + " (N/m), instead of --T" + k)->group(group);
    c->add_option("--h" + k, x.h, "height of building " + k + " (m)")->group(group);
    c->add_option("--fy" + k, x.fy, "yield force of building " + k + " (N)")->group(group);
    c->add_option("--storeys" + k, x.st.storeys, "storeys of building " + k)->group(group);
    add_number_list(c, "--storey-mass" + k, x.st.mass, "mass of each floor of building " + k + " (kg; one or per floor)")
        ->group(group);
    add_number_list(c, "--storey-stiffness" + k, x.st.stiffness,
                    "stiffness of each storey of building " + k + " (N/m; one or per storey)")
        ->group(group);
    add_number_list(c, "--storey-height" + k, x.st.height,
                    "height of each storey of building " + k + " (m; one or per storey)")
        ->group(group);
    add_number_list(c, "--storey-yield" + k, x.st.yield,
                    "yield force of each storey of building " + k + " (N; one or per storey)")
        ->group(group);
    add_number_list(c, "--rayleigh-modes" + k, x.st.rayleigh_modes, "Rayleigh's two modes i,j of building " + k)
        ->group(group);
  }
}

// Which row options were given; an option of a building beyond --buildings is refused.
void count_row_options(CLI::App* c, SimulateOptions& o) {
  if (o.buildings < 2 || o.buildings > SimulateOptions::max_buildings)
    throw InputError(fmt::format("--buildings = {} is out of range", o.buildings), "--buildings",
                     fmt::format("give 2 (a pair) to {} buildings in a row", SimulateOptions::max_buildings));
  for (int K = 3; K <= SimulateOptions::max_buildings; ++K) {
    const std::string k = std::to_string(K);
    SimulateOptions::RowBuilding& x = o.more[K - 3];
    x.T_given = c->count("--T" + k) > 0, x.m_given = c->count("--m" + k) > 0, x.k_given = c->count("--k" + k) > 0;
    x.h_given = c->count("--h" + k) > 0, x.fy_given = c->count("--fy" + k) > 0;
    x.m_user = x.m_given, x.k_user = x.k_given, x.fy_user = x.fy_given;
    x.st.storeys_given = c->count("--storeys" + k) > 0, x.st.mass_given = c->count("--storey-mass" + k) > 0;
    x.st.stiffness_given = c->count("--storey-stiffness" + k) > 0, x.st.height_given = c->count("--storey-height" + k) > 0;
    x.st.yield_given = c->count("--storey-yield" + k) > 0;
    x.st.rayleigh_given = c->count("--rayleigh-modes" + k) > 0, x.st.rayleigh_option = "--rayleigh-modes" + k;
    if (K <= o.buildings) continue;
    for (const char* name : {"--T", "--m", "--k", "--h", "--fy", "--storeys", "--storey-mass", "--storey-stiffness",
                             "--storey-height", "--storey-yield", "--rayleigh-modes"})
      if (c->count(name + k) > 0)
        throw InputError(fmt::format("{}{} is for building {} and the row has --buildings {}", name, k, k, o.buildings),
                         name + k, fmt::format("give --buildings {} (or more), or drop {}{}", K, name, k));
  }
}

// Which storey options of buildings 1 and 2 were given (and --scale, --yield-coefficientK).
void count_storey_options(CLI::App* c, SimulateOptions& o) {
  o.scale_given = c->count("--scale") > 0;
  o.cy_given[0] = c->count("--yield-coefficient1") > 0, o.cy_given[1] = c->count("--yield-coefficient2") > 0;
  for (int i = 0; i < 2; ++i) {
    const std::string k = std::to_string(i + 1);
    o.b[i].storeys_given = c->count("--storeys" + k) > 0, o.b[i].mass_given = c->count("--storey-mass" + k) > 0;
    o.b[i].stiffness_given = c->count("--storey-stiffness" + k) > 0;
    o.b[i].height_given = c->count("--storey-height" + k) > 0, o.b[i].yield_given = c->count("--storey-yield" + k) > 0;
    o.b[i].rayleigh_given = c->count("--rayleigh-modes" + k) > 0, o.b[i].rayleigh_option = "--rayleigh-modes" + k;
  }
}

// --initial-uK, --initial-vK: buildings 1 and 2 released displaced or moving (pull-back, free vibration); --scale and
// --yield-coefficientK (the record's factor and the strengths a study would give).
void add_initial_options(CLI::App* c, SimulateOptions& o) {
  c->add_option("--scale", o.scale, "a factor on the record's accelerations (as a study's [records] scale)");
  for (int i = 0; i < 2; ++i) {
    const std::string k = std::to_string(i + 1);
    c->add_option("--yield-coefficient" + k, o.cy[i],
                  "building " + k + " yields at a base shear Cy M g (an SDOF: fy = Cy m g; storeys: the upper ones by "
                  "the shear profile), instead of --fy" + k + " / --storey-yield" + k);
  }
  for (int i = 0; i < 2; ++i) {
    const std::string k = std::to_string(i + 1);
    add_number_list(c, "--initial-u" + k, o.initial_u[i],
                    "initial displacement of building " + k + " relative to the ground (m): one value (an SDOF, or "
                    "every floor) or one per floor from the bottom (an isolated building may lead with its base); a "
                    "pull-back test with a record of zeros and --duration");
    add_number_list(c, "--initial-v" + k, o.initial_v[i],
                    "initial velocity of building " + k + " (m/s), one value or one per floor as --initial-u" + k);
  }
}

// The bridge options (issue 26 §1).
void add_bridge_options(CLI::App* c, SimulateOptions& o) {
  c->add_option("--bridge", o.bridge,
                "a bridge: frames, joints (gap, contact, restrainers, bearings) and abutments in a TOML file "
                "(docs/bridges.md); the contact options apply at the joints");
  c->add_option("--support-record", o.support_records,
                "bridge: the record of support K (repeat the option, in support order; the file's support = K picks it)");
  c->add_option("--wave-delay", o.wave_delay,
                "bridge: --record reaches support K + 1 this much later than support K (s; wave passage)");
}

// --json and e(v0) (issue 26 §3: --restitution-*, an SDOF pair only).
void add_output_and_restitution_options(CLI::App* c, SimulateOptions& o) {
  c->add_flag("--json", o.json, "print every observer as one JSON object (per floor: peak_u1, peak_u2, ...; per "
                                "contact level: levels)");
  o.rest.add(c);
}

}  // namespace

// --zeta and --modal-zeta (multi-storey buildings: Rayleigh on modes 1, 2, or classical modal damping).
void add_damping_options(CLI::App* c, SimulateOptions* o) {
  c->add_option("--zeta", o->zeta, "viscous damping ratio of both structures (multi-storey: Rayleigh damping with this "
                                   "ratio at modes 1 and 2, or --rayleigh-modesK i,j)")
      ->capture_default_str();
  add_number_list(c, "--modal-zeta", o->modal_zeta,
                  "multi-storey buildings: classical modal damping instead of Rayleigh, the ratio of each mode from "
                  "mode 1 (z1,z2,...; the last repeats for the higher modes; one-storey buildings keep --zeta)");
}

void add_simulate(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  auto* c = app.add_subcommand("simulate", "one pair of SDOF structures (or multi-storey shear buildings, --storeys1/2) through one record; prints every observer");
  c->add_option("--record", o->record, "ground motion file (PEER .AT2, time/acc text, one-column text); "
                                       "default: built-in 0.4 g sweep");
  c->add_option("--units", o->units, "units of the record values: g, m/s2, cm/s2")->capture_default_str();
  c->add_option("--dt-record", o->dt_record, "time step of a one-column record (s)");
  c->add_option("--m1", o->m1, std::string("mass of structure 1, the left one (kg); default from --h1: ") + mass_model_text +
                                   " (30 m: 7.29e6 kg)");
  c->add_option("--T1", o->T1, "period of structure 1 (s)")->capture_default_str();
  c->add_option("--k1", o->k1, "initial stiffness of structure 1 (N/m), instead of --T1");
  c->add_option("--h1", o->h1, "height of structure 1 (m): yield displacement 0.02 h / 6, default mass")
      ->capture_default_str();
  c->add_option("--fy1", o->fy1, "yield force of structure 1 (N), instead of --h1");
  c->add_option("--m2", o->m2, "mass of structure 2 (kg); default from --h2 as for --m1 (45 m: 2.46e7 kg)");
  c->add_option("--T2", o->T2, "period of structure 2 (s)")->capture_default_str();
  c->add_option("--k2", o->k2, "initial stiffness of structure 2 (N/m), instead of --T2");
  c->add_option("--h2", o->h2, "height of structure 2 (m)")->capture_default_str();
  c->add_option("--fy2", o->fy2, "yield force of structure 2 (N), instead of --h2");
  c->add_flag("--elastic", o->elastic, "linear elastic structures (no yielding)");
  c->add_option("--alpha", o->alpha, "post-yield stiffness ratio, [0, 1)")->capture_default_str();
  add_damping_options(c, o.get());
  c->add_option("--gap", o->gap, "at-rest separation (m)")->capture_default_str();
  c->add_option("--contact", o->contact, std::string("contact law: ") + std::string(contact_law_names))
      ->capture_default_str();
  c->add_option("--damping-law", o->damping_law, std::string("Hertzdamp xibar law: ") + std::string(damping_law_names))
      ->capture_default_str();
  c->add_option("--e", o->e, "coefficient of restitution, (0, 1]")->capture_default_str();
  c->add_option("--kh", o->kh, "contact stiffness (N/m^n Hertz family, N/m linear/Kelvin); "
                               "default for Hertz: equivalent spheres");
  c->add_option("--n", o->n, "Hertz exponent")->capture_default_str();
  c->add_option("--density", o->density, "equivalent-sphere density (kg/m^3)")->capture_default_str();
  c->add_option("--E", o->youngs, "equivalent-sphere Young's modulus (Pa)")->capture_default_str();
  c->add_option("--nu", o->poisson, "equivalent-sphere Poisson ratio")->capture_default_str();
  c->add_option("--stepper", o->stepper, std::string("integrator: ") + std::string(stepper_names))
      ->capture_default_str();
  c->add_option("--dt", o->dt, "integration step (s); must divide the record step (default: the record step)");
  c->add_option("--duration", o->duration, "analysis length (s): shorter than the record, its first part (rounded to "
                                           "whole record steps); longer, free vibration after it (default: the record)");
  c->add_option("--u-limit", o->u_limit, "|u1| + |u2| above this (m) marks the run diverged")->capture_default_str();
  c->add_flag("--locate-contact", o->locate, "rk4: locate each contact onset inside its step (high-accuracy mode)");
  c->add_option("--series", o->series, "write the time series to FILE.csv or FILE.h5");
  add_initial_options(c, *o);
  add_storey_options(c, *o);
  add_bridge_options(c, *o);
  add_output_and_restitution_options(c, *o);
  c->callback([o, c] {
    o->curve = o->rest.get_instead_of_e(c);
    o->k1_given = c->count("--k1") > 0, o->k2_given = c->count("--k2") > 0;
    o->fy1_given = c->count("--fy1") > 0, o->fy2_given = c->count("--fy2") > 0;
    o->dt_given = c->count("--dt") > 0, o->kh_given = c->count("--kh") > 0;
    o->duration_given = c->count("--duration") > 0;
    o->m1_given = c->count("--m1") > 0, o->m2_given = c->count("--m2") > 0;
    o->h1_given = c->count("--h1") > 0, o->h2_given = c->count("--h2") > 0;
    count_storey_options(c, *o);
    for (int i = 0; i < 2; ++i) {
      const std::string k = std::to_string(i + 1);
      SimulateOptions::Isolation& s = o->iso[i];
      s.base_mass_given = c->count("--base-mass" + k) > 0, s.k_eff_given = c->count("--bearing-keff" + k) > 0;
      s.zeta_given = c->count("--bearing-zeta" + k) > 0;
      s.lrb_given = c->count("--bearing-k1-" + k) + c->count("--bearing-k2-" + k) + c->count("--bearing-qd" + k) > 0;
      s.moat_given = c->count("--moat-gap" + k) > 0;
      s.mu_fast_given = c->count("--bearing-mu-fast" + k) > 0;
      s.fps_given = c->count("--bearing-radius" + k) + c->count("--bearing-mu-slow" + k) + c->count("--bearing-rate" + k) +
                        c->count("--bearing-uy" + k) + (s.mu_fast_given ? 1 : 0) > 0;
      s.bw_given = c->count("--bearing-a" + k) + c->count("--bearing-beta" + k) + c->count("--bearing-gamma" + k) +
                       c->count("--bearing-eta" + k) > 0;
      s.moat_stiffness_given = c->count("--moat-stiffness" + k) > 0, s.moat_e_given = c->count("--moat-e" + k) > 0;
      s.moat_options_given = c->count("--moat-law" + k) > 0 || s.moat_stiffness_given || s.moat_e_given;
    }
    o->levels_given = any_given(c, {"--contact-levels", "--level-tolerance", "--gap-offsets", "--shape-functions"});
    count_row_options(c, *o);
    o->wave_delay_given = c->count("--wave-delay") > 0;
    if (const int code = run_simulate(*o)) throw ExitRequest{code};
  });
}

}  // namespace pounding::cli
