#include "mapper/scan_preprocessing.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::Rectangle;

TEST(ScanPreprocessingTest, OptionsAreValidated) {
  ScanPreprocessingOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.median_filter_size = 4;
  EXPECT_NE(ValidateOptions(o), "");
  o = {};
  o.min_range = 5;
  o.max_range = 4;
  EXPECT_NE(ValidateOptions(o), "");
  o = {};
  o.discontinuity_threshold = 0;
  EXPECT_NE(ValidateOptions(o), "");
}

TEST(ScanPreprocessingTest, MedianFilterRemovesAnOutlierAndKeepsInvalid) {
  std::vector<float> r = {5, 5, 5, 9, 5, 5, std::nanf(""), 5};
  std::vector<bool> v = {true, true, true, true, true, true, false, true};
  const auto f = MedianFilterRanges(r, v, 3);
  EXPECT_FLOAT_EQ(f[3], 5.0f);
  EXPECT_TRUE(std::isnan(f[6]));
  EXPECT_EQ(MedianFilterRanges(r, v, 1)[3], 9.0f);
}

TEST(ScanPreprocessingTest, ClosedRoomIsOnePartialScanAcrossTheSeam) {
  const auto world = Rectangle(-5, -4, 6, 3);
  const LadarScan scan = MakeScan(world, Pose2(0, 0, 0.3));
  const PreprocessedScan p = PreprocessScan(scan, {});
  ASSERT_EQ(p.partial_scans.size(), 1u);
  EXPECT_EQ(p.NumPoints(), 720);
  // Counter-clockwise about the sensor: the sensor is on the left of every step.
  const auto& pts = p.partial_scans[0].points;
  for (size_t i = 1; i < pts.size(); ++i) {
    const Eigen::Vector2d d = pts[i] - pts[i - 1];
    const Eigen::Vector2d to_sensor = -pts[i - 1];
    EXPECT_GE(d.x() * to_sensor.y() - d.y() * to_sensor.x(), -1e-9) << i;
  }
}

TEST(ScanPreprocessingTest, ClockwiseScansAreReversedToCounterClockwise) {
  const auto world = Rectangle(-5, -4, 6, 3);
  testing::ScanSpec spec;
  spec.clockwise = true;
  const PreprocessedScan p = PreprocessScan(MakeScan(world, Pose2(0.5, 0.2, -1.0), spec), {});
  ASSERT_EQ(p.partial_scans.size(), 1u);
  const auto& pts = p.partial_scans[0].points;
  const Eigen::Vector2d sensor(0, 0);
  int left = 0;
  for (size_t i = 1; i < pts.size(); ++i) {
    const Eigen::Vector2d d = pts[i] - pts[i - 1];
    const Eigen::Vector2d s = sensor - pts[i - 1];
    if (d.x() * s.y() - d.y() * s.x() > 0) ++left;
  }
  EXPECT_GT(left, static_cast<int>(pts.size()) - 5);
}

TEST(ScanPreprocessingTest, OcclusionSplitsPartialScansAndTrimDropsFarWalls) {
  // A pillar in a room: its faces are separate partial scans from the room walls.
  auto world = Rectangle(-10, -10, 10, 10);
  world = testing::Concat(world, Rectangle(3, -1, 5, 1));
  const LadarScan scan = MakeScan(world, Pose2(0, 0, 0));
  const PreprocessedScan p = PreprocessScan(scan, {});
  ASSERT_EQ(p.partial_scans.size(), 2u);  // the pillar face, and the wall with its shadow cut out
  // Trimming to 4 m keeps only the pillar face (x = 3).
  ScanPreprocessingOptions o;
  o.max_range = 4.0;
  const PreprocessedScan t = PreprocessScan(scan, o);
  ASSERT_EQ(t.partial_scans.size(), 1u);
  for (const auto& q : t.partial_scans[0].points) EXPECT_NEAR(q.x(), 3.0, 1e-6);
}

// A post 0.7 m in front of a wall, seen by a Typhoon-fine scan (2048 readings, 4.4 cm noise):
// post and wall are two partial scans (the gap is over the 0.5 m break distance), but one mixed
// reading half way between them (2.35 m) is under it from both and joins them, a bridge along
// the ray; it is dropped, and post and wall stay apart. At a SICK's 1 deg
// (mixed_pixel_max_step) the rule stays off.
TEST(ScanPreprocessingTest, AMixedPixelNoLongerBridgesAPostAndTheWallBehind) {
  auto world = Rectangle(-5, -5, 2.7, 5);  // the wall behind the post at x = 2.7
  world = testing::Concat(world, Rectangle(2.0, -0.3, 2.2, 0.3));
  testing::ScanSpec spec;
  spec.num_points = 2048;
  spec.range_sigma = 0.044;
  spec.seed = 3;
  LadarScan scan = MakeScan(world, Pose2(0, 0, 0), spec);
  // The post's left edge (y = 0.3 at x = 2.0) is at bearing atan(0.3 / 2.0): the first reading
  // past it sees the wall; make it a mix of the two.
  const double edge = std::atan2(0.3, 2.0);
  size_t past = 0;
  while (scan.Bearing(past) < edge) ++past;
  ASSERT_GT(scan.ranges[past], 2.5f);  // the wall
  scan.ranges[past] = static_cast<float>(2.35 / std::cos(scan.Bearing(past)));
  const auto partial_holding = [](const PreprocessedScan& p, double x, double y) {
    for (size_t k = 0; k < p.partial_scans.size(); ++k)
      for (const auto& q : p.partial_scans[k].points)
        if ((q - Eigen::Vector2d(x, y)).norm() < 0.05) return static_cast<int>(k);
    return -1;
  };
  ScanPreprocessingOptions kept;
  kept.drop_mixed_pixels = false;
  const PreprocessedScan bridged = PreprocessScan(scan, kept);
  const PreprocessedScan split = PreprocessScan(scan, {});
  // The post's face (2.0, 0) and the wall just above it (2.7, 0.5).
  ASSERT_GE(partial_holding(bridged, 2.0, 0.0), 0);
  EXPECT_EQ(partial_holding(bridged, 2.0, 0.0), partial_holding(bridged, 2.7, 0.5));
  ASSERT_GE(partial_holding(split, 2.0, 0.0), 0);
  ASSERT_GE(partial_holding(split, 2.7, 0.5), 0);
  EXPECT_NE(partial_holding(split, 2.0, 0.0), partial_holding(split, 2.7, 0.5));
  EXPECT_EQ(split.NumPoints(), bridged.NumPoints() - 1);  // the mixed reading, and only it
  // A coarse scan of the same world: nothing is dropped.
  spec.num_points = 360;
  const LadarScan coarse = MakeScan(world, Pose2(0, 0, 0), spec);
  EXPECT_EQ(PreprocessScan(coarse, {}).NumPoints(), PreprocessScan(coarse, kept).NumPoints());
}

TEST(ScanPreprocessingTest, AdaptiveDiscontinuityKeepsSparseFarWallsAndSplitsNearGaps) {
  // 1° readings (SICK-like) in a 60 m square room: the walls, 30–42 m away, have their
  // readings 0.52–1.05 m apart. A fixed 0.5 m threshold leaves only single points (all
  // dropped); the adaptive gap (incidence 10°) keeps the whole room as one partial scan.
  testing::ScanSpec spec;
  spec.num_points = 360;
  spec.max_range = 80.0;
  const LadarScan far = MakeScan(Rectangle(-30, -30, 30, 30), Pose2(0, 0, 0.1), spec);
  EXPECT_EQ(PreprocessScan(far, {}).NumPoints(), 0);
  ScanPreprocessingOptions adaptive;
  adaptive.discontinuity_angle = DegToRad(10.0);
  const PreprocessedScan kept = PreprocessScan(far, adaptive);
  ASSERT_EQ(kept.partial_scans.size(), 1u);
  EXPECT_EQ(kept.NumPoints(), 360);
  // The gap formula: at 30 m, Δφ 1°, λ 10°: 30 sin 1° / sin 9° = 3.35 m; near, the fixed floor.
  EXPECT_NEAR(DiscontinuityGap(30.0, DegToRad(1.0), adaptive), 30.0 * std::sin(DegToRad(1.0)) / std::sin(DegToRad(9.0)),
              1e-12);
  EXPECT_EQ(DiscontinuityGap(2.0, DegToRad(1.0), adaptive), 0.5);
  EXPECT_EQ(DiscontinuityGap(30.0, DegToRad(1.0), {}), 0.5);
  // Near objects 1 m apart at 3 m stay separate: two posts in a big room are two partial
  // scans each, apart from the walls, with and without the adaptive gap.
  auto world = Rectangle(-30, -30, 30, 30);
  world = testing::Concat(world, Rectangle(3.0, -1.0, 3.4, -0.5));
  world = testing::Concat(world, Rectangle(3.0, 0.5, 3.4, 1.0));
  spec.num_points = 720;  // 0.5°: the posts get enough readings to be kept
  const LadarScan posts = MakeScan(world, Pose2(0, 0, 0), spec);
  int near_partials = 0;
  for (const PartialScan& ps : PreprocessScan(posts, adaptive).partial_scans) {
    bool near_post = true;
    for (const auto& q : ps.points) near_post = near_post && q.norm() < 4.0;
    if (near_post) {
      ++near_partials;
    } else {
      for (const auto& q : ps.points) EXPECT_GT(q.norm(), 29.0);  // no wall run swallows a post
    }
  }
  EXPECT_EQ(near_partials, 2);
  ScanPreprocessingOptions bad;
  bad.discontinuity_angle = -0.1;
  EXPECT_NE(ValidateOptions(bad), "");
}

TEST(ScanPreprocessingTest, DensityReductionKeepsSpacingAndEnds) {
  std::vector<Eigen::Vector2d> line;
  for (int i = 0; i <= 100; ++i) line.emplace_back(0.01 * i, 0.0);
  const auto r = ReduceDensity(line, 0.099);  // every 10th point
  EXPECT_EQ(r.front(), line.front());
  EXPECT_EQ(r.back(), line.back());
  EXPECT_EQ(r.size(), 11u);
  for (size_t i = 1; i < r.size(); ++i) EXPECT_GE((r[i] - r[i - 1]).norm(), 0.05 - 1e-12);
}

TEST(ScanPreprocessingTest, SensorOffsetMovesPointsIntoTheVehicleFrame) {
  const auto world = Rectangle(-5, -4, 6, 3);
  LadarScan scan = MakeScan(world, Pose2(0, 0, 0));
  scan.sensor_offset = Pose2(1.0, 0.0, 0.0);  // reported ranges are from x = 1 in the vehicle
  const PreprocessedScan p = PreprocessScan(scan, {});
  EXPECT_EQ(p.sensor_position, Eigen::Vector2d(1.0, 0.0));
  double max_x = -1e9;
  for (const auto& q : p.partial_scans[0].points) max_x = std::max(max_x, q.x());
  EXPECT_NEAR(max_x, 7.0, 1e-3);
}

}  // namespace
}  // namespace minenav::mapper
