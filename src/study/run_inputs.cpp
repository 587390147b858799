// The run's inputs phase: the study and its records read on every rank, the outputs checked, the plan, the banner.
#include "run_phases.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <algorithm>
#include <memory>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/core/error.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/core/files.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/sdof.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/histories.hpp"
#include "pounding/study/make_results.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/refine.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/spill.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"

namespace pounding::study_run {

namespace {

// A finished results file is replaced by a rerun of its own study (the same study text) only: another study's
// results, or a file that is not a results file, need --force (as a checkpoint with progress does).
void check_replaceable_results(const std::string& out, const std::string& where, const Study& study) {
  struct stat st {};
  if (::stat(out.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) return;
  results::Header h;
  try {
    h = results::load_header(out);
  } catch (const std::exception&) {
    throw InputError(fmt::format("{} exists and is not a pounding results file", out), where,
                     "give another output path, or rerun with --force to replace it");
  }
  if (h.study_text == study.text) return;
  throw InputError(fmt::format("{} holds the results of another study (\"{}\", {}, written {})", out, h.title,
                               h.study_path, h.date),
                   where, "give another output path, or rerun with --force to replace them");
}

// The run's outputs -- the results file, its checkpoint <out>.ckpt and with [report] html = true the HTML report
// (the results' name with .html) -- before any work: none of them may be a file the study reads, nor one of the
// others (--out r.html would leave only the report), nor a folder, FIFO or device (the checkpoint is read back: a
// FIFO there would block the run forever).
void check_outputs(const Inputs& in) {
  const std::vector<std::string> inputs = study_input_files(in.study);
  const std::string ckpt = in.out + ".ckpt", ckpt_where = in.out_where + " (its checkpoint " + ckpt + ")";
  files::check_output_not_input(in.out, inputs, in.out_where);
  files::check_output_not_input(ckpt, inputs, ckpt_where);
  files::check_output_not_input(ckpt, {in.out}, ckpt_where, "the results file");
  files::check_output_path(in.out, in.out_where);
  files::check_replaceable(ckpt, ckpt_where, fmt::format("remove {} (the checkpoint is a regular file that pounding "
                                                          "writes and reads back), or give another --out", ckpt));
  if (!in.study.html) return;
  const std::string html = files::with_extension(in.out, ".html");
  const std::string html_where = in.out_where + " ([report] html = true: its .html, " + html + ")";
  files::check_output_not_input(html, {in.out}, html_where, "the results file",
                                fmt::format("give the results a name with another extension, e.g. --out {}: the report "
                                            "goes beside it as {}", files::with_extension(in.out, ".h5"), html));
  files::check_output_not_input(html, {ckpt}, html_where, "the checkpoint");
  files::check_output_not_input(html, inputs, html_where);
  files::check_output_path(html, html_where);
}

}  // namespace

// Every rank parses the same text (rank 0 reads the file) and holds the same records (each rank makes a share,
// the shares are exchanged). The output is checked and the checkpoint locked (rank 0) before any work: a bad path
// or a second run on one output stops here.
Inputs load_inputs(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                   std::optional<Checkpoint>& ckpt, const RunContext& ctx) {
  std::string text;
  session.agree([&] {
    if (session.root()) text = files::read_text(study_path, "the study file");
  });
  session.broadcast(text);
  std::optional<Inputs> in;
  session.agree([&] { in.emplace(Inputs{parse_study(text, study_path), {}, {}, {}, {}, {}, {}}); });
  in->out = opt.out_given ? opt.out : in->study.output;
  in->out_where = opt.out_given ? "--out" : study_path + ": output";
  session.agree([&] {
    if (!session.root()) return;
    check_outputs(*in);
    if (!opt.force) check_replaceable_results(in->out, in->out_where, in->study);
    ckpt.emplace(in->out + ".ckpt", !in->study.per_model);  // per_model = false: snapshots (study/checkpoint.hpp)
    files::remove_stale_temporaries(in->out);
    files::remove_stale_temporaries(ckpt->path());  // a snapshot's temporary left by a SIGKILL
  });
  // the records: each rank reads or synthesises its share (records rank, rank + ranks, ...) on its threads, the
  // shares are exchanged, and every rank joins them into the same records bit for bit (a record that failed is
  // the first error in record order on every rank)
  // (generated motions: with progress lines and the stop flag; a stop leaves records unmade on every rank's share,
  // so every rank sees it in the joined shares and returns stopped together)
  RecordPlan plan;
  std::string share;
  const WorkHook hook = ctx.hook();
  session.agree([&] {
    inject_fault("load", session.rank());
    plan = plan_study_records(in->study);
    share = make_record_share(plan, session.rank(), session.size(), 0, &hook);
  });
  const std::vector<std::string> shares = session.allgather(share);
  share.clear();
  session.agree([&] {
    if (in->study.select > 0) in->selection.emplace();
    std::vector<StudyRecord> made;
    try {
      made = join_record_shares(shares, plan.count);
    } catch (const Cancelled&) {
      in->stopped = true;
      return;
    }
    in->records = finish_study_records(in->study, std::move(made), in->selection ? &*in->selection : nullptr);
    if (in->records.empty()) throw InputError("the study resolves to no records", study_path, "check [records]");
    // shear buildings: every sample's highest frequency against the integration step, before any work; without
    // [analysis] substeps / max_dt it chooses a stable max_dt, so every rank runs it (the same choice everywhere)
    check_shear_steps(in->study, in->records);
    in->histories = resolve_histories(in->study, in->records);  // a record or model that is not there: before any work
    check_history_memory(in->study, in->records, in->histories.size());
    if (in->study.intensity.enabled) {
      std::vector<double> im;
      for (const auto& rr : in->records) im.push_back(intensity(rr.record, in->study.intensity.im));
      in->stripes = plan_stripes(in->study.intensity, im);
      check_stripes_reachable(in->study.intensity, in->stripes);  // before any work, not a failed fit after it
    }
  });
  return std::move(*in);
}

// ---- phase 2: the work plan ---------------------------------------------------------------------
WorkPlan plan_work(const Inputs& in) {
  const Study& s = in.study;
  WorkPlan L;
  L.records = in.records.size();
  L.stripes = in.stripes.stripes;  // a multiple-stripe unit analyses its block at every stripe
  L.pairs = static_cast<std::size_t>(s.structures.period_pair_count());
  L.samples = static_cast<std::size_t>(s.structures.samples_per_pair);
  L.batch = static_cast<std::size_t>(s.batch);
  L.blocks = (L.samples + L.batch - 1) / L.batch;
  L.gaps = s.gap_ratios.size();
  L.impacts = s.scene == Scene::impacts;
  L.ida = s.intensity.bisection;
  L.per_model = s.per_model;
  L.stream = s.stream;
  // shear buildings: results format 3 with the study's largest topology as /system (format 2 for an SDOF facing a
  // shear building, and for one storey each: system_table gives the SDOF pair nothing)
  if (runs_systems(s.structures))
    if (const std::optional<LaneTopology> t = table_topology(s.structures, s.seed)) {
      SystemBlock block(s);
      const model::System& sys = block.table_system(*t);
      L.system = system_table(sys, block.groups(*t, s.contact), block.element_offsets(sys));
    }
  L.fields = results::unit_schema(L.impacts, L.ida, L.stripes > 0, L.system.extents());
  if (s.restitution && L.impacts) L.fields.push_back(results::restitution_field);  // e(v0): impacts outside its range
  if (s.coarse == CoarsePolicy::refine && L.impacts) L.fields.push_back(results::refine_field);  // each one's substeps
  if (s.restitution && L.impacts && !L.system.empty()) {  // ... and per contact element
    results::FieldSpec f = results::restitution_element_field;
    f.count = static_cast<std::uint32_t>(L.system.extents().elements);
    L.fields.push_back(f);
  }
  return L;
}

namespace {

// "building1: shear building, storeys from each sample's height at 3.2 m, ..." (a study with a shear building)
std::string describe_structure(const StructureModel& m, int i) {
  const BuildingModel b = m.row_building(static_cast<std::size_t>(i));
  if (!b.shear()) return fmt::format("building{}: SDOF (one storey facing the other building's floor nearest its height)", i + 1);
  const std::string yield = b.hysteresis == Hysteresis::elastic ? "elastic storeys"
                            : !b.storey_yield.empty()
                                ? fmt::format("storeys yielding at {:g} N", fmt::join(b.storey_yield, ", "))
                            : b.yield_coefficient.given()       ? "storey yield from the base shear Cy M g"
                                                                 : fmt::format("storeys yielding at drift ratio {:.4g}",
                                                                               b.drift / b.ductility);
  return fmt::format("building{}: shear building, {}, {}, {}, {}, {}", i + 1,
                     !b.storey_heights.empty()
                         ? fmt::format("{} storeys of {:g} m", b.code.storeys, fmt::join(b.storey_heights, ", "))
                     : b.code.storeys > 0 ? fmt::format("{} storeys of {:g} m", b.code.storeys, b.storey_height())
                                        : fmt::format("storeys of {0:g} m, max(1, round(h / {0:g} m)) per sample",
                                                      b.storey_height()),
                     !b.floor_mass.empty() ? fmt::format("floors of {:g} kg", fmt::join(b.floor_mass, ", "))
                                           : "the mass split equally over the floors",
                     !b.storey_stiffness.empty() ? fmt::format("storeys of {:g} N/m", fmt::join(b.storey_stiffness, ", "))
                                            : fmt::format("{} storey stiffnesses scaled to T1", to_string(b.profile)),
                     yield, b.damping_text()) +
         (b.isolated ? "; isolated: " + b.isolation_text() : std::string()) +
         (b.moat ? "; moat: " + b.moat_text() : std::string());
}

// Heavy amplitude scaling distorts a record's magnitude-duration-shape consistency (the research note, 2.3; practice
// keeps factors within about [0.25, 4]): name each record scaled outside that range at a stripe, and where.
void warn_scale_factors(const Inputs& in, const RunContext& ctx) {
  const StripePlan& p = in.stripes;
  if (!p.stripes) return;
  // A selected record ([records] select) is already scaled by its selection factor f_i F: the record's factor
  // against its recording is that times the stripe's.
  const IntensitySpec& x = in.study.intensity;
  const std::size_t P = static_cast<std::size_t>(polarity_count(in.study.polarity));
  std::size_t outside = 0;
  for (std::size_t r = 0; r < p.records; r += P) {
    const double sel = in.selection && r / P < in.selection->selection.scale.size() ? in.selection->selection.scale[r / P] : 1.0;
    std::string at;
    for (std::size_t s = 0; s < p.stripes; ++s) {
      const double f = p.scale[s * p.records + r] * sel;
      if (!p.dropped[s * p.records + r] && (f < 0.25 || f > 4.0))
        at += fmt::format("{}x{:.3g}{} at {:g}", at.empty() ? "" : ", ", f,
                          in.selection ? fmt::format(" (selection {:.3g} x stripe {:.3g})", sel, p.scale[s * p.records + r])
                                       : std::string(),
                          x.levels[s]);
    }
    if (at.empty()) continue;
    ++outside;
    ctx.say(fmt::format("record {}: scale factor outside [0.25, 4] (IM {:.3g} {}): {}", in.records[r].id, p.im[r],
                        im_units(x.im.measure), at));
  }
  if (outside)
    ctx.say(fmt::format("{} of {} records are scaled outside [0.25, 4] at some stripe: large factors can bias "
                        "the response (Baker 2015 prefers records selected near each level); the report counts them",
                        outside, p.records / static_cast<std::size_t>(polarity_count(in.study.polarity))));
}

}  // namespace

void announce(const parallel::Session& session, const Inputs& in, const WorkPlan& L, const RunContext& ctx) {
  if (!session.root()) return;
  ctx.say(fmt::format("pounding run: {} ({} records{}, {} models, scene {}, {} units on {} rank{})", in.study.title,
                      in.records.size() / polarity_count(in.study.polarity),
                      in.study.polarity == Polarity::both ? " x 2 signs" : "", L.models(), to_string(in.study.scene), L.units(), session.size(),
                      session.size() > 1 ? "s" : ""));
  ctx.say(in.study.scene_reason);
  const StructureModel& sm = in.study.structures;
  const bool m = in.study.gap_metres;
  if (sm.bridge)
    ctx.say(fmt::format("a bridge: {}. The study gap {} sets every joint's gap to {} + (its gap - d), d = {:g} m "
                        "(the smallest joint gap); an analysis pounds when ANY joint closes",
                        sm.bridge->describe(), m ? "g (m)" : "ratio x", m ? "g" : "x d", sm.bridge->reference_gap));
  if (sm.row())
    ctx.say(fmt::format("a row of {} buildings, left to right: every joint with the study gap {}; an analysis pounds "
                        "when ANY joint touches",
                        sm.building_count(),
                        m ? "g ([gaps] metres)" : "ratio x d (d = the row's largest joint code separation)"));
  for (int b = 0; b < static_cast<int>(sm.building_count()) && sm.any_shear(); ++b) ctx.say(describe_structure(sm, b));
  if (in.study.polarity == Polarity::both)
    ctx.say(fmt::format("record polarity \"both\": each of the {} records applied with both signs, as two analyses of "
                        "the same record", in.records.size() / 2));
  if (in.selection) {
    ctx.say(fmt::format("records selected to the design spectrum ([records] select = {}, [target_spectrum]):",
                        in.study.select));
    for (const auto& line : in.selection->summary()) ctx.say(line);
  } else if (in.records.size() <= 500 * static_cast<std::size_t>(polarity_count(in.study.polarity))) {
    // A library used whole counts one recording twice when it holds two files of it (the El Centro 1940 N-S
    // motion is in ../shared/records/real as NGA's Array #9 180 and as Peknold's digitisation): say so
    // (motion/library.hpp; the pairwise check is skipped for libraries above 500 records).
    // (a record's reversed copy, [records] polarity = "both", is the same recording by design: left out)
    std::vector<RecordIdentity> ids;
    std::vector<std::size_t> row;
    for (std::size_t k = 0; k < in.records.size(); ++k)
      if (in.records[k].polarity > 0) ids.push_back(identity_of(in.records[k].record)), row.push_back(k);
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (std::size_t j = i + 1; j < ids.size(); ++j)
        if (same_recording(ids[i], ids[j]))
          ctx.say(fmt::format(" WARNING: records {} and {} are one recording ({}, {}, components {} and {}): the "
                              "statistics count that motion twice; drop one file, or choose records with [records] "
                              "select", in.records[row[i]].id, in.records[row[j]].id, ids[i].event_text(), ids[i].station,
                              ids[i].component, ids[j].component));
  }
  if (const StripePlan& p = in.stripes; p.stripes) {
    const IntensitySpec& x = in.study.intensity;
    std::string dropped;
    for (std::size_t s = 0; s < p.stripes; ++s)
      if (const std::size_t d = p.dropped_count(s))
        dropped += fmt::format("{}{} at {:g}", dropped.empty() ? "" : ", ", d, x.levels[s]);
    ctx.say(fmt::format("multiple-stripe analysis: {} stripes of {}{}; every record scaled to each level, the same "
                        "models at every stripe{}",
                        p.stripes, describe(x.im), x.period_pair ? " (period \"pair\": the geometric mean of the "
                                                                  "buildings' median periods)" : "",
                        dropped.empty() ? "" : fmt::format("; records dropped (factor above max_scale = {:g}): {}",
                                                           x.max_scale, dropped)));
  }
  warn_scale_factors(in, ctx);
  for (const auto& rr : in.records)
    if (rr.synthetic && rr.polarity > 0) ctx.say(fmt::format("record {}: synthetic stand-in ({})", rr.id, rr.note));
}

}  // namespace pounding::study_run
