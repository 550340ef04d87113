#include "common/geometry.h"

#include <gtest/gtest.h>

#include <random>

#include "common/angle.h"

namespace minenav {
namespace {

TEST(GeometryTest, ProjectionRegions) {
  const Segment s(0, 0, 2, 0);
  auto p = ProjectOntoSegment({1, 1}, s);
  EXPECT_EQ(p.region, SegmentRegion::kInterior);
  EXPECT_NEAR(p.distance, 1.0, 1e-12);
  EXPECT_NEAR(p.t, 0.5, 1e-12);
  p = ProjectOntoSegment({-3, 4}, s);
  EXPECT_EQ(p.region, SegmentRegion::kStartPoint);
  EXPECT_NEAR(p.distance, 5.0, 1e-12);
  p = ProjectOntoSegment({5, -4}, s);
  EXPECT_EQ(p.region, SegmentRegion::kEndPoint);
  EXPECT_NEAR(p.distance, 5.0, 1e-12);
}

TEST(GeometryTest, DistanceMatchesDenseSampling) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int trial = 0; trial < 200; ++trial) {
    const Segment s(u(rng), u(rng), u(rng), u(rng));
    const Eigen::Vector2d q(u(rng), u(rng));
    double brute = 1e9;
    for (int k = 0; k <= 20000; ++k) brute = std::min(brute, (q - (s.a + (k / 20000.0) * (s.b - s.a))).norm());
    EXPECT_NEAR(PointToSegmentDistance(q, s), brute, 2e-3);
    EXPECT_LE(PointToSegmentDistance(q, s), brute + 1e-12);
  }
}

TEST(GeometryTest, SignedDistanceIsPositiveOnTheLeft) {
  const Segment s(0, 0, 1, 0);
  EXPECT_NEAR(SignedDistanceToLine({5, 2}, s), 2.0, 1e-12);
  EXPECT_NEAR(SignedDistanceToLine({5, -2}, s), -2.0, 1e-12);
}

TEST(GeometryTest, RayHitsNearestWall) {
  const std::vector<Segment> walls = {{5, -1, 5, 1}, {3, -1, 3, 1}, {-2, -1, -2, 1}};
  auto hit = CastRay({0, 0}, 0.0, walls, 100.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range, 3.0, 1e-12);
  EXPECT_EQ(hit->segment, 1);
  hit = CastRay({0, 0}, kPi, walls, 100.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range, 2.0, 1e-12);
  EXPECT_FALSE(CastRay({0, 0}, kPi / 2, walls, 100.0));
  EXPECT_FALSE(CastRay({0, 0}, 0.0, walls, 2.5));  // beyond max range
}

TEST(GeometryTest, RayThroughASharedVertexHitsAWall) {
  // A closed polygon around the origin's neighbourhood: rays aimed exactly at its
  // vertices must not slip between the two segments meeting there.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector2d v(u(rng), u(rng));
    const Eigen::Vector2d p(u(rng), u(rng)), q(u(rng), u(rng));
    const std::vector<Segment> walls = {{p, v}, {v, q}};
    const Eigen::Vector2d origin(u(rng), u(rng));
    const Eigen::Vector2d d = v - origin;
    const auto hit = CastRay(origin, std::atan2(d.y(), d.x()), walls, 1e3);
    ASSERT_TRUE(hit) << "ray at vertex (" << v.transpose() << ") from (" << origin.transpose() << ") missed";
    EXPECT_LE(hit->range, d.norm() + 1e-9);
  }
}

TEST(GeometryTest, SegmentIntersection) {
  const auto x = SegmentIntersection(Segment(0, 0, 2, 2), Segment(0, 2, 2, 0));
  ASSERT_TRUE(x);
  EXPECT_TRUE(x->isApprox(Eigen::Vector2d(1, 1)));
  EXPECT_FALSE(SegmentIntersection(Segment(0, 0, 1, 1), Segment(0, 2, 0.9, 1.1)));
  EXPECT_FALSE(SegmentIntersection(Segment(0, 0, 1, 0), Segment(0, 1, 1, 1)));  // parallel
}

TEST(GeometryTest, Polyline) {
  const std::vector<Eigen::Vector2d> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NEAR(PolylineLength(square, false), 3.0, 1e-12);
  EXPECT_NEAR(PolylineLength(square, true), 4.0, 1e-12);
  EXPECT_NEAR(PointToPolylineDistance({-1, 0.5}, square, false), std::hypot(1.0, 0.5), 1e-12);
  EXPECT_NEAR(PointToPolylineDistance({-1, 0.5}, square, true), 1.0, 1e-12);
}

}  // namespace
TEST(GeometryTest, SameSegmentsComparesEndsInOrder) {
  const std::vector<Segment> a = {Segment(0, 0, 1, 0), Segment(1, 0, 1, 1)};
  EXPECT_TRUE(SameSegments(a, a));
  EXPECT_FALSE(SameSegments(a, {a[1], a[0]}));
  EXPECT_FALSE(SameSegments(a, {a[0]}));
  EXPECT_FALSE(SameSegments(a, {a[0], Segment(1, 0, 1, 1.5)}));
}

}  // namespace minenav
