// The HTML report's figures (report/html.hpp): tools/pounding_plots.py run as a child process with a time limit,
// its SVGs read back. POSIX only (fork, exec, waitpid), like the rest of the command line's process handling.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "pounding/core/files.hpp"
#include "pounding/report/html.hpp"

#ifndef POUNDING_FIGURE_PYTHON
#define POUNDING_FIGURE_PYTHON "/usr/bin/python3"
#endif

namespace pounding {

namespace {

namespace fs = std::filesystem;

struct Child {
  int code = -1;       // exit status; -1 killed or not started
  bool timed_out = false;
  std::string error;   // why it did not start
};

// Runs argv[0] with stdout and stderr to `log`, in its own process group, killed (the group) after timeout_s.
Child run_child(const std::vector<std::string>& argv, const std::string& log, double timeout_s) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  Child c;
  const pid_t pid = fork();
  if (pid < 0) return Child{-1, false, "fork failed"};
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    const int null = open("/dev/null", O_RDONLY);
    if (null >= 0) dup2(null, 0), close(null);
    execv(args[0], args.data());
    _exit(127);
  }
  setpgid(pid, pid);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  for (;;) {
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0) return Child{-1, false, "waitpid failed"};
    if (std::chrono::steady_clock::now() > end) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      c.timed_out = true;
      return c;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  c.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return c;
}

std::string last_line(const std::string& path) {
  std::string text;
  try {
    text = files::read_text(path, "the figure log", 1 << 20);
  } catch (const std::exception&) {
    return "";
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const std::size_t nl = text.find_last_of('\n');
  return nl == std::string::npos ? text : text.substr(nl + 1);
}

bool executable(const std::string& p) { return !p.empty() && access(p.c_str(), X_OK) == 0; }

struct TempDir {
  std::string path;
  TempDir() {
    const char* base = std::getenv("TMPDIR");
    std::string t = std::string(base && *base ? base : "/tmp") + "/pounding-figures-XXXXXX";
    if (mkdtemp(t.data())) path = t;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

// figures.tsv: "ok<TAB>name<TAB>file<TAB>caption" or "left-out<TAB>name<TAB><TAB>why", one line per figure.
void read_manifest(const std::string& dir, FigureSet& out) {
  std::ifstream in(dir + "/figures.tsv");
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, '\t');) f.push_back(cell);
    if (f.size() < 4) continue;
    if (f[0] != "ok") {
      out.left_out.push_back(f[1] + ": " + f[3]);
      continue;
    }
    std::string svg;
    try {
      svg = files::read_text(dir + "/" + f[2], "a figure", 32u << 20);
    } catch (const std::exception& e) {
      out.left_out.push_back(f[1] + ": " + e.what());
      continue;
    }
    const std::size_t at = svg.find("<svg");
    if (at == std::string::npos) {
      out.left_out.push_back(f[1] + ": the plotting module wrote no SVG");
      continue;
    }
    out.figures.push_back({f[1], f[3], svg.substr(at)});
  }
}

}  // namespace

// The plotting module beside this binary: <bindir>/../share/pounding/pounding_plots.py when installed, the copy in
// <build>/tools/ in the build tree (CMakeLists.txt); no source path is compiled in (installed files name no tree).
static std::string plots_beside_binary() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path dir = ec ? std::filesystem::path(".") : exe.parent_path();
  const std::filesystem::path installed = (dir / ".." / "share" / "pounding" / "pounding_plots.py").lexically_normal();
  const std::filesystem::path built = dir / "tools" / "pounding_plots.py";
  return std::filesystem::exists(built, ec) && !std::filesystem::exists(installed, ec) ? built.string() : installed.string();
}

FigureOptions default_figure_options() {
  FigureOptions o;
  o.python = POUNDING_FIGURE_PYTHON;
  o.script = plots_beside_binary();
  if (const char* p = std::getenv("POUNDING_PYTHON"); p && *p) o.python = p;
  if (const char* p = std::getenv("POUNDING_PLOTS"); p && *p) o.script = p;
  if (const char* p = std::getenv("POUNDING_FIGURE_TIMEOUT"); p && *p) {
    char* end = nullptr;
    const double t = std::strtod(p, &end);
    if (end != p && t > 0) o.timeout_s = t;
  }
  return o;
}

FigureSet report_figures(const results::Results& r, const std::string& report_csv, const FigureOptions& o) {
  FigureSet out;
  auto none = [&](const std::string& why) {
    out.left_out.push_back("figures: " + why);
    return out;
  };
  if (!executable(o.python))
    return none(fmt::format("no Python interpreter at '{}' (configure found it; $POUNDING_PYTHON names another)", o.python));
  if (access(o.script.c_str(), R_OK) != 0)
    return none(fmt::format("the plotting module '{}' is missing ($POUNDING_PLOTS names it)", o.script));
  struct stat st{};
  if (r.path.empty() || stat(r.path.c_str(), &st) != 0) return none("the results are not in a file the plots can read");
  TempDir dir;
  if (dir.path.empty()) return none("no temporary folder for them");
  try {
    files::write_text_atomically(dir.path + "/report.csv", report_csv);
  } catch (const std::exception& e) {
    return none(e.what());
  }
  const std::string log = dir.path + "/log.txt";
  std::vector<std::string> args{o.python, o.script, "figures", r.path, "--dir", dir.path, "--report-csv", dir.path + "/report.csv"};
  for (const std::string& w : o.with) args.insert(args.end(), {"--with", w});
  const Child c = run_child(args, log, o.timeout_s);
  if (c.timed_out) return none(fmt::format("{} did not finish within {:g} s ($POUNDING_FIGURE_TIMEOUT)", o.script, o.timeout_s));
  if (c.code != 0) {
    const std::string why = last_line(log);
    return none(why.empty() ? fmt::format("{} {} failed (exit {})", o.python, o.script, c.code) : why);
  }
  read_manifest(dir.path, out);
  return out;
}

}  // namespace pounding
