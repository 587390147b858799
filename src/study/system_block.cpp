// Shear buildings in studies: see system_block.hpp.
#include "pounding/study/system_block.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/bridge.hpp"
#include "pounding/physics/validate.hpp"

namespace pounding {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}  // namespace

namespace {

// A row mixing SDOF and shear buildings (n >= 3): each run of neighbouring SDOF buildings i..c shares one floor level,
// the floor of its shear neighbours (left of i, right of c) nearest the lowest of the run's heights, at most the
// lower of those neighbours' roofs (ties: the lower floor). So every SDOF meets each shear neighbour at a floor or,
// when the two neighbours' storey heights differ, a column below its roof, and neighbouring SDOFs meet floor to floor
// -- two buildings pound at the lower roof, and an SDOF's roof is its height (the pair's rule, sdof_level).
void mixed_row_levels(const StructureModel& model, const SampledPair& p, LaneTopology& t) {
  const std::size_t n = t.buildings();
  std::vector<char> shear(n);
  for (std::size_t i = 0; i < n; ++i) shear[i] = model.row_building(i).shear();
  for (std::size_t i = 0; i < n;) {
    if (shear[i]) { ++i; continue; }
    std::size_t c = i;
    double h = p.structure(i).h;
    while (c + 1 < n && !shear[c + 1]) h = std::min(h, p.structure(++c).h);
    std::vector<std::size_t> nb;  // the run's shear neighbours
    if (i > 0) nb.push_back(i - 1);
    if (c + 1 < n) nb.push_back(c + 1);
    double roof = std::numeric_limits<double>::infinity();
    for (std::size_t b : nb) roof = std::min(roof, t.level(b, t.storeys[b]));
    double best = nan;
    for (std::size_t b : nb)
      for (int k = 1; k <= t.storeys[b]; ++k) {
        const double z = t.level(b, k);
        if (z > roof + 1e-9) break;
        if (std::isnan(best) || std::abs(z - h) < std::abs(best - h) || (std::abs(z - h) == std::abs(best - h) && z < best))
          best = z;
      }
    for (std::size_t b = i; b <= c; ++b) t.storey_height[b] = best;
    i = c + 1;
  }
}

}  // namespace

double LaneTopology::level(std::size_t b, int k) const {
  if (heights[b].empty()) return k * storey_height[b];
  double z = 0.0;
  for (int i = 0; i < k; ++i) z += heights[b][static_cast<std::size_t>(i)];  // bottom first, as shear_buildings sums
  return z;
}

std::vector<double> LaneTopology::stick_heights(std::size_t b) const {
  return heights[b].empty() ? std::vector<double>{storey_height[b]} : heights[b];
}

namespace {
// The floor (1..storeys of building o) an SDOF facing it reaches: the nearest to its height h (ties: the upper).
long sdof_floor(const LaneTopology& t, std::size_t o, double h) {
  if (t.heights[o].empty()) return std::clamp<long>(std::lround(h / t.storey_height[o]), 1, t.storeys[o]);
  long best = 1;
  for (int k = 2; k <= t.storeys[o]; ++k)
    if (std::abs(t.level(o, k) - h) <= std::abs(t.level(o, static_cast<int>(best)) - h)) best = k;
  return best;
}
}  // namespace

LaneTopology lane_topology(const StructureModel& model, const SampledPair& p) {
  const std::size_t n = p.buildings();
  LaneTopology t;
  t.heights.assign(n, {});
  if (model.bridge) {  // every lane the same chain
    t.storeys.resize(n), t.isolated.assign(n, 0), t.moat.assign(n, 0), t.bridge = 1;
    t.storey_height.resize(n);
    for (std::size_t i = 0; i < n; ++i)  // (the System is bridge_system's: stick frames' levels are its bodies' DOFs)
      t.storeys[i] = model.bridge->spec.frames[i].storeys, t.storey_height[i] = model.bridge->spec.frames[i].height;
    return t;
  }
  t.storeys.resize(n), t.storey_height.resize(n), t.isolated.resize(n), t.moat.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BuildingModel b = model.row_building(i);
    t.storeys[i] = b.shear() ? b.storeys_at(p.structure(i).h) : 1;
    // an SDOF of a row of SDOFs: its one floor at the pair's 3.2 m (System::sdof_pair()), so every joint has one element
    t.storey_height[i] = b.shear() || n == 2 ? b.storey_height() : 3.2;
    if (b.shear()) t.heights[i] = b.storey_heights;
    t.isolated[i] = b.shear() && b.isolated, t.moat[i] = t.isolated[i] && b.moat;
  }
  bool sdof = false;
  for (std::size_t i = 0; i < n; ++i) sdof = sdof || !model.row_building(i).shear();
  if (n > 2 && sdof && model.any_shear()) mixed_row_levels(model, p, t);
  for (std::size_t i = 0; i < 2 && n == 2; ++i) {
    if (model.building(static_cast<int>(i)).shear()) continue;
    // an SDOF facing a shear building: one storey reaching the other's floor nearest its height (its roof at most)
    const std::size_t o = 1 - i;
    const long k = sdof_floor(t, o, p.structure(i).h);
    t.storey_height[i] = t.heights[o].empty() ? static_cast<double>(k) * t.storey_height[o] : t.level(o, static_cast<int>(k));
  }
  return t;
}

physics::ShearSpec shear_spec(const BuildingModel& b, const SampledStructure& s, int storeys) {
  physics::ShearSpec spec;
  spec.zeta = s.zeta;
  spec.alpha = s.alpha;
  spec.profile = b.profile;
  spec.modal = b.modal_damping, spec.modal_zeta = b.modal_zeta;
  if (storeys > 1) {  // rayleigh_modes, the highest two the sample has when it has fewer (model::rayleigh_modes_for)
    const model::ModePair r = model::rayleigh_modes_for(b.rayleigh_i, b.rayleigh_j, storeys);
    spec.mode_i = r.i, spec.mode_j = r.j;
  }
  if (storeys == 1 && b.floor_mass.empty() && b.storey_stiffness.empty()) {
    // the SDOF of the sample, bit for bit: k and c by Structure::from_period(m, T, zeta), its fy
    spec.floor_mass = {s.m};
    spec.period = s.T;
    spec.storey_yield = {s.fy};
    return spec;
  }
  const double n = storeys;
  spec.floor_mass = b.floor_mass.empty() ? std::vector<double>{s.m / n} : b.floor_mass;  // one, or one per floor
  if (!b.storey_stiffness.empty()) spec.storey_stiffness = b.storey_stiffness;
  else spec.period = s.T;
  if (b.hysteresis == Hysteresis::elastic) return spec;  // fy = inf
  if (!b.storey_yield.empty()) spec.storey_yield = b.storey_yield;  // given: one, or one per storey
  else if (b.yield_coefficient.given()) spec.yield_coefficient = s.fy / (s.m * physics::standard_gravity);  // the drawn Cy
  else spec.yield_drift = b.drift / b.ductility;  // the SDOF's u_y = drift h / ductility as a drift ratio per storey
  return spec;
}

void RunPeaks::resize(std::size_t n, std::size_t nb, const TableLayout& t) {
  status.assign(n, 0);
  u1.assign(n, 0.0), u2.assign(n, 0.0), closing.assign(n, 0.0);
  buildings = nb;
  u.assign(n * nb, 0.0);
  impact_count.assign(n, 0), restitution_outside.assign(n, 0);
  peak_force.assign(n, 0.0), t_first_impact.assign(n, nan), h_omega_contact.assign(n, nan);
  worst.assign(n, physics::StepResolution{});
  for (auto* f : {&floor_u, &floor_drift, &floor_acc}) {
    f->resize(t.floors.size());
    for (std::size_t b = 0; b < t.floors.size(); ++b) (*f)[b].assign(n * t.floors[b], nan);
  }
  for (auto* v : {&e_closing, &e_force, &e_penetration, &e_first, &e_hw}) v->assign(n * t.elements, nan);
  e_count.assign(n * t.elements, -1), e_outside.assign(n * t.elements, -1);
  springs.resize(0);
}

void RunPeaks::set_scaled(std::size_t to, const RunPeaks& from, std::size_t k, double scale) {
  status[to] = from.status[k];
  u1[to] = scale * from.u1[k], u2[to] = scale * from.u2[k], closing[to] = scale * from.closing[k];
  for (std::size_t b = 0; b < buildings; ++b) u[to * buildings + b] = scale * from.u[k * buildings + b];
  for (auto [mine, theirs] : {std::pair{&floor_u, &from.floor_u}, {&floor_drift, &from.floor_drift}, {&floor_acc, &from.floor_acc}})
    for (std::size_t b = 0; b < mine->size(); ++b) {
      const std::size_t f = (*mine)[b].size() / status.size();
      for (std::size_t x = 0; x < f; ++x) (*mine)[b][to * f + x] = scale * (*theirs)[b][k * f + x];
    }
  const std::size_t E = e_closing.size() / status.size();
  for (std::size_t e = 0; e < E; ++e) e_closing[to * E + e] = scale * from.e_closing[k * E + e];
}

void RunPeaks::set_lane(std::size_t to, const RunPeaks& from, std::size_t k) {
  const std::size_t n = status.size();
  const auto row = [&](auto& mine, const auto& theirs) {  // lane k's values of `theirs` (of any width) as lane `to`'s
    const std::size_t w = mine.size() / n;
    std::copy_n(theirs.begin() + static_cast<std::ptrdiff_t>(k * w), w, mine.begin() + static_cast<std::ptrdiff_t>(to * w));
  };
  row(status, from.status), row(u1, from.u1), row(u2, from.u2), row(closing, from.closing), row(u, from.u);
  row(impact_count, from.impact_count), row(restitution_outside, from.restitution_outside);
  row(peak_force, from.peak_force), row(t_first_impact, from.t_first_impact), row(h_omega_contact, from.h_omega_contact);
  row(worst, from.worst);
  for (auto [mine, theirs] : {std::pair{&floor_u, &from.floor_u}, {&floor_drift, &from.floor_drift}, {&floor_acc, &from.floor_acc}})
    for (std::size_t b = 0; b < mine->size(); ++b) row((*mine)[b], (*theirs)[b]);
  row(e_closing, from.e_closing), row(e_force, from.e_force), row(e_penetration, from.e_penetration);
  row(e_first, from.e_first), row(e_hw, from.e_hw), row(e_count, from.e_count), row(e_outside, from.e_outside);
  if (!springs.empty()) springs[to] = from.springs[k];
}

bool SystemBlock::scales_linearly(const RunPeaks& p, std::size_t k, double ratio, double limit) const {
  constexpr double margin = 1.0 - 1e-9;  // as the pair's (study/run.cpp elastic_at)
  // ratio >= 1: then every scaled peak within the elastic range puts the anchor's there too (the anchor is linear)
  if (!(ratio >= 1.0) || model_.bridge || !offsets_.empty() || !joint_offsets_.empty() || p.status[k] != 0 || k >= p.springs.size()) return false;
  const RunPeaks::Springs& s = p.springs[k];
  if (s.walls) return false;
  for (std::size_t i = 0; i < s.law.size(); ++i)
    if (!physics::spring_stays_elastic(s.law[i], s.spec[i], ratio * s.peak[i], margin)) return false;
  double sum = 0.0;
  for (std::size_t b = 0; b < p.buildings; ++b) sum += ratio * p.u[k * p.buildings + b];
  return sum <= limit;
}

std::optional<LaneTopology> table_topology(const StructureModel& model, std::uint64_t seed) {
  if (model.bridge) return lane_topology(model, StructureSampler(model, seed).sample(model.pair_id(0, 0)));
  if (!model.row() && (!model.building(0).shear() || !model.building(1).shear())) return std::nullopt;
  const StructureSampler sampler(model, seed);
  LaneTopology most;
  bool first = true;
  for (std::int64_t p = 0; p < model.period_pair_count(); ++p)
    for (std::int64_t k = 0; k < model.samples_per_pair; ++k) {
      const LaneTopology t = lane_topology(model, sampler.sample(model.pair_id(p, k)));
      if (first) most = t, first = false;
      for (std::size_t b = 0; b < t.buildings(); ++b) most.storeys[b] = std::max(most.storeys[b], t.storeys[b]);
    }
  return most;
}

void SystemBlock::set_table(const model::System& table) {
  layout_ = TableLayout{};
  table_elements_.clear();
  for (const model::Body& b : table.bodies()) layout_.floors.push_back(b.dofs.size());
  layout_.elements = table.contacts().size();
  for (std::size_t e = 0; e < table.contacts().size(); ++e) table_elements_[table.contacts()[e].label] = e;
  // a row's joint of one element (an SDOF of a mixed row meets each neighbour once, at a level that varies with the
  // sample): that element, whatever its level
  table_joints_.clear();
  std::map<std::string, int> count;
  for (std::size_t e = 0; e < table.contacts().size(); ++e)
    if (const std::string j = joint_of(table.contacts()[e].label); !j.empty()) ++count[j], table_joints_[j] = e;
  for (const auto& [j, c] : count)
    if (c != 1) table_joints_.erase(j);
}

std::vector<std::size_t> SystemBlock::table_indices(const model::System& sys) const {
  std::vector<std::size_t> to_table(sys.contacts().size(), layout_.elements);
  if (layout_.empty()) return to_table;
  std::map<std::string, int> joint_count;  // a joint of one element maps to the table's one (set_table)
  for (const model::ContactElement& ce : sys.contacts()) ++joint_count[joint_of(ce.label)];
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    const std::string& label = sys.contacts()[e].label;
    if (auto it = table_elements_.find(label); it != table_elements_.end()) to_table[e] = it->second;
    else if (auto jt = table_joints_.find(joint_of(label)); jt != table_joints_.end() && joint_count[jt->first] == 1)
      to_table[e] = jt->second;
  }
  return to_table;
}

std::size_t SystemBlock::joint_index(const model::System& sys, std::size_t e) {
  const model::ContactElement& ce = sys.contacts()[e];
  const auto body = [&](const model::Side& s) {  // a column side's floor above (its p may be the ground)
    return s.kind == model::SideKind::wall ? -1 : sys.body_of(s.kind == model::SideKind::interpolated ? s.q : s.p);
  };
  const int l = body(ce.left), r = body(ce.right);
  return static_cast<std::size_t>(l < 0 ? r : r < 0 ? l : std::min(l, r));
}

std::string SystemBlock::joint_of(const std::string& label) {
  const std::size_t bar = label.find('|'), space = label.find(' ');
  return bar != std::string::npos && space != std::string::npos && bar < space ? label.substr(0, space) : "";
}

const model::System& SystemBlock::system(const LaneTopology& t) {
  auto& slot = systems_[t];
  if (!slot && t.bridge) slot = std::make_unique<model::System>(physics::bridge_system(model_.bridge->spec));
  if (!slot) {
    std::vector<model::StickTopology> sticks(t.buildings());
    for (std::size_t i = 0; i < t.buildings(); ++i) {
      sticks[i].storeys = t.storeys[i], sticks[i].storey_heights = t.stick_heights(i);
      sticks[i].isolated = t.isolated[i], sticks[i].moat = t.moat[i];
      sticks[i].columns = model_.row_building(i).shear();  // an SDOF stands for a whole building: no column
      if (model_.row_building(i).modal_damping) sticks[i].damping = model::DampingForm::dense;
      if (t.isolated[i]) sticks[i].isolator_law = physics::isolator_law(model_.row_building(i).isolation.bearing);
    }
    slot = std::make_unique<model::System>(model::shear_buildings(sticks, tolerance_, levels_));
  }
  return *slot;
}

const model::System& SystemBlock::table_system(const LaneTopology& t) {
  if (levels_ == model::ContactLevels::common || t.bridge) return system(t);
  auto& slot = table_systems_[t];
  if (!slot) {
    std::vector<model::StickTopology> sticks(t.buildings());
    for (std::size_t i = 0; i < t.buildings(); ++i) {
      sticks[i].storeys = t.storeys[i], sticks[i].storey_heights = t.stick_heights(i);
      sticks[i].isolated = t.isolated[i], sticks[i].moat = t.moat[i];
      sticks[i].columns = model_.row_building(i).shear();  // an SDOF stands for a whole building: no column
      if (model_.row_building(i).modal_damping) sticks[i].damping = model::DampingForm::dense;
      if (t.isolated[i]) sticks[i].isolator_law = physics::isolator_law(model_.row_building(i).isolation.bearing);
    }
    slot = std::make_unique<model::System>(model::shear_buildings(sticks, tolerance_, model::ContactLevels::common));
  }
  return *slot;
}

void SystemBlock::set_lane(physics::SystemBatch& b, std::size_t lane, const SampledPair& p, const LaneTopology& t,
                           double gap, const ContactNumbers& cn) const {
  if (t.bridge) {  // the frames of sample p, every joint at gap + its offset, its own kc and e (sampling/bridge.hpp)
    physics::set_bridge(b, lane, lane_bridge(*model_.bridge, p, gap));
    return;
  }
  const std::size_t nb = t.buildings();
  for (int i = 0; i < static_cast<int>(nb); ++i) {
    const BuildingModel bm = model_.row_building(static_cast<std::size_t>(i));
    const physics::ShearSpec spec = shear_spec(bm, p.structure(static_cast<std::size_t>(i)), t.storeys[i]);
    if (!t.isolated[i]) {
      physics::set_shear_building(b, lane, i, spec);
      continue;
    }
    physics::IsolationSpec iso = bm.isolation;
    if (!(iso.base_mass > 0)) iso.base_mass = spec.floor_mass[0];  // one floor's mass
    physics::set_isolated_building(b, lane, i, spec, iso);
  }
  const model::System& sys = *b.system;
  if (offsets_.empty()) {
    physics::set_contacts(b, lane, gap, p.kh, cn.e, {}, shape_);
  } else {  // per level, 0 beyond the list
    int top = 0;
    for (const model::ContactElement& ce : sys.contacts()) top = std::max(top, ce.level);
    std::vector<double> per_level(static_cast<std::size_t>(std::max(top, 1)), 0.0);
    std::copy_n(offsets_.begin(), std::min(offsets_.size(), per_level.size()), per_level.begin());
    physics::set_contacts(b, lane, gap, p.kh, cn.e, per_level, shape_);
  }
  const std::size_t w = b.width;
  if (!joint_offsets_.empty())
    for (std::size_t e = 0; e < sys.contacts().size(); ++e)
      if (sys.groups()[static_cast<std::size_t>(sys.contacts()[e].group)].study_gap)
        b.gap[physics::SystemBatch::at(static_cast<int>(e), lane, w)] += joint_offsets_[joint_index(sys, e)];
  for (int i = 0; i < static_cast<int>(nb); ++i) {
    if (!t.moat[i]) continue;
    const BuildingModel bm = model_.row_building(static_cast<std::size_t>(i));
    const double m_base = b.m[physics::SystemBatch::at(sys.bodies()[static_cast<std::size_t>(i)].dofs[0], lane, w)];
    const double kc = bm.moat_stiffness > 0 ? bm.moat_stiffness
                                            : hertz_stiffness_spheres(m_base, m_base, model_.contact_density,
                                                                      model_.contact_youngs_modulus, model_.contact_poisson);
    physics::set_moat(b, lane, i, bm.moat_gap, bm.moat_gap, kc, bm.moat_e >= 0 ? bm.moat_e : e_);
  }
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    const model::ContactElement& ce = sys.contacts()[e];
    if (!sys.groups()[static_cast<std::size_t>(ce.group)].study_gap) continue;  // a moat wall: set_moat's
    double kc = cn.stiffness > 0 ? cn.stiffness : p.kh;
    // (a row of SDOFs: the spheres of the two floors are the two buildings', so joint 1|2 gets the pair's kh)
    if (!(cn.stiffness > 0) && !(model_.kh > 0) && !(nb == 2 && t.storeys[0] == 1 && t.storeys[1] == 1))
      kc = hertz_stiffness_spheres(physics::contact_masses(b, lane, static_cast<int>(e))[0],
                                   physics::contact_masses(b, lane, static_cast<int>(e))[1], model_.contact_density,
                                   model_.contact_youngs_modulus, model_.contact_poisson);  // the two floors' masses
    b.kc[physics::SystemBatch::at(static_cast<int>(e), lane, w)] = kc;
  }
}

std::vector<double> SystemBlock::element_offsets(const model::System& sys) const {
  if (model_.bridge) {  // joint j at the study gap + (gap_j - d)
    const std::vector<double>& o = model_.bridge->offsets;
    return std::all_of(o.begin(), o.end(), [](double x) { return x == 0.0; }) ? std::vector<double>{} : o;
  }
  std::vector<double> out(sys.contacts().size(), 0.0);
  bool any = !offsets_.empty() || !joint_offsets_.empty();
  for (std::size_t e = 0; e < out.size(); ++e) {
    const model::ContactElement& ce = sys.contacts()[e];
    if (!sys.groups()[static_cast<std::size_t>(ce.group)].study_gap) {
      // a moat wall: the whole gap, its building's moat gap (set_lane's set_moat; the base is the non-wall side)
      const model::Side& base = ce.left.kind == model::SideKind::wall ? ce.right : ce.left;
      out[e] = model_.row_building(static_cast<std::size_t>(sys.body_of(base.p))).moat_gap;
      any = true;
      continue;
    }
    if (ce.level >= 1 && static_cast<std::size_t>(ce.level) <= offsets_.size())
      out[e] = offsets_[static_cast<std::size_t>(ce.level - 1)];
    if (!joint_offsets_.empty()) out[e] += joint_offsets_[joint_index(sys, e)];  // set_lane's order: gap + level + joint
  }
  return any ? out : std::vector<double>{};
}

std::vector<ContactModel> SystemBlock::groups(const LaneTopology& t, const ContactModel& pounding) const {
  std::vector<ContactModel> out{pounding};
  for (std::size_t i = 0; i < t.buildings(); ++i) {
    if (!t.moat[i]) continue;
    ContactModel moat = contact_;
    if (const std::string& law = model_.row_building(i).moat_law; !law.empty()) moat.law = parse_contact_law(law);
    out.push_back(moat);
  }
  return out;
}

void SystemBlock::run(std::span<const SampledPair> pairs, std::span<const std::size_t> lanes, double ratio,
                      const ContactModel& cm, const ContactNumbers& cn, const GroundMotion& gm,
                      const KernelSettings& ks, RunPeaks& out, physics::SystemSeries* series) {
  const std::size_t n = lanes.size(), nb = body_count(model_);
  out.resize(n, nb, layout_), out.springs.resize(keep_springs_ ? n : 0);
  keys_.resize(n);
  for (std::size_t j = 0; j < n; ++j) keys_[j] = lane_topology(model_, pairs[lanes[j]]);
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return keys_[a] < keys_[b]; });
  for (std::size_t at = 0; at < n;) {
    std::size_t end = at;
    while (end < n && keys_[order_[end]] == keys_[order_[at]]) ++end;
    const LaneTopology& t = keys_[order_[at]];
    const model::System& sys = system(t);
    const std::vector<ContactModel> groups = this->groups(t, cm);
    const std::vector<double> offsets = element_offsets(sys);  // empty: none
    batch_.resize(sys, end - at);
    for (std::size_t j = at; j < end; ++j) {
      const SampledPair& p = pairs[lanes[order_[j]]];
      set_lane(batch_, j - at, p, t, ratio * (gap_metres_ ? 1.0 : p.d), cn);  // Study::gap_unit
    }
    run_lanes(groups, gm, ks, series);
    const std::size_t w = end - at;
    const std::vector<std::size_t> to_table = table_indices(sys);
    for (std::size_t j = at; j < end; ++j) {
      const std::size_t l = j - at, k = order_[j];
      out.status[k] = res_.status[l];
      double* u = out.u.data() + k * nb;
      for (std::size_t b = 0; b < nb; ++b)
        for (int d : sys.bodies()[b].dofs) u[b] = std::max(u[b], res_.peak_u[physics::SystemBatch::at(d, l, w)]);
      out.u1[k] = u[0], out.u2[k] = u[1];
      // over the study-gap elements: D and force the largest, the counts summed (-1: a failed lane), the first impact
      // the earliest, h omega_c the largest known; with one element its own values
      double D = -std::numeric_limits<double>::infinity(), force = nan, first = nan, hw = nan;
      std::int32_t count = 0, outside = 0;
      bool any = false;
      for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
        if (!sys.groups()[static_cast<std::size_t>(sys.contacts()[e].group)].study_gap) continue;
        const std::size_t x = physics::SystemBatch::at(static_cast<int>(e), l, w);
        const double f = res_.peak_force[x], tf = res_.t_first_impact[x], h = res_.h_omega_contact[x];
        D = std::max(D, offsets.empty() ? res_.peak_closing[x] : res_.peak_closing[x] - offsets[e]);
        count = count < 0 || res_.impact_count[x] < 0 ? -1 : count + res_.impact_count[x];
        outside = outside < 0 || res_.restitution_outside[x] < 0 ? -1 : outside + res_.restitution_outside[x];
        force = !any ? f : std::isnan(force) || std::isnan(f) ? nan : std::max(force, f);
        if (!std::isnan(tf) && !(tf >= first)) first = tf;
        if (!std::isnan(h) && !(h <= hw)) hw = h;
        any = true;
      }
      if (!any) force = 0.0;
      if (!layout_.empty()) table_lane(out, sys, to_table, l, w, k);
      if (keep_springs_) keep_lane_springs(out.springs[k], sys, groups, l, w);
      out.closing[k] = D, out.impact_count[k] = count, out.peak_force[k] = force, out.restitution_outside[k] = outside;
      out.t_first_impact[k] = first, out.h_omega_contact[k] = hw;
      out.worst[k] = physics::worst_element(sys, groups, ks, res_, l);
    }
    at = end;
  }
}

void SystemBlock::run_lanes(std::span<const ContactModel> groups, const GroundMotion& gm, const KernelSettings& ks,
                             physics::SystemSeries* series) {
  if (!series) {
    if (channels_.empty()) physics::run_system(batch_, groups, gm, ks, res_);
    else physics::run_system(batch_, groups, channels_, ks, res_);
    return;
  }
  series->lane = 0;
  if (!batch_.system->is_sdof_pair()) {
    physics::run_system_recorded(batch_, groups, channels_.empty() ? std::span<const GroundMotion>(&gm, 1) : channels_,
                                 ks, res_, *series);
    return;
  }
  // run_system's SDOF pair: the pair kernel (validated as run_system validates it), its recorder in the series' form
  physics::throw_first(physics::validate(batch_, groups, gm, ks));
  SeriesRecorder rec;
  KernelSettings k = ks;
  k.series = &rec;
  BatchResult r;
  pounding::run_batch(physics::to_pair_batch(batch_), groups[0], gm, k, r);
  res_ = physics::from_pair_result(r);
  series->clear();
  series->t = rec.t, series->ag = rec.ag;
  series->u = {rec.u1, rec.u2}, series->a_abs = {rec.a1_abs, rec.a2_abs}, series->force = {rec.force};
}

const model::System& SystemBlock::record(std::span<const SampledPair> pairs, double ratio, const ContactModel& cm,
                                         const ContactNumbers& cn, const GroundMotion& gm, const KernelSettings& ks,
                                         RunPeaks& out, physics::SystemSeries& series) {
  const std::size_t one[] = {0};
  run(pairs.first(1), one, ratio, cm, cn, gm, ks, out, &series);
  return system(lane_topology(model_, pairs[0]));
}

// Lane l (of w) of the last run into lane k of out's per-floor and per-element rows (the table's order: to_table).
void SystemBlock::table_lane(RunPeaks& out, const model::System& sys, std::span<const std::size_t> to_table,
                             std::size_t l, std::size_t w, std::size_t k) const {
  for (std::size_t b = 0; b < sys.bodies().size() && b < layout_.floors.size(); ++b) {
    const auto& dofs = sys.bodies()[b].dofs;
    for (std::size_t f = 0; f < dofs.size() && f < layout_.floors[b]; ++f) {
      const std::size_t x = physics::SystemBatch::at(dofs[f], l, w), o = k * layout_.floors[b] + f;
      out.floor_u[b][o] = res_.peak_u[x];
      out.floor_drift[b][o] = res_.peak_drift[physics::SystemBatch::at(sys.spring_below(dofs[f]), l, w)];
      out.floor_acc[b][o] = res_.peak_acc[x] / physics::standard_gravity;
    }
  }
  for (std::size_t e = 0; e < sys.contacts().size(); ++e) {
    if (to_table[e] >= layout_.elements) continue;
    const std::size_t x = physics::SystemBatch::at(static_cast<int>(e), l, w), o = k * layout_.elements + to_table[e];
    out.e_closing[o] = res_.peak_closing[x], out.e_count[o] = res_.impact_count[x];
    out.e_force[o] = res_.peak_force[x], out.e_penetration[o] = res_.peak_penetration[x];
    out.e_first[o] = res_.t_first_impact[x], out.e_hw[o] = res_.h_omega_contact[x];
    out.e_outside[o] = res_.restitution_outside[x];
  }
}

void SystemBlock::keep_lane_springs(RunPeaks::Springs& s, const model::System& sys,
                                    std::span<const ContactModel> groups, std::size_t l, std::size_t w) const {
  const std::size_t S = sys.springs().size();
  s.law.resize(S), s.spec.resize(S), s.peak.resize(S);
  for (std::size_t i = 0; i < S; ++i) {
    const std::size_t x = physics::SystemBatch::at(static_cast<int>(i), l, w);
    s.law[i] = sys.springs()[i].law, s.spec[i] = batch_.spring[x], s.peak[i] = res_.peak_drift[x];
  }
  s.walls = false;
  for (const model::ContactElement& ce : sys.contacts()) {
    const auto g = static_cast<std::size_t>(ce.group);
    if (!sys.groups()[g].study_gap && groups[g].law != ContactLaw::none) s.walls = true;
  }
}

void SystemBlock::uncoupled(std::span<const SampledPair> pairs, const ContactModel& none, const GroundMotion& gm,
                            const KernelSettings& ks, RunPeaks& out) {
  all_.resize(pairs.size());
  std::iota(all_.begin(), all_.end(), std::size_t{0});
  run(pairs, all_, 0.0, none, ContactNumbers{}, gm, ks, out);
}

void SystemBlock::coupled(std::span<const SampledPair> pairs, std::span<const std::size_t> lanes, double ratio,
                          const ContactModel& cm, const ContactNumbers& cn, const GroundMotion& gm,
                          const KernelSettings& ks, RunPeaks& out) {
  run(pairs, lanes, ratio, cm, cn, gm, ks, out);
}

void check_shear_steps(Study& study, std::span<const StudyRecord> records, std::size_t max_models) {
  const StructureModel& model = study.structures;
  // Newmark (average acceleration) is unconditionally stable for the linear part (contact: the resolution guard);
  // central difference and RK4 have their limits (physics::structure_step_max)
  if (!runs_systems(model) || records.empty() || study.stepper == Stepper::newmark ||
      study.stepper == Stepper::nigam_jennings)
    return;
  // the longest integration step over the records
  double h = 0.0, dt = 0.0;
  for (const StudyRecord& r : records) {
    const double x = r.record.dt / study_substeps(study, r.record.dt);
    if (x > h) h = x, dt = r.record.dt;
  }
  const StructureSampler sampler(model, study.seed);
  SystemBlock block(study);
  const auto pairs = model.period_pair_count();
  const auto per_pair = std::min<std::int64_t>(model.samples_per_pair,
                                               std::max<std::int64_t>(1, static_cast<std::int64_t>(max_models) / pairs));
  // physics::structure_step_max: the system stepper's damped limit h^2 omega^2 + 4 h (2 zeta omega) < 4 with
  // Gershgorin's bounds on M^-1 K0 and M^-1 C (the storey dashpots make C grow with the stiffest storey: tall
  // buildings of short storeys need it) -- the same bound physics::validate and pounding simulate check.
  physics::StructureStep worst{INFINITY, 0.0, 0.0, 0};
  SampleId at;
  std::map<LaneTopology, physics::SystemBatch> batches;
  for (std::int64_t p = 0; p < pairs; ++p)
    for (std::int64_t k = 0; k < per_pair; ++k) {
      const SampledPair pair = sampler.sample(model.pair_id(p, k));
      const LaneTopology t = lane_topology(model, pair);
      physics::SystemBatch& b = batches[t];
      if (!b.system) b.resize(block.system(t), 1);
      block.set_lane(b, 0, pair, t, 0.0, ContactNumbers{});
      const physics::StructureStep s = physics::structure_step_max(b, 0, study.stepper);
      if (s.h_max < worst.h_max) worst = s, at = pair.id;
    }
  const double h_min = worst.h_max, w_at = worst.omega_max, c_at = worst.damping;
  if (h < h_min) return;
  const double need = worst.substeps(dt);
  if (!study.step_given) {  // choose: the largest 3-digit step below 0.999 h_min
    const double q = std::pow(10.0, std::floor(std::log10(0.999 * h_min)) - 2.0);
    const double cap = std::floor(0.999 * h_min / q) * q;
    study.max_dt = study.max_dt > 0 ? std::min(study.max_dt, cap) : cap;
    study.scene_reason += fmt::format(
        "; step: max_dt = {:g} s, chosen for the {}' stability (sample ({}, {}, {}) needs h < {:.4g} s; the record step "
        "{:g} s needs {:g} substeps; give [analysis] substeps or max_dt to set the step yourself)",
        study.max_dt, model.bridge ? "bridge's frames and links" : "shear buildings", at.i1, at.i2, at.sample, h_min, dt,
        std::ceil(dt / study.max_dt - 1e-9));
    return;
  }
  const std::string rule = study.stepper == Stepper::central_difference
                               ? fmt::format("central difference (omega_max <= {:.6g} rad/s, 2 zeta omega <= {:.4g} 1/s by "
                                             "Gershgorin's bounds; h^2 omega^2 + 4 h (2 zeta omega) < 4)", w_at, c_at)
                               : fmt::format("{} (omega_max <= {:.6g} rad/s by Gershgorin's bound; h omega_max < {})",
                                             to_string(study.stepper), w_at, physics::structure_step_limit(study.stepper));
  throw InputError(
      fmt::format("the integration step {:.4g} s (record step {:g} s / {}) is too long for the {}: sample "
                  "({}, {}, {}) needs h <= {:.4g} s for {}",
                  h, dt, study_substeps(study, dt), model.bridge ? "bridge's frames and links" : "shear buildings", at.i1,
                  at.i2, at.sample, h_min, rule),
      study.path + " [analysis] substeps / max_dt",
      fmt::format("give [analysis] substeps >= {:g} or max_dt <= {:.4g} s (more storeys of the same period raise "
                  "omega_max and the storey dashpots' damping)",
                  need, 0.999 * h_min));
}

}  // namespace pounding
