// The options of spatially varying support motions and their checks, shared by `pounding motions` (command line)
// and a study's [records.motions] table: one set of checks and messages, naming --key-name or the study's key.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pounding/core/error.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/motion/spatial.hpp"

namespace pounding::spatial {

std::string OptionNames::name(std::string_view key) const {
  if (where) return std::string(key);
  if (key == "wave_passage") return "--no-wave-passage";
  std::string out = "--" + std::string(key);
  std::replace(out.begin(), out.end(), '_', '-');
  return out;
}

std::string OptionNames::at(std::string_view key) const { return where ? where(key) : name(key); }

namespace {

void in_range(double value, double lo, double hi, std::string_view key, const OptionNames& k, const std::string& text) {
  if (!std::isfinite(value) || value < lo || value > hi)
    throw InputError(fmt::format("{} = {} is out of range", k.name(key), value), k.at(key),
                     fmt::format("give a value in {}", text));
}

// A quantity that is also a [records.motions] key takes the registry's range (src/config/study_keys.cpp): one
// range for the command line and the study, shown as the reference documents it.
void key_range(double value, std::string_view key, const OptionNames& k) {
  const config::StudyKey& d = config::study_key("records.motions", key);
  in_range(value, d.lo, d.hi, key, k, d.units.empty() ? std::string(d.range) : fmt::format("{} {}", d.range, d.units));
}

constexpr const char* hv_keys[] = {"hv_a", "hv_alpha", "hv_k", "hv_f0", "hv_b"};

Coherency coherency_of(const Request& o, const OptionNames& k) {
  Coherency c;
  const auto model = parse_enum(coherency_model_names, o.coherency);
  if (!model)
    throw InputError(fmt::format("unknown coherency model '{}'", escaped_excerpt(o.coherency)), k.at("coherency"),
                     "use " + enum_name_list(coherency_model_names, " or "));
  c.model = *model;
  const bool loss = o.has("loss"), beta = o.has("beta");
  if (c.model == CoherencyModel::sobczyk) {
    if (loss && beta)
      throw InputError(fmt::format("both {} and {}", k.name("loss"), k.name("beta")), k.at("beta"),
                       "give one: a loss level or beta itself");
    if (!loss && !beta)
      throw InputError("sobczyk needs a coherency loss level", k.at("loss"),
                       fmt::format("give {} low|medium|high (beta 0.0005/0.001/0.002 1/m) or {}", k.name("loss"),
                                   k.name("beta")));
    if (loss) {
      const auto l = parse_enum(coherency_loss_names, o.loss);
      if (!l)
        throw InputError(fmt::format("unknown loss level '{}'", escaped_excerpt(o.loss)), k.at("loss"),
                         "use low, medium or high");
      c.beta = sobczyk_beta(*l);
    } else {
      c.beta = o.beta;
    }
  } else if (loss || beta) {
    const char* key = loss ? "loss" : "beta";
    throw InputError(fmt::format("{} applies to coherency sobczyk only", k.name(key)), k.at(key),
                     c.model == CoherencyModel::harichandran_vanmarcke
                         ? fmt::format("drop the option (Harichandran-Vanmarcke takes {}, {}, {}, {}, {})",
                                       k.name("hv_a"), k.name("hv_alpha"), k.name("hv_k"), k.name("hv_f0"),
                                       k.name("hv_b"))
                         : "drop the option");
  }
  for (const char* key : hv_keys)
    if (o.has(key) && c.model != CoherencyModel::harichandran_vanmarcke)
      throw InputError(fmt::format("{} applies to coherency harichandran-vanmarcke only", k.name(key)), k.at(key),
                       fmt::format("drop the option, or give {} harichandran-vanmarcke", k.name("coherency")));
  c.hv_a = o.hv_a, c.hv_alpha = o.hv_alpha, c.hv_k = o.hv_k, c.hv_f0 = o.hv_f0, c.hv_b = o.hv_b;
  if (o.has("luco_wong_a") && c.model != CoherencyModel::luco_wong)
    throw InputError(fmt::format("{} applies to coherency luco-wong only", k.name("luco_wong_a")), k.at("luco_wong_a"),
                     "drop the option");
  c.lw_a = o.luco_wong_a;
  return c;
}

// Der Kiureghian's site term: site_frequency and site_damping together, each one value for all supports or one
// per support.
std::vector<Site> sites_of(const Request& o, const OptionNames& k, std::size_t n) {
  const bool f = o.has("site_frequency"), z = o.has("site_damping");
  if (!f && !z) return {};
  if (f != z) {
    const char* missing = f ? "site_damping" : "site_frequency";
    throw InputError(fmt::format("{} without {}", k.name(f ? "site_frequency" : "site_damping"), k.name(missing)),
                     k.at(missing),
                     fmt::format("give both {} (Hz) and {} (one value for all supports or one per support)",
                                 k.name("site_frequency"), k.name("site_damping")));
  }
  for (const auto& [key, v] : {std::pair{"site_frequency", &o.site_frequency}, std::pair{"site_damping", &o.site_damping}})
    if (v->size() != 1 && v->size() != n)
      throw InputError(fmt::format("{} values of {} for {} supports", v->size(), k.name(key), n), k.at(key),
                       "give one value for all supports or one per support");
  std::vector<Site> out(n);
  for (std::size_t j = 0; j < n; ++j)
    out[j] = {o.site_frequency[o.site_frequency.size() == 1 ? 0 : j], o.site_damping[o.site_damping.size() == 1 ? 0 : j]};
  return out;
}

std::vector<DesignSpectrum> nzs_targets(const Request& o, const OptionNames& k, std::size_t n) {
  if (o.has("spectrum_file"))
    throw InputError(fmt::format("{} belongs to spectrum csv", k.name("spectrum_file")), k.at("spectrum_file"),
                     "give spectrum csv or drop it");
  if (!o.has("soil") || o.soil.empty())
    throw InputError("spectrum nzs1170.5 needs the site class", k.at("soil"),
                     fmt::format("give {} A|B|C|D|E, or one class per support", k.name("soil")));
  if (o.soil.size() != 1 && o.soil.size() != n)
    throw InputError(fmt::format("{} site classes for {} supports", o.soil.size(), n), k.at("soil"),
                     "give one class for all supports or one per support");
  std::vector<DesignSpectrum> out;
  for (const auto& text : o.soil) {
    const auto site = parse_nzs1170_site(text);
    if (!site)
      throw InputError(fmt::format("unknown NZS 1170.5 site class '{}'", escaped_excerpt(text)), k.at("soil"),
                       "use A, B, C, D or E");
    try {
      out.emplace_back(Nzs1170Spectrum{*site, o.z, o.r});
    } catch (const InputError& e) {
      const char* key = e.what_part().find("Z") != std::string::npos ? "z" : "r";
      throw InputError(e.what_part(), k.at(key), e.fix());
    }
  }
  return out;
}

std::vector<DesignSpectrum> targets_of(const Request& o, const OptionNames& k, std::size_t n) {
  if (o.spectrum == "nzs1170.5") return nzs_targets(o, k, n);
  if (o.spectrum != "csv")
    throw InputError(fmt::format("unknown spectrum '{}'", escaped_excerpt(o.spectrum)), k.at("spectrum"),
                     "use nzs1170.5 or csv");
  for (const char* key : {"soil", "z", "r"})
    if (o.has(key))
      throw InputError(fmt::format("{} belongs to spectrum nzs1170.5", k.name(key)), k.at(key), "drop it with csv");
  if (!o.has("spectrum_file"))
    throw InputError("spectrum csv needs a spectrum file", k.at("spectrum_file"),
                     fmt::format("give {} with period_s,sa_g lines", k.name("spectrum_file")));
  return {DesignSpectrum(read_tabulated_spectrum(o.spectrum_file))};
}

std::vector<double> positions_of(const Request& o, const OptionNames& k) {
  if (o.has("positions")) {
    for (const char* key : {"supports", "spacing"})
      if (o.has(key))
        throw InputError(fmt::format("{} with {}", k.name("positions"), k.name(key)), k.at("positions"),
                         fmt::format("give either {} or {} and {}", k.name("positions"), k.name("supports"),
                                     k.name("spacing")));
    return o.positions;
  }
  if (o.supports < 2 || o.supports > 16)
    throw InputError(fmt::format("{} supports given", o.supports), k.at("supports"), "give 2 to 16 supports");
  in_range(o.spacing, 1.0, 10000.0, "spacing", k, "[1, 10000] m");
  std::vector<double> x;
  for (int j = 0; j < o.supports; ++j) x.push_back(o.spacing * j);
  return x;
}

std::vector<double> match_periods_of(const Request& o, const OptionNames& k) {
  if (o.match_range.size() != 2 || !(o.match_range[0] > 0) || !(o.match_range[1] > o.match_range[0]))
    throw InputError(fmt::format("{} is not LO,HI with 0 < LO < HI", k.name("match_range")), k.at("match_range"),
                     fmt::format("give e.g. {} 0.05,4", k.name("match_range")));
  if (o.match_points < 2 || o.match_points > 200)
    throw InputError(fmt::format("{} matching points", o.match_points), k.at("match_points"), "give 2 to 200");
  std::vector<double> T;
  for (int i = 0; i < o.match_points; ++i)
    T.push_back(o.match_range[0] *
                std::pow(o.match_range[1] / o.match_range[0], static_cast<double>(i) / (o.match_points - 1)));
  return T;
}

void check_frequencies(const Settings& s, const OptionNames& k) {
  in_range(s.f_min, 0.01, 5.0, "f_min", k, "[0.01, 5] Hz");
  const double nyquist = 0.5 / s.dt;
  in_range(s.f_max, 1.0, 100.0, "f_max", k, "[1, 100] Hz");
  if (s.f_max >= nyquist)
    throw InputError(fmt::format("{} {} Hz is not below the Nyquist frequency 1/(2 dt) = {} Hz", k.name("f_max"), s.f_max,
                                 nyquist),
                     k.at("f_max"), fmt::format("give {} < 1/(2 dt) or a smaller {}", k.name("f_max"), k.name("dt")));
  if (s.f_min >= s.f_max)
    throw InputError(fmt::format("{} {} Hz >= {} {} Hz", k.name("f_min"), s.f_min, k.name("f_max"), s.f_max),
                     k.at("f_min"), "give f_min < f_max");
}

void check_matching(const Settings& s, const OptionNames& k) {
  const auto T = matching_periods(s);
  if (T.size() < 2 || T.size() > 200)
    throw InputError(fmt::format("{} matching periods", T.size()), k.at("match_range"), "give 2 to 200 periods");
  for (std::size_t i = 0; i < T.size(); ++i) {
    if (!(T[i] >= 0.02 && T[i] <= 10.0))
      throw InputError(fmt::format("matching period {} s", T[i]), k.at("match_range"), "give periods in [0.02, 10] s");
    if (i > 0 && T[i] <= T[i - 1])
      throw InputError("matching periods do not increase", k.at("match_range"), "give increasing periods");
  }
  if (1.0 / T.front() >= s.f_max || 1.0 / T.back() <= s.f_min)
    throw InputError(fmt::format("the matching band {}-{} s lies outside the simulated band {}-{} Hz", T.front(),
                                 T.back(), s.f_min, s.f_max),
                     k.at("match_range"), "give periods T with f_min < 1/T < f_max");
  if (s.iterations < 0 || s.iterations > 100)
    throw InputError(fmt::format("{} iterations", s.iterations), k.at("iterations"), "give 0 to 100");
  in_range(s.tolerance, 0.0, 1.0, "tolerance", k, "[0, 1]");
  for (std::size_t j = 0; j < s.targets.size(); ++j)
    for (double t : T)
      if (!(s.targets[j].sa(t) > 0.0))
        throw InputError(fmt::format("the target spectrum is {} g at {} s", s.targets[j].sa(t), t), k.at("spectrum"),
                         "give a target with Sa > 0 over the matching band");
}

void check_supports(const Settings& s, const OptionNames& k) {
  const std::size_t n = s.positions.size();
  if (n < 2 || n > 16) throw InputError(fmt::format("{} supports given", n), k.at("supports"), "give 2 to 16 supports");
  for (std::size_t j = 0; j < n; ++j) {
    if (!std::isfinite(s.positions[j]) || std::abs(s.positions[j]) > 1e5)
      throw InputError(fmt::format("support position {} m", s.positions[j]), k.at("positions"),
                       "give finite positions within 100 km");
    if (j > 0 && s.positions[j] <= s.positions[j - 1])
      throw InputError(fmt::format("support positions {} m then {} m do not increase", s.positions[j - 1], s.positions[j]),
                       k.at("positions"), "list the supports in increasing position along the direction of propagation");
  }
  if (s.targets.size() != 1 && s.targets.size() != n)
    throw InputError(fmt::format("{} target spectra for {} supports", s.targets.size(), n), k.at("soil"),
                     "give one site class for all supports or one per support");
}

void check_time(const Settings& s, const OptionNames& k) {
  in_range(s.damping, 0.005, 0.3, "damping", k, "[0.005, 0.3]");
  in_range(s.dt, 0.001, 0.05, "dt", k, "[0.001, 0.05] s");
  in_range(s.duration, 2.0, 600.0, "duration", k, "[2, 600] s");
  if (s.duration / s.dt > 1 << 17)
    throw InputError(fmt::format("{} s at {} s is {} steps", s.duration, s.dt, s.duration / s.dt), k.at("duration"),
                     "keep duration / dt <= 131072 steps");
  const std::size_t n = s.positions.size();
  const Grid g = grid_of(s);
  const double bytes = 16.0 * static_cast<double>(n * n * n) * static_cast<double>(g.n_freq);
  if (bytes > 1024.0 * 1024.0 * 1024.0)
    throw InputError(fmt::format("{} supports over {} frequencies need {:.1f} GiB of Cholesky factors", n, g.n_freq,
                                 bytes / (1024.0 * 1024.0 * 1024.0)),
                     k.at("supports"),
                     fmt::format("give fewer supports, a shorter {} or a smaller {}", k.name("duration"), k.name("f_max")));
  in_range(s.envelope.rise, 0.0, s.duration, "rise", k, "[0, duration] s");
  in_range(s.envelope.strong, 0.0, s.duration, "strong", k, "[0, duration] s");
  in_range(s.envelope.decay, 0.0, 20.0, "decay", k, "[0, 20] 1/s");
  if (s.envelope.rise + s.envelope.strong <= 0.0)
    throw InputError("rise + strong = 0 s", k.at("strong"), "give a strong phase longer than 0 s");
}

// The realisations are kept until they are written (`pounding motions`) or run (a study's records): every support's
// record, one double per step, must fit in the memory available before the first is made (issue 44 item 8:
// 10,000 realisations of 16 supports and 600 s at 0.005 s are 154 GB).
void check_records_memory(const Settings& s, int realisations, const OptionNames& k) {
  const double per = 8.0 * static_cast<double>(s.positions.size()) * static_cast<double>(grid_of(s).steps);
  const double need = per * realisations, avail = available_memory_bytes();
  if (!(std::isfinite(avail) && need > avail)) return;
  const double fit = std::floor(avail / per);
  throw InputError(fmt::format("{} realisations x {} supports x {} samples need {} of records, more than the {} of memory "
                               "available on this machine (MemAvailable)",
                               realisations, s.positions.size(), grid_of(s).steps, human_bytes(need), human_bytes(avail)),
                   k.at("realisations"),
                   fit >= 1 ? fmt::format("give {} <= {:.0f} and the rest in further parts ({} N), or a shorter {} or a "
                                          "longer {}",
                                          k.name("realisations"), fit, k.name("first"), k.name("duration"), k.name("dt"))
                            : fmt::format("give a shorter {} or a longer {}", k.name("duration"), k.name("dt")));
}

}  // namespace

void validate(const Settings& s, const OptionNames& k) {
  check_supports(s, k);
  in_range(s.velocity, 50.0, 1e5, "velocity", k, "[50, 100000] m/s (apparent wave velocity)");
  check_time(s, k);
  check_frequencies(s, k);
  check_matching(s, k);
  const auto& c = s.coherency;
  if (c.model == CoherencyModel::sobczyk) in_range(c.beta, 0.0, 0.1, "beta", k, "[0, 0.1] 1/m");
  if (c.model == CoherencyModel::luco_wong) in_range(c.lw_a, 0.0, 1e-2, "luco_wong_a", k, "[0, 0.01] s/m");
  if (c.model == CoherencyModel::harichandran_vanmarcke) {
    const double values[] = {c.hv_a, c.hv_alpha, c.hv_k, c.hv_f0, c.hv_b};
    for (std::size_t i = 0; i < std::size(hv_keys); ++i) key_range(values[i], hv_keys[i], k);
  }
  if (!s.sites.empty()) {
    if (s.sites.size() != s.positions.size())
      throw InputError(fmt::format("{} sites for {} supports", s.sites.size(), s.positions.size()),
                       k.at("site_frequency"), "give one value for all supports or one per support");
    for (const Site& site : s.sites) {
      key_range(site.frequency, "site_frequency", k);
      key_range(site.damping, "site_damping", k);
    }
  }
}

Settings settings_from(const Request& o, const OptionNames& k) {
  Settings s;
  s.positions = positions_of(o, k);
  s.velocity = o.velocity;
  s.wave_passage = o.wave_passage;
  s.coherency = coherency_of(o, k);
  s.sites = sites_of(o, k, s.positions.size());
  s.targets = targets_of(o, k, s.positions.size());
  s.damping = o.damping;
  s.dt = o.dt;
  s.duration = o.duration;
  s.envelope = {o.rise, o.strong, o.decay};
  s.f_min = o.f_min;
  s.f_max = o.f_max;
  s.match_periods = match_periods_of(o, k);
  s.iterations = o.iterations;
  s.tolerance = o.tolerance;
  s.seed = o.seed;
  validate(s, k);
  if (o.realisations < 1 || o.realisations > 10000)
    throw InputError(fmt::format("{} realisations", o.realisations), k.at("realisations"), "give 1 to 10000");
  if (o.first < 1 || o.first > 1000000)
    throw InputError(fmt::format("first realisation {}", o.first), k.at("first"), "give 1 to 1000000");
  check_records_memory(s, o.realisations, k);
  return s;
}

std::string describe(const Settings& s) {
  std::string t = fmt::format("Deodatis (1996) spectral representation, supports at x = {} m; ", fmt::join(s.positions, ", "));
  t += s.wave_passage ? fmt::format("wave passage at {:g} m/s; ", s.velocity) : "no wave passage; ";
  t += fmt::format("coherency {}; ", s.coherency.describe());
  if (!s.sites.empty()) {
    std::vector<std::string> sites;
    for (const Site& x : s.sites) sites.push_back(fmt::format("{:g} Hz/{:g}", x.frequency, x.damping));
    t += fmt::format("site response (Der Kiureghian 1996) f_g/zeta_g {}; ", fmt::join(sites, ", "));
  }
  for (std::size_t j = 0; j < s.targets.size(); ++j)
    t += fmt::format("target{} {}; ", s.targets.size() == 1 ? "" : fmt::format(" support {}", j + 1), s.targets[j].describe());
  t += fmt::format("damping {:g}, dt {:g} s, duration {:g} s, envelope {:g}/{:g} s/{:g} 1/s, PSD {:g}-{:g} Hz, "
                   "{} matching periods {:g}-{:g} s, at most {} updates to tolerance {:g}; seed {}",
                   s.damping, s.dt, s.duration, s.envelope.rise, s.envelope.strong, s.envelope.decay, s.f_min, s.f_max,
                   s.match_periods.size(), s.match_periods.empty() ? 0.0 : s.match_periods.front(),
                   s.match_periods.empty() ? 0.0 : s.match_periods.back(), s.iterations, s.tolerance, s.seed);
  return t;
}

}  // namespace pounding::spatial
