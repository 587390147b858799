// pounding: Monte Carlo seismic-pounding engine. Parses the command line and dispatches.
#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "pounding/cli.hpp"
#include "pounding/error.hpp"
#include "pounding/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"pounding: probability of seismic pounding between adjacent structures"};
  app.set_version_flag("--version", std::string(pounding::program_version) + " (" + pounding::git_commit + ")");
  app.require_subcommand(1);
  pounding::cli::add_run(app);
  pounding::cli::add_report(app);
  pounding::cli::add_simulate(app);
  pounding::cli::add_collide(app);
  pounding::cli::add_bench(app);
  pounding::cli::add_records(app);
  pounding::cli::add_sample(app);
  pounding::cli::add_accuracy(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const pounding::InputError& e) {
    fmt::print(stderr, " ERROR: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, " ERROR: {}\n", e.what());
    return 1;
  }
  return pounding::cli::exit_code();
}
