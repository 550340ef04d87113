#include "mapper/correspondence.h"

#include <gtest/gtest.h>

#include <random>

namespace minenav::mapper {
namespace {

// Brute force over every segment of the map, straight from the three conditions.
PointMatch BruteForce(const Eigen::Vector2d& p, const Eigen::Vector2d& sensor, const ContourMap& map, double thr) {
  PointMatch best;
  double best_abs = thr;
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k) {
      const Segment s = c.GetSegment(k);
      const auto proj = ProjectOntoSegment(p, s);
      if (proj.region != SegmentRegion::kInterior) continue;
      const double d = SignedDistanceToLine(p, s);
      if (std::abs(d) >= best_abs || SignedDistanceToLine(sensor, s) <= 0) continue;
      best_abs = std::abs(d);
      best.segment = {id, k};
      best.distance = d;
    }
  return best;
}

TEST(CorrespondenceTest, ThreeConditionsOnAWall) {
  ContourMap map;
  // A wall along y = 0 sensed from y > 0: runs left to right (free space on the left).
  map.Create({{0, 0}, {2, 0}, {4, 0}});
  const Eigen::Vector2d sensor(1, 3);
  const auto m = MatchPoints({{1.0, 0.05}, {3.0, -0.2}, {1.0, 0.5}, {-0.5, 0.0}}, sensor, map, 0.3);
  ASSERT_TRUE(m[0].matched());
  EXPECT_EQ(m[0].segment.segment, 0);
  EXPECT_NEAR(m[0].distance, 0.05, 1e-12);  // + on the sensed side
  EXPECT_NEAR(m[0].along, 1.0, 1e-12);
  ASSERT_TRUE(m[1].matched());
  EXPECT_NEAR(m[1].distance, -0.2, 1e-12);
  EXPECT_FALSE(m[2].matched());  // condition 3: too far
  EXPECT_FALSE(m[3].matched());  // condition 1: beyond the end perpendicular
  // Condition 2: seen from behind the wall nothing matches.
  const auto behind = MatchPoints({{1.0, -0.05}}, {1, -3}, map, 0.3);
  EXPECT_FALSE(behind[0].matched());
}

TEST(CorrespondenceTest, NearestWinsAndAgreesWithBruteForce) {
  ContourMap map(1.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 10), small(-0.8, 0.8);
  for (int c = 0; c < 25; ++c) {
    Eigen::Vector2d p(u(rng), u(rng));
    std::vector<Eigen::Vector2d> pts{p};
    for (int k = 0; k < 5; ++k) pts.push_back(pts.back() + Eigen::Vector2d(small(rng), small(rng)));
    map.Create(pts);
  }
  std::vector<Eigen::Vector2d> q;
  for (int k = 0; k < 2000; ++k) q.emplace_back(u(rng), u(rng));
  const Eigen::Vector2d sensor(5, 5);
  const auto m = MatchPoints(q, sensor, map, 0.4);
  int matched = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const PointMatch b = BruteForce(q[k], sensor, map, 0.4);
    ASSERT_EQ(m[k].segment, b.segment) << k;
    if (b.matched()) {
      EXPECT_NEAR(m[k].distance, b.distance, 1e-12);
      ++matched;
    }
  }
  EXPECT_GT(matched, 100);
}

TEST(CorrespondenceTest, PiecesAreSortedAlongEachSegment) {
  std::vector<PointMatch> m(6);
  // Points 0..5 on two segments, out of order along them.
  const double along[6] = {0.8, 0.2, 0.5, 0.1, 0.9, 0.4};
  const int seg[6] = {0, 0, 0, 1, 1, -1};
  for (int k = 0; k < 6; ++k) {
    m[static_cast<size_t>(k)].along = along[k];
    m[static_cast<size_t>(k)].segment = seg[k] < 0 ? SegmentRef{} : SegmentRef{7, seg[k]};
  }
  std::vector<ErrorPiece> pieces;
  AppendPieces(2, m, &pieces);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].i, 1);  // 0.2 -> 0.5 -> 0.8 along segment 0
  EXPECT_EQ(pieces[0].j, 2);
  EXPECT_EQ(pieces[1].i, 2);
  EXPECT_EQ(pieces[1].j, 0);
  EXPECT_EQ(pieces[2].i, 3);  // segment 1: 0.1 -> 0.9
  EXPECT_EQ(pieces[2].j, 4);
  EXPECT_EQ(pieces[2].partial, 2);
}

}  // namespace
}  // namespace minenav::mapper
