// How a command ends when it cannot do its work: every error as one line (what, where, fix) and its exit code.
#include "cli/errors.hpp"

#include <cerrno>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding::cli {

namespace {

// The deepest sub-command the parser selected and its path as typed ("pounding records show").
struct Selected {
  const CLI::App* app;
  std::string section;
};
Selected selected(const CLI::App& app) {
  Selected s{&app, "pounding"};
  while (!s.app->get_subcommands().empty()) {
    s.app = s.app->get_subcommands().front();
    s.section += " " + s.app->get_name();
  }
  return s;
}

std::string see_help(const std::string& section) { return fmt::format("see `{} --help`", section); }

// The sub-commands of `cur`, comma-separated.
std::string command_names(const CLI::App* cur) {
  std::string names;
  for (const CLI::App* s : cur->get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + s->get_name();
  return names;
}

// An unknown option, a surplus argument or an unknown sub-command, in the wording of every other unknown-key
// error (pounding::unknown_key_error); false when the parse error is something else.
bool unknown_name_error(const CLI::App& app, InputError& out) {
  const auto [cur, section] = selected(app);
  std::vector<std::string> extra = cur->remaining();
  if (extra.empty()) extra = app.remaining(true);
  if (extra.empty()) return false;
  const std::string& name = extra.front();
  const bool wants_command = cur->get_require_subcommand_min() > 0 && cur->get_subcommands().empty();
  if (wants_command && name.rfind("-", 0) != 0) {
    out = unknown_key_error(name, section, "command line", command_names(cur), "command");
    return true;
  }
  std::string allowed;
  for (const CLI::Option* o : cur->get_options()) {
    const std::string n = o->get_name(false, false);
    if (!n.empty() && n != "--help") allowed += (allowed.empty() ? "" : ", ") + n;
  }
  out = unknown_key_error(name, section, "command line", allowed + " (" + see_help(section) + ")",
                          name.rfind("-", 0) == 0 ? "option" : "argument");
  return true;
}

// A required option or argument, or the sub-command, that the command line left out.
InputError missing_error(const Selected& s, const CLI::ParseError& e) {
  if (s.app->get_require_subcommand_min() > 0 && s.app->get_subcommands().empty())
    return InputError(fmt::format("{} needs a command", s.section), "command line",
                      fmt::format("give one of: {} ({})", command_names(s.app), see_help(s.section)));
  for (const CLI::Option* o : s.app->get_options()) {
    if (!o->get_required() || o->count() > 0) continue;
    std::string name = o->get_name(false, false);
    const bool positional = name.rfind("-", 0) != 0;
    if (positional) name = "<" + name + ">";
    return InputError(fmt::format("{} needs {} {}", s.section, positional ? "the argument" : "the option", name),
                      "command line", fmt::format("give {}: {} ({})", name, o->get_description(), see_help(s.section)));
  }
  return InputError(fmt::format("{} ({})", e.what(), s.section), "command line", see_help(s.section));
}

// An option given more often than it takes values (`--out a --out b`), or without its value.
InputError mismatch_error(const Selected& s, const CLI::ParseError& e) {
  for (const CLI::Option* o : s.app->get_options()) {
    if (o->count() < 2 || o->get_items_expected_max() != 1) continue;
    const std::string name = o->get_name(false, false);
    return InputError(fmt::format("the option {} of {} is given {} times", name, s.section, o->count()),
                      "command line", fmt::format("give {} once", name));
  }
  const std::string text = e.what(), name = text.substr(0, text.find(':'));  // CLI11: "--out: 1 required TEXT missing"
  if (name.rfind("-", 0) == 0 && name.size() < text.size() && text.find("missing") != std::string::npos)
    return InputError(fmt::format("the option {} of {} has no value", name, s.section), "command line",
                      fmt::format("give {} a value ({})", name, see_help(s.section)));
  return InputError(fmt::format("{} ({})", text, s.section), "command line",
                    fmt::format("give each option its values, once ({})", see_help(s.section)));
}

// "A excludes B" and "A requires B" (CLI11's wording) as the two option names, or nullopt.
bool split_pair(const std::string& text, const std::string& verb, std::string& a, std::string& b) {
  const auto at = text.find(" " + verb + " ");
  if (at == std::string::npos) return false;
  a = text.substr(0, at), b = text.substr(at + verb.size() + 2);
  return true;
}

InputError parse_error_text(const CLI::App& app, const CLI::ParseError& e) {
  InputError unknown("", "", "");
  if ((dynamic_cast<const CLI::ExtrasError*>(&e) || dynamic_cast<const CLI::RequiredError*>(&e)) &&
      unknown_name_error(app, unknown))
    return unknown;
  const Selected s = selected(app);
  const std::string text = e.what();
  std::string a, b;
  if (dynamic_cast<const CLI::RequiredError*>(&e)) return missing_error(s, e);
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) return mismatch_error(s, e);
  if (dynamic_cast<const CLI::ExcludesError*>(&e) && split_pair(text, "excludes", a, b))
    return InputError(fmt::format("{} and {} of {} cannot be given together", a, b, s.section), "command line",
                      fmt::format("give one of them ({})", see_help(s.section)));
  if (dynamic_cast<const CLI::RequiresError*>(&e) && split_pair(text, "requires", a, b))
    return InputError(fmt::format("{} of {} needs {}", a, s.section, b), "command line",
                      fmt::format("add {} or leave out {}", b, a));
  // a value of the wrong type or outside an option's range: one house-style line naming the option
  if (dynamic_cast<const CLI::ConversionError*>(&e) || dynamic_cast<const CLI::ValidationError*>(&e))
    return InputError(text, "command line", "give a value of the option's type and range (--help lists them)");
  if (dynamic_cast<const CLI::FileError*>(&e))
    return InputError(fmt::format("{} ({})", text, s.section), "command line", "give an existing file");
  return InputError(fmt::format("{} ({})", text, s.section), "command line", see_help(s.section));
}

}  // namespace

int report_parse_error(const CLI::App& app, const CLI::ParseError& e) {
  if (dynamic_cast<const CLI::Success*>(&e)) return app.exit(e) == 0 ? 0 : 2;  // --help, --version
  fmt::print(stderr, " ERROR: {}\n", parse_error_text(app, e).what());
  return 2;
}

InputError describe_failure(const std::exception_ptr& e, const std::string& section) {
  const std::string memory_fix =
      section == "pounding run"
          ? "give the study fewer records, period pairs or samples_per_pair, or [outputs] per_model = false or "
            "\"stream\" (rank 0 then holds the reductions only; docs/studies.md), or run on a machine with more memory"
          : fmt::format("give the command a smaller problem (a shorter duration, a coarser step, a smaller width, "
                        "fewer storeys, periods or samples: {}), or run it where more memory is free",
                        see_help(section));
  try {
    std::rethrow_exception(e);
  } catch (const InputError& x) {
    return x;
  } catch (const std::bad_alloc&) {
    return InputError("out of memory", section, memory_fix);
  } catch (const std::length_error& x) {  // a size no allocation can reach
    return InputError(fmt::format("out of memory (a size beyond what can be allocated: {})", x.what()), section,
                      memory_fix);
  } catch (const std::system_error& x) {  // fmt::print's failed write to stdout (> /dev/full), a file's write
    const int err = x.code().category() == std::generic_category() || x.code().category() == std::system_category()
                        ? x.code().value() : 0;
    if (err == ENOSPC || err == EDQUOT || err == EFBIG || err == EIO)
      return InputError(fmt::format("{} (the command's output: standard output or a file it writes)", x.what()),
                        section, files::fix_for(err));
    return InputError(fmt::format("{} (unexpected: not an input error pounding knows how to name)", x.what()), section,
                      "check the files the command reads and writes and the free space; if they are sound, report "
                      "the command line and this message");
  } catch (const std::exception& x) {
    return InputError(fmt::format("{} (unexpected: not an input error pounding knows how to name)", x.what()), section,
                      "check the files the command reads and writes and the free space; if they are sound, report "
                      "the command line and this message");
  } catch (...) {
    return InputError("an unknown exception", section, "report the command line and this message");
  }
}

int report_failure(const CLI::App& app, const std::exception_ptr& e) {
  std::fflush(stdout);
  fmt::print(stderr, " ERROR: {}\n", describe_failure(e, selected(app).section).what());
  return 2;
}

int finish_output(const CLI::App& app, int code) {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return code;
  const int err = errno;  // 0: an earlier write failed (fmt::print reported none), flushing did not
  fmt::print(stderr, " ERROR: cannot write the output: {}, standard output of {}, {}\n",
             err ? files::os_error(err) : "a write failed", selected(app).section,
             err ? files::fix_for(err)
                 : "check where the output goes (a full disk, a device, a closed pipe) and rerun");
  return 2;
}

}  // namespace pounding::cli
