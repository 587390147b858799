// model::shear_buildings (docs/architecture.md §2.1 numbering, §2.2.4 floor to floor; issue 25 §2, §3): two
// one-storey buildings are the SDOF pair; level-major numbering; common floors of buildings with different
// storey counts and heights; the lower roof only; rows (neighbours only); refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "pounding/model/shear_building.hpp"

namespace pounding::model {
namespace {

StickTopology stick(int n, std::vector<double> h = {3.2}) {
  StickTopology s;
  s.storeys = n;
  s.storey_heights = std::move(h);
  return s;
}

struct Link {
  int left, right, level;
  std::string label;
};
// The floor-to-floor elements (floors against columns: tests/physics/test_floor_column.cpp).
std::vector<Link> links(const System& s) {
  std::vector<Link> out;
  for (const ContactElement& e : s.contacts()) {
    EXPECT_EQ(e.group, 0);
    if (e.left.kind != SideKind::point || e.right.kind != SideKind::point) continue;
    out.push_back({e.left.p, e.right.p, e.level, e.label});
  }
  return out;
}
void expect_links(const System& s, const std::vector<Link>& want) {
  const std::vector<Link> got = links(s);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].left, want[i].left) << i;
    EXPECT_EQ(got[i].right, want[i].right) << i;
    EXPECT_EQ(got[i].level, want[i].level) << i;
    EXPECT_EQ(got[i].label, want[i].label) << i;
  }
}

TEST(ShearTopology, TwoOneStoreyBuildingsAreTheSdofPair) {
  const std::vector<StickTopology> two{stick(1), stick(1)};
  EXPECT_EQ(shear_buildings(two), System::sdof_pair());
  // storey dashpots are never given to one storey (the SDOF's damping is its floor dashpot)
  std::vector<StickTopology> other{stick(1, {3.0}), stick(1, {3.0})};
  other[0].storey_dashpots = other[1].storey_dashpots = true;
  const System s = shear_buildings(other);
  EXPECT_TRUE(s.is_sdof_pair());
  EXPECT_FALSE(s.any_storey_dashpots());
  EXPECT_EQ(s.bodies()[0].heights, std::vector<double>{3.0});
  // beyond the tolerance the lower floor strikes the other's column (ground to roof, xi = 3.0/3.2) and the system
  // is no longer the pair
  const std::vector<StickTopology> apart{stick(1, {3.0}), stick(1, {3.2})};
  ASSERT_EQ(shear_buildings(apart).contacts().size(), 1u);
  EXPECT_EQ(shear_buildings(apart).contacts()[0].label, "level 1/column 0-1");
  EXPECT_EQ(shear_buildings(apart).contacts()[0].right.p, ground);
  EXPECT_DOUBLE_EQ(shear_buildings(apart).contacts()[0].xi, 3.0 / 3.2);
  EXPECT_FALSE(shear_buildings(apart).is_sdof_pair());
  EXPECT_EQ(links(shear_buildings(apart, 0.25)).size(), 1u);
  EXPECT_EQ(shear_buildings(apart, 0.25).contacts().size(), 1u);
}

TEST(ShearTopology, LevelMajorNumbering) {
  const std::vector<StickTopology> b{stick(3, {3.0}), stick(5, {3.0})};
  const System s = shear_buildings(b);
  ASSERT_EQ(s.ndof(), 8);
  EXPECT_EQ(s.bodies()[0].dofs, (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(s.bodies()[1].dofs, (std::vector<int>{1, 3, 5, 6, 7}));
  EXPECT_EQ(s.bodies()[0].heights, (std::vector<double>{3.0, 6.0, 9.0}));
  EXPECT_EQ(s.bodies()[1].label, "building2");
  EXPECT_TRUE(s.bodies()[0].storey_dashpots && s.bodies()[1].storey_dashpots);
  for (int d = 0; d < 8; ++d) {
    const Spring& sp = s.springs()[static_cast<std::size_t>(d)];
    EXPECT_EQ(sp.j, d);
    EXPECT_EQ(s.spring_below(d), d);
  }
  // storeys: building2's storey 4 joins its floors 3 (DOF 5) and 4 (DOF 6)
  EXPECT_EQ(s.springs()[6].i, 5);
  EXPECT_EQ(s.springs()[6].storey, 4);
  EXPECT_EQ(s.springs()[6].body, 1);
  EXPECT_EQ(s.springs()[1].i, ground);
  expect_links(s, {{0, 1, 1, "level 1"}, {2, 3, 2, "level 2"}, {4, 5, 3, "level 3"}});
  // the taller building on the left: the same floors pound, numbered the same way
  const std::vector<StickTopology> r{stick(5, {3.0}), stick(3, {3.0})};
  expect_links(shear_buildings(r), {{0, 1, 1, "level 1"}, {2, 3, 2, "level 2"}, {4, 5, 3, "level 3"}});
}

TEST(ShearTopology, CommonFloorsOfDifferentStoreyHeights) {
  // 3 storeys of 4 m (4, 8, 12) beside 5 of 3 m (3, 6, 9, 12, 15): only 12 m is common
  const std::vector<StickTopology> b{stick(3, {4.0}), stick(5, {3.0})};
  const System s = shear_buildings(b);
  expect_links(s, {{4, 6, 3, "level 3/4"}});  // building1 floor 3 (DOF 4), building2 floor 4 (DOF 6)
  // per-storey heights, and the tolerance: 3.0/6.0/9.0 against 3.04/6.08/9.12 meet at the first floor only
  const std::vector<StickTopology> c{stick(3, {3.0}), stick(3, {3.04})};
  expect_links(shear_buildings(c), {{0, 1, 1, "level 1"}});
  expect_links(shear_buildings(c, 0.1), {{0, 1, 1, "level 1"}, {2, 3, 2, "level 2"}});
  const std::vector<StickTopology> d{stick(3, {3.5, 3.0, 3.0}), stick(4, {3.5, 3.2, 2.8, 3.0})};
  EXPECT_EQ(shear_buildings(d).bodies()[1].heights, (std::vector<double>{3.5, 6.7, 9.5, 12.5}));
  expect_links(shear_buildings(d), {{0, 1, 1, "level 1"}, {4, 5, 3, "level 3"}});  // 9.5 m: 3.5+3+3 and 3.5+3.2+2.8
  // each floor pounds at most once: two floors 0.02 m apart within the tolerance of one floor take the nearest
  const std::vector<StickTopology> e{stick(2, {3.0, 0.03}), stick(1, {3.02})};
  expect_links(shear_buildings(e), {{2, 1, 2, "level 2/1"}});
}

TEST(ShearTopology, LowerRoofOnly) {
  const std::vector<StickTopology> b{stick(3, {3.0}), stick(5, {3.0})};
  expect_links(shear_buildings(b, 0.05, ContactLevels::top), {{4, 5, 3, "level 3"}});
  const std::vector<StickTopology> r{stick(5, {3.0}), stick(3, {3.0})};
  expect_links(shear_buildings(r, 0.05, ContactLevels::top), {{4, 5, 3, "level 3"}});
  // the lower roof facing no floor: no element
  const std::vector<StickTopology> c{stick(3, {4.0}), stick(5, {3.0})};  // 12 m faces building2 floor 4
  expect_links(shear_buildings(c, 0.05, ContactLevels::top), {{4, 6, 3, "level 3/4"}});
  const std::vector<StickTopology> d{stick(2, {4.0}), stick(5, {3.0})};  // 8 m faces building2's column 6-9 m
  const System top = shear_buildings(d, 0.05, ContactLevels::top);
  ASSERT_EQ(top.contacts().size(), 1u);
  EXPECT_EQ(top.contacts()[0].label, "level 2/column 2-3");
  EXPECT_DOUBLE_EQ(top.contacts()[0].xi, 2.0 / 3.0);
}

TEST(ShearTopology, RowPoundsNeighboursOnly) {
  // 3, 5 and 2 storeys of 3 m: DOFs level 1: 0 1 2, level 2: 3 4 5, level 3: 6 7, level 4: 8, level 5: 9
  const std::vector<StickTopology> row{stick(3, {3.0}), stick(5, {3.0}), stick(2, {3.0})};
  const System s = shear_buildings(row);
  ASSERT_EQ(s.ndof(), 10);
  EXPECT_EQ(s.bodies()[0].dofs, (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(s.bodies()[1].dofs, (std::vector<int>{1, 4, 7, 8, 9}));
  EXPECT_EQ(s.bodies()[2].dofs, (std::vector<int>{2, 5}));
  expect_links(s, {{0, 1, 1, "1|2 level 1"},
                   {1, 2, 1, "2|3 level 1"},
                   {3, 4, 2, "1|2 level 2"},
                   {4, 5, 2, "2|3 level 2"},
                   {6, 7, 3, "1|2 level 3"}});
  EXPECT_EQ(s.elements_at(1), (std::vector<int>{0, 1}));  // the interior building's floor meets both neighbours
  const std::vector<StickTopology> one{stick(4)};
  EXPECT_TRUE(shear_buildings(one).contacts().empty());
  EXPECT_EQ(shear_buildings(one).groups().size(), 1u);  // the study-gap group exists, empty
}

TEST(ShearTopology, RefusesWhatItCannotBuild) {
  EXPECT_THROW(shear_buildings({}), std::invalid_argument);
  const std::vector<StickTopology> zero{stick(0)};
  EXPECT_THROW(shear_buildings(zero), std::invalid_argument);
  const std::vector<StickTopology> sizes{stick(3, {3.0, 3.0})};
  EXPECT_THROW(shear_buildings(sizes), std::invalid_argument);
  const std::vector<StickTopology> height{stick(2, {3.0, 0.0})};
  EXPECT_THROW(shear_buildings(height), std::invalid_argument);
  const std::vector<StickTopology> ok{stick(2)};
  EXPECT_THROW(shear_buildings(ok, -0.1), std::invalid_argument);
  EXPECT_THROW(shear_buildings(ok, std::nan("")), std::invalid_argument);
  std::vector<StickTopology> same{stick(1), stick(1)};
  same[0].label = same[1].label = "twin";
  EXPECT_THROW(shear_buildings(same), std::logic_error);  // System::check: labels must differ
}

}  // namespace
}  // namespace pounding::model
