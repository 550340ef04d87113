// The grid ray caster must give exactly what brute force (common/geometry.h CastRay) gives.
#include "sensor_driver/segment_grid.h"

#include <gtest/gtest.h>

#include <random>

#include "common/angle.h"
#include "sim/mine_generator.h"

namespace minenav {
namespace {

// Compares grid and brute force on one ray; returns true when identical.
::testing::AssertionResult SameHit(const SegmentGrid& grid, const Eigen::Vector2d& o, double bearing,
                                   double max_range) {
  const auto brute = CastRay(o, bearing, grid.segments(), max_range);
  const auto fast = grid.CastRay(o, bearing, max_range);
  if (brute.has_value() != fast.has_value())
    return ::testing::AssertionFailure() << "hit mismatch at (" << o.transpose() << ") bearing " << bearing
                                         << ": brute " << brute.has_value() << " grid " << fast.has_value();
  if (brute && (brute->range != fast->range || brute->segment != fast->segment))
    return ::testing::AssertionFailure() << "at (" << o.transpose() << ") bearing " << bearing << ": brute "
                                         << brute->range << " #" << brute->segment << ", grid " << fast->range
                                         << " #" << fast->segment;
  return ::testing::AssertionSuccess();
}

TEST(SegmentGridTest, RandomRaysInSyntheticMineMatchBruteForce) {
  MineOptions o;
  o.pillar_rows = 3;
  o.pillar_cols = 4;
  const std::vector<Segment> world = GenerateRoomAndPillarMine(o);
  const Eigen::Vector2d size = MinePanelSize(o);
  for (double cell : {0.0, 0.37, 1.0, 5.0}) {
    const SegmentGrid grid(world, cell);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> ux(-10.0, size.x() + 10.0), uy(-10.0, size.y() + 10.0);
    std::uniform_real_distribution<double> ub(-kPi, kPi), ur(0.0, 80.0);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Vector2d origin(ux(rng), uy(rng));
      const double range = i % 3 == 0 ? ur(rng) : 200.0;
      ASSERT_TRUE(SameHit(grid, origin, ub(rng), range)) << "cell " << cell;
      hits += CastRay(origin, 0.3, world, 200.0).has_value();
    }
    EXPECT_GT(hits, 1000);
  }
}

TEST(SegmentGridTest, DegenerateRaysMatchBruteForce) {
  MineOptions o;
  const std::vector<Segment> world = GenerateRoomAndPillarMine(o);
  const SegmentGrid grid(world, 1.0);
  // Rays from every 7th vertex towards other vertices (through shared endpoints), and
  // axis-aligned rays from points on cell boundaries.
  for (size_t i = 0; i < world.size(); i += 7) {
    for (size_t j = 3; j < world.size(); j += 29) {
      const Eigen::Vector2d from = world[i].a, to = world[j].b;
      if ((to - from).norm() < 1e-9) continue;
      const double bearing = std::atan2(to.y() - from.y(), to.x() - from.x());
      ASSERT_TRUE(SameHit(grid, from, bearing, 100.0));
      ASSERT_TRUE(SameHit(grid, from + Eigen::Vector2d(0.5, 0.5), bearing, 100.0));
    }
  }
  for (double x = -2.0; x < 70.0; x += 1.0)
    for (double y = -2.0; y < 50.0; y += 1.0)
      for (double b : {0.0, kPi / 2, kPi, -kPi / 2, kPi / 4, -3 * kPi / 4})
        ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(x, y), b, 100.0));
}

TEST(SegmentGridTest, LongCrossingSegmentsMatchBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::vector<Segment> soup;
  for (int i = 0; i < 300; ++i) soup.emplace_back(u(rng), u(rng), u(rng), u(rng));
  soup.emplace_back(0, 0, 0, 0);  // degenerate
  for (double cell : {0.0, 0.25, 3.0}) {
    const SegmentGrid grid(soup, cell);
    std::uniform_real_distribution<double> ub(-kPi, kPi);
    for (int i = 0; i < 5000; ++i) ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(u(rng), u(rng)), ub(rng), 60.0));
  }
}

TEST(SegmentGridTest, EmptyWorldAndOutsideRays) {
  const SegmentGrid empty({});
  EXPECT_FALSE(empty.CastRay(Eigen::Vector2d(0, 0), 0.0, 100.0).has_value());
  const SegmentGrid one({Segment(10, -1, 10, 1)});
  const auto hit = one.CastRay(Eigen::Vector2d(0, 0), 0.0, 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->range, 10.0);
  EXPECT_EQ(hit->segment, 0);
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, 9.99).has_value());
  EXPECT_TRUE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, 10.0).has_value());  // exactly at max range
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), kPi, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(20, 0), 0.0, 100.0).has_value());
  // Non-finite input: no hit, no undefined behaviour.
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(NAN, 0), 0.0, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), INFINITY, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, NAN).has_value());
  EXPECT_FALSE(one.CastRayDir(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0), 100.0).has_value());
}

}  // namespace
}  // namespace minenav
