#pragma once
// A bridge's description as the input gives it (issue 26 §1; docs/bridges.md): ONE reader for the bridge file of
// `pounding simulate --bridge FILE.toml` (tables [[frame]], [[joint]], [abutment.left|right] at its top level) and
// for a study's [bridge] section ([[bridge.frame]], [[bridge.joint]], [bridge.abutment.left|right]). Every key is
// registered in src/config/study_keys.cpp (sections "bridge", "bridge.frame", "bridge.joint", "bridge.restrainer",
// "bridge.bearing", "bridge.abutment"; docs/study-reference.md lists them with units and ranges).
//
// In a study the joints' gaps become the study's gap axis: d = the smallest joint gap (> 0) is the "code gap" the
// [gaps] ratios multiply, and joint j's gap at ratio x is x d + (gap_j - d) (its offset), so D = max over joints of
// (peak closing_j - offset_j) answers every ratio at once in the probability scene (docs/architecture.md §2.6.2). A
// restrainer's slack must be given in a study (it would otherwise follow the gap, and the uncoupled run would depend
// on the ratio). Frames may be sampled per model: lognormal scatter of each frame's period and mass
// ([bridge] period_cov, mass_cov; median the frame's value), drawn from the bridge's own stream at the model's
// SampleId, so a model's bridge depends only on (seed, sample).
// A stick frame (storeys > 1) is sampled as a whole: its total mass and its T1 scatter, every level's mass scales by
// m / m0 and every storey's stiffness by (m / m0) (T0 / T)^2, so its mode shapes stay and T1 becomes T.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "pounding/physics/bridge.hpp"
#include "pounding/sampling/sampler.hpp"

namespace pounding {

namespace config {
class TableReader;
}

struct BridgeReadDefaults {
  double kc = std::numeric_limits<double>::quiet_NaN();  // a joint's contact_stiffness when absent (NaN: required)
  double e = 1.0;                                        // a joint's restitution when absent
  std::string kc_source = "--kh";                        // what gives kc (named in the error when it is missing)
  std::string e_source = "--e";                          // what gives e
  // kc and e given to a joint are checked against the joint's keys' ranges, as the joint's own values are
  bool study = false;                                    // a study: restrainer slack required, joint gaps > 0
  std::string restitution_given_by;  // non-empty: what gives every joint its restitution (a joint's own is refused)
};

// Reads frame, joint and abutment of `r` (the bridge file's top level, or a study's [bridge]); the tables are named
// prefix + "frame1", prefix + "joint2.restrainer", prefix + "abutment.left" in errors (prefix "" or "bridge.").
// Checks the result with physics::check_bridge. The caller reads its own keys of `r` and calls r.finish().
physics::BridgeSpec read_bridge(config::TableReader& r, const std::string& file, std::string_view prefix,
                                const BridgeReadDefaults& defaults);

// The bridge of a study ([bridge] section).
struct BridgeModel {
  physics::BridgeSpec spec;
  double reference_gap = 0.0;    // d (m): the smallest joint gap
  std::vector<double> offsets;   // per joint: gap_j - d (m)
  double period_cov = 0.0;       // lognormal CoV of each frame's period (0: fixed)
  double mass_cov = 0.0;         // lognormal CoV of each frame's mass (0: fixed)
  bool restitution_given = false;  // some joint gives its own restitution
  std::size_t frames() const { return spec.frames.size(); }
  std::string frame_label(std::size_t k) const;  // the frame's label, or "frame K"
  std::string joint_label(std::size_t j) const;  // "joint J (F1|F2)"
  bool sampled() const { return period_cov > 0 || mass_cov > 0; }
  // "4 frames (F1 2880 t, T 0.47 s, Q-Hyst; ...), 3 joints (...)" for logs and reports.
  std::string describe() const;
};

// Reads a study's [bridge] table: frames, joints, abutments (read_bridge) and samples (models per record, written
// to *samples), period_cov, mass_cov.
// restitution_given_by: non-empty ("[contact] restitution") when a curve gives every joint e(v0): a joint's own
// restitution is then refused.
BridgeModel parse_bridge_model(const toml::table* bridge, const std::string& file, double kc_default,
                               double e_default, std::int64_t* samples, const std::string& restitution_given_by = "");

// Stream of the frames' scatter (sampler.hpp's stream ids).
inline constexpr std::uint64_t bridge_stream = 0x4272696467ull;

// One model's frames (SampledPair::s1, s2, more: frame k = structure(k)): period T (s; lognormal about the frame's
// own, truncated to [0.02, 20] s), mass m (kg; about the frame's, truncated to [1, 1e10] kg), stiffness
// k = m (2 pi / T)^2 (N/m), c = 2 zeta sqrt(k m), the frame's yield force (N; inf: linear), alpha, zeta, height;
// aspect, r, rho, mbar NaN; d = the reference gap, kh = joint 1's contact stiffness. `u` holds two uniforms per
// frame (period, mass), which StructureSampler draws from stream_seed(seed, bridge_stream, id) whether or not a CoV
// is given.
SampledPair bridge_pair(const BridgeModel& b, const SampleId& id, std::span<const double> u);

// The spec of one lane: the model's spec with pair p's frames and every joint's gap = gap + offset_j.
physics::BridgeSpec lane_bridge(const BridgeModel& b, const SampledPair& p, double gap);

}  // namespace pounding
