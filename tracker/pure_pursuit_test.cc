// The pure-pursuit pieces against closed-form geometry: the runs of a path with a cusp and a
// turn in place, the projection and lookahead on a straight run, the curvature of the arc
// through the goal point (checked against the circle through it), the quantisation, the speed
// regulation, and the tracker's refusal of a path through a wall.

#include "tracker/pure_pursuit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "common/angle.h"
#include "tracker/path_tracker.h"

namespace minenav {
namespace {

PlannedPath ForwardTurnReverse() {
  // 2 m forward, a quarter turn in place, 1 m reverse, 1 m reverse on a left arc.
  PlannedPath p;
  p.start = Pose2(0, 0, 0);
  Pose2 at = p.start;
  auto add = [&](Motion m, double amount, double radius) {
    at = PoseAfter(at, m, amount, radius);
    p.pieces.push_back({m, amount, radius, at});
  };
  add(Motion::kForward, 2.0, 0.0);
  add(Motion::kTurnInPlace, kPi / 2, 0.0);
  add(Motion::kReverse, 1.0, 0.0);
  add(Motion::kArcLeftReverse, 1.0, 4.0);
  return p;
}

TEST(PurePursuitTest, SplitsAPathIntoRunsAtCuspsAndTurnsInPlace) {
  const PlannedPath p = ForwardTurnReverse();
  const std::vector<TrackedRun> runs = SplitIntoRuns(p, 0.1);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].direction, 1);
  EXPECT_NEAR(runs[0].length, 2.0, 1e-12);
  EXPECT_EQ(runs[0].samples.size(), 21u);
  EXPECT_EQ(runs[1].direction, 0);
  EXPECT_NEAR(runs[1].end.theta, kPi / 2, 1e-12);
  EXPECT_EQ(runs[2].direction, -1);
  EXPECT_NEAR(runs[2].length, 2.0, 1e-12);  // the reverse straight and the reverse arc: one run
  EXPECT_NEAR(TranslationDistance(runs[2].end, p.pieces.back().end), 0.0, 1e-12);
  // Reversing from (2, 0) facing +y: backwards is -y.
  EXPECT_NEAR(runs[2].samples[10].y, -1.0, 1e-9);
}

TEST(PurePursuitTest, ProjectsAndLooksAheadOnAStraightRun) {
  PlannedPath p;
  p.start = Pose2(0, 0, 0);
  p.pieces.push_back({Motion::kForward, 10.0, 0.0, Pose2(10, 0, 0)});
  const TrackedRun run = SplitIntoRuns(p, 0.05).front();
  const RunProjection a = ProjectOnRun(run, {3.01, 0.2}, 0, 5.0);
  EXPECT_NEAR(a.arc_length, 3.0, 1e-9);
  EXPECT_NEAR(a.cross_track, 0.2, 1e-9);  // left of the travel direction
  EXPECT_NEAR(a.remaining, 7.0, 1e-9);
  const RunProjection b = ProjectOnRun(run, {9.5, -0.1}, a.index, 7.0);
  EXPECT_NEAR(b.remaining, 0.5, 1e-9);
  EXPECT_NEAR(b.cross_track, -0.1, 1e-9);
  // The search window: from index of 3 m, 1 m ahead at most.
  EXPECT_NEAR(ProjectOnRun(run, {9.0, 0.0}, a.index, 1.0).arc_length, 4.0, 1e-9);
  EXPECT_NEAR((LookaheadPoint(run, 3.0, 1.5) - Eigen::Vector2d(4.5, 0)).norm(), 0.0, 1e-9);
  // Beyond the end: straight on along the end heading.
  EXPECT_NEAR((LookaheadPoint(run, 9.5, 1.5) - Eigen::Vector2d(11.0, 0)).norm(), 0.0, 1e-9);
}

TEST(PurePursuitTest, CurvatureIsTheCircleTangentToTheHeadingThroughTheGoal) {
  // The circle tangent to the x axis at the origin with radius r passes through
  // (r sin a, r (1 - cos a)); its curvature is 1 / r.
  for (const double r : {2.0, 4.0, -3.0})
    for (const double a : {0.2, 0.6}) {
      const Eigen::Vector2d g(std::abs(r) * std::sin(a), r * (1 - std::cos(a)));
      EXPECT_NEAR(PursuitCurvature(Pose2(0, 0, 0), g, 1), 1.0 / r, 1e-9);
      // The same from a rotated, shifted pose.
      const Pose2 pose(5, -2, 0.7);
      EXPECT_NEAR(PursuitCurvature(pose, pose * g, 1), 1.0 / r, 1e-9);
    }
  // Reversing with the goal behind on the vehicle's left: the rear swings left by turning
  // the heading clockwise.
  EXPECT_LT(PursuitCurvature(Pose2(0, 0, 0), {-2.0, 0.5}, -1), 0.0);
  EXPECT_NEAR(BearingInEffectiveFrame(Pose2(0, 0, 0), {-2.0, 0.0}, -1), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(BearingInEffectiveFrame(Pose2(0, 0, 0), {-2.0, 0.0}, 1)), kPi, 1e-12);
}

TEST(PurePursuitTest, QuantisesAndRegulates) {
  EXPECT_EQ(QuantiseCurvature(0.01, 0.02, 1.0), QuantisedMotion::kStraight);
  EXPECT_EQ(QuantiseCurvature(0.05, 0.02, 1.0), QuantisedMotion::kArcLeft);
  EXPECT_EQ(QuantiseCurvature(-0.3, 0.02, 1.0), QuantisedMotion::kArcRight);
  EXPECT_EQ(QuantiseCurvature(-1.5, 0.02, 1.0), QuantisedMotion::kTurnInPlace);
  EXPECT_EQ(QuantiseCurvature(std::nan(""), 0.02, 1.0), QuantisedMotion::kTurnInPlace);
  EXPECT_DOUBLE_EQ(CurvatureRegulatedSpeed(0.08, 4.0, 8.0), 0.04);
  EXPECT_DOUBLE_EQ(CurvatureRegulatedSpeed(0.08, 10.0, 8.0), 0.08);
  EXPECT_DOUBLE_EQ(ProximityRegulatedSpeed(0.1, 0.25, 0.5, 0.3), 0.05);
  EXPECT_DOUBLE_EQ(ProximityRegulatedSpeed(0.1, 0.0, 0.5, 0.3), 0.03);
  EXPECT_DOUBLE_EQ(ApproachRegulatedSpeed(0.1, 0.15, 0.3, 0.005), 0.05);
  EXPECT_DOUBLE_EQ(ApproachRegulatedSpeed(0.1, -0.1, 0.3, 0.005), 0.005);
  EXPECT_DOUBLE_EQ(TurnRateFor(-0.01, 1.0, 0.005, 0.05), -0.01);
  EXPECT_DOUBLE_EQ(TurnRateFor(2.0, 1.0, 0.005, 0.05), 0.05);
  EXPECT_DOUBLE_EQ(TurnRateFor(0.001, 1.0, 0.005, 0.05), 0.005);
}

// A 40 m x 8 m room with a wall across it at x = 20.
std::vector<Segment> RoomWithWall() {
  return {{0, -4, 40, -4}, {40, -4, 40, 4}, {40, 4, 0, 4}, {0, 4, 0, -4}, {20, -4, 20, 4}};
}

TEST(PathTrackerTest, RefusesAPathThroughAWallAndStopsShortOfOneItWasNotTold) {
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  PlannedPath p;
  p.start = Pose2(6, 0, 0);
  p.pieces.push_back({Motion::kForward, 28.0, 0.0, Pose2(34, 0, 0)});
  PathTracker tracker({}, miner);
  auto map = std::make_shared<TrackerMap>(RoomWithWall(), miner, 0.0, 4.0);
  ASSERT_EQ(map->error(), "");
  tracker.SetMap(map);
  EXPECT_EQ(tracker.SetPath(p), TrackState::kBlocked);
  EXPECT_NE(tracker.message().find("piece 0"), std::string::npos) << tracker.message();
  EXPECT_EQ(tracker.Update(p.start).command.mode, DriveCommand::Mode::kStop);

  // Without the map the path is taken; once the wall is known, the tracker stops short of it:
  // the nose (5 m ahead of the centre) within collision_time * speed of x = 20.
  PathTracker blind({}, miner);
  ASSERT_EQ(blind.SetPath(p), TrackState::kActive);
  for (double x = 6.0; x <= 14.0; x += 0.5)  // the tracker follows the vehicle along the path
    EXPECT_EQ(blind.Update(Pose2(x, 0, 0)).command.mode, DriveCommand::Mode::kVelocity) << x;
  blind.SetMap(map);
  EXPECT_EQ(blind.Update(Pose2(14.0, 0, 0)).command.mode, DriveCommand::Mode::kVelocity) << "1 m to spare";
  const TrackStep s = blind.Update(Pose2(14.9, 0, 0));
  EXPECT_EQ(s.command.mode, DriveCommand::Mode::kStop);
  EXPECT_EQ(s.state, TrackState::kBlocked);
  EXPECT_TRUE(s.finished_now);
  EXPECT_NE(s.message.find("blocked"), std::string::npos) << s.message;
}

TEST(PathTrackerTest, NearAWallItKeepsConvergingOnThePathSlowerRatherThanGoingStraightOn) {
  // A path along y = 0 with a wall 25 cm right of the miner's side; the vehicle 6 cm left of
  // the path. Pure pursuit asks for the right arc; 3 s of it at 0.5 m/s (1.5 m, 21 deg) would
  // touch the wall, a few centimetres of it would not. The tracker takes the arc over the
  // distance found free, slower (that distance / collision_time), not straight on at speed
  // (which is free, but keeps the 6 cm it could never take out beside the wall).
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  PlannedPath p;
  p.start = Pose2(4.9, 0, 0);
  p.pieces.push_back({Motion::kForward, 25.1, 0.0, Pose2(30, 0, 0)});
  PathTrackerOptions o;
  o.cruise_speed = 0.5;
  o.regulated = false;
  PathTracker tracker(o, miner);
  const std::vector<Segment> walls = {{-10, -1.9, 40, -1.9}, {-10, 4, 40, 4}};
  tracker.SetMap(std::make_shared<TrackerMap>(walls, miner, 0.0, 4.0));
  ASSERT_EQ(tracker.SetPath(p), TrackState::kActive);
  const Pose2 left_of_path(5.0, 0.06, 0.0);
  const TrackStep s = tracker.Update(left_of_path);
  EXPECT_LT(s.curvature, -o.straight_deadband) << "the pursuit turns right: " << s.message;
  EXPECT_EQ(s.command.mode, DriveCommand::Mode::kVelocity) << s.message;
  EXPECT_LT(s.command.omega, 0.0) << s.message;
  EXPECT_GT(s.command.v, 0.0);
  EXPECT_LT(s.command.v, 0.1) << "slower: only a short arc is free";
  EXPECT_NE(s.message.find("arc_right"), std::string::npos) << s.message;
  // What it took is free for collision_time at its speed; the full arc is not.
  const TrackerMap map(walls, miner, 0.0, 4.0);
  const double checked = s.command.v * o.collision_time;
  EXPECT_FALSE(map.PieceCollides(left_of_path, {Motion::kArcRight, checked, 4.0,
                                                PoseAfter(left_of_path, Motion::kArcRight, checked, 4.0)}));
  EXPECT_TRUE(map.PieceCollides(left_of_path, {Motion::kArcRight, 1.5, 4.0,
                                               PoseAfter(left_of_path, Motion::kArcRight, 1.5, 4.0)}));
}

TEST(PathTrackerTest, HonoursThePathsSpeedLimitsFromBeforeTheyStart) {
  // 2 m at no limit, then 2 m limited to 0.03 m/s (path_t's segment speed), one run.
  PlannedPath p;
  p.start = Pose2(0, 0, 0);
  p.pieces.push_back({Motion::kForward, 2.0, 0.0, Pose2(2, 0, 0)});
  p.pieces.push_back({Motion::kForward, 2.0, 0.0, Pose2(4, 0, 0)});
  for (const bool regulated : {true, false}) {
    PathTrackerOptions o;
    o.regulated = regulated;
    PathTracker tracker(o, Footprint::Rectangle(3.3, 10.0));
    ASSERT_EQ(tracker.SetPath(p, {0.0, 0.03}), TrackState::kActive);
    EXPECT_DOUBLE_EQ(tracker.Update(Pose2(0.5, 0, 0)).command.v, 0.076) << "cruise before the limit";
    // The lookahead (0.6 m) reaches the limited piece: slower before it starts.
    EXPECT_DOUBLE_EQ(tracker.Update(Pose2(1.6, 0, 0)).command.v, 0.03);
    EXPECT_DOUBLE_EQ(tracker.Update(Pose2(2.5, 0, 0)).command.v, 0.03);
  }
  // Without limits, cruise all along.
  PathTracker free({}, Footprint::Rectangle(3.3, 10.0));
  ASSERT_EQ(free.SetPath(p), TrackState::kActive);
  for (double x : {0.5, 1.5, 2.5}) EXPECT_DOUBLE_EQ(free.Update(Pose2(x, 0, 0)).command.v, 0.076) << x;
}

TEST(PathTrackerTest, AtACuspItTurnsToTheNextRunsHeadingBeforeDrivingIt) {
  // 1 m forward, then 2 m reversed on a right arc at the miner's radius (no turn in place
  // planned at the cusp). The vehicle reaches the cusp 3 deg short of the heading: it stops,
  // turns in place (counter-clockwise, the error's sign) until within heading_tolerance, and
  // only then reverses on the arc.
  PlannedPath p;
  p.start = Pose2(0, 0, 0);
  const Pose2 cusp = PoseAfter(p.start, Motion::kForward, 1.0, 0.0);
  p.pieces.push_back({Motion::kForward, 1.0, 0.0, cusp});
  p.pieces.push_back({Motion::kArcRightReverse, 2.0, 4.0, PoseAfter(cusp, Motion::kArcRightReverse, 2.0, 4.0)});
  PathTracker tracker({}, Footprint::Rectangle(3.3, 10.0));
  ASSERT_EQ(tracker.SetPath(p), TrackState::kActive);
  EXPECT_EQ(tracker.Update(Pose2(0.5, 0, 0)).command.mode, DriveCommand::Mode::kVelocity);
  const Pose2 lagging(1.0, 0.0, -DegToRad(3.0));
  EXPECT_EQ(tracker.Update(lagging).command.mode, DriveCommand::Mode::kStop);  // the run's end
  const TrackStep turn = tracker.Update(lagging);
  EXPECT_EQ(turn.command.mode, DriveCommand::Mode::kTurnInPlace) << turn.message;
  EXPECT_GT(turn.command.omega, 0.0);
  EXPECT_EQ(tracker.corrections(), 1);
  EXPECT_EQ(tracker.Update(Pose2(1.0, 0.0, -DegToRad(1.0))).command.mode, DriveCommand::Mode::kTurnInPlace);
  const TrackStep drive = tracker.Update(Pose2(1.0, 0.0, -DegToRad(0.2)));
  EXPECT_EQ(drive.command.mode, DriveCommand::Mode::kVelocity) << drive.message;
  EXPECT_LT(drive.command.v, 0.0);
  EXPECT_EQ(tracker.run_index(), 1);
  // Aligned once: a lag that builds up on the run is pure pursuit's to take out, not a turn.
  EXPECT_EQ(tracker.Update(Pose2(1.0, 0.0, -DegToRad(1.0))).command.mode, DriveCommand::Mode::kVelocity);
}

TEST(PathTrackerTest, ClearanceIsTheFootprintsDistanceToTheNearestWall) {
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const TrackerMap map(RoomWithWall(), miner, 0.0, 4.0);
  EXPECT_NEAR(map.Clearance(Pose2(8, 0, 0), 10.0), 4.0 - 1.65, 1e-9);        // the side walls
  EXPECT_NEAR(map.Clearance(Pose2(14.5, 0, 0), 1.0), 0.5, 1e-9);              // the nose to x = 20
  EXPECT_NEAR(map.Clearance(Pose2(8, 0, 0), 1.0), 1.0, 1e-12);                // capped
}

TEST(PathTrackerTest, EveryOptionIsDeclaredAndTheDefaultsAreValid) {
  EXPECT_EQ(ValidatePathTrackerOptions({}), "");
  PathTrackerOptions bad;
  bad.straight_deadband = 0.3;
  EXPECT_NE(ValidatePathTrackerOptions(bad).find("straight_deadband"), std::string::npos);
}

}  // namespace
}  // namespace minenav
