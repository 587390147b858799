#pragma once
// Command-line front end: each sub-command lives in src/cli/commands/<name>.cpp and registers itself on the
// CLI11 app; main() only parses and dispatches. Handlers throw InputError for bad input.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <functional>

#include "pounding/study/run.hpp"

#include "pounding/core/error.hpp"

namespace pounding::cli {

void add_simulate(CLI::App& app);  // src/cli/commands/simulate.cpp
void add_collide(CLI::App& app);   // src/cli/commands/collide.cpp
void add_bench(CLI::App& app);     // src/cli/commands/bench.cpp
void add_records(CLI::App& app);   // src/cli/commands/records.cpp (ground motions)
void add_records_im(CLI::App* records);      // src/cli/commands/records_select.cpp (`records im`)
void add_records_select(CLI::App* records);  // src/cli/commands/records_select.cpp (`records select`)
void add_sample(CLI::App& app);    // src/cli/commands/sample.cpp (stochastic structure model)
void add_run(CLI::App& app);       // src/cli/commands/run.cpp (the study)
void add_report(CLI::App& app);    // src/cli/commands/run.cpp
void add_results(CLI::App& app);   // src/cli/commands/results.cpp (the datasets of a results file)
void add_study_reference(CLI::App& app);  // src/cli/commands/study_reference.cpp (docs/study-reference.md)
void add_spectrum(CLI::App& app);  // src/cli/commands/spectrum.cpp (a code design spectrum at given periods)
void add_motions(CLI::App& app);  // src/cli/commands/motions.cpp (spatially varying support motions)
void add_inventory(CLI::App& app);  // src/cli/commands/inventory.cpp (building inventories, ELF design)
void add_modes(CLI::App& app);     // src/cli/commands/modes.cpp (modes and Rayleigh damping of a shear building)
void add_stiffness(CLI::App& app);   // src/cli/commands/stiffness.cpp (impact-stiffness rules)
void add_similitude(CLI::App& app);  // src/cli/commands/stiffness.cpp (shake-table model scale factors)
void add_replay(CLI::App& app);      // src/cli/commands/replay.cpp (a contact law on imposed kinematics)
void add_accuracy(CLI::App& app);  // src/cli/commands/accuracy.cpp (accuracy/speed chart, stability, restitution, validation)

// Several studies in one MPI session, one after another (`pounding inventory run`; `pounding run` is one): each as
// `pounding run STUDY --out OUT` with the flags; `done` is called on rank 0 after each finished study (code 0 or 3)
// with its outcome, instead of printing its report. Returns the first non-zero exit code (a stop ends the list).
struct StudyJob {
  std::string study, out;
};
struct StudyRunFlags {
  bool resume = false, force = false, quiet = false, timings = false;
  int threads = -1;
};
using StudyDone = std::function<void(std::size_t index, const RunOutcome& outcome)>;
int run_study_files(const std::vector<StudyJob>& jobs, const StudyRunFlags& flags, const StudyDone& done);

// Runs a shared parser (parse_stepper, parse_units, ...) and names the command-line option in its InputError.
template <class Parse>
auto as_option(const char* option, Parse parse) {
  try {
    return parse();
  } catch (const InputError& e) {
    throw InputError(e.what_part(), option, e.fix());
  }
}

// Every option of `app` and of its sub-commands that takes a value refuses an empty one, and an integer option refuses
// what CLI11 would silently change (a negative value for an unsigned one, a value beyond the type, a leading zero it
// reads as octal): a CLI::ValidationError "--seed: -1 is negative: give a whole number in [0, 2^64 - 1] ..." (issue 44
// item 10; src/cli/values.cpp). main() applies it once, after every command is registered.
void require_values(CLI::App& app);

// A comma-separated list of numbers as ONE option value (CLI11's delimiter drops empty fields: "0.02,,0.05" was two
// values): every field must be a number, else InputError naming `option` and the accepted form.
std::vector<double> number_list(const std::string& text, const std::string& option);
CLI::Option* add_number_list(CLI::App* c, const std::string& name, std::vector<double>& out, const std::string& help);
// The same for a list option that also takes several values (`--laws linear kelvin` or `--laws linear,kelvin`): every
// value split at commas, an empty field refused; words as given, or numbers checked as number_list does.
CLI::Option* add_list(CLI::App* c, const std::string& name, std::vector<std::string>& out, const std::string& help);
CLI::Option* add_list(CLI::App* c, const std::string& name, std::vector<double>& out, const std::string& help);

// Thrown by a sub-command that wrote its output but must end with a non-zero exit code (3: a run diverged or
// a collision failed, its numbers are not results); main() returns `code`. Nothing process-wide holds it.
struct ExitRequest {
  int code;
};


}  // namespace pounding::cli
