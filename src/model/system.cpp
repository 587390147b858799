// The System's checks, its derived adjacency and the SDOF pair (model/system.hpp; docs/architecture.md §2.2.1).
#include "pounding/model/system.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <stdexcept>

namespace pounding::model {

namespace {

std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
std::string num(int v) { return std::to_string(v); }

std::string body_name(const System::Parts& p, std::size_t b) {
  const std::string& l = p.bodies[b].label;
  return "body " + std::to_string(b) + (l.empty() ? std::string() : " (" + l + ")");
}
std::string element_name(const System::Parts& p, std::size_t e) {
  const std::string& l = p.contacts[e].label;
  return "contact element " + std::to_string(e) + (l.empty() ? std::string() : " (" + l + ")");
}

// Where each DOF sits: body and position (bottom first); -1 for a DOF in no body (reported once).
struct Placement {
  std::vector<int> body, pos;
  bool valid(int dof) const { return dof >= 0 && static_cast<std::size_t>(dof) < body.size() && body[dof] >= 0; }
};

void check_bodies(const System::Parts& p, int ndof, Placement& at, std::vector<Problem>& out) {
  std::set<std::string> labels;
  for (std::size_t b = 0; b < p.bodies.size(); ++b) {
    const Body& body = p.bodies[b];
    const std::string where = body_name(p, b);
    if (body.dofs.empty())
      out.push_back({"a body has no DOFs", where, "give each body at least one DOF (bottom first)"});
    if (body.heights.size() != body.dofs.size())
      out.push_back({"heights has " + std::to_string(body.heights.size()) + " values for " +
                         std::to_string(body.dofs.size()) + " DOFs",
                     where + " heights", "give one floor height per DOF, bottom first"});
    for (std::size_t k = 0; k < body.heights.size(); ++k) {
      const double h = body.heights[k];
      const std::string wk = where + " heights[" + std::to_string(k) + "]";
      const bool base0 = k == 0 && body.isolated && h == 0.0;  // an isolated base sits at the support's level
      if (!std::isfinite(h) || (h <= 0.0 && !base0))
        out.push_back({"floor height " + num(h) + " must be positive and finite", wk,
                       "give the floor's level above its support in m"});
      else if (k > 0 && !(h > body.heights[k - 1]))
        out.push_back({"floor height " + num(h) + " is not above the floor below (" + num(body.heights[k - 1]) + ")",
                       wk, "give heights strictly increasing up the body"});
    }
    for (std::size_t k = 0; k < body.dofs.size(); ++k) {
      const int d = body.dofs[k];
      const std::string wk = where + " dofs[" + std::to_string(k) + "]";
      if (d < 0 || d >= ndof) {
        out.push_back({"DOF " + num(d) + " is out of range", wk,
                       "number the DOFs 0.." + std::to_string(ndof - 1) + " (ndof = the DOFs of all bodies)"});
      } else if (at.body[d] >= 0) {
        out.push_back({"DOF " + num(d) + " is already in " + body_name(p, static_cast<std::size_t>(at.body[d])), wk,
                       "put every DOF in exactly one body"});
      } else {
        at.body[d] = static_cast<int>(b);
        at.pos[d] = static_cast<int>(k);
      }
    }
    if (body.channel < 0 || body.channel >= p.channels)
      out.push_back({"channel " + num(body.channel) + " is out of range", where + " channel",
                     "give a channel in 0.." + std::to_string(p.channels - 1)});
    const bool base_ref = !body.dofs.empty() && body.floor_dashpot_ref == body.dofs[0];
    if (body.floor_dashpot_ref != ground && !base_ref)
      out.push_back({"floor dashpot reference " + num(body.floor_dashpot_ref) + " is neither ground nor the base",
                     where + " floor_dashpot_ref", "give ground (-1) or dofs[0] of an isolated body"});
    if (base_ref && !body.isolated)
      out.push_back({"floor dashpots reference the base of a body that is not isolated", where + " floor_dashpot_ref",
                     "reference ground, or mark the body isolated"});
    if (body.label.empty())
      out.push_back({"a body has no label", where + " label", "give a label such as \"building1\""});
    else if (!labels.insert(body.label).second)
      out.push_back({"body label '" + body.label + "' is used twice", where + " label", "give each body its own label"});
  }
  for (int d = 0; d < ndof; ++d)
    if (at.body[d] < 0)
      out.push_back({"DOF " + num(d) + " is in no body", "bodies", "put every DOF in exactly one body"});
}

void check_springs(const System::Parts& p, int ndof, const Placement& at, std::vector<Problem>& out) {
  std::vector<int> below(static_cast<std::size_t>(ndof), 0);
  for (std::size_t s = 0; s < p.springs.size(); ++s) {
    const Spring& sp = p.springs[s];
    const std::string where = "spring " + std::to_string(s);
    if (sp.law < 0)
      out.push_back({"hysteresis law " + num(sp.law) + " is out of range", where + " law",
                     "give the index of a hysteresis law (0 = bilinear kinematic hardening)"});
    if (!at.valid(sp.j)) {
      out.push_back({"DOF j = " + num(sp.j) + " is not a DOF of a body", where + " j", "give a DOF of the system"});
      continue;
    }
    const int b = at.body[sp.j], k = at.pos[sp.j];
    const Body& body = p.bodies[static_cast<std::size_t>(b)];
    if (sp.role == SpringRole::link) {
      if (sp.i != ground && !at.valid(sp.i))
        out.push_back({"DOF i = " + num(sp.i) + " is neither ground nor a DOF", where + " i", "give ground (-1) or a DOF"});
      else if (sp.i == sp.j)
        out.push_back({"a link joins DOF " + num(sp.j) + " to itself", where + " i", "give two distinct DOFs"});
      if (sp.i == ground && (sp.channel < 0 || sp.channel >= p.channels))
        out.push_back({"the wall channel " + num(sp.channel) + " is not a ground-motion channel", where + " channel",
                       "give a channel in [0, channels)"});
      continue;
    }
    ++below[static_cast<std::size_t>(sp.j)];
    const int want_i = k == 0 ? ground : body.dofs[static_cast<std::size_t>(k - 1)];
    if (sp.i != want_i)
      out.push_back({"a storey or isolator spring on DOF " + num(sp.j) + " starts at " + num(sp.i) +
                         ", not at the DOF directly below it (" + num(want_i) + ")",
                     where + " i", "join each DOF to the one below it in its body (ground for the lowest)"});
    if (sp.body != b)
      out.push_back({"spring.body = " + num(sp.body) + " but DOF " + num(sp.j) + " is in " +
                         body_name(p, static_cast<std::size_t>(b)),
                     where + " body", "give the body of j"});
    const bool base = body.isolated && k == 0;
    if (base != (sp.role == SpringRole::isolator))
      out.push_back({base ? "the base of an isolated body rests on a storey spring"
                          : "an isolator spring is not under the base of an isolated body",
                     where + " role", "give role isolator exactly to the spring under an isolated body's dofs[0]"});
    const int storey = body.isolated ? k : k + 1;  // isolated: the base is floor 0, the isolator storey 0
    if (sp.storey != storey)
      out.push_back({"storey " + num(sp.storey) + " of a spring on floor position " + num(k) + " should be " +
                         num(storey),
                     where + " storey", "number storeys from 1 up (0: the isolator)"});
  }
  for (int d = 0; d < ndof; ++d)
    if (at.valid(d) && below[static_cast<std::size_t>(d)] != 1)
      out.push_back({"DOF " + num(d) + " has " + std::to_string(below[static_cast<std::size_t>(d)]) +
                         " storey or isolator springs below it",
                     body_name(p, static_cast<std::size_t>(at.body[d])),
                     "give every DOF exactly one spring with j = the DOF (its storey or isolator)"});
}

// The side's DOFs (appended to `dofs`) or a problem.
void check_side(const System::Parts& p, const Placement& at, const Side& side, const std::string& where,
                std::vector<int>& dofs, std::vector<Problem>& out) {
  switch (side.kind) {
    case SideKind::point:
      if (!at.valid(side.p))
        out.push_back({"DOF " + num(side.p) + " is not a DOF of a body", where + " p", "give a DOF of the system"});
      else
        dofs.push_back(side.p);
      return;
    case SideKind::interpolated:
      if (side.p == ground && at.valid(side.q)) {  // the column between the ground and a first floor
        if (at.pos[side.q] != 0 || p.bodies[static_cast<std::size_t>(at.body[side.q])].isolated)
          out.push_back({"DOF q = " + num(side.q) + " is not the first floor of a fixed body", where,
                         "give p = ground only with q = the lowest DOF of a body that is not isolated"});
        dofs.push_back(side.q);
        return;
      }
      if (!at.valid(side.p) || !at.valid(side.q)) {
        out.push_back({"DOFs p = " + num(side.p) + ", q = " + num(side.q) + " are not DOFs of a body", where,
                       "give two DOFs of the system"});
        return;
      }
      if (at.body[side.p] != at.body[side.q] || at.pos[side.q] != at.pos[side.p] + 1)
        out.push_back({"DOFs p = " + num(side.p) + " and q = " + num(side.q) + " are not adjacent floors of one body",
                       where, "give q = the floor directly above p in the same body"});
      dofs.push_back(side.p);
      dofs.push_back(side.q);
      return;
    case SideKind::wall:
      if (side.channel < 0 || side.channel >= p.channels)
        out.push_back({"wall channel " + num(side.channel) + " is out of range", where + " channel",
                       "give a channel in 0.." + std::to_string(p.channels - 1)});
      return;
  }
  out.push_back({"unknown side kind", where + " kind", "give point, interpolated or wall"});
}

void check_contacts(const System::Parts& p, const Placement& at, std::vector<Problem>& out) {
  for (std::size_t e = 0; e < p.contacts.size(); ++e) {
    const ContactElement& el = p.contacts[e];
    const std::string where = element_name(p, e);
    std::vector<int> left, right;
    check_side(p, at, el.left, where + " left", left, out);
    check_side(p, at, el.right, where + " right", right, out);
    if (el.left.kind == SideKind::wall && el.right.kind == SideKind::wall)
      out.push_back({"both sides are walls", where, "give at least one side on a DOF"});
    if (el.left.kind == SideKind::interpolated && el.right.kind == SideKind::interpolated)
      out.push_back({"both sides are interpolated", where, "interpolate one side only (a floor meets a column)"});
    for (int d : left)
      if (std::find(right.begin(), right.end(), d) != right.end())
        out.push_back({"DOF " + num(d) + " is on both sides", where, "give the two sides distinct DOFs"});
    if (el.group < 0 || static_cast<std::size_t>(el.group) >= p.groups.size())
      out.push_back({"group " + num(el.group) + " is out of range", where + " group",
                     "give a group in 0.." + std::to_string(static_cast<int>(p.groups.size()) - 1)});
    if (!(el.xi >= 0.0 && el.xi <= 1.0))
      out.push_back({"xi = " + std::to_string(el.xi) + " is outside [0, 1]", where + " xi",
                     "give the interpolated side's position along its column, 0 at p, 1 at q"});
    if (el.level < 0)
      out.push_back({"level " + num(el.level) + " is negative", where + " level", "give the floor number (1 = first)"});
    if (el.label.empty())
      out.push_back({"a contact element has no label", where + " label", "give a label such as \"level 1\""});
  }
  std::set<std::string> names;
  for (std::size_t g = 0; g < p.groups.size(); ++g) {
    const std::string where = "contact group " + std::to_string(g);
    if (p.groups[g].name.empty())
      out.push_back({"a contact group has no name", where + " name", "give a name such as \"pounding\""});
    else if (!names.insert(p.groups[g].name).second)
      out.push_back({"contact group name '" + p.groups[g].name + "' is used twice", where + " name",
                     "give each group its own name"});
  }
}

bool pair_structure(const System& s) {
  if (s.ndof() != 2 || s.channels() != 1 || s.bodies().size() != 2 || s.springs().size() != 2 ||
      s.contacts().size() != 1 || s.groups().size() != 1 || !s.groups()[0].study_gap)
    return false;
  for (int b = 0; b < 2; ++b) {
    const Body& body = s.bodies()[static_cast<std::size_t>(b)];
    const Spring& sp = s.springs()[static_cast<std::size_t>(b)];
    if (body.dofs != std::vector<int>{b} || body.channel != 0 || body.floor_dashpot_ref != ground ||
        body.storey_dashpots || body.damping != DampingForm::dashpots || body.isolated)
      return false;
    if (sp.i != ground || sp.j != b || sp.law != 0 || sp.role != SpringRole::storey) return false;
  }
  const ContactElement& el = s.contacts()[0];
  return el.left.kind == SideKind::point && el.left.p == 0 && el.right.kind == SideKind::point && el.right.p == 1 &&
         el.group == 0;
}

}  // namespace

std::vector<Problem> System::check(const Parts& p) {
  std::vector<Problem> out;
  if (p.channels < 1)
    out.push_back({"channels = " + num(p.channels) + " must be >= 1", "channels", "give one channel per support motion"});
  if (p.bodies.empty()) {
    out.push_back({"a system has no bodies", "bodies", "give at least one body"});
    return out;
  }
  int ndof = 0;
  for (const Body& b : p.bodies) ndof += static_cast<int>(b.dofs.size());
  Placement at{std::vector<int>(static_cast<std::size_t>(ndof), -1), std::vector<int>(static_cast<std::size_t>(ndof), -1)};
  check_bodies(p, ndof, at, out);
  check_springs(p, ndof, at, out);
  check_contacts(p, at, out);
  return out;
}

System System::build(Parts parts) {
  const std::vector<Problem> problems = check(parts);
  if (!problems.empty())
    throw std::logic_error("System::build: " + problems.front().what + ", " + problems.front().where);
  System s;
  s.parts_ = std::move(parts);
  const Parts& p = s.parts_;
  for (const Body& b : p.bodies) s.ndof_ += static_cast<int>(b.dofs.size());
  const auto n = static_cast<std::size_t>(s.ndof_);
  s.body_of_.assign(n, -1);
  s.below_.assign(n, -1);
  s.above_.assign(n, {});
  s.elements_at_.assign(n, {});
  for (std::size_t b = 0; b < p.bodies.size(); ++b)
    for (int d : p.bodies[b].dofs) s.body_of_[static_cast<std::size_t>(d)] = static_cast<int>(b);
  for (std::size_t k = 0; k < p.springs.size(); ++k) {
    const Spring& sp = p.springs[k];
    if (sp.role != SpringRole::link) s.below_[static_cast<std::size_t>(sp.j)] = static_cast<int>(k);
    if (sp.i != ground) s.above_[static_cast<std::size_t>(sp.i)].push_back(static_cast<int>(k));
  }
  for (std::size_t e = 0; e < p.contacts.size(); ++e) {
    const ContactElement& el = p.contacts[e];
    for (const Side* side : {&el.left, &el.right}) {
      if (side->kind == SideKind::wall) continue;
      for (int d : {side->p, side->q}) {
        if (d < 0) continue;
        auto& list = s.elements_at_[static_cast<std::size_t>(d)];
        if (list.empty() || list.back() != static_cast<int>(e)) list.push_back(static_cast<int>(e));
      }
    }
  }
  s.sdof_pair_ = pair_structure(s);
  return s;
}

bool System::any_storey_dashpots() const {
  return std::any_of(parts_.bodies.begin(), parts_.bodies.end(), [](const Body& b) { return b.storey_dashpots; });
}

bool System::any_dense_damping() const {
  return std::any_of(parts_.bodies.begin(), parts_.bodies.end(),
                     [](const Body& b) { return b.damping == DampingForm::dense; });
}

System System::sdof_pair() {
  Parts p;
  for (int b = 0; b < 2; ++b) {
    Body body;
    body.dofs = {b};
    body.heights = {3.2};
    body.label = "building" + std::to_string(b + 1);
    p.bodies.push_back(std::move(body));
    Spring sp;
    sp.i = ground, sp.j = b, sp.body = b, sp.storey = 1;
    p.springs.push_back(sp);
  }
  ContactElement el;
  el.left = {SideKind::point, 0, -1, 0};
  el.right = {SideKind::point, 1, -1, 0};
  el.group = 0;
  el.level = 1;
  el.label = "level 1";
  p.contacts.push_back(std::move(el));
  p.groups.push_back(ContactGroup{"pounding", true});
  return build(std::move(p));
}

}  // namespace pounding::model
