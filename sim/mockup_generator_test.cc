#include "sim/mockup_generator.h"

#include <gtest/gtest.h>

#include "common/angle.h"
#include "sim/world.h"

namespace minenav {
namespace {

double NearestWall(const Eigen::Vector2d& p, const std::vector<Segment>& world) {
  double best = 1e300;
  for (const Segment& s : world) best = std::min(best, PointToSegmentDistance(p, s));
  return best;
}

TEST(MockupGeneratorTest, Table1StationsInASixMetreCorridor) {
  const MockupWorld m = GenerateIndoorMockup(1);
  ASSERT_EQ(m.stations.size(), 16u);
  EXPECT_DOUBLE_EQ(m.stations[0].pose.x, 9.822);
  EXPECT_DOUBLE_EQ(m.stations[15].pose.y, 16.517);
  EXPECT_NEAR(m.stations[1].pose.theta, NormalizeAngle(DegToRad(187.587)), 1e-12);
  const World map(m.map);
  for (const Station& s : m.stations) {
    EXPECT_GT(NearestWall(s.pose.translation(), m.map), 1.5);
    EXPECT_TRUE(map.SameSpace(s.pose.translation(), m.stations[0].pose.translation()));
    EXPECT_GT(NearestWall(s.pose.translation(), m.clutter), 1.0);
  }
  // Corridor width: from a point on the first leg's centreline, walls 3 m either side.
  const auto up = CastRay(Eigen::Vector2d(12.0, 3.3), kPi / 2, m.map, 100.0);
  const auto down = CastRay(Eigen::Vector2d(12.0, 3.3), -kPi / 2, m.map, 100.0);
  ASSERT_TRUE(up && down);
  EXPECT_NEAR(up->range + down->range, 6.0, 1e-9);
  // Everything fits in the 20 x 30 m bay.
  for (const Segment& s : m.World())
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      EXPECT_GE(p.x(), 0.0);
      EXPECT_LE(p.x(), 20.0);
      EXPECT_GE(p.y(), 0.0);
      EXPECT_LE(p.y(), 30.0);
    }
}

TEST(MockupGeneratorTest, ClutterDependsOnSeedMapDoesNot) {
  const MockupWorld a = GenerateIndoorMockup(1), b = GenerateIndoorMockup(2), a2 = GenerateIndoorMockup(1);
  ASSERT_EQ(a.map.size(), b.map.size());
  for (size_t i = 0; i < a.map.size(); ++i) EXPECT_EQ(a.map[i].a, b.map[i].a);
  EXPECT_GE(a.clutter.size(), 30u);  // a dozen objects of 4-8 edges
  ASSERT_EQ(a.clutter.size(), a2.clutter.size());
  EXPECT_EQ(a.clutter[3].a, a2.clutter[3].a);
  EXPECT_NE(a.clutter.front().a, b.clutter.front().a);
  // Clutter stands in free space, never crossing a wall.
  const World map(a.map);
  for (const Segment& s : a.clutter) {
    EXPECT_TRUE(map.SameSpace(s.a, a.stations[0].pose.translation()));
    for (const Segment& w : a.map) EXPECT_FALSE(SegmentIntersection(s, w).has_value());
  }
  EXPECT_EQ(a.World().size(), a.map.size() + a.clutter.size());
}

}  // namespace
}  // namespace minenav
