// `pounding sample STUDY.toml [--pair T1,T2] [--n N] [--seed S] --out FILE.csv|.h5`: dumps the structure
// pairs the stochastic structure model draws (sampler.hpp) for a study's seed and [structures] table.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cli/commands.hpp"
#include "pounding/config/config.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/io/hdf5.hpp"
#include "pounding/sampling/sampler.hpp"

namespace pounding::cli {

namespace {

struct SampleOptions {
  std::string study, pair, out;
  std::optional<std::int64_t> n;  // default: the study's samples_per_pair
  std::optional<std::int64_t> seed;
};

constexpr const char* vs_note =
    "soil shear-wave velocity Vs (175-375 m/s in the paper) is not sampled: a fixed-base SDOF does not use it";

// Columns of the dump, in order; values(p) returns them for one pair.
const std::vector<std::string> columns{
    "T1",    "T2",   "h1",  "h2",  "aspect1", "aspect2", "r1",     "r2",     "rho1", "rho2",
    "mbar1", "mbar2", "m1", "m2",  "k1",      "k2",      "c1",     "c2",     "fy1",  "fy2",
    "alpha1", "alpha2", "d", "kh", "zeta1", "zeta2"};
const char* units =
    "T s, h m, aspect -, r m, rho kg/m^3, mbar -, m kg, k N/m, c N s/m, fy N (inf: elastic), alpha -, "
    "d m (code separation 0.005 (h1 + h2)), kh N/m^1.5, zeta - (damping ratio); aspect, r, rho, mbar NaN when the "
    "mass is given";

std::vector<double> values(const SampledPair& p) {
  return {p.s1.T,     p.s2.T,     p.s1.h,  p.s2.h,  p.s1.aspect, p.s2.aspect, p.s1.r,     p.s2.r,
          p.s1.rho,   p.s2.rho,   p.s1.mbar, p.s2.mbar, p.s1.m,   p.s2.m,      p.s1.k,     p.s2.k,
          p.s1.c,     p.s2.c,     p.s1.fy, p.s2.fy, p.s1.alpha, p.s2.alpha, p.d,        p.kh,
          p.s1.zeta,  p.s2.zeta};
}

std::string join(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{:.6g}", i ? ", " : "", v[i]);
  return s;
}

std::vector<std::string> header_lines(const SampleOptions& o, const StructureSampler& s, std::int64_t n) {
  const StructureModel& m = s.model();
  std::vector<std::string> h;
  h.push_back("pounding sample: stochastic structure model (stochastic-pounding-monte-carlo.txt, sections 2.1-3.1)");
  h.push_back(fmt::format("study: {}", o.study));
  h.push_back(fmt::format("seed: {}  stream: {}  engine: boost::random::taus88 seeded with "
                          "SplitMix64(seed, stream, (i1, i2), sample)",
                          s.seed(), s.stream()));
  h.push_back(fmt::format("periods (s): building 1 [{}], building 2 [{}]  samples per pair written: {} (study: {})",
                          join(s.building(0).periods), join(s.building(1).periods), n, m.samples_per_pair));
  for (int b = 0; b < 2; ++b) {
    const BuildingModel& bm = s.building(b);
    h.push_back(fmt::format("building {}: period {}; height {}; mass {}; zeta {}; yield {}; alpha {}", b + 1,
                            bm.period_text(), bm.height_text(), bm.mass_text(), bm.zeta_text(), bm.yield_text(),
                            bm.alpha));
  }
  h.push_back(fmt::format("h uniform on [max({}, (T/{})^(1/{})), min({}, (T/{})^(1/{}))] m; aspect h/r in [{}] "
                          "equally likely; r = h / aspect",
                          m.height_min, m.ct_upper, m.height_exponent, m.height_max, m.ct_lower, m.height_exponent,
                          join(m.aspect_ratios)));
  h.push_back(fmt::format("rho lognormal mean {} CoV {}; mbar lognormal mean {} CoV {} (parent) truncated to "
                          "[{}, {}], sampled by exact inverse CDF; m = mbar rho r^2 h",
                          m.rho_mean, m.rho_cov, m.mbar_mean, m.mbar_cov, m.mbar_min, m.mbar_max));
  h.push_back(fmt::format("k = 4 pi^2 m / T^2; c = 2 {} sqrt(k m); hysteresis {}: fy = k {} h / {}, alpha {}",
                          m.zeta, to_string(m.hysteresis), m.drift, m.ductility, m.alpha));
  h.push_back(m.kh > 0 ? fmt::format("d = {} (h1 + h2); kh = {} N/m^1.5 (given)", m.code_gap_coefficient, m.kh)
                       : fmt::format("d = {} (h1 + h2); kh from equivalent concrete spheres (density {} kg/m^3, "
                                     "E {} Pa, nu {})",
                                     m.code_gap_coefficient, m.contact_density, m.contact_youngs_modulus,
                                     m.contact_poisson));
  h.push_back(vs_note);
  h.push_back(std::string("units: ") + units);
  return h;
}

std::int32_t find_period(const std::vector<double>& grid, double T, const std::string& text) {
  for (std::size_t i = 0; i < grid.size(); ++i)
    if (std::abs(grid[i] - T) <= 1e-6) return static_cast<std::int32_t>(i);
  throw InputError(fmt::format("period {} is not on the study's grid", text), "--pair",
                   fmt::format("choose T1,T2 from [{}] s", join(grid)));
}

double parse_period(const std::string& text) {
  try {
    std::size_t used = 0;
    double T = std::stod(text, &used);
    if (used == text.size() && std::isfinite(T)) return T;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("--pair has \"{}\", not a period", text), "--pair", "write --pair T1,T2, e.g. 1.1,1.3");
}

void write_csv(const std::string& path, const std::vector<std::string>& header, const std::vector<SampledPair>& rows) {
  fmt::memory_buffer out;
  for (const auto& line : header) fmt::format_to(std::back_inserter(out), "# {}\n", line);
  fmt::format_to(std::back_inserter(out), "i1,i2,sample");
  for (const auto& c : columns) fmt::format_to(std::back_inserter(out), ",{}", c);
  fmt::format_to(std::back_inserter(out), "\n");
  for (const SampledPair& p : rows) {
    fmt::format_to(std::back_inserter(out), "{},{},{}", p.id.i1, p.id.i2, p.id.sample);
    for (double v : values(p)) fmt::format_to(std::back_inserter(out), ",{:.17g}", v);  // round-trips every double
    fmt::format_to(std::back_inserter(out), "\n");
  }
  files::write_text_atomically(path, std::string_view(out.data(), out.size()));
}

void write_h5(const std::string& path, const std::vector<std::string>& header, const std::vector<SampledPair>& rows,
              const StructureSampler& s, const std::string& study) {
  h5::AtomicFile f(path);
  auto g = h5::create_group(f.root(), "samples");
  std::vector<std::int32_t> i1, i2;
  std::vector<std::int64_t> idx;
  for (const auto& p : rows) {
    i1.push_back(p.id.i1);
    i2.push_back(p.id.i2);
    idx.push_back(p.id.sample);
  }
  h5::write_dataset(g.get(), "i1", std::span<const std::int32_t>(i1));
  h5::write_dataset(g.get(), "i2", std::span<const std::int32_t>(i2));
  h5::write_dataset(g.get(), "sample", std::span<const std::int64_t>(idx));
  std::vector<std::vector<double>> cols(columns.size());
  for (const auto& p : rows) {
    auto v = values(p);
    for (std::size_t c = 0; c < v.size(); ++c) cols[c].push_back(v[c]);
  }
  for (std::size_t c = 0; c < columns.size(); ++c) h5::write_dataset(g.get(), columns[c], std::span<const double>(cols[c]));
  h5::write_dataset(f.root(), "periods", std::span<const double>(s.building(0).periods));
  h5::write_dataset(f.root(), "periods1", std::span<const double>(s.building(0).periods));
  h5::write_dataset(f.root(), "periods2", std::span<const double>(s.building(1).periods));
  h5::write_attribute(f.root(), "seed", static_cast<std::int64_t>(s.seed()));
  h5::write_attribute(f.root(), "stream", static_cast<std::int64_t>(s.stream()));
  h5::write_attribute(f.root(), "study", study);
  h5::write_attribute(f.root(), "units", std::string(units));
  h5::write_attribute(f.root(), "not_sampled", std::string(vs_note));
  std::string text;
  for (const auto& line : header) text += line + "\n";
  h5::write_attribute(f.root(), "header", text);
  f.commit();
}

void run_sample(const SampleOptions& o) {
  // --- validate everything before any work or output
  const bool csv = o.out.ends_with(".csv"), h5 = o.out.ends_with(".h5");
  if (!csv && !h5)
    throw InputError(fmt::format("--out {} has no .csv or .h5 extension", o.out), "--out",
                     "name the output FILE.csv or FILE.h5");
  files::check_output_not_input(o.out, {o.study}, "--out");  // before any work: never the study file
  files::check_output_path(o.out, "--out");                    // nor a device, FIFO or folder
  const toml::table root =
      config::parse(files::read_text(o.study, "the study file"), o.study, "fix the study file's syntax");
  // only the seed and [structures] are read: the rest of the study need not be complete
  const toml::table empty;
  const toml::table* table = config::TableReader(&root, o.study, "").table("structures");
  StructureModel model = parse_structure_model(table ? *table : empty, o.study);
  std::uint64_t seed = 0;
  if (o.seed) {
    if (*o.seed < 0) throw InputError(fmt::format("--seed = {} is negative", *o.seed), "--seed", "give a seed >= 0");
    seed = static_cast<std::uint64_t>(*o.seed);
  } else {
    seed = parse_study_seed(root, o.study);
  }
  const std::int64_t n = o.n.value_or(model.samples_per_pair);
  if (n < 1 || n > 100'000'000)
    throw InputError(fmt::format("--n = {} is out of range", n), "--n", "give 1 <= N <= 1e8 samples per pair");
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  if (!o.pair.empty()) {
    auto comma = o.pair.find(',');
    if (comma == std::string::npos)
      throw InputError(fmt::format("--pair {} is not T1,T2", o.pair), "--pair", "write --pair T1,T2, e.g. 1.1,1.3");
    std::string a = o.pair.substr(0, comma), b = o.pair.substr(comma + 1);
    pairs.emplace_back(find_period(model.building(0).periods, parse_period(a), a),
                       find_period(model.building(1).periods, parse_period(b), b));
  } else {
    for (std::int64_t p = 0; p < model.period_pair_count(); ++p) {
      const SampleId id = model.pair_id(p);
      pairs.emplace_back(id.i1, id.i2);
    }
  }
  if (static_cast<double>(pairs.size()) * static_cast<double>(n) > 5e7)
    throw InputError(fmt::format("{} pairs x {} samples is too many rows", pairs.size(), n), "--n",
                     "use --pair or a smaller --n");
  StructureSampler sampler(std::move(model), seed, structure_stream);

  std::vector<SampledPair> rows(pairs.size() * static_cast<std::size_t>(n));
  for (std::size_t p = 0; p < pairs.size(); ++p)
    sampler.sample_block(pairs[p].first, pairs[p].second, 0,
                         std::span<SampledPair>(rows).subspan(p * static_cast<std::size_t>(n), static_cast<std::size_t>(n)));
  auto header = header_lines(o, sampler, n);
  if (csv) write_csv(o.out, header, rows);
  else write_h5(o.out, header, rows, sampler, o.study);
  fmt::print("wrote {} sampled pairs ({} period pairs x {} samples) to {}\n", rows.size(), pairs.size(), n, o.out);
  fmt::print("seed {}, stream {}; {}\n", sampler.seed(), sampler.stream(), vs_note);
}

}  // namespace

void add_sample(CLI::App& app) {
  auto o = std::make_shared<SampleOptions>();
  auto* c = app.add_subcommand("sample", "dump the structure pairs the stochastic structure model draws for a study "
                                         "(T, h, r, rho, mbar, m, k, c, fy, alpha per structure; d, kh per pair)");
  c->add_option("study", o->study, "study file (TOML): top-level seed and the [structures] table")->required();
  c->add_option("--pair", o->pair, "only the period pair T1,T2 (s), e.g. 1.1,1.3; default: every pair of the grid");
  c->add_option("--n", o->n, "samples per period pair (default: the study's samples_per_pair); the first N of the "
                             "study's samples, whatever N");
  c->add_option("--seed", o->seed, "override the study's seed");
  c->add_option("--out", o->out, "output FILE.csv or FILE.h5 (written atomically)")->required();
  c->callback([o] { run_sample(*o); });
}

}  // namespace pounding::cli
