#pragma once
// How the command line ends when it cannot do its work (docs/failure-behaviour.md, the exit-code table): every
// error, CLI11's parse errors included, as one line " ERROR: <what>, <where>, <how to fix>" on stderr and exit 2.
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "pounding/core/error.hpp"

namespace pounding::cli {

// A parse error of CLI11 (unknown, missing, repeated or excluded options, a value of the wrong type, a missing
// sub-command) in the house wording; returns the exit code: 0 for --help and --version (CLI11 prints them), else 2.
int report_parse_error(const CLI::App& app, const CLI::ParseError& e);

// Any exception as the ERROR line's three parts: an InputError as it is; out of memory (std::bad_alloc, a
// std::length_error) said so, with how to make the problem smaller; anything else named unexpected, with its text.
// `section`: the command as typed ("pounding run"), the line's <where>.
InputError describe_failure(const std::exception_ptr& e, const std::string& section);

// An exception that no command turned into an InputError (out of memory, an HDF5 or zlib error, a defect): one
// ERROR line naming the command, what failed and what to do; returns 2.
int report_failure(const CLI::App& app, const std::exception_ptr& e);

// The command's end: standard output flushed; a write that failed there (> /dev/full, a full disk) is an error
// (exit 2, one ERROR line), not a success whose output was lost. Returns `code` otherwise.
int finish_output(const CLI::App& app, int code);

}  // namespace pounding::cli
