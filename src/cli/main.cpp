// pounding: Monte Carlo seismic-pounding engine. Parses the command line and dispatches.
#include <exception>
#include <string>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "pounding/core/timing.hpp"
#include "pounding/core/version.hpp"
#include "pounding/io/hdf5.hpp"

int main(int argc, char** argv) {
  pounding::timing::program_start();  // the clock of the run's wall time and phases (core/timing.hpp)
  pounding::h5::skip_cleanup_at_exit();  // a file whose close failed must not crash the exit (io/hdf5.hpp)
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
  pounding::cli::add_inventory(app);
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
    return pounding::cli::report_parse_error(app, e);
  } catch (const pounding::cli::ExitRequest& e) {
    return pounding::cli::finish_output(app, e.code);
  } catch (...) {  // every other error: one ERROR line and exit 2 (docs/failure-behaviour.md)
    return pounding::cli::report_failure(app, std::current_exception());
  }
  return pounding::cli::finish_output(app, 0);
}
