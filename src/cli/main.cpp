// pounding: Monte Carlo seismic-pounding engine. Parses the command line and dispatches.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/timing.hpp"
#include "pounding/core/version.hpp"

namespace {

// An unknown option, a surplus argument or an unknown sub-command, in the wording of every other unknown-key
// error (pounding::unknown_key_error); nullptr-free: returns false when the parse error is something else.
bool unknown_name_error(const CLI::App& app, pounding::InputError& out) {
  // the deepest sub-command the parser selected, and its path ("pounding records show")
  const CLI::App* cur = &app;
  std::string section = "pounding";
  while (!cur->get_subcommands().empty()) {
    cur = cur->get_subcommands().front();
    section += " " + cur->get_name();
  }
  std::vector<std::string> extra = cur->remaining();
  if (extra.empty()) extra = app.remaining(true);
  if (extra.empty()) return false;
  const std::string& name = extra.front();
  std::string allowed;
  auto add = [&](const std::string& s) { allowed += (allowed.empty() ? "" : ", ") + s; };
  const bool wants_command = cur->get_require_subcommand_min() > 0 && cur->get_subcommands().empty();
  if (wants_command && name.rfind("-", 0) != 0) {
    for (const CLI::App* s : cur->get_subcommands([](const CLI::App*) { return true; })) add(s->get_name());
    out = pounding::unknown_key_error(name, section, "command line", allowed, "command");
    return true;
  }
  for (const CLI::Option* o : cur->get_options()) {
    const std::string n = o->get_name(false, false);
    if (!n.empty() && n != "--help") add(n);
  }
  out = pounding::unknown_key_error(name, section, "command line", allowed + " (see " + section + " --help)",
                                    name.rfind("-", 0) == 0 ? "option" : "argument");
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  pounding::timing::program_start();  // the clock of the run's wall time and phases (core/timing.hpp)
  CLI::App app{"pounding: probability of seismic pounding between adjacent structures"};
  app.set_version_flag("--version", std::string(pounding::program_version) + " (" + pounding::git_commit + ")");
  app.require_subcommand(1);
  pounding::cli::add_run(app);
  pounding::cli::add_report(app);
  pounding::cli::add_results(app);
  pounding::cli::add_simulate(app);
  pounding::cli::add_collide(app);
  pounding::cli::add_bench(app);
  pounding::cli::add_records(app);
  pounding::cli::add_sample(app);
  pounding::cli::add_spectrum(app);
  pounding::cli::add_modes(app);
  pounding::cli::add_stiffness(app);
  pounding::cli::add_similitude(app);
  pounding::cli::add_replay(app);
  pounding::cli::add_motions(app);
  pounding::cli::add_accuracy(app);
  pounding::cli::add_study_reference(app);
  pounding::cli::require_values(app);  // no empty value, no silently wrapped integer (issue 44 item 10)
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    pounding::InputError unknown("", "", "");
    if ((dynamic_cast<const CLI::ExtrasError*>(&e) || dynamic_cast<const CLI::RequiredError*>(&e)) &&
        unknown_name_error(app, unknown)) {
      fmt::print(stderr, " ERROR: {}\n", unknown.what());
      return 2;
    }
    // a value of the wrong type or outside an option's range: one house-style line naming the option
    if (dynamic_cast<const CLI::ConversionError*>(&e) || dynamic_cast<const CLI::ValidationError*>(&e)) {
      fmt::print(stderr, " ERROR: {}, command line, give a value of the option's type and range (--help lists them)\n",
                 e.what());
      return 2;
    }
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const pounding::cli::ExitRequest& e) {
    return e.code;
  } catch (const pounding::InputError& e) {
    fmt::print(stderr, " ERROR: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, " ERROR: {}\n", e.what());
    return 1;
  }
  return 0;
}
