// `pounding records ...`: ground-motion tools.
//   show FILE...        dt, npts, duration, PGA, PGV, PGD, Arias intensity, D5-95, t_mid
//   spectrum FILE...    pseudo-acceleration (or PSV, SD) spectra to CSV; --suite for a whole suite
//   synth               one Rezaeian & Der Kiureghian (2010) record for (M, R, Vs30, F, seed) as AT2
//                       (a record that `run`/`simulate` would refuse -- shorter than 2 s, PGA above 5 g -- is
//                       shown with a WARNING on stderr; records.hpp)
//   im FILE...          one intensity measure per record: PGA, PGV, Sa(T), Sa_avg (records_select.cpp)
//   select              choose and scale records to a code design spectrum (records_select.cpp)
//   suite [FILE]        resolve a suite (default: the embedded seed-study suite): which records are
//                       real, which synthetic; --write DIR writes every resolved record as AT2
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/records_options.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/spectrum.hpp"
#include "pounding/motion/suite.hpp"
#include "pounding/motion/synthetic.hpp"

namespace pounding::cli {

namespace {

struct SuiteOpts {
  std::string suite, records_dir;
  bool synthetic_only = false, require_real = false;
};

void add_suite_options(CLI::App* c, SuiteOpts& o) {
  c->add_option("--records-dir", o.records_dir, "directory of PEER/real records to resolve suite entries to");
  c->add_flag("--synthetic-only", o.synthetic_only, "ignore files: every suite entry synthetic");
  c->add_flag("--require-real", o.require_real, "fail when an entry has no real record");
}

std::vector<ResolvedRecord> resolve(const SuiteOpts& o, const std::string& suite_path) {
  const Suite s = suite_path.empty() || suite_path == "default" ? default_suite() : load_suite(suite_path);
  ResolveOptions ro;
  ro.records_dir = o.records_dir;
  ro.synthetic_only = o.synthetic_only;
  ro.allow_synthetic = !o.require_real;
  return resolve_suite(s, ro);
}

std::vector<double> parse_periods(const std::string& text) {
  if (text.empty()) return default_periods();
  return parse_number_list(text, "--periods", "period", "give periods in s, e.g. 0.1,0.5,1,2");
}

// The spectra as CSV: a comment line, the header, a "#kind" row (real or synthetic), one row per period.
std::string spectra_csv(const std::string& quantity, double damping, const std::vector<double>& T,
                        const std::vector<std::string>& names, const std::vector<std::string>& kinds,
                        const std::vector<Spectrum>& spectra) {
  std::string csv = fmt::format("# {} ({}), damping {}; row 2 says which records are synthetic\nperiod_s",
                                quantity, quantity == "psa" ? "g" : quantity == "psv" ? "m/s" : "m", damping);
  for (const auto& n : names) csv += "," + n;
  csv += "\n#kind";
  for (const auto& k : kinds) csv += "," + k;
  csv += "\n";
  for (std::size_t i = 0; i < T.size(); ++i) {
    csv += fmt::format("{:.6g}", T[i]);
    for (const auto& s : spectra) {
      const double v = quantity == "psa" ? s.psa[i] / g_accel : quantity == "psv" ? s.psv[i] : s.sd[i];
      csv += fmt::format(",{:.6e}", v);
    }
    csv += "\n";
  }
  return csv;
}

// `records show`
void add_show(CLI::App* records) {
  struct Opts {
    std::vector<std::string> files;
    ReadOpts read;
  };
  auto o = std::make_shared<Opts>();
  auto* c = records->add_subcommand("show", "dt, npts, duration, PGA, PGV, PGD, Arias intensity, D5-95 of records");
  c->add_option("files", o->files, "record files (.AT2, two-column time/acc, one-column with --dt-record)")->required();
  add_read_options(c, o->read);
  c->callback([o] {
    const ReadOptions ro = o->read.get();
    std::vector<Record> recs;  // read all first: a bad file prints nothing but the error
    for (const auto& f : o->files) recs.push_back(read_record(f, ro));
    fmt::print("{:<44} {:>16} {:>8} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}\n", "record", "format", "dt_s",
               "npts", "dur_s", "PGA_g", "PGV_m/s", "PGD_m", "Ia_m/s", "D5-95_s", "tmid_s");
    for (const Record& r : recs) {
      warn_if_not_analysable(r);
      const Measures m = measure(r);
      fmt::print("{:<44} {:>16} {:>8.5g} {:>7} {:>8.3f} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.3f} {:>8.3f}\n", r.name,
                 r.meta.count("format") ? r.meta.at("format") : "?", r.dt, r.acc.size(), r.duration(), m.pga / g_accel,
                 m.pgv, m.pgd, m.arias, m.d5_95(), m.t45);
    }
  });
}

// `records spectrum`
void add_spectrum(CLI::App* records) {
  struct Opts {
    std::vector<std::string> files;
    ReadOpts read;
    SuiteOpts suite;
    double damping = 0.05;
    std::string periods, quantity = "psa", out;
  };
  auto o = std::make_shared<Opts>();
  auto* c = records->add_subcommand("spectrum", "elastic response spectra (Nigam-Jennings, exact for piecewise-linear "
                                            "records) to CSV: period_s, one column per record");
  c->add_option("files", o->files, "record files");
  c->add_option("--suite", o->suite.suite, "also every record of this suite ('default': the embedded seed-study suite)");
  add_suite_options(c, o->suite);
  add_read_options(c, o->read);
  c->add_option("--damping", o->damping, "damping ratio")->capture_default_str();
  c->add_option("--periods", o->periods, "comma-separated periods in s (default: 0 and 100 log-spaced 0.01-10 s)");
  c->add_option("--quantity", o->quantity, "psa (g), psv (m/s) or sd (m)")->capture_default_str();
  c->add_option("-o,--output", o->out, "CSV file (default: standard output)");
  c->callback([o] {
    if (!o->out.empty()) {  // before any work: never over a record, the suite file or a file of --records-dir
      std::vector<std::string> inputs = records_read(o->files, o->suite.records_dir);
      if (o->suite.suite != "default") inputs.push_back(o->suite.suite);
      files::check_output_not_input(o->out, inputs, "-o");
      files::check_output_path(o->out, "-o");
    }
    if (o->quantity != "psa" && o->quantity != "psv" && o->quantity != "sd")
      throw InputError(fmt::format("--quantity {}", o->quantity), "--quantity", "use psa, psv or sd");
    if (!(o->damping >= 0 && o->damping < 1))
      throw InputError(fmt::format("--damping {} is outside [0, 1)", o->damping), "--damping", "give e.g. 0.05");
    const std::vector<double> T = parse_periods(o->periods);
    std::vector<std::string> names, kinds;
    std::vector<Spectrum> spectra;
    const ReadOptions ro = o->read.get();
    for (const auto& f : o->files) {
      const Record r = read_record(f, ro);
      warn_if_not_analysable(r);
      names.push_back(r.name);
      kinds.push_back("real");
      spectra.push_back(response_spectrum(r, T, o->damping));
    }
    if (!o->suite.suite.empty())
      for (const auto& rr : resolve(o->suite, o->suite.suite)) {
        names.push_back(rr.id);
        kinds.push_back(rr.synthetic ? "synthetic" : "real");
        spectra.push_back(response_spectrum(rr.record, T, o->damping));
      }
    if (spectra.empty()) throw InputError("no records", "records spectrum", "give record files or --suite");
    const std::string csv = spectra_csv(o->quantity, o->damping, T, names, kinds, spectra);
    if (o->out.empty()) fmt::print("{}", csv);
    else {
      files::write_text_atomically(o->out, csv);
      int nsyn = 0;
      for (const auto& k : kinds) nsyn += k == "synthetic";
      fmt::print("wrote {} ({} spectra, {} synthetic)\n", o->out, spectra.size(), nsyn);
    }
  });
}

// `records synth`
void add_synth(CLI::App* records) {
  struct Opts {
    double M = 6.9, R = 15.0, vs30 = 300.0, pga = 0.0, dt = 0.01, duration = 0.0;
    int F = 0;
    std::uint64_t seed = 1;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  auto* c = records->add_subcommand("synth", "one Rezaeian & Der Kiureghian (2010) site-based synthetic record, "
                                         "written as an AT2 file (values in g)");
  c->add_option("--M", o->M, "moment magnitude")->capture_default_str();
  c->add_option("--R", o->R, "rupture distance R_rup (km)")->capture_default_str();
  c->add_option("--vs30", o->vs30, "Vs30 (m/s)")->capture_default_str();
  c->add_option("--F", o->F, "faulting: 0 strike-slip, 1 reverse or reverse-oblique")->capture_default_str();
  c->add_option("--seed", o->seed, "random seed (the same seed gives the same record)")->capture_default_str();
  c->add_option("--pga", o->pga, "scale to this PGA in g (default: the model's own amplitude)");
  c->add_option("--dt", o->dt, "time step (s)")->capture_default_str();
  c->add_option("--duration", o->duration, "length (s); default: until 99.95 % of the envelope's Ia");
  c->add_option("-o,--output", o->out, "output AT2 file (default: synthetic-M<M>-R<R>-V<vs30>-F<F>-s<seed>.AT2)");
  c->callback([o] {
    const SiteParams site{o->M, o->R, o->vs30, o->F};
    validate(site, "--M/--R/--vs30/--F");
    if (o->pga < 0 || o->pga > 5) throw InputError(fmt::format("--pga {}", o->pga), "--pga", "give a PGA in (0, 5] g");
    if (!(o->dt > 0 && o->dt <= 0.05)) throw InputError(fmt::format("--dt {}", o->dt), "--dt", "give a step in (0, 0.05] s");
    if (o->duration < 0) throw InputError("--duration < 0", "--duration", "give a length in s");
    SynthOptions so;
    so.dt = o->dt;
    so.pga_g = o->pga;
    so.duration = o->duration;
    Record r = synthesize(site, o->seed, so);
    const ModelParams p = sample_params(site, o->seed);
    r.meta["description"] = fmt::format("synthetic R&DK 2010, M {} R {} km Vs30 {} F {} seed {}", o->M, o->R, o->vs30,
                                        o->F, o->seed);
    const std::string out = o->out.empty()
                                ? fmt::format("synthetic-M{}-R{}-V{}-F{}-s{}.AT2", o->M, o->R, o->vs30, o->F, o->seed)
                                : o->out;
    write_at2(r, out);
    const Measures m = measure(r);
    fmt::print("wrote {}\n", out);
    fmt::print("model (before PGA scaling): Ia {:.4g} s*g, D5-95 {:.3f} s, t_mid {:.3f} s, f_mid {:.3f} Hz, f' {:.4f} Hz/s, zeta_f {:.3f}\n",
               p.arias_sg, p.d5_95, p.t_mid, p.f_mid_hz, p.f_slope_hz_s, p.zeta_f);
    fmt::print("record: dt {} s, npts {}, PGA {:.4f} g, PGV {:.4f} m/s, Ia {:.4g} s*g, D5-95 {:.3f} s, t_mid {:.3f} s\n",
               r.dt, r.acc.size(), m.pga / g_accel, m.pgv, m.arias_sg(), m.d5_95(), m.t45);
  });
}

// `records suite`
void add_suite(CLI::App* records) {
  struct Opts {
    SuiteOpts suite;
    std::string write_dir;
  };
  auto o = std::make_shared<Opts>();
  auto* c = records->add_subcommand("suite", "resolve a record suite (default: the embedded 25-record seed-study suite) "
                                         "and say which records are real and which synthetic");
  c->add_option("file", o->suite.suite, "suite TOML file (default: built-in)");
  add_suite_options(c, o->suite);
  c->add_option("--write", o->write_dir, "write every resolved record as <dir>/<id>.AT2");
  c->callback([o] {
    const auto rs = resolve(o->suite, o->suite.suite);
    if (!o->write_dir.empty()) {
      // before any file is written: no <dir>/<id>.AT2 may be a record just read or the suite file (--write into
      // --records-dir would replace the real records by their copies)
      std::vector<std::string> inputs = records_read({o->suite.suite}, o->suite.records_dir);
      for (const auto& r : rs) inputs.push_back(r.record.source);
      for (const auto& r : rs)
        files::check_output_not_input((std::filesystem::path(o->write_dir) / (r.id + ".AT2")).string(), inputs, "--write");
      std::error_code ec;
      std::filesystem::create_directories(o->write_dir, ec);
      if (ec) throw InputError("cannot create directory", o->write_dir, ec.message());
    }
    int nsyn = 0;
    fmt::print("{:<6} {:<9} {:>7} {:>7} {:>7} {:>8} {:>8}  {}\n", "id", "kind", "dt_s", "npts", "PGA_g", "Ia_m/s",
               "D5-95_s", "resolved as");
    for (const auto& r : rs) {
      const Measures m = measure(r.record);
      nsyn += r.synthetic;
      fmt::print("{:<6} {:<9} {:>7.4g} {:>7} {:>7.4f} {:>8.4f} {:>8.3f}  {}\n", r.id, r.synthetic ? "synthetic" : "real",
                 r.record.dt, r.record.acc.size(), m.pga / g_accel, m.arias, m.d5_95(), r.note);
      if (!o->write_dir.empty()) {
        Record w = r.record;
        w.meta["description"] = r.note;
        write_at2(w, (std::filesystem::path(o->write_dir) / (r.id + ".AT2")).string());
      }
    }
    fmt::print("{} records: {} real, {} synthetic\n", rs.size(), rs.size() - nsyn, nsyn);
  });
}

}  // namespace

void add_records(CLI::App& app) {
  auto* records = app.add_subcommand("records", "ground motions: show, spectrum, im, select, synth, suite");
  records->require_subcommand(1);
  add_show(records);
  add_spectrum(records);
  add_records_im(records);
  add_records_select(records);
  add_synth(records);
  add_suite(records);
}

}  // namespace pounding::cli
