#include "mapper/map_disappearance.h"

#include <gtest/gtest.h>

#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using Vec = Eigen::Vector2d;
using testing::MakeScan;

PreprocessedScan ScanOf(const std::vector<Segment>& world, const Pose2& pose, int points = 2048) {
  testing::ScanSpec spec;
  spec.num_points = points;
  return PreprocessScan(MakeScan(world, pose, spec), {});
}

// A square room, 10 m, around the sensor at (0, 0): every beam returns.
std::vector<Segment> Room() { return testing::Rectangle(-5, -5, 5, 5); }

TEST(MapDisappearanceTest, AContourSeenThroughIsRemoved) {
  // A door leaf mapped at x = 2 between the sensor and the wall x = 5: the scan sees the wall.
  ContourMap map;
  map.Create(ResamplePolyline({{2, -1}, {2, 1}}, false, 0.5));
  const MapDisappearanceResult r = RemoveDisappeared(ScanOf(Room(), Pose2(0, 0, 0)), Pose2(0, 0, 0), map);
  EXPECT_EQ(map.NumContours(), 0);
  EXPECT_EQ(r.contours_removed, 1);
  EXPECT_NEAR(r.removed_length, 2.0, 1e-9);
}

TEST(MapDisappearanceTest, WhatCorrespondsOrIsHiddenOrGlancingStays) {
  ContourMap map;
  const int on_wall = map.Create(ResamplePolyline({{5, -2}, {5, 2}}, false, 0.5));  // the wall itself
  const int near_wall = map.Create({{4.93, -2}, {4.93, 2}});  // within the 0.1 m threshold
  const int behind = map.Create({{7, -2}, {7, 2}});           // behind the wall: occluded, not gone
  // Nearly along the beams: it starts on the beam at bearing 0.5 rad and runs 8 degrees off
  // it, so every beam meets it at 8 degrees or less.
  const Vec start(std::cos(0.5), std::sin(0.5));
  const int glancing = map.Create({start, Vec(start + 2.0 * Vec(std::cos(0.64), std::sin(0.64)))});
  const MapDisappearanceResult r = RemoveDisappeared(ScanOf(Room(), Pose2(0, 0, 0)), Pose2(0, 0, 0), map);
  EXPECT_EQ(r.removed_length, 0.0);
  for (const int id : {on_wall, near_wall, behind, glancing}) EXPECT_NE(map.Find(id), nullptr);
  // The glancing one goes when the view-angle condition is dropped.
  MapDisappearanceOptions o;
  o.min_view_angle = 0.0;
  RemoveDisappeared(ScanOf(Room(), Pose2(0, 0, 0)), Pose2(0, 0, 0), map, o);
  EXPECT_EQ(map.Find(glancing), nullptr);
  EXPECT_NE(map.Find(behind), nullptr);
}

TEST(MapDisappearanceTest, OnlyThePartSeenThroughAHoleIsRemoved) {
  // A near wall x = 1.5 with a 0.6 m hole; a mapped contour at x = 3 behind it. Through the
  // hole the beams cover y in [-0.6, 0.6] at x = 3 (similar triangles) and hit x = 5.
  std::vector<Segment> world = Room();
  world.push_back(Segment(1.5, -4.9, 1.5, -0.3));
  world.push_back(Segment(1.5, 0.3, 1.5, 4.9));
  ContourMap map;
  const int id = map.Create(ResamplePolyline({{3, -2}, {3, 2}}, false, 0.5));
  const MapDisappearanceResult r = RemoveDisappeared(ScanOf(world, Pose2(0, 0, 0), 4096), Pose2(0, 0, 0), map);
  EXPECT_NEAR(r.removed_length, 1.2, 0.02);
  ASSERT_EQ(map.NumContours(), 2);
  // The first piece keeps the id; both pieces end at the edges of the seen-through part.
  EXPECT_NEAR(map.Get(id).points.front().y(), -2.0, 1e-9);
  EXPECT_NEAR(map.Get(id).points.back().y(), -0.6, 0.01);
  for (const auto& [cid, c] : map.contours()) EXPECT_NEAR(c.Length(), 1.4, 0.01);
}

TEST(MapDisappearanceTest, AClosedContourSeenThroughGoesAndSmallNibblesStay) {
  ContourMap map;
  // A parked machine (closed, clockwise: seen from outside) that has gone, turned 45 degrees
  // so no face is seen glancingly.
  map.Create({{2, 0}, {2.5, 0.5}, {3, 0}, {2.5, -0.5}}, true);
  // A contour whose end pokes 10 cm into the beams that pass a corner: too little to remove.
  std::vector<Segment> world = Room();
  world.push_back(Segment(2, -4.9, 2, 1.0));  // a wall whose end is at (2, 1); beams beyond it hit x = 5
  const int poking = map.Create({{1.9, -2.0}, {1.9, 1.1}});
  const MapDisappearanceResult r = RemoveDisappeared(ScanOf(world, Pose2(0, 0, 0), 4096), Pose2(0, 0, 0), map);
  EXPECT_EQ(r.contours_removed, 0);  // the machine is hidden by the new wall: kept
  EXPECT_NE(map.Find(poking), nullptr);
  EXPECT_NEAR(map.Get(poking).Length(), 3.1, 1e-9);
  // Without the wall the machine is seen through all round and goes entirely.
  const MapDisappearanceResult r2 = RemoveDisappeared(ScanOf(Room(), Pose2(0, 0, 0), 4096), Pose2(0, 0, 0), map);
  EXPECT_GE(r2.contours_removed, 1);
  EXPECT_EQ(map.NumContours(), 0);  // the poking contour is seen through too now
}

TEST(MapDisappearanceTest, BeamDivergenceWidensEachTriangle) {
  // 64 beams, 2 pi / 64 apart; beams k = -4..4 cross the mapped segment x = 2, |y| <= 1.
  // Without divergence the removed part runs from beam -4 to beam 4; with divergence d each
  // triangle reaches d / 2 further on either side.
  const double step = 2.0 * kPi / 64.0;
  for (const double divergence : {0.0, 0.05}) {
    ContourMap map;
    map.Create({{2.0, -1.0}, {2.0, 1.0}});
    MapDisappearanceOptions o;
    o.beam_divergence = divergence;
    o.min_piece_length = 0.0;
    // A small room, so that 64 beams still form partial scans (points 0.25 m apart).
    const MapDisappearanceResult r =
        RemoveDisappeared(ScanOf(testing::Rectangle(-2.5, -2.5, 2.5, 2.5), Pose2(0, 0, 0), 64), Pose2(0, 0, 0), map, o);
    EXPECT_NEAR(r.removed_length, 2.0 * 2.0 * std::tan(4 * step + 0.5 * divergence), 1e-9) << divergence;
    EXPECT_EQ(map.NumContours(), 2);  // the two ends between the last beams stay
  }
}

TEST(MapDisappearanceTest, Validation) {
  MapDisappearanceOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.beam_divergence = -1;
  EXPECT_NE(ValidateOptions(o), "");
  o = {};
  o.min_view_angle = 2.0;
  EXPECT_NE(ValidateOptions(o), "");
}

}  // namespace
}  // namespace minenav::mapper
