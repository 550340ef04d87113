#include "mapper/map_expansion.h"

#include <gtest/gtest.h>

#include "mapper/correspondence.h"
#include "mapper/pose_estimation.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::Rectangle;

// Fraction of the scan's points that correspond to the map after expansion.
double Covered(const PreprocessedScan& scan, const Pose2& pose, const ContourMap& map, double thr) {
  return MeasureScanFit(scan, pose, map, thr).MatchedFraction();
}

// Largest distance from a contour vertex to the true walls.
double MaxVertexDeviation(const ContourMap& map, const std::vector<Segment>& world) {
  double worst = 0;
  for (const auto& [id, c] : map.contours())
    for (const auto& p : c.points) {
      double d = 1e9;
      for (const Segment& s : world) d = std::min(d, PointToSegmentDistance(p, s));
      worst = std::max(worst, d);
    }
  return worst;
}

TEST(MapExpansionTest, EmptyMapCreatesOneContourPerPartialScan) {
  auto world = Rectangle(0, 0, 20, 12);
  world = testing::Concat(world, Rectangle(12, 3, 15, 5));
  const Pose2 pose(6, 6, 0.1);
  const PreprocessedScan scan = PreprocessScan(MakeScan(world, pose), {});
  ContourMap map;
  const MapExpansionResult r = ExpandMap(scan, pose, map);
  EXPECT_EQ(static_cast<int>(r.created.size()), static_cast<int>(scan.partial_scans.size()));
  EXPECT_EQ(map.NumContours(), static_cast<int>(scan.partial_scans.size()));
  EXPECT_GT(Covered(scan, pose, map, 0.2), 0.97);
  EXPECT_LT(MaxVertexDeviation(map, world), 1e-4);
  // Contours follow the scan: free space (the sensor) on the left of every segment.
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k) EXPECT_GT(SignedDistanceToLine(pose.translation(), c.GetSegment(k)), 0);
  // Nominal segment length: the last vertex may be dropped for crowding the end (1.5x).
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k) EXPECT_LT(c.GetSegment(k).length(), 1.5 * 0.5 + 0.2);
  // A second pass changes nothing.
  const MapExpansionResult again = ExpandMap(scan, pose, map);
  EXPECT_TRUE(again.Touched().empty());
}

TEST(MapExpansionTest, ExtendsAContourAtItsEndAndAtItsStart) {
  // A long wall y = 0 seen from y > 0 (runs +x). The map holds its middle; the scan sees more.
  const std::vector<Segment> world = {Segment(-30, 0, 30, 0)};
  ContourMap map;
  const int id = map.Create(ResamplePolyline({{-2, 0}, {2, 0}}, false, 0.5));
  const Pose2 pose(0, 3, 0);
  testing::ScanSpec spec;
  spec.max_range = 10;
  const PreprocessedScan scan = PreprocessScan(MakeScan(world, pose, spec), {});
  const MapExpansionResult r = ExpandMap(scan, pose, map);
  EXPECT_TRUE(r.created.empty());
  ASSERT_EQ(map.NumContours(), 1);
  EXPECT_EQ(map.Ids()[0], id);
  const Contour& c = map.Get(id);
  EXPECT_LT(c.points.front().x(), -9.0);  // extended at the start ...
  EXPECT_GT(c.points.back().x(), 9.0);    // ... and at the end
  EXPECT_EQ(r.extended.size(), 2u);
  EXPECT_GT(Covered(scan, pose, map, 0.2), 0.97);
  EXPECT_LT(MaxVertexDeviation(map, world), 1e-4);
}

TEST(MapExpansionTest, ConnectsTwoContoursAndClosesARoom) {
  const auto world = Rectangle(0, 0, 10, 8);
  ContourMap map;
  // Two pieces of the room's counter-clockwise boundary with gaps between them.
  const int a = map.Create(ResamplePolyline({{1, 0}, {10, 0}, {10, 3}}, false, 0.5));
  const int b = map.Create(ResamplePolyline({{10, 5}, {10, 8}, {0, 8}, {0, 2}}, false, 0.5));
  const Pose2 pose(5, 4, 0);
  const PreprocessedScan scan = PreprocessScan(MakeScan(world, pose), {});
  const MapExpansionResult r = ExpandMap(scan, pose, map);
  EXPECT_TRUE(r.created.empty());
  ASSERT_EQ(map.NumContours(), 1);
  const Contour& c = map.Get(map.Ids()[0]);
  EXPECT_TRUE(c.closed);
  EXPECT_TRUE(c.id == a || c.id == b);
  EXPECT_NEAR(c.Length(), 36.0, 0.3);  // the rough fit cuts corners
  EXPECT_GT(Covered(scan, pose, map, 0.2), 0.97);
}

TEST(MapExpansionTest, ShortUnmatchedRunsAreIgnored) {
  const std::vector<Segment> world = {Segment(-30, 0, 30, 0)};
  ContourMap map;
  map.Create(ResamplePolyline({{-10, 0}, {10, 0}}, false, 0.5));
  const Pose2 pose(0, 3, 0);
  testing::ScanSpec spec;
  spec.max_range = 9;
  LadarScan raw = MakeScan(world, pose, spec);
  // Two outliers in the middle of the wall: a run of 2 points, below min_new_points.
  raw.ranges[540] += 0.5f;
  raw.ranges[541] += 0.5f;
  ScanPreprocessingOptions pre;
  pre.discontinuity_threshold = 1.0;
  const MapExpansionResult r = ExpandMap(PreprocessScan(raw, pre), pose, map);
  EXPECT_TRUE(r.Touched().empty());
  EXPECT_EQ(map.NumContours(), 1);
}

}  // namespace
}  // namespace minenav::mapper
