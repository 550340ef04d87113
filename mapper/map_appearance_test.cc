#include "mapper/map_appearance.h"

#include <gtest/gtest.h>

#include "mapper/map_expansion.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using Vec = Eigen::Vector2d;
using Kind = RunAnchor::Kind;
using testing::Concat;
using testing::MakeScan;
using testing::Rectangle;

RunAnchor Make(Kind kind, int contour, int segment, const Vec& p) {
  RunAnchor a;
  a.kind = kind;
  a.contour = contour;
  a.segment = segment;
  a.point = p;
  return a;
}

// The contour holding point p (within `tolerance`), -1 if none.
int ContourAt(const ContourMap& map, const Vec& p, double tolerance = 0.01) {
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k)
      if (PointToSegmentDistance(p, c.GetSegment(k)) < tolerance) return id;
  return -1;
}

// The box of 4.8: 1.4 m at the wall, 1.0 m in front, 0.8 m deep, as a run in scan order
// (counter-clockwise about a sensor at y > 0: +x along the wall).
std::vector<Vec> BoxRun() {
  std::vector<Vec> run;
  for (double t = 0.05; t < 1.0; t += 0.1) run.push_back(Vec(4.0, 0.0) + t * Vec(0.2, 0.8));
  for (double t = 0.05; t < 1.0; t += 0.1) run.push_back(Vec(4.2, 0.8) + t * Vec(1.0, 0.0));
  for (double t = 0.05; t < 1.0; t += 0.1) run.push_back(Vec(5.2, 0.8) + t * Vec(0.2, -0.8));
  return run;
}

TEST(MapAppearanceTest, EightCasesFromTheTwoNeighbours) {
  const RunAnchor none, end = Make(Kind::kContourEnd, 1, 0, Vec::Zero()),
                        start = Make(Kind::kContourStart, 1, 0, Vec::Zero()),
                        in = Make(Kind::kInterior, 1, 0, Vec::Zero());
  EXPECT_EQ(AppearanceCase(none, start), 1);
  EXPECT_EQ(AppearanceCase(none, in), 2);
  EXPECT_EQ(AppearanceCase(end, start), 3);
  EXPECT_EQ(AppearanceCase(in, in), 4);
  EXPECT_EQ(AppearanceCase(end, in), 5);
  EXPECT_EQ(AppearanceCase(in, start), 6);
  EXPECT_EQ(AppearanceCase(end, none), 7);
  EXPECT_EQ(AppearanceCase(in, none), 8);
  EXPECT_EQ(AppearanceCase(none, none), 0);
}

TEST(MapAppearanceTest, Case4SplicesABoxIntoAWallAndLeavesTheWallBehindAlone) {
  ContourMap map;
  const int wall = map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
  const MapExpansionOptions o;
  const AppearanceEdit e = ApplyAppearance(map, BoxRun(), Make(Kind::kInterior, wall, 7, Vec(4.0, 0.0)),
                                           Make(Kind::kInterior, wall, 10, Vec(5.4, 0.0)), o);
  EXPECT_EQ(e.case_number, 4);
  EXPECT_TRUE(e.connected);
  ASSERT_EQ(map.NumContours(), 2);
  // One contour runs wall -> box -> wall; the occluded 1.4 m of wall is a contour of its own.
  const int joined = ContourAt(map, Vec(0.5, 0.0));
  EXPECT_EQ(ContourAt(map, Vec(4.7, 0.8)), joined);
  EXPECT_EQ(ContourAt(map, Vec(9.5, 0.0)), joined);
  const int behind = ContourAt(map, Vec(4.7, 0.0));
  ASSERT_NE(behind, joined);
  EXPECT_NEAR(map.Get(behind).Length(), 1.4, 1e-9);
  EXPECT_EQ(map.Get(behind).points.front(), Vec(4.0, 0.0));
  EXPECT_EQ(map.Get(behind).points.back(), Vec(5.4, 0.0));
  // Wall 4 m + box (0.82 + 1.0 + 0.82) + wall 4.6 m, less what the rough fit's vertices (at
  // least 0.5 m apart, 4.4.1) cut off the box's corners.
  EXPECT_NEAR(map.Get(joined).Length(), 4.0 + 1.0 + 2 * std::hypot(0.2, 0.8) + 4.6, 0.3);
  EXPECT_GT(map.Get(joined).Length(), 10.0 + 0.5);
  EXPECT_EQ(map.Get(joined).points.front(), Vec(0, 0));
  EXPECT_EQ(map.Get(joined).points.back(), Vec(10, 0));
}

TEST(MapAppearanceTest, Cases2And8SpliceOneSide) {
  const std::vector<Vec> box = BoxRun();
  const std::vector<Vec> up(box.begin(), box.begin() + 20);   // left side and front
  const std::vector<Vec> down(box.begin() + 10, box.end());   // front and right side
  {
    ContourMap map;
    const int wall = map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
    const AppearanceEdit e = ApplyAppearance(map, up, Make(Kind::kInterior, wall, 7, Vec(4.0, 0.0)), RunAnchor{}, {});
    EXPECT_EQ(e.case_number, 8);  // splice, then extend: [0 .. 4] + the run
    const Contour& c = map.Get(e.contour);
    EXPECT_EQ(c.points.front(), Vec(0, 0));
    EXPECT_NEAR((c.points.back() - up.back()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(map.Get(ContourAt(map, Vec(7, 0))).Length(), 6.0, 1e-9);  // [4 .. 10] left alone
  }
  {
    ContourMap map;
    const int wall = map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
    const AppearanceEdit e = ApplyAppearance(map, down, RunAnchor{}, Make(Kind::kInterior, wall, 10, Vec(5.4, 0.0)), {});
    EXPECT_EQ(e.case_number, 2);  // join: the run + [5.4 .. 10]
    const Contour& c = map.Get(e.contour);
    EXPECT_EQ(c.points.back(), Vec(10, 0));
    EXPECT_NEAR((c.points.front() - down.front()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(map.Get(ContourAt(map, Vec(2, 0))).Length(), 5.4, 1e-9);
  }
}

TEST(MapAppearanceTest, Cases5And6ExtendOneContourIntoAnother) {
  // Contour A ends at (4, 0); the run goes over the box onto wall B's interior (case 5).
  ContourMap map;
  const int a = map.Create({{0, 0}, {2, 0}, {4, 0}});
  const int b = map.Create(ResamplePolyline({{4, 0}, {10, 0}}, false, 0.5));
  const AppearanceEdit e5 = ApplyAppearance(map, BoxRun(), Make(Kind::kContourEnd, a, 1, Vec(4, 0)),
                                            Make(Kind::kInterior, b, 2, Vec(5.4, 0.0)), {});
  EXPECT_EQ(e5.case_number, 5);
  EXPECT_EQ(e5.contour, a);
  EXPECT_EQ(map.Get(a).points.back(), Vec(10, 0));
  EXPECT_NEAR(map.Get(ContourAt(map, Vec(4.7, 0))).Length(), 1.4, 1e-9);

  // Case 6: wall A's interior, then the start of contour B at (5.4, 0).
  ContourMap m6;
  const int wall = m6.Create(ResamplePolyline({{0, 0}, {5, 0}}, false, 0.5));
  const int b6 = m6.Create({{5.4, 0}, {8, 0}, {10, 0}});
  const AppearanceEdit e6 = ApplyAppearance(m6, BoxRun(), Make(Kind::kInterior, wall, 7, Vec(4.0, 0.0)),
                                            Make(Kind::kContourStart, b6, 0, Vec(5.4, 0)), {});
  EXPECT_EQ(e6.case_number, 6);
  EXPECT_EQ(m6.Get(e6.contour).points.front(), Vec(0, 0));
  EXPECT_EQ(m6.Get(e6.contour).points.back(), Vec(10, 0));
  EXPECT_NEAR(m6.Get(ContourAt(m6, Vec(4.5, 0))).Length(), 1.0, 1e-9);  // [4 .. 5] left alone
}

TEST(MapAppearanceTest, InteriorAnchorsNeedALongRunAndAPlausibleBypass) {
  ContourMap map;
  const int wall = map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
  const int before = map.Get(wall).NumPoints();
  MapExpansionOptions o;
  // 0.3 m of run beside interior matches: a corner or noise, not an object.
  const std::vector<Vec> short_run = {{4.0, 0.3}, {4.1, 0.3}, {4.2, 0.3}, {4.3, 0.3}};
  AppearanceEdit e = ApplyAppearance(map, short_run, Make(Kind::kInterior, wall, 7, Vec(4, 0)),
                                     Make(Kind::kInterior, wall, 8, Vec(4.3, 0)), o);
  EXPECT_EQ(e.case_number, 0);
  EXPECT_EQ(map.Get(wall).NumPoints(), before);
  // A run across the mouth of a 5 m deep alcove would cut 11.4 m of wall out of the
  // contour for a 2.6 m run: something covering the alcove (a curtain, a door), not an
  // object standing against the wall. It becomes a contour of its own instead.
  {
    ContourMap alcove;
    const int id = alcove.Create(
        ResamplePolyline({{0, 0}, {4, 0}, {4, -5}, {5.4, -5}, {5.4, 0}, {10, 0}}, false, 0.5));
    const int points = alcove.Get(id).NumPoints();
    auto segment_at = [&](const Vec& p) {
      const Contour& c = alcove.Get(id);
      for (int k = 0; k < c.NumSegments(); ++k)
        if (PointToSegmentDistance(p, c.GetSegment(k)) < 1e-9) return k;
      return -1;
    };
    const AppearanceEdit a = ApplyAppearance(alcove, BoxRun(), Make(Kind::kInterior, id, segment_at(Vec(3.9, 0)), Vec(3.9, 0)),
                                             Make(Kind::kInterior, id, segment_at(Vec(5.5, 0)), Vec(5.5, 0)), o);
    EXPECT_EQ(a.case_number, 0);
    EXPECT_EQ(alcove.Get(id).NumPoints(), points);
    EXPECT_EQ(alcove.NumContours(), 2);
  }
  // Static expansion: the box becomes a contour of its own.
  o.splice_interior = false;
  e = ApplyAppearance(map, BoxRun(), Make(Kind::kInterior, wall, 7, Vec(4.0, 0.0)),
                      Make(Kind::kInterior, wall, 10, Vec(5.4, 0.0)), o);
  EXPECT_EQ(e.case_number, 0);
  EXPECT_EQ(map.Get(wall).NumPoints(), before);
  EXPECT_EQ(map.NumContours(), 3);
}

TEST(MapAppearanceTest, ExpandMapSplicesABoxIntoAClosedRoomFromAScan) {
  // A mapped room; then a box stands against its south wall. One scan from in front of it.
  const std::vector<Segment> room = Concat(Rectangle(0, 0, 24, 10), Rectangle(16, 4, 19, 6));
  ContourMap map;
  map.Create(ResamplePolyline({{0, 0}, {24, 0}, {24, 10}, {0, 10}}, true, 0.5), true);
  std::vector<Segment> with_box = room;
  with_box.insert(with_box.end(), {Segment(11.0, 0.0, 11.2, 0.8), Segment(11.2, 0.8, 12.2, 0.8),
                                   Segment(12.2, 0.8, 12.4, 0.0)});
  const Pose2 pose(11.7, 4.0, 0.1);
  testing::ScanSpec spec;
  spec.num_points = 2048;
  const PreprocessedScan scan = PreprocessScan(MakeScan(with_box, pose, spec), {});
  const MapExpansionResult r = ExpandMap(scan, pose, map);
  EXPECT_EQ(r.cases[4], 1);
  // The box's three faces joined the room's contour; the wall behind stays, apart.
  const int room_id = ContourAt(map, Vec(0, 5));
  EXPECT_EQ(ContourAt(map, Vec(11.7, 0.8)), room_id);
  // (The rough fit's vertices are 0.5 m apart: the 0.82 m sides are followed within 10 cm;
  // contour fitting then pulls them onto the scans.)
  EXPECT_EQ(ContourAt(map, Vec(11.1, 0.4), 0.1), room_id);
  EXPECT_EQ(ContourAt(map, Vec(12.3, 0.4), 0.1), room_id);
  const int behind = ContourAt(map, Vec(11.7, 0.0));
  ASSERT_GE(behind, 0);
  EXPECT_NE(behind, room_id);
  EXPECT_NEAR(map.Get(behind).Length(), 1.4, 0.2);
  EXPECT_TRUE(map.Get(room_id).closed);  // the room is still one closed contour
}

}  // namespace
}  // namespace minenav::mapper
