// model::System (docs/architecture.md §2.2.1, issue 25 step 2): every problem System::check() reports for a bad
// Parts, the adjacency build() derives for a 3-storey and a 5-storey building side by side (level-major
// numbering, written out by hand here), and the SDOF pair's structure.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

#include "pounding/model/system.hpp"

namespace pounding::model {
namespace {

// Two sticks of na and nb floors (left, right), numbered level-major by hand: level k (1-based) holds A's
// floor k then B's floor k where they exist. Springs in DOF order (spring d has j = d), storey heights 3 m,
// one floor-to-floor element per common level.
System::Parts two_sticks(int na, int nb) {
  System::Parts p;
  p.bodies.resize(2);
  p.bodies[0].label = "building1", p.bodies[1].label = "building2";
  int d = 0;
  for (int level = 1; level <= std::max(na, nb); ++level)
    for (int b = 0; b < 2; ++b)
      if (level <= (b == 0 ? na : nb)) {
        p.bodies[static_cast<std::size_t>(b)].dofs.push_back(d++);
        p.bodies[static_cast<std::size_t>(b)].heights.push_back(3.0 * level);
      }
  p.springs.resize(static_cast<std::size_t>(d));
  for (int b = 0; b < 2; ++b) {
    const Body& body = p.bodies[static_cast<std::size_t>(b)];
    for (std::size_t k = 0; k < body.dofs.size(); ++k) {
      Spring& s = p.springs[static_cast<std::size_t>(body.dofs[k])];
      s.i = k == 0 ? ground : body.dofs[k - 1], s.j = body.dofs[k], s.body = b, s.storey = static_cast<int>(k) + 1;
    }
  }
  for (int level = 1; level <= std::min(na, nb); ++level) {
    ContactElement e;
    e.left = {SideKind::point, p.bodies[0].dofs[static_cast<std::size_t>(level - 1)], -1, 0};
    e.right = {SideKind::point, p.bodies[1].dofs[static_cast<std::size_t>(level - 1)], -1, 0};
    e.level = level, e.label = "level " + std::to_string(level);
    p.contacts.push_back(e);
  }
  p.groups.push_back(ContactGroup{});
  return p;
}

// check(p) holds a problem whose what contains `what` and whose where contains `where`.
::testing::AssertionResult has_problem(const System::Parts& p, const std::string& what, const std::string& where) {
  const std::vector<Problem> problems = System::check(p);
  std::string all;
  for (const Problem& q : problems) {
    if (q.what.find(what) != std::string::npos && q.where.find(where) != std::string::npos)
      return ::testing::AssertionSuccess();
    all += "\n  " + q.what + " | " + q.where + " | " + q.fix;
  }
  return ::testing::AssertionFailure() << "no problem '" << what << "' at '" << where << "' among:" << all;
}

TEST(System, ValidPartsHaveNoProblems) {
  EXPECT_TRUE(System::check(System::sdof_pair().parts()).empty());
  EXPECT_TRUE(System::check(two_sticks(3, 5)).empty());
  EXPECT_TRUE(System::check(two_sticks(1, 1)).empty());
}

TEST(System, CheckReportsEveryProblemOfTheBodies) {
  const System::Parts good = two_sticks(3, 5);
  System::Parts p;
  EXPECT_TRUE(has_problem(p, "no bodies", "bodies"));
  p = good, p.channels = 0;
  EXPECT_TRUE(has_problem(p, "channels = 0", "channels"));
  p = good, p.bodies[0].heights.pop_back();
  EXPECT_TRUE(has_problem(p, "heights has 2 values for 3 DOFs", "body 0 (building1) heights"));
  p = good, p.bodies[1].heights[0] = 0.0;
  EXPECT_TRUE(has_problem(p, "must be positive", "body 1 (building2) heights[0]"));
  p = good, p.bodies[1].heights[2] = p.bodies[1].heights[1];
  EXPECT_TRUE(has_problem(p, "not above the floor below", "heights[2]"));
  p = good, p.bodies[1].dofs[4] = 8;
  EXPECT_TRUE(has_problem(p, "DOF 8 is out of range", "body 1 (building2) dofs[4]"));
  EXPECT_TRUE(has_problem(p, "DOF 7 is in no body", "bodies"));
  p = good, p.bodies[1].dofs[0] = 0;  // building1's first floor as well
  EXPECT_TRUE(has_problem(p, "DOF 0 is already in body 0 (building1)", "body 1 (building2) dofs[0]"));
  p = good, p.bodies[0].channel = 1;
  EXPECT_TRUE(has_problem(p, "channel 1 is out of range", "body 0 (building1) channel"));
  p = good, p.bodies[0].floor_dashpot_ref = 4;
  EXPECT_TRUE(has_problem(p, "neither ground nor the base", "floor_dashpot_ref"));
  p = good, p.bodies[0].floor_dashpot_ref = 0;
  EXPECT_TRUE(has_problem(p, "not isolated", "body 0 (building1) floor_dashpot_ref"));
  p = good, p.bodies[1].label.clear();
  EXPECT_TRUE(has_problem(p, "no label", "body 1 label"));
  p = good, p.bodies[1].label = "building1";
  EXPECT_TRUE(has_problem(p, "used twice", "body 1 (building1) label"));
  p = good, p.bodies.push_back(Body{.dofs = {}, .heights = {}, .label = "empty"});
  EXPECT_TRUE(has_problem(p, "no DOFs", "body 2 (empty)"));
}

TEST(System, CheckReportsEveryProblemOfTheSprings) {
  const System::Parts good = two_sticks(3, 5);  // spring d has j = d; building1: 0, 2, 4; building2: 1, 3, 5, 6, 7
  System::Parts p = good;
  p.springs[2].law = -1;
  EXPECT_TRUE(has_problem(p, "hysteresis law -1", "spring 2 law"));
  p = good, p.springs[2].j = 9;
  EXPECT_TRUE(has_problem(p, "DOF j = 9", "spring 2 j"));
  EXPECT_TRUE(has_problem(p, "DOF 2 has 0 storey or isolator springs below it", "body 0 (building1)"));
  p = good, p.springs.push_back(Spring{.i = 0, .j = 2, .body = 0, .storey = 2});
  EXPECT_TRUE(has_problem(p, "DOF 2 has 2 storey or isolator springs", "body 0 (building1)"));
  p = good, p.springs[4].i = 0;  // skips floor 2
  EXPECT_TRUE(has_problem(p, "not at the DOF directly below it (2)", "spring 4 i"));
  p = good, p.springs[0].i = 1;  // the lowest floor must stand on ground
  EXPECT_TRUE(has_problem(p, "not at the DOF directly below it (-1)", "spring 0 i"));
  p = good, p.springs[3].body = 0;
  EXPECT_TRUE(has_problem(p, "spring.body = 0 but DOF 3 is in body 1", "spring 3 body"));
  p = good, p.springs[5].storey = 2;
  EXPECT_TRUE(has_problem(p, "should be 3", "spring 5 storey"));
  p = good, p.springs[0].role = SpringRole::isolator;
  EXPECT_TRUE(has_problem(p, "not under the base of an isolated body", "spring 0 role"));
  p = good, p.bodies[0].isolated = true;  // its base now needs an isolator (storey 0)
  EXPECT_TRUE(has_problem(p, "rests on a storey spring", "spring 0 role"));
  EXPECT_TRUE(has_problem(p, "should be 0", "spring 0 storey"));
  p = good, p.springs.push_back(Spring{.i = 3, .j = 3, .role = SpringRole::link});
  EXPECT_TRUE(has_problem(p, "joins DOF 3 to itself", "spring 8 i"));
  p = good, p.springs.push_back(Spring{.i = 11, .j = 3, .role = SpringRole::link});
  EXPECT_TRUE(has_problem(p, "DOF i = 11", "spring 8 i"));
  // a link between buildings is no storey spring: the DOFs keep one spring below each
  p = good, p.springs.push_back(Spring{.i = 4, .j = 5, .role = SpringRole::link});
  EXPECT_TRUE(System::check(p).empty());
}

TEST(System, IsolatedBodyWithItsIsolatorIsValid) {
  System::Parts p = two_sticks(3, 5);
  p.bodies[0].isolated = true, p.bodies[0].floor_dashpot_ref = 0;
  p.springs[0].role = SpringRole::isolator;
  for (int d : {0, 2, 4}) --p.springs[static_cast<std::size_t>(d)].storey;  // the base is floor 0
  EXPECT_TRUE(System::check(p).empty());
}

TEST(System, CheckReportsEveryProblemOfTheContacts) {
  const System::Parts good = two_sticks(3, 5);
  System::Parts p = good;
  p.contacts[1].right.p = 12;
  EXPECT_TRUE(has_problem(p, "DOF 12 is not a DOF", "contact element 1 (level 2) right p"));
  p = good, p.contacts[0].left = {SideKind::interpolated, 0, 4, 0};  // floors 1 and 3 of building1
  EXPECT_TRUE(has_problem(p, "are not adjacent floors of one body", "contact element 0 (level 1) left"));
  p = good, p.contacts[0].left = {SideKind::interpolated, 0, 3, 0};  // two bodies
  EXPECT_TRUE(has_problem(p, "are not adjacent floors of one body", "contact element 0 (level 1) left"));
  p = good, p.contacts[0].left = {SideKind::interpolated, 0, 99, 0};
  EXPECT_TRUE(has_problem(p, "are not DOFs of a body", "contact element 0 (level 1) left"));
  p = good, p.contacts[0].right = {SideKind::wall, -1, -1, 2};
  EXPECT_TRUE(has_problem(p, "wall channel 2", "contact element 0 (level 1) right channel"));
  p = good, p.contacts[0].left = {SideKind::wall}, p.contacts[0].right = {SideKind::wall};
  EXPECT_TRUE(has_problem(p, "both sides are walls", "contact element 0"));
  p = good, p.contacts[0].left = {SideKind::interpolated, 0, 2, 0}, p.contacts[0].right = {SideKind::interpolated, 1, 3, 0};
  EXPECT_TRUE(has_problem(p, "both sides are interpolated", "contact element 0"));
  p = good, p.contacts[0].right.p = 0;
  EXPECT_TRUE(has_problem(p, "DOF 0 is on both sides", "contact element 0"));
  p = good, p.contacts[2].group = 1;
  EXPECT_TRUE(has_problem(p, "group 1 is out of range", "contact element 2 (level 3) group"));
  p = good, p.contacts[2].level = -1;
  EXPECT_TRUE(has_problem(p, "level -1", "contact element 2 (level 3) level"));
  p = good, p.contacts[2].label.clear();
  EXPECT_TRUE(has_problem(p, "no label", "contact element 2 label"));
  p = good, p.groups[0].name.clear();
  EXPECT_TRUE(has_problem(p, "no name", "contact group 0 name"));
  p = good, p.groups.push_back(ContactGroup{});
  EXPECT_TRUE(has_problem(p, "'pounding' is used twice", "contact group 1 name"));
  // a wall side and a floor against a column between two floors are valid
  p = good, p.contacts[0].right = {SideKind::wall, -1, -1, 0};
  p.contacts[1].right = {SideKind::interpolated, 5, 6, 0};  // building2 floors 3 and 4 (DOFs 5, 6)
  EXPECT_TRUE(System::check(p).empty());
  // the column between the ground and a fixed building's first floor (p = ground, q its lowest DOF), xi in [0, 1]
  p.contacts[1].right = {SideKind::interpolated, ground, 1, 0}, p.contacts[1].xi = 0.4;
  EXPECT_TRUE(System::check(p).empty());
  EXPECT_EQ(System::build(p).elements_at(1), (std::vector<int>{1}));  // element 0 faces a wall here
  p.contacts[1].right = {SideKind::interpolated, ground, 3, 0};  // building2's floor 2 is not a first floor
  EXPECT_TRUE(has_problem(p, "is not the first floor of a fixed body", "contact element 1 (level 2) right"));
  p.contacts[1].right = {SideKind::interpolated, ground, 1, 0}, p.contacts[1].xi = 1.5;
  EXPECT_TRUE(has_problem(p, "xi = 1.5", "contact element 1 (level 2) xi"));
}

TEST(System, BuildRefusesBadPartsAsAProgrammingError) {
  System::Parts p = two_sticks(3, 5);
  p.springs.pop_back();
  EXPECT_THROW(System::build(p), std::logic_error);
}

TEST(System, ThreeAndFiveStoreysLevelMajorAdjacency) {
  const System s = System::build(two_sticks(3, 5));
  ASSERT_EQ(s.ndof(), 8);
  EXPECT_EQ(s.bodies()[0].dofs, (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(s.bodies()[1].dofs, (std::vector<int>{1, 3, 5, 6, 7}));
  const std::vector<int> body{0, 1, 0, 1, 0, 1, 1, 1};
  for (int d = 0; d < 8; ++d) {
    EXPECT_EQ(s.body_of(d), body[static_cast<std::size_t>(d)]) << d;
    EXPECT_EQ(s.spring_below(d), d) << d;
  }
  // springs_above: the storey spring of the floor above in the same body
  const std::vector<std::vector<int>> above{{2}, {3}, {4}, {5}, {}, {6}, {7}, {}};
  // elements_at: level k's element on both buildings' floor k
  const std::vector<std::vector<int>> at{{0}, {0}, {1}, {1}, {2}, {2}, {}, {}};
  for (int d = 0; d < 8; ++d) {
    EXPECT_EQ(s.springs_above(d), above[static_cast<std::size_t>(d)]) << d;
    EXPECT_EQ(s.elements_at(d), at[static_cast<std::size_t>(d)]) << d;
  }
  EXPECT_FALSE(s.any_storey_dashpots());
  EXPECT_FALSE(s.is_sdof_pair());
  System::Parts p = two_sticks(3, 5);
  p.bodies[1].storey_dashpots = true;
  EXPECT_TRUE(System::build(p).any_storey_dashpots());
  // a column element touches both floors it interpolates, once each; links count as springs above their i
  p.contacts.push_back(ContactElement{{SideKind::point, 4, -1, 0}, {SideKind::interpolated, 5, 6, 0}, 0, 3, "column"});
  p.springs.push_back(Spring{.i = 4, .j = 7, .role = SpringRole::link});
  const System c = System::build(p);
  EXPECT_EQ(c.elements_at(4), (std::vector<int>{2, 3}));
  EXPECT_EQ(c.elements_at(5), (std::vector<int>{2, 3}));
  EXPECT_EQ(c.elements_at(6), (std::vector<int>{3}));
  EXPECT_EQ(c.springs_above(4), (std::vector<int>{8}));
  EXPECT_EQ(c.spring_below(7), 7);  // the link is not the storey spring below DOF 7
}

TEST(System, SdofPairStructure) {
  const System s = System::sdof_pair();
  ASSERT_EQ(s.ndof(), 2);
  ASSERT_EQ(s.bodies().size(), 2u);
  ASSERT_EQ(s.springs().size(), 2u);
  ASSERT_EQ(s.contacts().size(), 1u);
  ASSERT_EQ(s.groups().size(), 1u);
  EXPECT_EQ(s.channels(), 1);
  for (int b = 0; b < 2; ++b) {
    const Body& body = s.bodies()[static_cast<std::size_t>(b)];
    EXPECT_EQ(body.dofs, std::vector<int>{b});
    EXPECT_EQ(body.heights, std::vector<double>{3.2});
    EXPECT_EQ(body.label, "building" + std::to_string(b + 1));
    EXPECT_EQ(body.floor_dashpot_ref, ground);
    EXPECT_FALSE(body.storey_dashpots || body.isolated);
    const Spring& sp = s.springs()[static_cast<std::size_t>(b)];
    EXPECT_EQ(sp.i, ground);
    EXPECT_EQ(sp.j, b);
    EXPECT_EQ(sp.law, 0);
    EXPECT_EQ(sp.role, SpringRole::storey);
    EXPECT_EQ(s.spring_below(b), b);
    EXPECT_TRUE(s.springs_above(b).empty());
    EXPECT_EQ(s.elements_at(b), std::vector<int>{0});
  }
  const ContactElement& e = s.contacts()[0];
  EXPECT_EQ(e.left, (Side{SideKind::point, 0, -1, 0}));   // L = building 1: pushed left
  EXPECT_EQ(e.right, (Side{SideKind::point, 1, -1, 0}));  // R = building 2
  EXPECT_EQ(e.label, "level 1");
  EXPECT_EQ(s.groups()[0].name, "pounding");
  EXPECT_TRUE(s.groups()[0].study_gap);
  EXPECT_TRUE(s.is_sdof_pair());
  const System copy = s;  // a value: copies compare equal
  EXPECT_EQ(copy, s);
  EXPECT_TRUE(System::build(two_sticks(1, 1)).is_sdof_pair());
  // is_sdof_pair() is the pair's structure: other heights and labels keep it, anything else loses it
  System::Parts p = s.parts();
  p.bodies[0].heights = {2.7}, p.bodies[1].label = "right";
  EXPECT_TRUE(System::build(p).is_sdof_pair());
  EXPECT_NE(System::build(p), s);
  p = s.parts(), p.bodies[1].storey_dashpots = true;
  EXPECT_FALSE(System::build(p).is_sdof_pair());
  p = s.parts(), std::swap(p.contacts[0].left, p.contacts[0].right);
  EXPECT_FALSE(System::build(p).is_sdof_pair());
  p = s.parts(), p.groups[0].study_gap = false;
  EXPECT_FALSE(System::build(p).is_sdof_pair());
}

}  // namespace
}  // namespace pounding::model
