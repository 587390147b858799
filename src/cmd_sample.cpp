// Placeholder: the owner of this command replaces this file.
#include "pounding/cli.hpp"
namespace pounding::cli {
void add_sample(CLI::App&) {}
}  // namespace pounding::cli
