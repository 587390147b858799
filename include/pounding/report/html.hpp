#pragma once
// The HTML report (issue 29): one self-contained file per study (inline CSS and SVG figures, no script, no network,
// a Content-Security-Policy that forbids any load) that opens with the answer, then the figures, then every table
// of the Markdown report, then the provenance. `pounding report R.h5 --html out.html`; [report] html = true writes
// it next to the results at the end of a run; `pounding report A.h5 B.h5 --html out.html` compares two studies.
//
// The tables ARE the Markdown report: report_markdown()'s text is read back block by block (markdown_html.hpp) and
// written as HTML, and the answer block quotes cells of its tables, so every number equals the Markdown's by
// construction. The figures come from tools/pounding_plots.py (the module behind tools/plot_*.py), run by the
// Python found at configure time with a time limit; a missing interpreter or matplotlib, or a failing figure, leaves
// that figure out and the report says which and why.
#include <string>
#include <vector>

#include "pounding/core/progress.hpp"
#include "pounding/results/results.hpp"

namespace pounding {

struct FigureOptions {
  std::string python;      // the interpreter ("" : no figures, said so in the report)
  std::string script;      // tools/pounding_plots.py
  double timeout_s = 300;  // for all of one file's figures
  bool enabled = true;     // false: `--no-figures` (the report says they were left out on request)
  // results files given beside this one (`pounding_plots.py figures --with`): compare_html gives study A the others'
  // paths, so a bridge study compared with the same bridge under the other input gets the uniform-versus-multi-support
  // figure ("inputs")
  std::vector<std::string> with;
};
// The configure-time interpreter and the module beside the binary (<bindir>/../share/pounding, or build/tools);
// $POUNDING_PYTHON, $POUNDING_PLOTS and $POUNDING_FIGURE_TIMEOUT (s) override them.
FigureOptions default_figure_options();

struct HtmlFigure {
  std::string name, caption, svg;  // svg: an <svg> element (its ids prefixed with the figure's name)
};
struct FigureSet {
  std::vector<HtmlFigure> figures;
  std::vector<std::string> left_out;  // "<figure or 'figures'>: <why>", one per figure not drawn
};
// The figures of a results file on disk (r.path); `report_csv` is report_csv(r) (the pair figure draws its rows).
FigureSet report_figures(const results::Results& r, const std::string& report_csv, const FigureOptions& options);

// The whole page. `hook` (may be null): progress and stop of the report's bootstrap, as report_markdown.
std::string report_html(const results::Results& r, const FigureOptions& options, const WorkHook* hook = nullptr);
// Two (or more) studies side by side: each one's answer in a column, then the tables of each, then the figures and
// provenance of each.
std::string compare_html(const std::vector<const results::Results*>& files, const FigureOptions& options);

}  // namespace pounding
