#pragma once
// Command-line front end: each sub-command lives in src/cmd_<name>.cpp and registers itself on the
// CLI11 app; main() only parses and dispatches. Handlers throw InputError for bad input.
#include <CLI/CLI.hpp>

namespace pounding::cli {

void add_simulate(CLI::App& app);  // src/cli/commands/simulate.cpp
void add_collide(CLI::App& app);   // src/cli/commands/collide.cpp
void add_bench(CLI::App& app);     // src/cli/commands/bench.cpp
void add_records(CLI::App& app);   // src/cli/commands/records.cpp (ground motions)
void add_sample(CLI::App& app);    // src/cli/commands/sample.cpp (stochastic structure model)
void add_run(CLI::App& app);       // src/cli/commands/run.cpp (the study)
void add_report(CLI::App& app);    // src/cli/commands/run.cpp
void add_accuracy(CLI::App& app);  // src/cli/commands/accuracy.cpp (accuracy/speed chart, stability, restitution, validation)

// Exit code the sub-command asked for (set by handlers that fail without an exception).
int& exit_code();

}  // namespace pounding::cli
