// path_planner's node on FakeRuntime: requests answered on the worker and tagged with their
// id, bad requests refused in one line, a goal behind a frontier refused unless exploring, a
// deadline named, and replanning when a wall appears across the active path (every path
// judged by the independent checker against the map it was planned on).

#include "planner/path_planner_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "common/angle.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "common/node/map_updates.h"
#include "minenav/pose_estimate_t.hpp"
#include "planner/testing/path_checker.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000'000;

ContourPolyline Poly(std::vector<Eigen::Vector2d> points, bool closed) {
  ContourPolyline c;
  c.closed = closed;
  c.points = std::move(points);
  return c;
}

// A 40 x 24 m room seen from inside (closed, counter-clockwise).
ContourPolyline Room() { return Poly({{0, 0}, {40, 0}, {40, 24}, {0, 24}}, true); }
// A box seen from outside (closed, clockwise).
ContourPolyline Box(double x0, double y0, double x1, double y1) {
  return Poly({{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}}, true);
}

contour_map_t MapMessage(int64_t version, std::vector<ContourPolyline> contours, int64_t utime) {
  ContourMapMessage m;
  m.utime = utime;
  m.version = version;
  m.num_scans = 1;
  m.contours = std::move(contours);
  return ContourMapToLcm(m);
}

path_request_t Request(int64_t id, const Pose2& start, const Pose2& goal, int64_t utime) {
  path_request_t r{};
  r.utime = utime;
  r.request_id = id;
  r.start = ToLcm(start);
  r.goal = ToLcm(goal);
  r.position_tolerance = 0.1;
  r.heading_tolerance = 0.05;
  r.allow_reverse = true;
  r.clearance = 0.1;
  r.allow_unknown = false;
  return r;
}

testing::PathCheckReport Check(const path_t& p, const std::vector<Segment>& map, double clearance) {
  std::vector<testing::CheckedPiece> pieces;
  for (const path_segment_t& s : p.segments) pieces.push_back({s.motion, FromLcm(s.end)});
  testing::PathCheckSettings settings;
  settings.polygon = Footprint::Rectangle(3.3, 10.0).vertices;
  settings.clearance = clearance;
  settings.sample_step = 0.02;
  return testing::CheckPath(map, FromLcm(p.start), pieces, settings);
}

struct Harness {
  explicit Harness(PathPlannerNodeOptions options = {})
      : node(fake.runtime(), std::move(options), Footprint::Rectangle(3.3, 10.0)) {}
  // Runs the loop (real time passes for the worker) until `count` PATH messages were
  // published or `seconds` passed.
  std::vector<path_t> WaitForPaths(size_t count, double seconds = 60.0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
      clock.Advance(20'000);
      fake.runtime().SpinOnce(0);
      if (fake.bus().PublishedOn("PATH").size() >= count) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return fake.bus().Decoded<path_t>("PATH");
  }
  int64_t now() const { return clock.NowUtime(); }

  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  PathPlannerNode node;
};

TEST(PathPlannerNode, AnswersARequestWithAPathTaggedWithItsId) {
  Harness h;
  const std::vector<ContourPolyline> room = {Room()};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, room, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(7, {7, 12, 0}, {33, 12, 0}, h.now()));
  const std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  const path_t& p = paths[0];
  EXPECT_EQ(p.request_id, 7);
  ASSERT_TRUE(p.feasible) << p.status;
  EXPECT_EQ(p.status.rfind("ok: ", 0), 0u) << p.status;
  EXPECT_EQ(p.num_segments, static_cast<int32_t>(p.segments.size()));
  ASSERT_GT(p.num_segments, 0);
  EXPECT_NEAR(p.segments.back().end.x, 33.0, 1e-6);
  EXPECT_NEAR(p.segments.back().end.y, 12.0, 1e-6);
  EXPECT_NEAR(p.length, 26.0, 1e-6);  // straight across the room
  for (const path_segment_t& s : p.segments) {
    EXPECT_GE(s.motion, 0);
    EXPECT_LE(s.motion, 6);
    EXPECT_DOUBLE_EQ(s.speed, 0.076);
  }
  const auto report = Check(p, ContourMapSegments(ContourMapMessage{0, 1, 1, room}), 0.1);
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_TRUE(h.node.has_active_path());
}

// A miner that stopped short 4 cm beside a pillar (the map grew around it) leaves with the
// clearance it has: the answer says so, the path keeps that clearance everywhere (the
// independent checker, never in contact) and reaches the goal. A start in contact stays refused.
TEST(PathPlannerNode, AStartWithinTheClearanceLeavesWithTheClearanceItHas) {
  Harness h;
  const std::vector<ContourPolyline> map = {Room(), Box(8, 6, 20, 12)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, map, h.now()));
  const double beside = 6.0 - 1.65 - 0.04;  // its left side 0.04 m below the pillar's south face
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(8, {14.0, beside, 0.0}, {33, 16, kPi / 2}, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(9, {14.0, beside + 0.06, 0.0}, {33, 16, kPi / 2}, h.now()));
  const std::vector<path_t> paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  const path_t& p = paths[0].request_id == 8 ? paths[0] : paths[1];
  const path_t& touching = paths[0].request_id == 8 ? paths[1] : paths[0];
  ASSERT_TRUE(p.feasible) << p.status;
  EXPECT_NE(p.status.find("start within 0.10 m of a wall: planned with a clearance of 0.01 m"), std::string::npos)
      << p.status;
  const auto report = Check(p, ContourMapSegments(ContourMapMessage{0, 1, 1, map}), 0.0125);
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_NEAR(p.segments.back().end.x, 33.0, 0.1);
  EXPECT_NEAR(p.segments.back().end.y, 16.0, 0.1);
  EXPECT_FALSE(touching.feasible);
  EXPECT_NE(touching.status.find("start"), std::string::npos) << touching.status;
}

// Closer than the half collision step (a tracker stops where its own check says contact, so
// a vehicle can stand a centimetre from a wall the map grew): clearance 0 with a step fine
// enough, and the path is never in contact (the checker samples every 2 mm).
TEST(PathPlannerNode, AStartACentimetreFromAWallLeavesWithAFinerStep) {
  Harness h;
  const std::vector<ContourPolyline> map = {Room(), Box(8, 6, 20, 12)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, map, h.now()));
  const double beside = 6.0 - 1.65 - 0.0123;  // its left side 12.3 mm below the pillar
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(10, {14.0, beside, 0.0}, {33, 16, kPi / 2}, h.now()));
  const std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  const path_t& p = paths[0];
  ASSERT_TRUE(p.feasible) << p.status;
  EXPECT_NE(p.status.find("start within 0.10 m of a wall: planned with a clearance of 0.00 m (checked every 0.022 m)"),
            std::string::npos)
      << p.status;
  testing::PathCheckReport report = Check(p, ContourMapSegments(ContourMapMessage{0, 1, 1, map}), 0.0);
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_GT(report.min_clearance, 0.0);
  EXPECT_NEAR(p.segments.back().end.x, 33.0, 0.1);
  EXPECT_NEAR(p.segments.back().end.y, 16.0, 0.1);
}

// A vehicle standing across a frontier (MakeContourFreeSpace closed a gap in the wall through
// where the ladar looked from) is not in collision: the frontier is ignored for its start, the
// answer says so, and the path keeps the clearance from every wall. The goal must still be in
// the known free space.
TEST(PathPlannerNode, AFrontierThroughTheVehicleIsNoWallWhereItStands) {
  Harness h;
  // The room with its south wall unseen from x = 12 to 16 (the frontier (12, 0) -> (16, 0)),
  // and a pillar 20 m south of it: the map's box holds the vehicle standing in the gap.
  const std::vector<ContourPolyline> map = {Poly({{16, 0}, {40, 0}, {40, 24}, {0, 24}, {0, 0}, {12, 0}}, false),
                                            Box(30, -21, 31, -20)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, map, h.now()));
  const Pose2 in_the_gap(14, 3, kPi / 2);  // from y = -2 to 8, 0.35 m from the wall's ends
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(11, in_the_gap, {33, 16, kPi / 2}, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(12, in_the_gap, {14, -10, kPi / 2}, h.now()));  // unknown
  const std::vector<path_t> paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  const path_t& p = paths[0].request_id == 11 ? paths[0] : paths[1];
  const path_t& outside = paths[0].request_id == 11 ? paths[1] : paths[0];
  ASSERT_TRUE(p.feasible) << p.status;
  EXPECT_EQ(p.status.rfind("1 frontier(s) through the vehicle's footprint ignored; ok: ", 0), 0u) << p.status;
  const auto report = Check(p, ContourMapSegments(ContourMapMessage{0, 1, 1, map}), 0.1);
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_NEAR(p.segments.back().end.x, 33.0, 0.1);
  EXPECT_NEAR(p.segments.back().end.y, 16.0, 0.1);
  EXPECT_FALSE(outside.feasible);
  EXPECT_NE(outside.status.find("is not in the known free space"), std::string::npos) << outside.status;
}

// A request before any map, within first_map_wait of the start, is left for its repeat (the
// coordinator repeats; a restarted planner gets the map within the mapper's republish period);
// its repeat after the map is planned; after the wait, "no map" is answered at once.
TEST(PathPlannerNode, ARequestBeforeTheFirstMapIsLeftForItsRepeat) {
  PathPlannerNodeOptions o;
  o.first_map_wait = 10.0;
  Harness h(o);
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(1, {7, 12, 0}, {33, 12, 0}, h.now()));
  EXPECT_TRUE(h.WaitForPaths(1, 0.3).empty()) << "answered without a map";
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Room()}, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(1, {7, 12, 0}, {33, 12, 0}, h.now()));  // the repeat
  const std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(paths[0].request_id, 1);
  EXPECT_TRUE(paths[0].feasible) << paths[0].status;

  Harness late(o);
  late.clock.Advance(11'000'000);  // past the wait: no map is the answer
  late.fake.bus().InjectMessage("PATH_REQUEST", Request(2, {7, 12, 0}, {33, 12, 0}, late.now()));
  const std::vector<path_t> refused = late.WaitForPaths(1);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_FALSE(refused[0].feasible);
  EXPECT_EQ(refused[0].status.rfind("no map: nothing received on CONTOUR_MAP yet", 0), 0u) << refused[0].status;
}

TEST(PathPlannerNode, BadRequestsAreRefusedInOneLine) {
  PathPlannerNodeOptions no_wait;
  no_wait.first_map_wait = 0.0;  // "no map" answered at once
  Harness h(no_wait);
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(1, {7, 12, 0}, {33, 12, 0}, h.now()));  // no map yet
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Room()}, h.now()));
  path_request_t nan = Request(2, {5, 10, 0}, {std::nan(""), 12, 0}, h.now());
  path_request_t tolerance = Request(3, {7, 12, 0}, {33, 12, 0}, h.now());
  tolerance.position_tolerance = -1.0;
  path_request_t clearance = Request(4, {7, 12, 0}, {33, 12, 0}, h.now());
  clearance.clearance = 5.0;
  path_request_t heading = Request(5, {7, 12, 0}, {33, 12, 0}, h.now());
  heading.heading_tolerance = std::nan("");
  path_request_t in_wall = Request(6, {7, 12, 0}, {38, 12, 0}, h.now());  // the miner's nose in the wall
  for (const auto& r : {nan, tolerance, clearance, heading, in_wall}) h.fake.bus().InjectMessage("PATH_REQUEST", r);
  const std::vector<path_t> paths = h.WaitForPaths(6);
  ASSERT_EQ(paths.size(), 6u);
  const char* expected[] = {"no map", "goal is not finite", "position_tolerance", "clearance 5.00 m",
                            "heading_tolerance", "collision"};
  std::vector<int64_t> ids;
  for (const path_t& p : paths) {
    EXPECT_FALSE(p.feasible);
    EXPECT_EQ(p.num_segments, 0);
    EXPECT_EQ(p.status.find('\n'), std::string::npos);
    ids.push_back(p.request_id);
    EXPECT_NE(p.status.find(expected[p.request_id - 1]), std::string::npos) << p.request_id << ": " << p.status;
  }
  EXPECT_EQ(ids, (std::vector<int64_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_FALSE(h.node.has_active_path());
}

TEST(PathPlannerNode, AGoalBehindAFrontierIsRefusedUnlessUnknownSpaceIsAllowed) {
  Harness h;
  // A 20 m room with a doorway (y 7..13) in its east wall; beyond it, a pillar seen through
  // the doorway. The doorway is a frontier: (27, 10) is behind it.
  const std::vector<ContourPolyline> map = {
      Poly({{20, 13}, {20, 20}, {0, 20}, {0, 0}, {20, 0}, {20, 7}}, false), Box(36, 8, 38, 12)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(3, map, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(1, {8, 10, 0}, {27, 10, 0}, h.now()));
  path_request_t explore = Request(2, {8, 10, 0}, {27, 10, 0}, h.now());
  explore.allow_unknown = true;
  h.fake.bus().InjectMessage("PATH_REQUEST", explore);
  const std::vector<path_t> paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(paths[0].request_id, 1);
  EXPECT_FALSE(paths[0].feasible);
  EXPECT_NE(paths[0].status.find("not in the known free space"), std::string::npos) << paths[0].status;
  EXPECT_EQ(paths[1].request_id, 2);
  ASSERT_TRUE(paths[1].feasible) << paths[1].status;
  // Through the doorway, clear of the walls (the frontier is not a wall for exploration).
  const auto report = Check(paths[1], ContourMapSegments(ContourMapMessage{0, 3, 1, map}), 0.1);
  EXPECT_TRUE(report.ok) << report.problem;
}

TEST(PathPlannerNode, ARequestThatDoesNotAllowReversingGetsNoReverseMotion) {
  Harness h;
  // A 6 m entry: the miner cannot turn round in it, so a goal behind it takes reversing.
  const std::vector<ContourPolyline> entry = {Poly({{0, 0}, {40, 0}, {40, 6}, {0, 6}}, true)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, entry, h.now()));
  path_request_t back = Request(1, {20, 3, 0}, {12, 3, 0}, h.now());
  back.allow_reverse = false;
  h.fake.bus().InjectMessage("PATH_REQUEST", back);
  back.request_id = 2;
  back.allow_reverse = true;
  h.fake.bus().InjectMessage("PATH_REQUEST", back);
  path_request_t ahead = Request(3, {12, 3, 0}, {30, 3, 0}, h.now());
  ahead.allow_reverse = false;
  h.fake.bus().InjectMessage("PATH_REQUEST", ahead);
  const std::vector<path_t> paths = h.WaitForPaths(3);
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_FALSE(paths[0].feasible);
  EXPECT_NE(paths[0].status.find("does not allow reversing"), std::string::npos) << paths[0].status;
  ASSERT_TRUE(paths[1].feasible) << paths[1].status;
  EXPECT_EQ(paths[1].segments.front().motion, path_segment_t::REVERSE);
  ASSERT_TRUE(paths[2].feasible) << paths[2].status;
  for (const path_segment_t& s : paths[2].segments) EXPECT_NE(DriveDirection(static_cast<Motion>(s.motion)), -1);
}

TEST(PathPlannerNode, TheDeadlineStopsASearchAndIsNamed) {
  PathPlannerNodeOptions options;
  options.deadline = 0.001;
  options.planner.analytic_shot_interval = 1000;  // no shot straight to the goal
  Harness h(options);
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Room(), Box(19, 0, 21, 18)}, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(9, {7, 12, 0}, {33, 12, kPi}, h.now()));
  const std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_FALSE(paths[0].feasible);
  EXPECT_NE(paths[0].status.find("deadline"), std::string::npos) << paths[0].status;
}

TEST(PathPlannerNode, AWallAcrossTheActivePathIsAvoidedByAReplannedPathWithTheSameId) {
  Harness h;
  const std::vector<ContourPolyline> v1 = {Room()};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, v1, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(42, {7, 12, 0}, {33, 12, 0}, h.now()));
  std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  ASSERT_TRUE(paths[0].feasible) << paths[0].status;

  // The vehicle has driven 2 m; a map version that changes nothing on the path: no new PATH.
  pose_estimate_t pose{};
  pose.utime = h.now();
  pose.source = "clue";
  pose.pose = ToLcm(Pose2(9, 12, 0));
  pose.converged = true;
  pose.status = "ok";
  h.fake.bus().InjectMessage("POSE", pose);
  const std::vector<ContourPolyline> v2 = {Room(), Box(36, 20, 38, 22)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(2, v2, h.now()));
  paths = h.WaitForPaths(2, 1.0);
  EXPECT_EQ(paths.size(), 1u) << "a map change off the path replanned it";

  // A wall appears across the path ahead (a box from y 10 to 14 at x 19..21).
  const std::vector<ContourPolyline> v3 = {Room(), Box(36, 20, 38, 22), Box(19, 10, 21, 14)};
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(3, v3, h.now()));
  paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  const path_t& p = paths[1];
  EXPECT_EQ(p.request_id, 42);
  ASSERT_TRUE(p.feasible) << p.status;
  EXPECT_EQ(p.status.rfind("replanned: map version 3 blocks piece", 0), 0u) << p.status;
  EXPECT_NEAR(p.start.x, 9.0, 1e-9);  // from the latest pose
  EXPECT_NEAR(p.segments.back().end.x, 33.0, 1e-6);
  const std::vector<Segment> walls = ContourMapSegments(ContourMapMessage{0, 3, 1, v3});
  const auto report = Check(p, walls, 0.1);
  EXPECT_TRUE(report.ok) << report.problem;
  // The old path did collide with the new wall (so the replan was needed).
  EXPECT_FALSE(Check(paths[0], walls, 0.01).ok);
  EXPECT_EQ(h.node.replans(), 1);
}

TEST(PathPlannerNode, ARepeatedRequestIdIsAnsweredAgainNotPlannedTwice) {
  Harness h;
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Room()}, h.now()));
  // Sent three times before the answer (the coordinator re-sends until it hears one).
  for (int i = 0; i < 3; ++i)
    h.fake.bus().InjectMessage("PATH_REQUEST", Request(77, {7, 12, 0}, {33, 12, 0}, h.now()));
  std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  paths = h.WaitForPaths(2, 0.5);
  EXPECT_EQ(paths.size(), 1u) << "repeats during the search are not planned again";
  // A repeat after the answer: the stored answer, byte for byte.
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(77, {7, 12, 0}, {33, 12, 0}, h.now()));
  paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(EncodeMessage(paths[1]), EncodeMessage(paths[0]));
  EXPECT_EQ(h.node.planners_built(), 1);
}

TEST(PathPlannerNode, WithDrivePathTheForwardedPathIsTheOneReplanned) {
  Harness h;
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Room()}, h.now()));
  // 50 is driven; 51 is the next subtask's path planned ahead (not driven yet).
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(50, {7, 12, 0}, {33, 12, 0}, h.now()));
  std::vector<path_t> paths = h.WaitForPaths(1);
  ASSERT_EQ(paths.size(), 1u);
  h.fake.bus().InjectMessage("DRIVE_PATH", paths[0]);
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(51, {33, 12, 0}, {7, 20, 0}, h.now()));
  paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  ASSERT_TRUE(paths[1].feasible) << paths[1].status;
  // A wall across 50's way (x 19..21, y 10..14): 50 is replanned, not 51.
  pose_estimate_t pose{};
  pose.utime = h.now();
  pose.source = "clue";
  pose.pose = ToLcm(Pose2(9, 12, 0));
  pose.converged = true;
  pose.status = "ok";
  h.fake.bus().InjectMessage("POSE", pose);
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(2, {Room(), Box(19, 10, 21, 14)}, h.now()));
  paths = h.WaitForPaths(3);
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_EQ(paths[2].request_id, 50);
  EXPECT_EQ(paths[2].status.rfind("replanned: ", 0), 0u) << paths[2].status;
  // Canceled on DRIVE_PATH: nothing is active, a new map replans nothing.
  path_t cancel = paths[2];
  cancel.feasible = false;
  cancel.num_segments = 0;
  cancel.segments.clear();
  h.fake.bus().InjectMessage("DRIVE_PATH", cancel);
  h.WaitForPaths(4, 0.2);
  EXPECT_FALSE(h.node.has_active_path());
}

TEST(PathPlannerNode, ACompressedMapIsReadAndARepeatedRequestReusesThePlanner) {
  Harness h;
  // Many small contours: the plain encoding exceeds the compression threshold.
  std::vector<ContourPolyline> map = {Room()};
  for (int k = 0; k < 1500; ++k) {
    const double x = 1.0 + 0.025 * k;
    map.push_back(Poly({{x, 23.5}, {x + 0.01, 23.6}, {x + 0.02, 23.5}, {x + 0.01, 23.4}}, true));
  }
  const contour_map_t m = MapMessage(1, map, h.now());
  ASSERT_EQ(m.encoding, contour_map_t::ENCODING_ZLIB);
  h.fake.bus().InjectMessage("CONTOUR_MAP", m);
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(1, {7, 12, 0}, {30, 10, 0.3}, h.now()));
  h.fake.bus().InjectMessage("PATH_REQUEST", Request(2, {8, 12, 0}, {30, 10, 0.3}, h.now()));
  const std::vector<path_t> paths = h.WaitForPaths(2);
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_TRUE(paths[0].feasible) << paths[0].status;
  EXPECT_TRUE(paths[1].feasible) << paths[1].status;
  EXPECT_EQ(h.node.map_version(), 1);
  EXPECT_EQ(h.node.planners_built(), 1);  // the second request used the first's planner
}

}  // namespace
}  // namespace minenav
