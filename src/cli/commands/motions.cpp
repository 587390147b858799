// `pounding motions`: spatially varying, spectrum-compatible support motions for multi-support structures
// (bridges), written as one PEER AT2 file (g) per support per realisation (issue 26 section 2; the method:
// motion/spatial.hpp).
//
//   motions --supports 4 --spacing 100 --velocity 500 --coherency sobczyk --loss high --spectrum nzs1170.5
//           --soil D [--z 0.4 --r 1] --realisations 20 --seed 1 --out DIR
//
// DIR must be new or an empty folder. It receives, all at once at the end (built in DIR.tmp<pid> and renamed),
//   r001_s01.AT2 ...   realisation 1 .. R, support 1 .. n (acceleration in g, DT = --dt)
//   MANIFEST.tsv       file, event, station, component, realisation, support, position_m, pga_g, misfit, updates
//                      (event "<label> realisation RRR", station "support JJ at X m": the engine's directory reader
//                      sees the supports of one realisation as one event -- motion/library.hpp)
//   README.md          every setting, the coherency model and the target spectra, with their sources, and the
//                      coherency table (below) at the supports' separations
// --coherency-table prints the coherency the generator uses (spatial::coherency_table) at --coherency-frequencies
// (Hz, default 0.5,1,2,5,10) and --coherency-distances (m, default: every distinct separation of the supports):
// with --out it then generates as usual, without --out it only prints.
// A stop (SIGINT/SIGTERM) between or within realisations ends the command with exit 130 and writes nothing.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <unistd.h>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/spatial.hpp"

namespace pounding::cli {

namespace {

namespace fs = std::filesystem;

std::atomic<bool> motions_stop{false};
extern "C" void on_motions_stop(int) { motions_stop.store(true); }

// The options as given (spatial::Request: the checks are the motion layer's, shared with [records.motions]), and
// what only the command has: the output folder, the label, --quiet.
struct MotionsOpts {
  spatial::Request req;
  std::string soil, out, label = "svgm";
  bool no_wave_passage = false, quiet = false, coherency_table = false;
  std::vector<double> table_frequencies{0.5, 1.0, 2.0, 5.0, 10.0}, table_distances;  // Hz, m (empty: the supports')
};

// The table's frequencies and separations (options of the command only, not of a study).
void check_table_points(const std::vector<double>& v, double lo, double hi, const char* option, const char* range) {
  if (v.empty() || v.size() > 100)
    throw InputError(fmt::format("{} holds {} values", option, v.size()), option, "give 1 to 100 values");
  for (double x : v)
    if (!std::isfinite(x) || x < lo || x > hi)
      throw InputError(fmt::format("{} holds {}, out of range", option, x), option, fmt::format("give values in {}", range));
}

std::string table_of(const MotionsOpts& o, const spatial::Settings& s) {
  const std::vector<double> d = o.table_distances.empty() ? spatial::support_separations(s) : o.table_distances;
  return spatial::coherency_table(s, o.table_frequencies, d);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string x; std::getline(ss, x, ',');) out.push_back(x);
  return out;
}

// The given options' keys (--f-max -> f_max, --no-wave-passage -> wave_passage) and the derived values.
spatial::Settings settings_of(MotionsOpts& o, const CLI::App& c) {
  spatial::Request& r = o.req;
  for (const auto* opt : c.get_options())
    if (opt->count() > 0 && opt->get_name().rfind("--", 0) == 0) {
      std::string key = opt->get_name().substr(2);
      if (key == "no-wave-passage") key = "wave-passage";
      std::replace(key.begin(), key.end(), '-', '_');
      r.given.insert(key);
    }
  r.wave_passage = !o.no_wave_passage;
  if (r.has("soil")) r.soil = split_commas(o.soil);
  const spatial::Settings s = spatial::settings_from(r);
  check_table_points(o.table_frequencies, 0.01, 100.0, "--coherency-frequencies", "[0.01, 100] Hz");
  if (!o.table_distances.empty())
    check_table_points(o.table_distances, 0.0, 1e5, "--coherency-distances", "[0, 100000] m");
  if (o.label.empty() || o.label.size() > 40 || o.label.find_first_of("\t\n\r") != std::string::npos)
    throw InputError("--label is empty, longer than 40 characters or holds a tab/newline", "--label", "give a short name");
  return s;
}

// DIR must be new or an empty folder, in an existing parent folder.
void check_out_dir(const std::string& dir) {
  if (dir.empty()) throw InputError("no output folder", "--out", "give --out DIR");
  std::error_code ec;
  const fs::path p(dir);
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec))
      throw InputError(fmt::format("'{}' exists and is not a folder", dir), "--out", "give a new or empty folder");
    if (!fs::is_empty(p, ec))
      throw InputError(fmt::format("the folder '{}' is not empty", dir), "--out",
                       "give a new or empty folder (nothing is overwritten)");
  }
  const fs::path parent = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw InputError(fmt::format("the parent folder of '{}' does not exist", dir), "--out", "create it first");
  files::check_output_path((p.lexically_normal().string() + ".probe"), "--out");
}

std::string readme(const MotionsOpts& o, const spatial::Settings& s, const std::string& command_line) {
  std::string t = fmt::format("# Spatially varying support motions ({})\n\nWritten by `{}`.\n\n", o.label, command_line);
  t += "Method: Deodatis (1996), Probab. Eng. Mech. 11(3):149-167, spectral representation of a uniformly modulated "
       "vector process with double-indexed frequencies, spectrum-compatible by Deodatis' iteration on the auto-spectra "
       "(pounding motion/spatial.hpp).\n\n";
  t += fmt::format("- supports at x = {} m\n", fmt::join(s.positions, ", "));
  t += s.wave_passage ? fmt::format("- wave passage: apparent velocity {:g} m/s\n", s.velocity) : "- no wave passage\n";
  t += fmt::format("- coherency: {}\n", s.coherency.describe());
  for (std::size_t j = 0; j < s.targets.size(); ++j)
    t += fmt::format("- target{}: {}\n", s.targets.size() == 1 ? "" : fmt::format(" support {}", j + 1), s.targets[j].describe());
  t += fmt::format("- damping {:g}; dt {:g} s, duration {:g} s; envelope rise {:g} s, strong {:g} s, decay {:g} 1/s; "
                   "PSD band {:g}-{:g} Hz\n",
                   s.damping, s.dt, s.duration, s.envelope.rise, s.envelope.strong, s.envelope.decay, s.f_min, s.f_max);
  t += fmt::format("- matching: {} periods {:g}-{:g} s, at most {} updates, tolerance {:g} (largest |PSA/Sa - 1|)\n",
                   s.match_periods.size(), s.match_periods.front(), s.match_periods.back(), s.iterations, s.tolerance);
  t += fmt::format("- seed {}, realisations {} to {}\n", s.seed, o.req.first, o.req.first + o.req.realisations - 1);
  t += "\nThe coherency the generator used (|gamma| dimensionless, phases in rad; `pounding motions --coherency-table`):"
       "\n\n```\n" + table_of(o, s) + "```\n";
  t += "\nUnits: acceleration in g (AT2). MANIFEST.tsv: misfit = largest |PSA/Sa - 1| over the matching band, updates "
       "= spectrum-matching updates made.\n";
  return t;
}

void write_folder(const std::string& dir, const MotionsOpts& o, const spatial::Settings& s,
                  const std::vector<spatial::Realisation>& rs, const std::string& command_line) {
  const fs::path final_dir = fs::path(dir).lexically_normal();
  const fs::path tmp = fs::path(final_dir.string() + fmt::format(".tmp{}", ::getpid()));
  std::error_code ec;
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec))
    throw InputError(fmt::format("cannot create '{}': {}", tmp.string(), ec.message()), "--out", "check the folder's permissions");
  try {
    std::string manifest = "file\tevent\tstation\tcomponent\trealisation\tsupport\tposition_m\tpga_g\tmisfit\tupdates\n";
    for (const auto& r : rs)
      for (std::size_t j = 0; j < r.supports.size(); ++j) {
        Record rec = r.supports[j];
        const std::string file = fmt::format("r{:03}_s{:02}.AT2", r.index + 1, j + 1);
        rec.meta["description"] = fmt::format("{} realisation {}, support {} at {:g} m, seed {}", o.label, r.index + 1,
                                              j + 1, s.positions[j], s.seed);
        write_at2(rec, (tmp / file).string());
        manifest += fmt::format("{}\t{} realisation {:03}\tsupport {:02} at {:g} m\tx\t{}\t{}\t{:g}\t{:.6g}\t{:.4f}\t{}\n",
                                file, o.label, r.index + 1, j + 1, s.positions[j], r.index + 1, j + 1, s.positions[j],
                                rec.pga() / g_accel, r.misfit[j], r.updates[j]);
      }
    files::write_text_atomically((tmp / "MANIFEST.tsv").string(), manifest);
    files::write_text_atomically((tmp / "README.md").string(), readme(o, s, command_line));
    if (fs::exists(final_dir, ec)) fs::remove(final_dir, ec);  // empty (checked before the work)
    fs::rename(tmp, final_dir, ec);
    if (ec) throw InputError(fmt::format("cannot rename '{}' to '{}': {}", tmp.string(), dir, ec.message()), "--out",
                             "check the folder");
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

// The records a study would refuse: [records.motions] runs require_analysable on the same realisations (a PGA above
// 5 g, records.hpp), so `motions` refuses them too, before anything is written (a csv target of Sa 1e29 g wrote AT2
// files of PGA 5.4e29 g).
void check_analysable(const MotionsOpts& o, const std::vector<spatial::Realisation>& rs) {
  for (const spatial::Realisation& r : rs)
    for (std::size_t j = 0; j < r.supports.size(); ++j)
      if (const auto e = analysis_problem(r.supports[j], {1.0, "", ""}))
        throw InputError(fmt::format("realisation {} support {}: {}", r.index + 1, j + 1, e->what_part()),
                         o.req.spectrum == "csv" ? "--spectrum-file" : "--z/--r",
                         fmt::format("a study refuses these records ([records.motions] with the same options): give a "
                                     "target spectrum in g whose motions stay within {} g",
                                     record_pga_max_g));
}

// The coherency model, its parameters, the site response and the table of what is used.
void add_coherency_options(CLI::App* c, MotionsOpts& o) {
  spatial::Request& q = o.req;
  c->add_option("--coherency", q.coherency, "coherency model: sobczyk (default), harichandran-vanmarcke, luco-wong, none");
  c->add_option("--loss", q.loss, "coherency loss (sobczyk): low, medium, high (beta 0.0005/0.001/0.002 1/m)");
  c->add_option("--beta", q.beta, "sobczyk beta, 1/m (instead of --loss)");
  c->add_option("--luco-wong-a", q.luco_wong_a, "luco-wong alpha/v_s, s/m (default 2.5e-4)");
  c->add_option("--hv-a", q.hv_a, "harichandran-vanmarcke A (default 0.736, SMART-1 Event 20)");
  c->add_option("--hv-alpha", q.hv_alpha, "harichandran-vanmarcke alpha (default 0.147)");
  c->add_option("--hv-k", q.hv_k, "harichandran-vanmarcke k, m (default 5210)");
  c->add_option("--hv-f0", q.hv_f0, "harichandran-vanmarcke f0, Hz (default 1.09)");
  c->add_option("--hv-b", q.hv_b, "harichandran-vanmarcke b (default 2.78)");
  add_number_list(c, "--site-frequency", q.site_frequency,
                  "site response (Der Kiureghian 1996): soil filter frequency f_g, Hz, one for all or one per support");
  add_number_list(c, "--site-damping", q.site_damping,
                  "site response: soil filter damping zeta_g, one for all or one per support (with --site-frequency)");
  c->add_flag("--coherency-table", o.coherency_table,
              "print the coherency used (|gamma|, phases, gamma) at --coherency-frequencies x --coherency-distances; "
              "without --out only print");
  add_number_list(c, "--coherency-frequencies", o.table_frequencies, "frequencies of the table, Hz (default 0.5,1,2,5,10)");
  add_number_list(c, "--coherency-distances", o.table_distances,
                  "separations of the table, m (default: every distinct separation of the supports)");
}

}  // namespace

void add_motions(CLI::App& app) {
  auto o = std::make_shared<MotionsOpts>();
  auto* c = app.add_subcommand("motions", "spatially varying, spectrum-compatible support motions (bridges): one AT2 "
                                          "file per support per realisation (Deodatis 1996)");
  spatial::Request& q = o->req;
  c->add_option("--supports", q.supports, "number of supports, evenly spaced (2-16; default 2)");
  c->add_option("--spacing", q.spacing, "support spacing, m (default 100)");
  add_number_list(c, "--positions", q.positions, "support positions along the propagation direction, m "
                                                 "(increasing; instead of --supports/--spacing)");
  c->add_option("--velocity", q.velocity, "apparent wave velocity, m/s (default 500)");
  c->add_flag("--no-wave-passage", o->no_wave_passage, "no time delay between supports");
  add_coherency_options(c, *o);
  c->add_option("--spectrum", q.spectrum, "target: nzs1170.5 (default) or csv");
  c->add_option("--soil", o->soil, "NZS 1170.5 site class A-E, or one per support (A,A,D,D)");
  c->add_option("--z", q.z, "NZS 1170.5 hazard factor Z (default 0.4)");
  c->add_option("--r", q.r, "NZS 1170.5 return period factor R (default 1)");
  c->add_option("--spectrum-file", q.spectrum_file, "csv target: period_s,sa_g lines");
  c->add_option("--damping", q.damping, "damping ratio of the spectra (default 0.05)");
  c->add_option("--dt", q.dt, "time step, s (default 0.01)");
  c->add_option("--duration", q.duration, "duration, s (default 20)");
  c->add_option("--rise", q.rise, "envelope rise time t1, s (default 2)");
  c->add_option("--strong", q.strong, "envelope strong phase t2 - t1, s (default 8)");
  c->add_option("--decay", q.decay, "envelope decay rate after t2, 1/s (default 0.5)");
  c->add_option("--f-min", q.f_min, "lowest frequency of the PSD, Hz (default 0.1)");
  c->add_option("--f-max", q.f_max, "highest frequency of the PSD, Hz (default 25)");
  add_number_list(c, "--match-range", q.match_range, "matching periods LO,HI, s (default 0.05,4)");
  c->add_option("--match-points", q.match_points, "matching periods, log-spaced (default 30)");
  c->add_option("--iterations", q.iterations, "spectrum-matching updates at most (default 10; 0: none)");
  c->add_option("--tolerance", q.tolerance, "largest |PSA/Sa - 1| that ends the matching (default 0.1)");
  c->add_option("--realisations", q.realisations, "number of realisations (default 20)");
  c->add_option("--first", q.first, "number of the first realisation (default 1)");
  c->add_option("--seed", q.seed, "master seed (default 1)");
  c->add_option("--label", o->label, "name of the set in MANIFEST.tsv (default svgm)");
  c->add_option("--out", o->out, "output folder (new or empty; not needed with --coherency-table)");
  c->add_flag("--quiet", o->quiet, "no progress lines");
  c->callback([o, c] {
    while (o->out.size() > 1 && o->out.back() == '/') o->out.pop_back();
    const spatial::Settings s = settings_of(*o, *c);
    if (o->coherency_table && o->out.empty()) {
      fmt::print("{}", table_of(*o, s));
      return;
    }
    check_out_dir(o->out);
    if (o->coherency_table) fmt::print("{}", table_of(*o, s));
    std::string command_line = "pounding motions";
    for (const auto* opt : c->get_options())
      if (opt->count() > 0 && opt->get_name() != "--help") {
        command_line += " " + opt->get_name();
        for (const auto& r : opt->results()) command_line += " " + r;
      }
    motions_stop.store(false);
    std::signal(SIGINT, on_motions_stop);
    std::signal(SIGTERM, on_motions_stop);
    WorkHook hook;
    hook.cancel = &motions_stop;
    if (!o->quiet)
      hook.progress = [](const PhaseProgress& p) {
        fmt::print(stderr, "{}: {}/{} {} ({:.1f} s)\n", p.phase, p.done, p.total, p.unit, p.elapsed_s);
      };
    std::vector<spatial::Realisation> rs;
    try {
      rs = spatial::simulate_all(s, static_cast<std::uint64_t>(o->req.first - 1),
                                    static_cast<std::size_t>(o->req.realisations), &hook);
    } catch (const Cancelled& e) {
      fmt::print(stderr, " stopped: {}; nothing written\n", e.what());
      throw ExitRequest{130};
    }
    check_analysable(*o, rs);
    write_folder(o->out, *o, s, rs, command_line);
    double worst = 0;
    for (const auto& r : rs)
      for (double m : r.misfit) worst = std::max(worst, m);
    fmt::print("{} realisations x {} supports written to {} (largest spectrum misfit {:.3f})\n", rs.size(),
               s.positions.size(), o->out, worst);
  });
}

}  // namespace pounding::cli
