#pragma once
// The command-line form of a velocity-dependent restitution e(v0) (contact/restitution.hpp, issue 26 §3), shared
// by the commands that take one (collide):
//   --restitution-preset lindsay2011 | --restitution-polynomial c0,c1,... | --restitution-table v1:e1,v2:e2,...
//   [--restitution-units m/s|cm/s|mm/s] [--restitution-valid vmin,vmax]
#include <limits>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/commands/records_options.hpp"
#include "pounding/contact/restitution.hpp"
#include "pounding/core/error.hpp"

namespace pounding::cli {

struct RestitutionOpts {
  std::string preset, polynomial, table, units = "m/s", valid;

  void add(CLI::App* c) {
    c->add_option("--restitution-preset", preset,
                  fmt::format("e(v0) preset: {} (the bridge paper's eq. 15, provisional: see docs/contact.md)",
                              contact::restitution_preset_names));
    c->add_option("--restitution-polynomial", polynomial,
                  "e(v0) = c0 + c1 v + c2 v^2 + ... : the coefficients, constant term first, comma-separated");
    c->add_option("--restitution-table", table, "e(v0) as points v:e, comma-separated, v ascending (linear between "
                                                "points, the end values beyond)");
    c->add_option("--restitution-units", units, "velocity units of the polynomial/table and of --restitution-valid: "
                                                "m/s, cm/s, mm/s")->capture_default_str();
    c->add_option("--restitution-valid", valid, "vmin,vmax: the calibrated velocity range (impacts outside it are "
                                                "counted and reported; default: the table's range, or [0, inf))");
  }

  // The option that gave the curve (for errors about where it may be used).
  std::string option() const {
    return !preset.empty() ? "--restitution-preset" : !polynomial.empty() ? "--restitution-polynomial" : "--restitution-table";
  }

  // get(), refusing --e beside a curve.
  std::optional<contact::RestitutionCurve> get_instead_of_e(const CLI::App* c) const {
    std::optional<contact::RestitutionCurve> r = get(c);
    if (r && c->count("--e") > 0)
      throw InputError("--e and a restitution curve both given", "--e", "drop --e: the curve gives e(v0)");
    return r;
  }

  // The curve, or nothing when no restitution option is given; InputError naming the option otherwise.
  std::optional<contact::RestitutionCurve> get(const CLI::App* c) const {
    const int forms = int(!preset.empty()) + int(!polynomial.empty()) + int(!table.empty());
    const bool extras = c->count("--restitution-units") > 0 || !valid.empty();
    if (forms == 0) {
      if (extras)
        throw InputError("--restitution-units or --restitution-valid without a restitution curve",
                         c->count("--restitution-units") > 0 ? "--restitution-units" : "--restitution-valid",
                         "give --restitution-polynomial or --restitution-table (or a --restitution-preset)");
      return std::nullopt;
    }
    if (forms > 1)
      throw InputError("more than one of --restitution-preset, --restitution-polynomial, --restitution-table",
                       !preset.empty() ? "--restitution-preset" : "--restitution-polynomial", "give one");
    contact::RestitutionCurve r;
    if (!preset.empty()) {
      if (!contact::restitution_preset(preset, r))
        throw InputError(fmt::format("unknown restitution preset '{}'", escaped_excerpt(preset)),
                         "--restitution-preset", fmt::format("give one of: {}", contact::restitution_preset_names));
      if (extras)
        throw InputError("a preset carries its own units and valid range", c->count("--restitution-units") > 0
                                                                               ? "--restitution-units"
                                                                               : "--restitution-valid",
                         "drop the option, or give the preset's numbers as --restitution-polynomial");
      return r;
    }
    const double neg = -std::numeric_limits<double>::infinity();
    r.units = units;
    r.per_mps = contact::restitution_units_per_mps(units);
    if (!(r.per_mps > 0.0))
      throw InputError(fmt::format("unknown velocity units '{}'", escaped_excerpt(units)), "--restitution-units",
                       "give m/s, cm/s or mm/s");
    const char* opt = "--restitution-polynomial";
    if (!polynomial.empty()) {
      r.form = contact::RestitutionCurve::Form::polynomial;
      r.name = "polynomial";
      r.coefficients = parse_number_list(polynomial, opt, "number", "give the coefficients c0,c1,... as numbers", neg);
    } else {
      opt = "--restitution-table";
      r.form = contact::RestitutionCurve::Form::table;
      r.name = "table";
      std::string pairs = table;
      for (char& ch : pairs) ch = ch == ':' ? ',' : ch;
      const std::vector<double> xs =
          parse_number_list(pairs, opt, "number", "give points v:e separated by commas, e.g. 0.5:0.9,3:0.7", neg);
      if (xs.size() % 2 != 0 || table.find(':') == std::string::npos)
        throw InputError("the table is not pairs v:e", opt, "give points v:e separated by commas, e.g. 0.5:0.9,3:0.7");
      for (std::size_t i = 0; i < xs.size(); i += 2) r.table_v.push_back(xs[i]), r.table_e.push_back(xs[i + 1]);
      if (!r.table_v.empty()) r.vmin = r.table_v.front(), r.vmax = r.table_v.back();
    }
    if (!valid.empty()) {
      const std::vector<double> v =
          parse_number_list(valid, "--restitution-valid", "velocity", "give vmin,vmax with 0 <= vmin < vmax");
      if (v.size() != 2 || !(v[0] < v[1]))
        throw InputError(fmt::format("'{}' is not vmin,vmax with vmin < vmax", escaped_excerpt(valid)),
                         "--restitution-valid", "give two velocities, e.g. 0.99,3.13");
      r.vmin = v[0], r.vmax = v[1];
    }
    if (const std::string p = contact::restitution_problem(r); !p.empty())
      throw InputError(fmt::format("the restitution curve is not usable: {}", p), opt, "correct it");
    return r;
  }
};

}  // namespace pounding::cli
