// `pounding bench`: the kernel benchmark (ns per pair-step, median of repeats) on the named workload; with
// --storeys N the system stepper's (ns per DOF-step) on two N-storey shear buildings.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <ctime>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "pounding/physics/bridge.hpp"

#include "cli/commands.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_stepper.hpp"
#include "pounding/workloads/workloads.hpp"

namespace pounding::cli {

namespace {

struct SystemBenchOptions {
  int storeys, repeats;
  std::size_t width;
  bool dynamic;
  std::string isolation;  // "": the shear pair; else building 1 on this bearing (isolated_pair_system)
  int bridge = 0;         // > 0: a chain of this many frames (bridge_spec)
  bool modal = false;     // the shear pair with classical modal damping (dense C) instead of Rayleigh
};

// The bridge workload (issue 26 §5): n frames alternating the four-frame bridge's outer and inner frames (1306 t at
// 0.47 s, 3211 t at 1.12 s, Q-Hyst), 1/2 in hinges with Hertzdamp, a restrainer and a bearing at every joint,
// Caltrans EPP abutments with bearings at both ends. storeys > 1: every frame a shear stick of that many levels (the
// frame's mass spread over them, the same T1, Rayleigh 5 %, Q-Hyst in every storey).
physics::BridgeSpec bridge_spec(int n, int storeys) {
  physics::BridgeSpec b;
  for (int k = 0; k < n; ++k) {
    physics::BridgeFrame f;
    const bool outer = k % 2 == 0;
    f.mass = outer ? 1.30635e6 : 3.21145e6, f.period = outer ? 0.47 : 1.12, f.qhyst = true;
    f.fy = outer ? 3.44291e6 : 8.11355e6;
    if (storeys > 1) f.storeys = storeys, f.mass /= storeys;
    b.frames.push_back(f);
  }
  for (int k = 0; k + 1 < n; ++k) {
    physics::BridgeJoint j;
    j.gap = 0.0127, j.kc = 2.808e10, j.e = 0.6;
    j.restrainer = model::TensionGap::Spec{3.50254e7, 3.73651e6, 0.05, 0.0127, 1};
    j.bearing = physics::BridgeBilinear{1.050761e6, 10675.73, 0.33};
    b.joints.push_back(j);
  }
  for (physics::BridgeAbutment* a : {&b.left, &b.right}) {
    a->backfill = physics::Backfill::epp;
    a->epp = {4.553e8, 6.36e6, 0.0, 0.0254, 1};
    a->bearing = physics::BridgeBilinear{1.050761e6, 10675.73, 0.33};
  }
  return b;
}

// ns per DOF-step (wall / (lanes x DOFs x steps)) of the shear-pair workload through run_system.
void bench_system(const SystemBenchOptions& o, const ContactModel& cm, const KernelSettings& ks,
                  const GroundMotion& gm) {
  const bool iso = !o.isolation.empty();
  if (o.bridge > 0 && iso) throw InputError("--bridge is its own workload", "--bridge", "drop --isolation");
  if (o.modal && (o.bridge > 0 || iso || o.storeys < 2))
    throw InputError("--modal damps the shear pair of 2 or more storeys", "--modal",
                     "give --storeys N >= 2 without --isolation/--bridge, or drop --modal");
  const physics::BridgeSpec spec = bridge_spec(std::max(o.bridge, 1), o.bridge > 0 ? o.storeys : 1);
  const model::System S = o.bridge > 0 ? physics::bridge_system(spec)
                          : iso        ? isolated_pair_system(o.storeys, o.isolation)
                                       : shear_pair_system(o.storeys, o.modal);
  physics::SystemBatch b;
  if (o.bridge > 0) {
    b.resize(S, o.width);
    for (std::size_t l = 0; l < o.width; ++l) {  // lanes differ a little (masses), as a study's samples do
      physics::BridgeSpec x = spec;
      for (physics::BridgeFrame& f : x.frames) f.mass *= 1.0 + 1e-3 * static_cast<double>(l % 97);
      physics::set_bridge(b, l, x);
    }
  } else {
    b = iso ? isolated_pair_batch(S, o.width, o.isolation) : shear_pair_batch(S, o.width);
  }
  const ContactModel groups[] = {cm};
  physics::SystemResult r;
  auto run = [&] {
    if (o.dynamic)
      physics::testing::run_system_dynamic(b, groups, gm, ks, r);
    else
      physics::run_system(b, groups, gm, ks, r);
  };
  run();  // warm-up
  const double steps = static_cast<double>(gm.ag.size() - 1) * ks.substeps;
  const double dof_steps = steps * static_cast<double>(o.width) * S.ndof();
  const std::size_t batches = std::max<std::size_t>(1, static_cast<std::size_t>(4e7 / dof_steps));
  // wall time, and the process's CPU time (std::clock): on a shared, loaded machine the second leaves out the
  // time the process waited for a core
  std::vector<double> ns, cpu;
  for (int rep = 0; rep < o.repeats; ++rep) {
    const std::clock_t c0 = std::clock();
    auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < batches; ++k) run();
    auto t1 = std::chrono::steady_clock::now();
    const std::clock_t c1 = std::clock();
    ns.push_back(std::chrono::duration<double>(t1 - t0).count() * 1e9 / (dof_steps * static_cast<double>(batches)));
    cpu.push_back(static_cast<double>(c1 - c0) / CLOCKS_PER_SEC * 1e9 / (dof_steps * static_cast<double>(batches)));
  }
  std::sort(cpu.begin(), cpu.end());
  std::size_t bad = 0, coarse = 0;  // coarse: the resolution guard's (physics/resolution.hpp), not a failure
  for (auto s : r.status) bad += s != 0, coarse += s == static_cast<std::uint8_t>(LaneStatus::coarse);
  std::sort(ns.begin(), ns.end());
  if (o.bridge > 0)
    fmt::print("workload: bridge ({} frames of {} level(s), {} DOFs, {} joints, {} link springs; {} s record at {} s, {} substeps)\n",
               o.bridge, std::max(o.storeys, 1), S.ndof(), S.contacts().size(), S.springs().size() - S.ndof(),
               gm.total_duration(), gm.dt, ks.substeps);
  else
    fmt::print("workload: {} ({} storeys each, {} DOFs, {} contact elements; {} s record at {} s, {} substeps)\n",
               iso ? "isolated-pair (building 1 on " + o.isolation + ")" : std::string(o.modal ? "shear-pair, modal damping" : "shear-pair"), o.storeys, S.ndof(),
               S.contacts().size(), gm.total_duration(), gm.dt, ks.substeps);
  fmt::print("layout: {}\n", S.is_sdof_pair() && !o.dynamic ? "pair kernel" : "system stepper (dynamic)");
  fmt::print("stepper: {}\ncontact: {}\nwidth: {}\n", to_string(ks.stepper), to_string(cm.law), o.width);
  fmt::print("hardware_threads: {}\n", std::thread::hardware_concurrency());
  fmt::print("ns_per_dof_step_median: {:.3f}\n", ns[ns.size() / 2]);
  fmt::print("ns_per_dof_step_min: {:.3f}\n", ns.front());
  fmt::print("ns_per_dof_step_max: {:.3f}\n", ns.back());
  fmt::print("cpu_ns_per_dof_step_median: {:.3f}\n", cpu[cpu.size() / 2]);
  fmt::print("repeats: {}\n", o.repeats);
  fmt::print("lanes_not_ok: {} ({} coarse)\n", bad, coarse);
}

// --duration > 0, --substeps >= 1, and the record's samples (the motion and its copy in the ground motion) and, for the system workloads, one schedule
// value per integration step (physics::make_schedule), before anything is allocated: --duration 1e9 ended in
// std::bad_alloc.
void check_bench_sizes(double duration, double dt, int substeps) {
  require_positive(duration, "--duration");
  if (substeps < 1) throw InputError("--substeps must be >= 1", "--substeps", "give 1 or more integration steps per record step");
  const double samples = std::floor(duration / dt) + 2.0;
  const double need = 8.0 * (2.0 * samples + samples * std::max(1, substeps)), avail = available_memory_bytes();
  if (!std::isfinite(avail) || need <= avail) return;
  throw InputError(fmt::format("--duration = {:g} s needs {} for its {:.4g} samples at {:g} s, more than the {} of "
                               "memory available on this machine (MemAvailable)",
                               duration, human_bytes(need), samples, dt, human_bytes(avail)),
                   "--duration",
                   fmt::format("give --duration <= {:.4g} s (the default 40 s is the benchmark's workload)",
                               avail / need * duration));
}

}  // namespace

void add_bench(CLI::App& app) {
  struct Opts {
    std::string stepper = "central-difference", contact = "hertzdamp", damping = "lankarani-nikravesh";
    std::size_t width = 256;
    int repeats = 5, substeps = 1;
    double duration = 40.0, dt = 0.005;
    bool energy = false, dynamic = false, modal = false;
    int storeys = 0;
    std::string isolation;
    int bridge = 0;
  };
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("bench", "kernel benchmark: ns per pair-step on a 40 s record at 0.005 s, "
                                        "bilinear pairs (workload 'kernel-bilinear')");
  c->add_option("--stepper", o->stepper, std::string(stepper_names))->capture_default_str();
  c->add_option("--contact", o->contact, std::string(contact_law_names))->capture_default_str();
  c->add_option("--damping-law", o->damping, std::string(damping_law_names))->capture_default_str();
  c->add_option("--width", o->width, "pairs per batch")->capture_default_str();
  c->add_option("--repeats", o->repeats, "timed repeats (the median is reported)")->capture_default_str();
  c->add_option("--substeps", o->substeps, "integration steps per record step")->capture_default_str();
  c->add_option("--duration", o->duration, "record length (s)")->capture_default_str();
  c->add_flag("--energy", o->energy, "also track the energy terms");
  c->add_option("--storeys", o->storeys,
                "workload 'shear-pair': two N-storey shear buildings pounding at every floor (Hertzdamp), "
                "reported in ns per DOF-step; 0: the SDOF pairs")
      ->check(CLI::Range(0, 100));
  c->add_flag("--dynamic", o->dynamic,
              "with --storeys 1: run the SDOF pair through the system stepper's dynamic layout, not the pair kernel");
  c->add_flag("--modal", o->modal, "with --storeys N > 1: classical modal damping (a dense C per building, 5 % each mode)");
  c->add_option("--isolation", o->isolation,
                "with --storeys N: workload 'isolated-pair', building 1 base-isolated on lead-rubber, friction-pendulum "
                "or bouc-wen, building 2 fixed")
      ->check(CLI::IsMember({"lead-rubber", "friction-pendulum", "bouc-wen"}));
  c->add_option("--bridge", o->bridge, "workload 'bridge': a chain of N frames (Q-Hyst, Hertzdamp hinges, restrainers, "
                                       "bearings, abutments), ns per DOF-step; give --substeps 10; with --storeys S "
                                       "every frame a shear stick of S levels")->check(CLI::Range(0, 64));
  c->callback([o] {
    if (o->width < 1) throw InputError("--width must be >= 1", "--width", "give a batch width of 1 or more");
    if (o->repeats < 1) throw InputError("--repeats must be >= 1", "--repeats", "give 1 or more");
    check_bench_sizes(o->duration, o->dt, o->substeps);
    ContactModel cm;
    cm.law = parse_contact_law(o->contact);
    cm.damping = parse_damping_law(o->damping);
    KernelSettings ks;
    ks.stepper = parse_stepper(o->stepper);
    ks.substeps = o->substeps;
    ks.energy = o->energy;
    std::vector<double> ag = builtin_motion(o->dt, o->duration);
    GroundMotion gm{o->dt, ag, 0.0};
    if (!o->isolation.empty() && o->storeys < 1)
      throw InputError("--isolation needs --storeys", "--isolation", "give --storeys N (1 or more)");
    if (o->storeys > 0 || o->bridge > 0)
      return bench_system({o->storeys, o->repeats, o->width, o->dynamic, o->isolation, o->bridge, o->modal}, cm, ks, gm);
    // enough pairs that one repeat takes a measurable time, in batches of `width`
    const double steps = static_cast<double>(ag.size() - 1) * o->substeps;
    const std::size_t batches = std::max<std::size_t>(1, static_cast<std::size_t>(2e7 / (steps * o->width)));
    PairBatch b = benchmark_batch(o->width);
    BatchResult r;
    run_batch(b, cm, gm, ks, r);  // warm-up (and calibration cache)
    std::vector<double> ns;
    std::size_t bad = 0;
    for (int rep = 0; rep < o->repeats; ++rep) {
      auto t0 = std::chrono::steady_clock::now();
      for (std::size_t k = 0; k < batches; ++k) run_batch(b, cm, gm, ks, r);
      auto t1 = std::chrono::steady_clock::now();
      double sec = std::chrono::duration<double>(t1 - t0).count();
      ns.push_back(sec * 1e9 / (steps * static_cast<double>(o->width * batches)));
    }
    for (auto s : r.status) bad += s != 0;
    std::sort(ns.begin(), ns.end());
    fmt::print("workload: kernel-bilinear ({} s record at {} s, {} substeps)\n", o->duration, o->dt, o->substeps);
    fmt::print("stepper: {}\ncontact: {}\nwidth: {}\n", to_string(ks.stepper), to_string(cm.law), o->width);
    fmt::print("hardware_threads: {}\n", std::thread::hardware_concurrency());
    fmt::print("ns_per_pair_step_median: {:.3f}\n", ns[ns.size() / 2]);
    fmt::print("ns_per_pair_step_min: {:.3f}\n", ns.front());
    fmt::print("ns_per_pair_step_max: {:.3f}\n", ns.back());
    fmt::print("repeats: {}\n", o->repeats);
    fmt::print("lanes_not_ok: {}\n", bad);
  });
}

}  // namespace pounding::cli
