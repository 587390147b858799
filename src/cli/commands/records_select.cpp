// `pounding records im` and `pounding records select` (issue 14 parts 1 and 4).
//
//   records im FILES... --measure PGA|PGV|Sa|Sa_avg [--period T] [--periods T1,T2,...] [--damping 0.05] [--csv]
//     One line per record: its id (file stem), the intensity measure and its units (g; PGV m/s). Sa takes one
//     period (--period), Sa_avg two or more (--periods; geometric mean of Sa). --units/--dt-record are the
//     units of the values in text files and the step of one-column files, as for `records show`.
//
//   records select TARGET --period T[,T2] [--range 0.2,2.0] [--rule RULE] [--count 11] [--points 30]
//                  [--min-scale 0.25 --max-scale 4] [--damping 0.05] (--directory DIR | FILES...) [-o FILE.csv]
//     Chooses the --count records whose log-space least-squares fit to the target over the period range is best
//     (smallest MSE, factor within the scale limits) and one suite factor F >= 1 so the code's condition holds
//     (motion/selection.hpp). The range is [lo min(T), hi max(T)] for --range lo,hi and --period T or T1,T2
//     (a pair: both periods); --range defaults to 0.2,1.5 for ASCE 7-10 and 0.2,2.0 otherwise. RULE is
//     "ASCE 7-16", "ASCE 7-10", "EC8" or "none"; default EC8 with --ec8, ASCE 7-16 with any other target.
//     TARGET, exactly one of (design_spectrum.hpp):
//       --asce7 SDS,SD1,TL              ASCE 7-16 11.4.6 design spectrum (g, g, s); --mcer multiplies it by 1.5
//                                       (the MCER spectrum ASCE 7-16 16.2 scales to)
//       --ec8 TYPE,GROUND,AGR[,GAMMA_I] EN 1998-1 elastic spectrum: TYPE 1 or 2, GROUND A-E, agR in g, gammaI
//                                       (default 1); its damping is --damping
//       --iran2800 A,SOIL[,I]           Standard 2800 (4th ed.) A B I: A 0.2-0.35, SOIL I-IV, I (default 1)
//       --target-csv FILE               tabulated "period,sa" (s, g) lines
//     --directory DIR takes every .AT2 and .txt file in DIR (sorted by name; record_files_in, the reader of a
//     study's [records] directory); FILES are any record files. A MANIFEST.tsv beside the files names each one's
//     event, station and component (else the PEER header does, motion/library.hpp); --max-per-event N (default 2)
//     and --components one|both (default one) keep one recording, one station and N records of an event at most,
//     and the table says what was passed over and why. Every candidate is checked as `run` checks a record
//     (duration >= 2 s, PGA <= 5 g) before any work, and again with its final factor.
//     Ranges (the study file's): --period and the range within [0.01, 20] s, --points 2-1000, --damping
//     [0, 0.5], scale limits within [0.001, 1000].
//     -o writes the selection as CSV for tools/plot_spectra.py: "# key: value" lines (target, rule, fraction,
//     range, suite factor, condition), then period_s,target_g,mean_g,<id>... with the SCALED spectra.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/records_options.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/intensity.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/selection.hpp"
#include "pounding/motion/target_spectrum.hpp"

namespace pounding::cli {

namespace {

// ---------------- records im ----------------

IntensityMeasure im_from(const std::string& measure, const std::string& period, const std::string& periods,
                         double damping) {
  IntensityMeasure im;
  im.measure = parse_im_measure(measure);
  im.damping = damping;
  if (!period.empty() && !periods.empty())
    throw InputError("both --period and --periods", "--period/--periods", "give --period T for Sa, --periods for Sa_avg");
  if (!period.empty()) im.periods = parse_number_list(period, "--period", "period", "give one period in s, e.g. 1.0", 0, true);
  if (!periods.empty())
    im.periods = parse_number_list(periods, "--periods", "period", "give periods in s, e.g. 0.2,0.5,1,2", 0, true);
  if (im.measure == ImMeasure::sa_avg && !period.empty())
    throw InputError("Sa_avg takes --periods", "--period", "give --periods T1,T2,... (two or more)");
  if (im.measure == ImMeasure::sa && im.periods.empty())
    throw InputError("Sa needs a period", "--period", "give e.g. --period 1.0");
  validate(im);
  return im;
}

}  // namespace

void add_records_im(CLI::App* records) {
  struct Opts {
    std::vector<std::string> files;
    ReadOpts read;
    std::string measure = "Sa", period, periods;
    double damping = 0.05;
    bool csv = false;
  };
  auto o = std::make_shared<Opts>();
  auto* c = records->add_subcommand("im", "intensity measure of each record: PGA (g), PGV (m/s), Sa(T) (g) or Sa_avg "
                                          "(geometric mean of Sa over periods, g)");
  c->add_option("files", o->files, "record files (.AT2, two-column time/acc, one-column with --dt-record)")->required();
  c->add_option("--measure", o->measure, "PGA, PGV, Sa or Sa_avg")->capture_default_str();
  c->add_option("--period", o->period, "period of Sa (s)");
  c->add_option("--periods", o->periods, "comma-separated periods of Sa_avg (s), two or more");
  c->add_option("--damping", o->damping, "damping ratio of Sa, Sa_avg")->capture_default_str();
  c->add_flag("--csv", o->csv, "CSV: record,<measure>,units");
  add_read_options(c, o->read);
  c->callback([o] {
    const IntensityMeasure im = im_from(o->measure, o->period, o->periods, o->damping);
    const ReadOptions ro = o->read.get();
    std::vector<Record> recs;  // read all first: a bad file prints nothing but the error
    for (const auto& f : o->files) recs.push_back(read_record(f, ro));
    const std::string name(to_string(im.measure));
    if (o->csv) fmt::print("# {}\nrecord,{},units\n", describe(im), name);
    else fmt::print("# {}\n{:<44} {:>14} {}\n", describe(im), "record", name, "units");
    for (const Record& r : recs) {
      warn_if_not_analysable(r);
      const double v = intensity(r, im);
      if (o->csv) fmt::print("{},{:.9g},{}\n", r.name, v, im_units(im.measure));
      else fmt::print("{:<44} {:>14.6g} {}\n", r.name, v, im_units(im.measure));
    }
  });
}

namespace {

// ---------------- records select ----------------

struct SelectOpts {
  std::vector<std::string> files;
  std::string directory;
  ReadOpts read;
  std::string asce7, ec8, iran2800, target_csv;
  bool mcer = false;
  std::string period, range, rule, out;  // rule "": EC8 with --ec8, else ASCE 7-16
  std::size_t count = 11, max_per_event = default_max_per_event;
  int points = 30;
  std::string components = "one";
  double min_scale = 0.25, max_scale = 4.0, damping = 0.05;
};

// The comma-separated fields of a target flag, lo..hi of them.
std::vector<std::string> spec_fields(const std::string& text, const char* flag, std::size_t lo, std::size_t hi,
                                     const char* form) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    parts.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  if (parts.size() < lo || parts.size() > hi)
    throw InputError(fmt::format("{} '{}' has {} fields", flag, escaped_excerpt(text), parts.size()), flag,
                     fmt::format("give {}", form));
  return parts;
}

double spec_number(const std::string& field, const char* flag, const char* form) {
  return parse_number_list(field, flag, "number", fmt::format("give {}", form), 0, true).front();
}

void ec8_fields(const SelectOpts& o, TargetSpectrumSpec& spec) {
  const char* form = "TYPE,GROUND,AGR[,GAMMA_I], e.g. 1,C,0.25";
  const auto f = spec_fields(o.ec8, "--ec8", 3, 4, form);
  Ec8Spectrum& s = spec.ec8;
  if (f[0] != "1" && f[0] != "2") throw InputError(fmt::format("EC8 type '{}'", escaped_excerpt(f[0])), "--ec8", "TYPE is 1 or 2");
  s.type = f[0] == "1" ? Ec8Type::type1 : Ec8Type::type2;
  const std::string grounds = "ABCDE";
  const std::size_t g = f[1].size() == 1 ? grounds.find(static_cast<char>(std::toupper(f[1][0]))) : std::string::npos;
  if (g == std::string::npos)
    throw InputError(fmt::format("EC8 ground '{}'", escaped_excerpt(f[1])), "--ec8", "GROUND is one of A, B, C, D, E");
  s.ground = static_cast<Ec8Ground>(g);
  s.agr = spec_number(f[2], "--ec8", form);
  if (f.size() > 3) s.importance = spec_number(f[3], "--ec8", form);
}

void iran_fields(const SelectOpts& o, TargetSpectrumSpec& spec) {
  const char* form = "A,SOIL[,I], e.g. 0.35,III";
  const auto f = spec_fields(o.iran2800, "--iran2800", 2, 3, form);
  Iran2800Spectrum& s = spec.iran2800;
  s.a = spec_number(f[0], "--iran2800", form);
  const char* soils[] = {"I", "II", "III", "IV"};
  const auto* it = std::find(std::begin(soils), std::end(soils), f[1]);
  if (it == std::end(soils))
    throw InputError(fmt::format("soil '{}'", escaped_excerpt(f[1])), "--iran2800", "SOIL is one of I, II, III, IV");
  s.soil = static_cast<Iran2800Soil>(it - std::begin(soils));
  if (f.size() > 2) s.importance = spec_number(f[2], "--iran2800", form);
}

// The target flags as a TargetSpectrumSpec (motion/target_spectrum.hpp, shared with a study's [target_spectrum]).
TargetSpectrumSpec target_spec(const SelectOpts& o) {
  const int given = !o.asce7.empty() + !o.ec8.empty() + !o.iran2800.empty() + !o.target_csv.empty();
  if (given != 1)
    throw InputError(fmt::format("{} target spectra given", given), "--asce7/--ec8/--iran2800/--target-csv",
                     "give exactly one target, e.g. --asce7 1.0,0.6,8");
  if (o.mcer && o.asce7.empty()) throw InputError("--mcer without --asce7", "--mcer", "--mcer scales the --asce7 spectrum");
  TargetSpectrumSpec spec;
  if (!o.asce7.empty()) {
    const char* form = "SDS,SD1,TL in g, g, s, e.g. 1.0,0.6,8";
    const auto f = spec_fields(o.asce7, "--asce7", 3, 3, form);
    spec.code = TargetCode::asce7_16;
    spec.asce7 = {spec_number(f[0], "--asce7", form), spec_number(f[1], "--asce7", form),
                  spec_number(f[2], "--asce7", form)};
    spec.mcer = o.mcer;
  } else if (!o.ec8.empty()) {
    spec.code = TargetCode::ec8;
    ec8_fields(o, spec);
  } else if (!o.iran2800.empty()) {
    spec.code = TargetCode::iran2800;
    iran_fields(o, spec);
  } else {
    spec.code = TargetCode::csv;
    spec.table = read_tabulated_spectrum(o.target_csv);
  }
  return spec;
}

const char* target_flag(TargetCode code) {
  switch (code) {
    case TargetCode::asce7_16: return "--asce7";
    case TargetCode::ec8: return "--ec8";
    case TargetCode::iran2800: return "--iran2800";
    case TargetCode::csv: return "--target-csv";
  }
  return "--target-csv";
}

struct Library {
  std::vector<std::string> files;
  std::vector<Record> records;
};

// The candidates: the files of --directory (record_files_in, the reader a study's [records] directory uses) or
// the files given, read and annotated from their directories' MANIFEST.tsv (library.hpp), each checked as `run`
// checks a record (require_analysable: duration, PGA) before any spectrum is computed.
Library read_candidates(const SelectOpts& o) {
  Library lib;
  if (!o.directory.empty() && !o.files.empty())
    throw InputError("both --directory and record files", "--directory", "give either a directory or files");
  if (!o.directory.empty()) lib.files = record_files_in(o.directory, "--directory");
  else lib.files = o.files;
  if (lib.files.empty()) throw InputError("no records", "records select", "give record files or --directory DIR");
  lib.records = read_library(lib.files, o.read.get());
  for (const Record& r : lib.records) require_analysable(r, {1.0, "", "give --units cm/s2"});
  return lib;
}

SelectionOptions selection_options(const SelectOpts& o) {
  SelectionOptions so;
  so.rule = o.rule.empty() ? default_scaling_rule(!o.ec8.empty() ? TargetCode::ec8 : TargetCode::asce7_16)
                           : as_option("--rule", [&] { return parse_scaling_rule(o.rule); });
  const auto T = parse_number_list(o.period, "--period", "period", "give the period(s) in s, e.g. 1.2 or 0.9,1.3", 0, true);
  if (T.size() > 2) throw InputError("more than two periods", "--period", "give T or T1,T2 (a pair)");
  const auto def = default_range_multiples(so.rule);
  const std::string range = !o.range.empty() ? o.range : fmt::format("{},{}", def[0], def[1]);
  const auto r = parse_number_list(range, "--range", "multiple of the period", "give e.g. 0.2,2.0", 0, true);
  if (r.size() != 2) throw InputError(fmt::format("--range '{}'", range), "--range", "give two multiples, e.g. 0.2,2.0");
  for (double t : T)
    if (t > selection_period_max)
      throw InputError(fmt::format("--period {:g} s is above {:g} s", t, selection_period_max), "--period",
                       "give the building's period in s (the spectra are defined to 20 s)");
  so.t_lo = r[0] * *std::min_element(T.begin(), T.end());
  so.t_hi = r[1] * *std::max_element(T.begin(), T.end());
  if (so.t_lo < selection_period_min || so.t_hi > selection_period_max)
    throw InputError(fmt::format("the period range {:g}-{:g} s ({} x --period {}) is outside [{:g}, {:g}] s", so.t_lo,
                                 so.t_hi, range, o.period, selection_period_min, selection_period_max),
                     o.range.empty() ? "--period" : "--period/--range",
                     "give the building's period(s) and range multiples that keep the range within the spectra");
  so.count = o.count, so.points = o.points, so.min_scale = o.min_scale, so.max_scale = o.max_scale;
  so.damping = o.damping;
  so.max_per_event = o.max_per_event;
  so.components = as_option("--components", [&] { return parse_component_rule(o.components); });
  validate(so);
  return so;
}

std::string selection_csv(const Selection& s, const std::vector<SelectionCandidate>& c, const std::string& target,
                          const SelectionOptions& so) {
  std::string csv = fmt::format("# pounding records select\n# target: {}\n# rule: {}\n# rule_fraction: {}\n"
                                "# range_s: {:.6g} {:.6g}\n# suite_factor: {:.9g}\n# min_ratio: {:.9g}\n"
                                "# condition_holds: {}\nperiod_s,target_g,mean_g",
                                target, s.rule_text, rule_fraction(so.rule), so.t_lo, so.t_hi, s.suite_factor,
                                s.min_ratio, s.meets ? "yes" : "no");
  for (std::size_t i : s.chosen) csv += "," + c[i].id;
  csv += "\n";
  for (std::size_t j = 0; j < s.periods.size(); ++j) {
    csv += fmt::format("{:.9g},{:.9g},{:.9g}", s.periods[j], s.target[j], s.mean[j]);
    for (std::size_t i = 0; i < s.chosen.size(); ++i) csv += fmt::format(",{:.9g}", s.scale[i] * s.spectra[i][j]);
    csv += "\n";
  }
  return csv;
}

void print_selection(const Selection& s, const Library& lib, const std::vector<SelectionCandidate>& c,
                     const std::string& target, const SelectionOptions& so) {
  std::vector<std::string> ids;
  for (const auto& x : c) ids.push_back(x.id);
  for (const auto& line : selection_summary(s, ids, lib.files, target, so)) fmt::print("{}\n", line);
}

}  // namespace

void add_records_select(CLI::App* records) {
  auto o = std::make_shared<SelectOpts>();
  auto* c = records->add_subcommand("select", "choose and scale records to a code design spectrum (ASCE 7-16, "
                                              "ASCE 7-10 or EC8 rule); docs/ground-motions.md \"Records to a "
                                              "design spectrum\" explains the "
                                              "method; inside a study: [target_spectrum] in docs/study-reference.md");
  c->add_option("files", o->files, "record files (or --directory)");
  c->add_option("--directory", o->directory, "a folder: every .AT2 and .txt file in it, sorted by name");
  c->add_option("--asce7", o->asce7, "target: ASCE 7-16 design spectrum SDS,SD1,TL (g, g, s)");
  c->add_flag("--mcer", o->mcer, "with --asce7: the MCER spectrum, 1.5 x the design spectrum (ASCE 7-16 16.2)");
  c->add_option("--ec8", o->ec8, "target: EN 1998-1 elastic spectrum TYPE,GROUND,AGR[,GAMMA_I], e.g. 1,C,0.25");
  c->add_option("--iran2800", o->iran2800, "target: Standard 2800 A,SOIL[,I], e.g. 0.35,III");
  c->add_option("--target-csv", o->target_csv, "target: tabulated period,sa lines (s, g)");
  c->add_option("--period", o->period, "the structure's period T in s, or T1,T2 for a pair")->required();
  c->add_option("--range", o->range, "period range as multiples lo,hi of T (default 0.2,2.0; ASCE 7-10: 0.2,1.5)");
  c->add_option("--rule", o->rule, "\"ASCE 7-16\", \"ASCE 7-10\", \"EC8\" or \"none\" (default: EC8 with --ec8, else ASCE 7-16)");
  c->add_option("--count", o->count, "number of records to choose")->capture_default_str();
  c->add_option("--points", o->points, "log-spaced periods in the range")->capture_default_str();
  c->add_option("--min-scale", o->min_scale, "smallest eligible least-squares factor")->capture_default_str();
  c->add_option("--max-scale", o->max_scale, "largest eligible least-squares factor")->capture_default_str();
  c->add_option("--damping", o->damping, "damping ratio of the spectra")->capture_default_str();
  c->add_option("--max-per-event", o->max_per_event, "at most this many records of one earthquake (0: no limit; "
                                                     "FEMA P-695 takes 2)")->capture_default_str();
  c->add_option("--components", o->components, "one: one component per station (the better match); both: both "
                                                "may be chosen")->capture_default_str();
  c->add_option("-o,--output", o->out, "CSV for tools/plot_spectra.py (scaled spectra, target, mean)");
  add_read_options(c, o->read);
  c->callback([o] {
    if (!o->out.empty()) {  // before any work: never over a record, a file of --directory or the target table
      std::vector<std::string> inputs = records_read(o->files, o->directory);
      inputs.push_back(o->target_csv);
      files::check_output_not_input(o->out, inputs, "-o");
      files::check_output_path(o->out, "-o");  // no device or FIFO replaced
    }
    if (!(o->damping >= 0 && o->damping < 1))
      throw InputError(fmt::format("--damping {} is outside [0, 1)", o->damping), "--damping", "give e.g. 0.05");
    SelectionOptions so = selection_options(*o);
    so.mcer_target = o->mcer;
    const TargetSpectrumSpec spec = target_spec(*o);
    const DesignSpectrum target = as_option(target_flag(spec.code), [&] { return make_target_spectrum(spec, o->damping); });
    const std::string target_text = describe_target(spec, target);
    const Library lib = read_candidates(*o);
    if (so.count > lib.records.size())
      throw InputError(fmt::format("--count {} but {} record{} given", so.count, lib.records.size(),
                                   lib.records.size() == 1 ? "" : "s"),
                       "--count", fmt::format("give --count <= {}, or more records", lib.records.size()));
    std::vector<SelectionCandidate> cands;
    for (const auto& r : lib.records) cands.push_back({r.name, &r});
    const Selection s = select_records(cands, target, so);
    for (std::size_t k = 0; k < s.chosen.size(); ++k) {  // the factors must leave a record `run` accepts
      Record scaled = lib.records[s.chosen[k]];
      for (double& a : scaled.acc) a *= s.scale[k];
      require_analysable(scaled, {s.scale[k], fmt::format("the selection's factor of {} (f_i {:.4g} x F {:.4g}; lower "
                                                          "--max-scale or drop the record)", cands[s.chosen[k]].id,
                                                          s.individual_scale[k], s.suite_factor),
                                  "give --units cm/s2"});
    }
    print_selection(s, lib, cands, target_text, so);
    if (!o->out.empty()) {
      files::write_text_atomically(o->out, selection_csv(s, cands, target_text, so));
      fmt::print("wrote {}\n", o->out);
    }
  });
}

}  // namespace pounding::cli
