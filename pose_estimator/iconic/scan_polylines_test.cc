#include "pose_estimator/iconic/scan_polylines.h"

#include <gtest/gtest.h>

#include <random>

#include "pose_estimator/iconic/correspondence.h"

namespace minenav {
namespace {

TEST(ScanPolylinesTest, SplitsAtGapsAndClosesTheRing) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 10; ++i) points.emplace_back(0.1 * i, 0.0);   // run A: x 0 .. 0.9
  for (int i = 0; i < 10; ++i) points.emplace_back(5.0 + 0.1 * i, 0.0);  // run B after a 4.1 m gap
  points.emplace_back(std::nan(""), 0.0);                            // ignored
  for (int i = 0; i < 2; ++i) points.emplace_back(9.0, 0.1 * i);     // too short: dropped
  const auto runs = SplitIntoPartialScans(points, PartialScanOptions{});
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].size(), 10u);
  EXPECT_EQ(runs[1].size(), 10u);
  EXPECT_EQ(PartialScansToSegments(runs).size(), 18u);

  // A ring: the last point is next to the first, so the two ends join into one run.
  std::vector<Eigen::Vector2d> ring;
  for (int i = 0; i < 36; ++i) ring.emplace_back(2.0 * std::cos(i * 0.1745), 2.0 * std::sin(i * 0.1745));
  std::rotate(ring.begin(), ring.begin() + 5, ring.end());
  ring.insert(ring.begin() + 20, Eigen::Vector2d(50, 50));  // a lone far point splits it
  const auto ring_runs = SplitIntoPartialScans(ring, PartialScanOptions{});
  ASSERT_EQ(ring_runs.size(), 1u);
  EXPECT_EQ(ring_runs[0].size(), 36u);
}

TEST(ScanPolylinesTest, FitAveragesNoiseOut) {
  // A straight wall y = 3 sampled every 2 cm with 5 cm noise.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<Eigen::Vector2d> wall;
  for (int i = 0; i <= 250; ++i) wall.emplace_back(0.02 * i, 3.0 + noise(rng));
  PolylineFitOptions o;
  const auto fit = FitPolylines({wall}, o);
  ASSERT_GE(fit.size(), 8u);
  ASSERT_LE(fit.size(), 11u);
  for (size_t k = 0; k < fit.size(); ++k) {
    EXPECT_NEAR(fit[k].a.y(), 3.0, 0.05) << k;
    EXPECT_NEAR(fit[k].length(), 0.5, 0.3) << k;
    if (k > 0) {
      EXPECT_EQ(fit[k].a, fit[k - 1].b);  // a connected polyline
    }
  }
  // The raw polyline zigzags by the noise; the fit stays within a few cm.
  double worst_fit = 0.0;
  for (const Segment& s : fit) worst_fit = std::max({worst_fit, std::abs(s.a.y() - 3.0), std::abs(s.b.y() - 3.0)});
  EXPECT_LT(worst_fit, 0.05);
}

TEST(ScanPolylinesTest, OpenEndsAreTheEndsOfEachPolyline) {
  const std::vector<std::vector<Eigen::Vector2d>> runs = {{{0, 0}, {1, 0}, {2, 0}}, {{5, 5}, {6, 5}}};
  const std::vector<Segment> segments = PartialScansToSegments(runs);
  const std::vector<uint8_t> open = ComputeOpenEnds(segments);
  ASSERT_EQ(open.size(), 3u);
  EXPECT_EQ(open[0], 1);  // (0,0) starts the first polyline; (1,0) is shared
  EXPECT_EQ(open[1], 2);  // (2,0) ends it
  EXPECT_EQ(open[2], 3);  // a lone segment: both ends open
  EXPECT_TRUE(IsOpenEnd(open, 0, SegmentRegion::kStartPoint));
  EXPECT_FALSE(IsOpenEnd(open, 0, SegmentRegion::kEndPoint));
  EXPECT_FALSE(IsOpenEnd(open, 1, SegmentRegion::kInterior));
}

}  // namespace
}  // namespace minenav
