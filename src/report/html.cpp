// The HTML report (report/html.hpp): the answer, the figures, the Markdown report's blocks, the provenance.
#include "pounding/report/html.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <optional>

#include <fmt/format.h>

#include "data.hpp"
#include "markdown_html.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/kernel/batch.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/single_impact.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/report/report.hpp"

namespace pounding {

namespace {

using report_detail::MdBlock;
using report_detail::html_escape;
using report_detail::inline_html;

// Colours: text #1b1f24 on white (16:1), links #0b4fa8 (8:1), the warning's text on #fff4e5 (14:1); nothing is
// told by colour alone. Print: the paper's own size (A4 or Letter), 14 mm margins, no break inside a figure or row.
constexpr const char* kStyle = R"css(
:root{--ink:#1b1f24;--muted:#4a525c;--rule:#c9d0d8;--band:#f2f4f7;--accent:#0b4fa8;--warn:#8a3b00;--warnbg:#fff4e5}
*{box-sizing:border-box}
body{font:15px/1.45 "DejaVu Sans","Segoe UI",Helvetica,Arial,sans-serif;color:var(--ink);background:#fff;margin:0 auto;
 max-width:1180px;padding:14px 22px 40px}
h1{font-size:1.45em;margin:0 0 2px}h2{font-size:1.2em;margin:1.6em 0 .5em;border-bottom:2px solid var(--rule);
 padding-bottom:2px}h3{font-size:1.05em;margin:1.3em 0 .4em}
.sub{color:var(--muted);margin:0 0 8px;font-size:.92em}
a{color:var(--accent)}
code,pre{font-family:"DejaVu Sans Mono",Consolas,monospace;font-size:.88em}
pre{background:var(--band);padding:8px 10px;overflow-x:auto;white-space:pre-wrap;border:1px solid var(--rule)}
.answer{border:2px solid var(--accent);border-radius:6px;padding:8px 14px 10px;margin:6px 0 10px;background:#f7faff}
.answer h2{border:0;margin:0 0 4px;font-size:1.15em}
.answer p{margin:.35em 0}
.answer table{font-size:1.02em}
.advice{font-size:1.08em}
.table-wrap{overflow-x:auto;margin:.4em 0 .9em}
table{border-collapse:collapse;font-size:.86em}
caption{text-align:left;font-weight:bold;padding:2px 0}
th,td{border:1px solid var(--rule);padding:3px 7px;vertical-align:top}
th{background:#e6eaf0;text-align:left}
tbody tr:nth-child(even){background:var(--band)}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
blockquote.warning,.warning{border-left:5px solid var(--warn);background:var(--warnbg);color:#3d1a00;margin:.6em 0;
 padding:6px 12px}
nav.toc{columns:2;font-size:.9em;border:1px solid var(--rule);padding:6px 12px 6px 4px;margin:8px 0}
nav.toc ol{margin:0}
figure{margin:1em 0;break-inside:avoid;page-break-inside:avoid}
figure svg{display:block;width:100%;max-width:1000px;height:auto}
figcaption{color:var(--muted);font-size:.9em}
.left-out{color:var(--warn)}
h2.study-title{font-size:1em;margin:.2em 0;border:0}
.columns{display:grid;grid-template-columns:repeat(auto-fit,minmax(340px,1fr));gap:14px}
dl.meta{display:grid;grid-template-columns:max-content 1fr;gap:2px 12px;font-size:.9em}
dl.meta dt{font-weight:bold}dl.meta dd{margin:0}
@page{margin:14mm}
@media print{body{max-width:none;padding:0;font-size:10pt}nav.toc{columns:2}.table-wrap{overflow:visible}
 table{font-size:8pt}h2{break-after:avoid;page-break-after:avoid}tr{break-inside:avoid;page-break-inside:avoid}
 pre{white-space:pre-wrap;font-size:7.5pt}a{color:var(--ink);text-decoration:none}.answer{break-inside:avoid}}
)css";

std::string page_head(const std::string& title) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; "
      "img-src data:\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n",
      html_escape(title), kStyle);
}

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// The blocks after the heading that starts with `title` up to the next heading; empty when there is none.
std::vector<const MdBlock*> section_of(const std::vector<MdBlock>& blocks, std::string_view title, std::string* heading = nullptr) {
  std::vector<const MdBlock*> out;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].kind != MdBlock::Kind::heading || !starts_with(blocks[i].text, title)) continue;
    if (heading) *heading = blocks[i].text;
    for (std::size_t j = i + 1; j < blocks.size() && blocks[j].kind != MdBlock::Kind::heading; ++j) out.push_back(&blocks[j]);
    break;
  }
  return out;
}

const MdBlock* first_table(const std::vector<const MdBlock*>& section) {
  for (const MdBlock* b : section)
    if (b->kind == MdBlock::Kind::table && !b->rows.empty()) return b;
  return nullptr;
}

// The columns of `t` whose header starts with one of `wanted` ("~text": contains it), in that order; a missing one is
// skipped.
std::vector<std::vector<std::string>> pick_columns(const MdBlock& t, std::initializer_list<std::string_view> wanted) {
  std::vector<std::size_t> cols;
  for (std::string_view w : wanted)
    for (std::size_t c = 0; c < t.rows.front().size(); ++c)
      if ((starts_with(w, "~") ? t.rows.front()[c].find(w.substr(1)) != std::string::npos : starts_with(t.rows.front()[c], w)) &&
          std::find(cols.begin(), cols.end(), c) == cols.end()) {
        cols.push_back(c);
        break;
      }
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : t.rows) {
    rows.emplace_back();
    for (std::size_t c : cols) rows.back().push_back(c < row.size() ? row[c] : "");
  }
  return rows;
}

// The answer, quoted from the Markdown's own blocks: a pair study's separation in metres per target, a risk study's
// risk-targeted separation and probability in the design life, a grid study's advice in ratios of d.
std::string answer_body(const std::vector<MdBlock>& blocks) {
  std::string heading;
  if (auto sec = section_of(blocks, "Separation for this pair", &heading); const MdBlock* t = first_table(sec))
    return "<p>Separation between the two buildings for each target probability of at least one impact in the "
           "study's records: the estimate, its interval over records and models, and the advice (the interval's upper "
           "end, or the lognormal's where the records cannot resolve the target).</p>\n" +
           report_detail::table_html(pick_columns(*t, {"P(at least one impact)", "separation m", "~% interval m", "advice",
                                                       "records above"}));
  if (auto sec = section_of(blocks, "Risk-targeted separation", &heading); !sec.empty()) {
    std::string s = "<p class=\"advice\"><strong>" + inline_html(heading) + "</strong></p>\n";
    for (const MdBlock* b : sec)
      if (b->kind == MdBlock::Kind::paragraph &&
          (b == sec.front() || starts_with(b->text, "**WARNING") || starts_with(b->text, "**not found")))
        s += (starts_with(b->text, "**WARNING") ? "<p class=\"warning\">" : "<p class=\"advice\">") + inline_html(b->text) + "</p>\n";
    return s;
  }
  if (auto sec = section_of(blocks, "Separation advice in metres", &heading); const MdBlock* t = first_table(sec))
    return "<p>Separation advice in metres (the study's gaps are metres, every model's the same): the estimate, its "
           "interval over records and models, and the advice (the interval's upper end).</p>\n" +
           report_detail::table_html(pick_columns(*t, {"target", "x m", "~% interval", "advice"}));
  if (auto sec = section_of(blocks, "Separation advice in gap ratios", &heading); const MdBlock* t = first_table(sec))
    return "<p>Separation advice as a ratio x of the code gap d (heights from the period-height rule, so no metres): "
           "the estimate, its interval over records and models, and the advice (the interval's upper end).</p>\n" +
           report_detail::table_html(pick_columns(*t, {"target", "x", "~% interval", "advice"}));
  if (auto sec = section_of(blocks, "Total probability of pounding", &heading); const MdBlock* t = first_table(sec))
    return "<p>Probability of at least one impact at each gap ratio (this study gives no separation advice):</p>\n" +
           report_detail::table_html(t->rows);
  return "<p>This results file holds no separation advice; the tables below hold what it has.</p>\n";
}

// An isolated building's moat: the probability that its base hits the walls, quoted from the Markdown's table
// (issue 45 item 2); "" without a moat.
std::string moat_answer(const std::vector<MdBlock>& blocks) {
  std::string heading;
  const auto sec = section_of(blocks, "Moat walls", &heading);
  const MdBlock* t = first_table(sec);
  if (!t) return "";
  return "<p>Probability that the isolated base hits its moat walls (at least one moat-wall impact), with its "
         "interval:</p>\n" +
         report_detail::table_html(pick_columns(*t, {"building", "moat gap", "run", "level", "P(moat impact)",
                                                     "~% interval", "records with", "base peak 84th"}));
}

// [gaps] existing: P(pounding) at the as-built gap with its intervals, quoted from the Markdown's paragraph; "" without.
std::string existing_answer(const std::vector<MdBlock>& blocks) {
  std::string heading;
  for (const MdBlock* b : section_of(blocks, "At the existing gap", &heading))
    if (b->kind == MdBlock::Kind::paragraph) return "<p class=\"advice\">" + inline_html(b->text) + "</p>\n";
  return "";
}

std::string answer_html(const std::vector<MdBlock>& blocks, const std::string& id = "answer") {
  std::string s = "<section class=\"answer\" id=\"" + id + "\" aria-labelledby=\"" + id + "-title\">\n<h2 id=\"" + id +
                  "-title\">The answer</h2>\n";
  for (const MdBlock& b : blocks)  // the banner of a run with too many excluded analyses
    if (b.kind == MdBlock::Kind::quote) s += block_html(b);
  return s + existing_answer(blocks) + answer_body(blocks) + moat_answer(blocks) + "</section>\n";
}

struct Toc {
  std::vector<std::pair<std::string, std::string>> entries;  // id, title
  std::string html() const {
    std::string s = "<nav class=\"toc\" aria-label=\"Contents\"><ol>";
    for (const auto& [id, t] : entries) s += "<li><a href=\"#" + id + "\">" + inline_html(t) + "</a></li>";
    return s + "</ol></nav>\n";
  }
};

// The Markdown's blocks after its title (the page's h1), headings numbered into the table of contents.
std::string tables_html(const std::vector<MdBlock>& blocks, const std::string& prefix, Toc& toc) {
  std::string s;
  if (blocks.size() > 1 && blocks[0].kind == MdBlock::Kind::heading && blocks[1].kind != MdBlock::Kind::heading) {
    toc.entries.emplace_back(prefix + "overview", "Study overview");  // the Markdown's lines under its title
    s += "<h2 id=\"" + prefix + "overview\">Study overview</h2>\n";
  }
  for (const MdBlock& b : blocks) {
    if (b.kind == MdBlock::Kind::heading && b.level == 1) continue;
    if (b.kind == MdBlock::Kind::heading) toc.entries.emplace_back(prefix + report_detail::slug(b.text), b.text);
    s += block_html(b, prefix);
  }
  return s;
}

std::string figures_html(const FigureSet& f, const std::string& id) {
  std::string s = "<section id=\"" + id + "\">\n<h2>Figures</h2>\n";
  for (const HtmlFigure& fig : f.figures)
    s += fmt::format("<figure id=\"{}-{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n", id, fig.name, fig.svg,
                     html_escape(fig.caption));
  if (!f.left_out.empty()) {
    s += "<p class=\"left-out\"><strong>Figures left out</strong> (every table below is complete without them):</p>\n<ul class=\"left-out\">";
    for (const std::string& w : f.left_out) s += "<li>" + html_escape(w) + "</li>";
    s += "</ul>\n";
  }
  if (f.figures.empty() && f.left_out.empty()) s += "<p>This results file has nothing to draw.</p>\n";
  return s + "</section>\n";
}

std::string dl(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string s = "<dl class=\"meta\">";
  for (const auto& [k, v] : rows) s += "<dt>" + html_escape(k) + "</dt><dd>" + v + "</dd>";
  return s + "</dl>\n";
}

std::string setting_text(const results::SettingValue& v) {
  struct V {
    std::string operator()(double x) const { return fmt::format("{:.6g}", x); }
    std::string operator()(std::int64_t x) const { return std::to_string(x); }
    std::string operator()(const std::string& x) const { return x; }
    std::string operator()(const std::vector<double>& x) const {
      std::string s = "[";
      for (std::size_t i = 0; i < x.size(); ++i) s += (i ? ", " : "") + fmt::format("{:.6g}", x[i]);
      return s + "]";
    }
    std::string operator()(const std::vector<std::string>& x) const {
      std::string s = "[";
      for (std::size_t i = 0; i < x.size(); ++i) s += (i ? ", " : "") + x[i];
      return s + "]";
    }
  };
  std::string s = std::visit(V{}, v);
  return s.size() > 400 ? s.substr(0, 400) + " ... (" + std::to_string(s.size()) + " characters)" : s;
}

// A hint written for the command line ("use --damping-law calibrated ...", physics/single_impact.cpp) names the
// study key first when the results come from a study: that is where the reader changes it.
std::string study_hint(const std::string& note, bool from_study) {
  static const std::pair<std::string_view, std::string_view> keys[] = {{"--damping-law ", "[contact] damping_law = "}};
  if (!from_study) return note;
  std::string out;
  std::size_t from = 0;
  for (std::size_t at = 0; at < note.size(); ++at)
    for (const auto& [option, key] : keys)
      if (std::string_view(note).substr(at, option.size()) == option) {
        const std::size_t v0 = at + option.size(), v1 = std::min(note.find_first_of(" ,;).", v0), note.size());
        out += note.substr(from, at - from);
        out += fmt::format("{}\"{}\" in the study ({} on the command line)", key, note.substr(v0, v1 - v0),
                           note.substr(at, v1 - at));
        from = v1, at = v1 - 1;
        break;
      }
  return out + note.substr(from);
}

std::string accuracy_statement(const results::Header& h) {
  const bool from_study = !h.study_path.empty() || !h.study_text.empty();
  std::string s = fmt::format("Stepper <strong>{}</strong>, {} substep(s) per record step{}. ", html_escape(h.stepper),
                              h.substeps, h.max_dt > 0 ? fmt::format(", steps no longer than {:g} s", h.max_dt) : "");
  try {
    const ContactLaw law = parse_contact_law(h.contact_law);
    const Stepper st = parse_stepper(h.stepper);
    const double limit = physics::resolution_limit(st, false, law);
    s += std::isfinite(limit)
             ? fmt::format("Contact law <strong>{}</strong> ({}): the peak contact force of an impact is within {:g} % of "
                           "the converged impact while h·ω<sub>c</sub> ≤ {:g} (measured per stepper and law, "
                           "docs/accuracy.md \"Resolution guard\"); coupled analyses beyond it are marked coarse and "
                           "counted in the report. {}",
                           html_escape(h.contact_law), html_escape(h.damping_law), 100 * physics::resolution_tolerance, limit,
                           from_study ? "A finer step brings h·ω<sub>c</sub> down: <code>[analysis] substeps = N</code> "
                                        "or <code>max_dt</code> in the study (<code>--substeps N</code>, "
                                        "<code>--max-dt</code> on the command line). "
                                      : "A finer step brings h·ω<sub>c</sub> down: <code>--substeps N</code> or "
                                        "<code>--max-dt</code>. ")
             : fmt::format("Contact law <strong>{}</strong>: no contact force element, so no resolution limit. ",
                           html_escape(h.contact_law));
    ContactModel cm;
    cm.law = law;
    if (!h.damping_law.empty()) cm.damping = parse_damping_law(h.damping_law);
    s += fmt::format("Restitution asked e = {:g}: {}. ", h.restitution, html_escape(study_hint(restitution_promise(cm).note, from_study)));
  } catch (const std::exception&) {
    s += fmt::format("Contact law {} ({}), e = {:g}. ", html_escape(h.contact_law), html_escape(h.damping_law), h.restitution);
  }
  if (starts_with(h.scene, "probability") || starts_with(h.scene, "stripes"))
    s += "The probabilities and separations come from uncoupled runs (whether a pair touches at a gap depends only on "
         "the motion before the first contact), so the contact law does not enter them.";
  return "<p>" + s + "</p>\n";
}

std::string records_html(const results::Results& r) {
  const results::RecordTable& rec = r.records;
  const std::size_t per = std::max<std::size_t>(1, r.polarities());
  std::vector<std::vector<std::string>> rows{{"record", "name (event, station)", "source", "synthetic", "PGA g", "dt s",
                                              "points", "duration s"}};
  for (std::size_t k = 0; k < rec.size(); k += per)
    // table_html reads Markdown inline text: the names escaped for it, shown as they are
    rows.push_back({report::md_cell(rec.id[k]), report::md_cell(k < rec.name.size() ? rec.name[k] : ""),
                    report::md_cell(k < rec.source.size() ? rec.source[k] : ""), report_detail::synthetic_cell(rec, k),
                    fmt::format("{:.3f}", rec.pga_g[k]), fmt::format("{:g}", rec.dt[k]), std::to_string(rec.npts[k]),
                    fmt::format("{:.2f}", rec.duration[k])});
  return report_detail::table_html(rows, per == 2 ? "Records (each applied with both signs)" : "Records");
}

std::string provenance_html(const results::Results& r, const std::string& id, Toc& toc) {
  const results::Header& h = r.header;
  toc.entries.emplace_back(id, "Provenance: run, accuracy, settings, records, study file");
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  std::string s = "<section id=\"" + id + "\">\n<h2>Provenance</h2>\n";
  s += dl({{"results file", "<code>" + html_escape(r.path) + "</code>"},
           {"study file", "<code>" + html_escape(h.study_path) + "</code>"},
           {"written", html_escape(h.date)},
           {"program", html_escape(h.program_version) + ", commit <code>" + html_escape(h.git_commit) + "</code>"},
           {"build", html_escape(h.build) + fmt::format("; {} MPI rank(s)", h.ranks)},
           {"machine", html_escape(run_machine(h))},
           {"wall time", std::isfinite(h.wall_time_s) ? fmt::format("{:.2f} s", h.wall_time_s) : "n/a"},
           {"seed", std::to_string(h.seed)},
           {"analyses", fmt::format("{} ({} excluded)", h.total_analyses, h.excluded_analyses)},
           {"report rendered", fmt::format("on host '{}'", html_escape(host))}});
  s += "<h3>Accuracy of the engine for this study</h3>\n" + accuracy_statement(h);
  std::vector<std::vector<std::string>> rows{{"section", "key", "value"}};
  for (const auto& e : r.settings.entries)  // Markdown inline text for table_html: escaped, shown as they are
    rows.push_back({e.section.empty() ? "(top)" : report::md_cell(e.section), report::md_cell(e.key),
                    report::md_cell(setting_text(e.value))});
  s += "<h3>Settings as the run used them</h3>\n" + report_detail::table_html(rows);
  s += "<h3>Records</h3>\n";
  if (const auto* g = r.settings.find("records.motions", "generator"); g && std::holds_alternative<std::string>(*g))
    s += "<p>Generated by the study (<code>[records.motions]</code>, the generator of <code>pounding motions</code>): " +
         html_escape(std::get<std::string>(*g)) + "</p>\n";
  s += records_html(r);
  s += "<h3>Study file</h3>\n<pre><code>" + html_escape(h.study_text) + "</code></pre>\n";
  return s + "</section>\n";
}

std::string subtitle(const results::Results& r) {
  return fmt::format("<p class=\"sub\">{} · <code>{}</code> · written {} · commit {}</p>\n",
                     r.header.scene.empty() ? "study" : html_escape(r.header.scene + " scene"), html_escape(r.path),
                     html_escape(r.header.date), html_escape(r.header.git_commit.substr(0, 12)));
}

// One study's parts: its Markdown blocks and its figures.
struct Study {
  const results::Results* r;
  std::vector<MdBlock> blocks;
  FigureSet figures;
};

Study study_of(const results::Results& r, const FigureOptions& options, const WorkHook* hook) {
  const ReportTexts t = report_texts(r, options.enabled, hook);  // one bootstrap for the tables and the pair figure
  Study s{&r, report_detail::parse_markdown(t.markdown), {}};
  if (!options.enabled)
    s.figures.left_out.push_back("figures: left out on request (--no-figures)");
  else
    s.figures = report_figures(r, t.csv, options);
  return s;
}

std::string title_of(const Study& s) { return s.r->header.title.empty() ? s.r->path : s.r->header.title; }

}  // namespace

std::string report_html(const results::Results& r, const FigureOptions& options, const WorkHook* hook) {
  const Study s = study_of(r, options, hook);
  Toc toc;
  toc.entries.emplace_back("answer", "The answer");
  toc.entries.emplace_back("figures", "Figures");
  std::string tables = tables_html(s.blocks, "", toc);
  std::string prov = provenance_html(r, "provenance", toc);
  return page_head(title_of(s)) + "<header><h1>" + html_escape(title_of(s)) + "</h1>\n" + subtitle(r) + "</header>\n" +
         answer_html(s.blocks) + toc.html() + figures_html(s.figures, "figures") +
         "<section id=\"report\">\n" + tables + "</section>\n" + prov + "</body>\n</html>\n";
}

std::string compare_html(const std::vector<const results::Results*>& files, const FigureOptions& options) {
  std::vector<Study> studies;
  for (std::size_t i = 0; i < files.size(); ++i) {
    FigureOptions o = options;  // study A's figures see the others (a bridge's other input: the "inputs" figure)
    if (i == 0)
      for (std::size_t j = 1; j < files.size(); ++j) o.with.push_back(files[j]->path);
    studies.push_back(study_of(*files[i], o, nullptr));
  }
  Toc toc;
  toc.entries.emplace_back("answers", "The answers side by side");
  std::string answers = "<section id=\"answers\" aria-label=\"The answers side by side\"><div class=\"columns\">\n";
  std::string parts;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    const Study& s = studies[i];
    const std::string letter(1, static_cast<char>('A' + i)), p = fmt::format("s{}", i + 1);
    answers += "<div class=\"study\"><h2 class=\"study-title\">" + letter + ": " + html_escape(title_of(s)) + "</h2>\n" +
               answer_html(s.blocks, p + "-answer") + "</div>\n";
    toc.entries.emplace_back(p, letter + ": " + report::md_text(title_of(s)));  // Toc::html reads Markdown
    Toc inner;
    parts += "<section id=\"" + p + "\"><h2>" + letter + ": " + html_escape(title_of(s)) + "</h2>\n" +
             figures_html(s.figures, p + "-figures") + tables_html(s.blocks, p + "-", inner) +
             provenance_html(*s.r, p + "-provenance", inner) + "</section>\n";
  }
  answers += "</div></section>\n";
  std::string title = "Comparison:", files_line;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    title += fmt::format(" {} {}", i ? "vs" : "", title_of(studies[i]));
    files_line += fmt::format("{}{}: <code>{}</code>", i ? " · " : "", static_cast<char>('A' + i), html_escape(studies[i].r->path));
  }
  return page_head(title) + fmt::format("<header><h1>Comparison of {} studies</h1>\n<p class=\"sub\">{}</p></header>\n",
                                        studies.size(), files_line) +
         answers + toc.html() + parts + "</body>\n</html>\n";
}

}  // namespace pounding
