#pragma once
// A system of bodies (docs/architecture.md Part 2, §2.1–2.2.4): the topology that every lane of a batch shares
// (D1). Bodies are chains of DOFs (an SDOF, a shear stick, an isolated stick), springs are hysteretic elements
// between a DOF and the support or another DOF, contact elements join two sides (a DOF, two DOFs with shape
// functions, or a wall). Per-lane numbers (masses, stiffnesses, gaps) live in physics::SystemBatch; a System holds
// none. Layer `model`: no I/O, no exceptions (build() reports problems, the caller raises them).
//
// Conventions (§2.1): a DOF is one lateral translation relative to its body's support, numbered level-major by
// the builders; a spring's deformation is d = u_j - u_i (u_i = 0 for the support, i = ground: no subtraction is
// formed), its force f acts -f on j and +f on i; a contact element's penetration is delta = x_L - x_R - gap and
// its force F >= 0 pushes L left (-F) and R right (+F) -- for the SDOF pair, L = building 1, R = building 2.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "pounding/core/problem.hpp"

namespace pounding::model {

inline constexpr int ground = -1;  // a spring's or a dashpot's i, or a side's DOF: the body's support

enum class SpringRole : std::uint8_t { storey, isolator, link };
enum class SideKind : std::uint8_t { point, interpolated, wall };
enum class DampingForm : std::uint8_t { dashpots, dense };  // dense: classical modal damping (§2.2.3)

// A chain of DOFs, bottom first. `heights` are the floor levels above the support (m), one per DOF: topology,
// the same in every lane (a sample with another storey count is another topology, §2.6.4).
struct Body {
  std::vector<int> dofs;
  std::vector<double> heights;
  int channel = 0;                // the ground-motion channel of its support (one channel until issue 26)
  int floor_dashpot_ref = ground; // ground, or dofs[0] for an isolated superstructure (SB §1 pitfall 3)
  bool storey_dashpots = false;   // Rayleigh's stiffness-proportional part: a dashpot on each storey spring
  DampingForm damping = DampingForm::dashpots;
  bool isolated = false;          // dofs[0] is the base mass on the isolators
  std::string label;              // "building1": results and messages
  bool operator==(const Body&) const = default;
};

// A hysteretic element between DOF i (or ground) and DOF j. `law`: index in the hysteresis registry
// (0 = bilinear kinematic hardening, model/hysteresis/bilinear_kinematic.hpp). `storey`: 1-based storey number in
// its body for role storey (storey s joins floor s-1 and floor s), 0 for the isolator.
struct Spring {
  int i = ground, j = 0;
  int law = 0;
  SpringRole role = SpringRole::storey;
  int body = 0;
  int storey = 1;
  int channel = 0;  // a link to the ground (i = ground): the ground-motion channel of its wall (issue 26)
  bool operator==(const Spring&) const = default;
};

// One side of a contact element: a point (DOF p), an interpolated point (x = N1 u_p + N2 u_q, N2 per lane in
// SystemBatch::weight, N1 = 1 - N2: a floor striking the column between floor p and floor q = the floor above; p =
// ground for the column between the ground and a fixed building's first floor, x = N2 u_q) or a wall (the support
// of `channel`, x = 0 relative to it).
struct Side {
  SideKind kind = SideKind::point;
  int p = -1, q = -1;
  int channel = 0;
  bool operator==(const Side&) const = default;
};

struct ContactElement {
  Side left, right;   // L and R: delta = x_L - x_R - gap
  int group = 0;      // index in System::groups()
  int level = 0;      // the floor number where it acts (1 = first floor), for results and labels
  std::string label;  // "level 3", "moat left"
  // an interpolated side's position along its column, xi = (z_c - z_p) / (z_q - z_p) (linear shape functions: N2 =
  // xi), from the floor levels (topology); physics::set_contacts copies it into SystemBatch::weight. 0 otherwise.
  double xi = 0.0;
  bool operator==(const ContactElement&) const = default;
};

// The elements that share one contact law (one ContactModel per group at run time). The probability scene
// switches the study_gap groups off (law none) for the uncoupled run (§2.6.2, D11).
struct ContactGroup {
  std::string name = "pounding";
  bool study_gap = true;  // the element's gap is the study gap (plus a per-element offset, SystemBatch::gap)
  bool operator==(const ContactGroup&) const = default;
};

// Immutable after build(); a value (copied into a study's plan, compared with ==, written to /system).
class System {
 public:
  struct Parts {
    std::vector<Body> bodies;
    std::vector<Spring> springs;
    std::vector<ContactElement> contacts;
    std::vector<ContactGroup> groups;
    int channels = 1;
    bool operator==(const Parts&) const = default;
  };

  System() = default;  // empty: ndof() == 0

  // Every problem of `parts` (empty: build() may be called): at least one body; every DOF index in [0, ndof)
  // and in exactly one body (ndof = the number of DOFs of all bodies); heights one per DOF, finite, > 0 and
  // strictly increasing up each body; every DOF has exactly one storey or isolator spring with j == dof whose
  // i is the DOF directly below j in its body (ground for the lowest), role isolator exactly at the base of an
  // isolated body and storey numbers counting floors from 1 (spring.body = the body of j); link springs join two
  // distinct DOFs; laws >= 0; sides' DOFs valid (a point: p; an interpolated point: p and q = the DOF directly
  // above p in one body, or p = ground and q the lowest DOF of a body that is not isolated; xi in [0, 1]; a wall: a
  // valid channel), at most one interpolated side and at most one wall per
  // element, no DOF on both sides; groups in range with unique non-empty names; non-empty, unique body labels
  // and non-empty element labels; channels >= 1 and bodies' channels in range. Each problem names the part
  // ("body 1 (building2) dofs[2]") in `where`.
  static std::vector<Problem> check(const Parts& parts);
  // The system of `parts`, with the derived adjacency below. Precondition: check(parts) is empty (a violated
  // precondition is a programming error: std::logic_error naming the first problem).
  static System build(Parts parts);

  // The pair of today, the smallest system: DOF 0 = building 1 (left), DOF 1 = building 2 (right), spring s
  // from ground to DOF s (bilinear), floor dashpots to ground, no storey dashpots, one point-point element
  // (L = DOF 0, R = DOF 1, "level 1") in one study-gap group "pounding"; both floors at the default storey
  // height 3.2 m, labels "building1", "building2". model::shear_buildings of two one-storey sticks of 3.2 m is
  // this system (==); of other heights it differs only in heights, and is_sdof_pair() still holds.
  static System sdof_pair();

  int ndof() const { return ndof_; }
  int channels() const { return parts_.channels; }
  const std::vector<Body>& bodies() const { return parts_.bodies; }
  const std::vector<Spring>& springs() const { return parts_.springs; }
  const std::vector<ContactElement>& contacts() const { return parts_.contacts; }
  const std::vector<ContactGroup>& groups() const { return parts_.groups; }
  const Parts& parts() const { return parts_; }

  // Derived once by build() (src/model/system.cpp):
  int body_of(int dof) const { return body_of_[static_cast<std::size_t>(dof)]; }
  // the storey or isolator spring with j == dof (exactly one per DOF)
  int spring_below(int dof) const { return below_[static_cast<std::size_t>(dof)]; }
  // every spring with i == dof (storey springs of the floor above, links), in spring order
  const std::vector<int>& springs_above(int dof) const { return above_[static_cast<std::size_t>(dof)]; }
  // every element with a side on dof (p or q), in element order, each once
  const std::vector<int>& elements_at(int dof) const { return elements_at_[static_cast<std::size_t>(dof)]; }
  bool any_storey_dashpots() const;
  // Some body with DampingForm::dense (classical modal damping: SystemBatch::c_dense).
  bool any_dense_damping() const;
  // The pair's structure (what run_system sends to the pair kernel): sdof_pair() up to heights and labels --
  // two one-DOF bodies (DOF 0 left, DOF 1 right) on ground springs of law 0 with floor dashpots to ground, no
  // storey dashpots, not isolated, one channel, and one point-point element L = 0, R = 1 in one study-gap group.
  bool is_sdof_pair() const { return sdof_pair_; }

  bool operator==(const System& o) const { return parts_ == o.parts_; }

 private:
  Parts parts_;
  int ndof_ = 0;
  std::vector<int> body_of_, below_;
  std::vector<std::vector<int>> above_, elements_at_;
  bool sdof_pair_ = false;
};

}  // namespace pounding::model
