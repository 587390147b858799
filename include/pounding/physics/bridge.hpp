#pragma once
// A bridge as a chain of segments (issue 26 §1; docs/architecture.md §2.2.5; ../shared/research/
// systems-and-bridges.md §5): frames (SDOF bodies, left to right) joined at expansion joints (a gap and the contact
// law of contact group 0, "joints"), with cable restrainers and hinge bearings across the joints and abutments at the
// two ends (walls with springs: backfill after the expansion gap, and a bearing acting both ways). Every connection
// but the joint's contact is a link spring (model::SpringRole::link) of a registered hysteresis law
// (model/hysteresis/registry.hpp): restrainer law 3 (tension gap, slack), bearings law 0 (bilinear kinematic
// hardening: k0, F_y, alpha; M&D's 6 kip/in, 2.4 kip, 33 %), backfill law 4 (elastic-perfectly-plastic after the
// gap, Caltrans SDC) or 5 (hyperbolic, Shamsabadi et al. 2007). Frames are SDOF (a pier and its deck) with
// bilinear or Q-Hyst (law 6) hysteresis: an SDOF (a pier and its deck, `storeys` = 1), or a short shear stick of
// `storeys` = n levels (pier levels under the deck; issue 26 §1), whose numbers are a shear building's
// (physics/shear_building.hpp shear_numbers: level masses, storey stiffnesses given or scaled to the frame's period
// T1 with a uniform profile, storey strengths, Rayleigh damping on modes 1 and 2 or classical modal damping) and
// whose every storey spring has the frame's hysteresis. Joints, restrainers, bearings and abutments attach to the
// DECK, the frame's top level; the frame's pier stands on its support's channel.
//
// Numbering (frame-major): frame k's levels are DOFs base_k .. base_k + n_k - 1 bottom first (base_k = the levels of
// the frames left of it), its deck the last; springs: the frames' storey springs in DOF order (spring d under DOF d),
// then per joint its restrainer and bearing (when present), then the left abutment's backfill and bearing, then the
// right one's; element k = joint k (between the decks of frames k and k+1, L = frame k's deck: penetration
// u_deck(k) - u_deck(k+1) - gap). With one level per frame DOF k = frame k, spring k = frame k's. Sign conventions as model/system.hpp: a link's
// deformation is u_j - u_i, the restrainer's j the right frame (its opening), a wall link's i the ground.
// Multi-support: frame k sits on channel `support` (0 for uniform input), the left abutment's wall on channel
// left.support, the right one's on right.support (model::Spring::channel of the wall links).
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pounding/model/system.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {

struct BridgeBilinear {  // a bilinear link (hinge or abutment bearing): k0, F_y (inf: linear), alpha
  double k = 0.0, fy = std::numeric_limits<double>::infinity(), alpha = 0.0;
};
struct BridgeFrame {
  std::string label;           // "frame1" when empty
  double mass = 0.0;           // kg
  double period = 0.0;         // s (k = m (2 pi / T)^2) when stiffness is 0
  double stiffness = 0.0;      // N/m
  double zeta = 0.05;          // floor dashpot c = 2 zeta sqrt(k m)
  double fy = std::numeric_limits<double>::infinity();  // N (inf: linear)
  double alpha = 0.0;          // post-yield ratio
  bool qhyst = false;          // Q-Hyst (law 6) instead of bilinear kinematic hardening
  double beta = 0.5;           // Q-Hyst's unloading exponent
  double height = 10.0;        // m: the pier height (labels, drift ratio); a stick's levels at height / n steps
  int support = 0;             // ground-motion channel of the frame's pier
  // A short shear stick (storeys > 1): `mass` and `stiffness` (or `period`: T1 of the stick, uniform stiffness
  // profile) and `fy` are each level's / storey's unless these lists (one value, or one per level, bottom first)
  // give them; zeta is Rayleigh's ratio at modes 1 and 2, or (modal) every mode's (modal_zeta per mode, the last
  // repeating). One level: the SDOF above, bit for bit.
  int storeys = 1;
  std::vector<double> storey_mass, storey_stiffness, storey_yield, storey_height;
  bool modal = false;
  std::vector<double> modal_zeta;
};
struct BridgeJoint {
  double gap = 0.0;                             // m: the expansion joint's gap (contact element, group 0)
  double kc = 0.0, e = 1.0;                     // the joint's contact stiffness (law units) and restitution
  std::optional<model::TensionGap::Spec> restrainer;  // side is set by the builder (+1: opening)
  std::optional<BridgeBilinear> bearing;
};
enum class Backfill { none, epp, hyperbolic };
struct BridgeAbutment {
  Backfill backfill = Backfill::none;
  model::CompressionGap::Spec epp;      // k, fy (P_bw), alpha, gap; side set by the builder
  model::HyperbolicGap::Spec hyperbolic;  // k_max, k_ur, rf, f_ult, gap; side set by the builder
  std::optional<BridgeBilinear> bearing;
  int support = 0;  // the wall's ground-motion channel
  double width = 0.0, height = 0.0;  // m: the back wall that gave epp's k and fy by Caltrans SDC (0: k, fy given)
  bool present() const { return backfill != Backfill::none || bearing.has_value(); }
};
struct BridgeSpec {
  std::vector<BridgeFrame> frames;  // >= 1, left to right
  std::vector<BridgeJoint> joints;  // frames - 1
  BridgeAbutment left, right;
  int channels() const;             // 1 + the largest support index
};

// Where the builder put things (indices into the System's springs and contacts; -1: absent).
struct BridgeIndex {
  std::vector<int> frame_spring, restrainer, bearing;  // per frame (its first storey's); per joint; per joint
  std::vector<int> frame_dof, deck;                     // per frame: its first level's DOF, its deck's DOF
  std::vector<std::string> frame_label;                 // per frame: its label, or "frame<k>"
  int left_backfill = -1, left_bearing = -1, right_backfill = -1, right_bearing = -1;
  std::vector<std::string> spring_label;                // every spring: "frame 1", "restrainer 1", "abutment left backfill"
};
BridgeIndex bridge_index(const BridgeSpec& spec);

// Problems of the spec's numbers (empty: bridge_system and set_bridge may be called): masses, periods/stiffnesses,
// damping, yields, hardening, gaps, restrainer/bearing/backfill values, supports >= 0. `where` prefix per item
// ("frames[2] mass").
std::vector<Problem> check_bridge(const BridgeSpec& spec);
// The topology: one body per frame (channel = its support), springs and elements as numbered above, one contact
// group "joints" (study_gap: the study gap is the joint gap).
model::System bridge_system(const BridgeSpec& spec);
// Lane `lane` of batch (whose system is bridge_system(spec)): masses, dashpots, springs, joint gaps, kc and e.
void set_bridge(SystemBatch& batch, std::size_t lane, const BridgeSpec& spec);
// A frame's stiffness (given, or from its period; a stick: its storeys' first).
double frame_stiffness(const BridgeFrame& f);
// A stick frame's numbers (storeys >= 1; shear_numbers of its levels). For one level the SDOF's own numbers are
// set_bridge's (k = m (2 pi / T)^2, c = 2 zeta sqrt(k m)), not these.
ShearNumbers frame_numbers(const BridgeFrame& f);
// The frame's total mass (kg) and fundamental period (s): m and 2 pi sqrt(m / k) for one level.
double frame_mass(const BridgeFrame& f);
double frame_period(const BridgeFrame& f);
// The frame's storey heights (m, bottom first): height / storeys each unless storey_height gives them.
std::vector<double> frame_storey_heights(const BridgeFrame& f);
// Scale a frame's masses by fm and its stiffnesses by fk (a sampled frame): one level its mass and stiffness; a
// stick its resolved level masses and storey stiffnesses (lists afterwards).
void scale_frame(BridgeFrame& f, double fm, double fk);

}  // namespace pounding::physics
