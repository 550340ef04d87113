// The mission report's figures against hand-made cases with known answers: a room with a
// pillar (free area 184 m²), a face moved by exactly 0.80 m, poses with a known offset, a set
// of planner status lines with malformed ones, mission status sequences, heartbeats.

#include "evaluation/mission_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/angle.h"
#include "evaluation/mission_picture.h"
#include "render/svg_render.h"

namespace minenav {
namespace {

// The closed loop through `corners`, each side split into `pieces` segments.
std::vector<Segment> Loop(const std::vector<Eigen::Vector2d>& corners, int pieces = 1) {
  std::vector<Segment> out;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d a = corners[i], b = corners[(i + 1) % corners.size()];
    for (int k = 0; k < pieces; ++k)
      out.push_back(Segment(a + (b - a) * k / pieces, a + (b - a) * (k + 1) / pieces));
  }
  return out;
}

std::vector<Eigen::Vector2d> Box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// A 20 x 10 m room with a 4 x 4 m pillar: 184 m² free.
std::vector<Segment> RoomWithPillar() {
  std::vector<Segment> w = Loop(Box(0, 0, 20, 10), 7);
  const std::vector<Segment> pillar = Loop(Box(8, 3, 12, 7), 3);
  w.insert(w.end(), pillar.begin(), pillar.end());
  return w;
}

// The same as a contour map: free space on the left of every contour (the room
// counter-clockwise, the pillar clockwise).
mapper::ContourMap RoomWithPillarMap() {
  mapper::ContourMap map;
  map.Create(Box(0, 0, 20, 10), true);
  std::vector<Eigen::Vector2d> pillar = Box(8, 3, 12, 7);
  std::reverse(pillar.begin(), pillar.end());
  map.Create(pillar, true);
  return map;
}

// ---------------------------------------------------------------------------------------

TEST(Summarize, MedianP95MaxMean) {
  std::vector<double> v;
  for (int i = 20; i >= 1; --i) v.push_back(i);
  const Distribution d = Summarize(v);
  EXPECT_EQ(d.count, 20);
  EXPECT_DOUBLE_EQ(d.median, 10.5);
  EXPECT_DOUBLE_EQ(d.p95, 19.0);  // nearest rank: the 19th of 20
  EXPECT_DOUBLE_EQ(d.max, 20.0);
  EXPECT_DOUBLE_EQ(d.mean, 10.5);
  const Distribution odd = Summarize({3.0, 1.0, 2.0});
  EXPECT_DOUBLE_EQ(odd.median, 2.0);
  EXPECT_DOUBLE_EQ(odd.p95, 3.0);
  EXPECT_EQ(Summarize({}).count, 0);
}

TEST(ExploredArea, RoomWithPillarIs184SquareMetres) {
  const std::vector<Segment> walls = RoomWithPillar();
  EXPECT_TRUE(FreeByParity(walls, {1.0, 1.0}));
  EXPECT_FALSE(FreeByParity(walls, {10.0, 5.0}));   // in the pillar
  EXPECT_FALSE(FreeByParity(walls, {-1.0, 5.0}));   // outside the room
  EXPECT_TRUE(FreeByParity(walls, {10.0, 2.0}));    // level with a split point of a wall
  // Known free: everything left of x = 10.
  const AreaGrid g = MakeAreaGrid(walls, [](const Eigen::Vector2d& p) { return p.x() < 10.0; }, {-1, -1}, {21, 11}, 0.2);
  const AreaFigures a = MeasureArea(g);
  EXPECT_NEAR(a.true_free_m2, 184.0, 1e-9);
  EXPECT_NEAR(a.explored_m2, 92.0, 1e-9);  // 100 m² left of x = 10 less 8 m² of pillar
  // Left of x = 10 but not free: the strip outside the room (55 x 60 cells) less the free cells.
  EXPECT_NEAR(a.falsely_free_m2, 55 * 60 * 0.04 - 92.0, 1e-9);
  EXPECT_NEAR(a.explored_fraction, 0.5, 1e-12);
}

TEST(ExploredArea, ScanLineAgreesWithParityEverywhereAndWithAPolygonsArea) {
  // A 64-gon of radius 5 with a triangle pillar, off the grid's axes.
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i < 64; ++i) circle.push_back({0.3 + 5 * std::cos(i * 2 * kPi / 64), -0.2 + 5 * std::sin(i * 2 * kPi / 64)});
  std::vector<Segment> walls = Loop(circle);
  const std::vector<Segment> tri = Loop({{-1.0, -1.0}, {2.0, -0.5}, {0.5, 2.0}});
  walls.insert(walls.end(), tri.begin(), tri.end());
  const AreaGrid g = MakeAreaGrid(walls, [](const Eigen::Vector2d&) { return false; }, {-6, -6}, {6, 6}, 0.05);
  int mismatches = 0;
  for (int iy = 0; iy < g.frame.ny; ++iy)
    for (int ix = 0; ix < g.frame.nx; ++ix) {
      const Eigen::Vector2d c = g.frame.CellMin(ix, iy) + Eigen::Vector2d::Constant(0.025);
      mismatches += (g.truly_free[static_cast<size_t>(g.frame.Index(ix, iy))] != 0) != FreeByParity(walls, c);
    }
  EXPECT_EQ(mismatches, 0);
  const double polygon = 0.5 * 64 * 25 * std::sin(2 * kPi / 64);
  const double triangle = 0.5 * std::abs(3.0 * 3.0 - 0.5 * 1.5);  // |AB x AC| / 2
  EXPECT_NEAR(MeasureArea(g).true_free_m2, polygon - triangle, 0.005 * polygon);
}

TEST(ExploredArea, TheClosedContourMapOfTheRoomIsKnownFreeExactly) {
  MissionInputs in;
  in.initial_world = in.final_world = RoomWithPillar();
  in.map = RoomWithPillarMap();
  const MissionFigures f = EvaluateMission(in);
  EXPECT_NEAR(f.area.true_free_m2, 184.0, 1e-6);
  EXPECT_NEAR(f.area.known_free_m2, 184.0, 1e-6);
  EXPECT_NEAR(f.area.explored_fraction, 1.0, 1e-9);
  EXPECT_NEAR(f.area.falsely_free_m2, 0.0, 1e-9);
  EXPECT_EQ(f.map.contours, 2);
  EXPECT_NEAR(f.map.length_m, 60.0 + 16.0, 1e-9);
  EXPECT_NEAR(f.map.deviation.max, 0.0, 1e-9);
  // The east half of the room mapped without the pillar (an open contour; its frontier closes
  // it at x = 10): 100 m² less the pillar's 8 m² explored, and the pillar's 8 m² shown free.
  MissionInputs half = in;
  half.map = mapper::ContourMap();
  half.map.Create({{10, 0}, {20, 0}, {20, 10}, {10, 10}}, false);
  const MissionFigures h = EvaluateMission(half);
  EXPECT_NEAR(h.area.explored_m2, 92.0, 0.5);
  EXPECT_NEAR(h.area.falsely_free_m2, 8.0, 0.5);
}

// ---------------------------------------------------------------------------------------

std::vector<StampedPose> StraightTruth(int n, int64_t dt_us) {
  std::vector<StampedPose> truth;
  for (int i = 0; i < n; ++i) truth.push_back({i * dt_us, Pose2(0.1 * i, 2.0, 0.3)});
  return truth;
}

TEST(PoseError, KnownOffsetGivesKnownStatistics) {
  const std::vector<StampedPose> truth = StraightTruth(101, 100000);  // 10 s at 10 Hz
  std::vector<StampedPose> est;
  // Between truth readings (interpolated), 0.3 m east and 0.4 m north: 0.5 m; heading +0.1 rad.
  for (int i = 0; i < 20; ++i) {
    const int64_t t = 50000 + i * 400000;
    const double x = 0.1 * (static_cast<double>(t) / 100000.0);
    est.push_back({t, Pose2(x + 0.3, 2.4, 0.4)});
  }
  est.push_back({99000000, Pose2(0, 0, 0)});  // after the truth ends: unmatched
  const PoseErrorFigures e = ComparePoses(est, truth, 500000);
  EXPECT_EQ(e.compared, 20);
  EXPECT_EQ(e.unmatched, 1);
  EXPECT_NEAR(e.mean_m, 0.5, 1e-9);
  EXPECT_NEAR(e.rms_m, 0.5, 1e-9);
  EXPECT_NEAR(e.max_m, 0.5, 1e-9);
  EXPECT_NEAR(e.max_heading_rad, 0.1, 1e-9);
  // Errors 0.1, 0.2, 0.3, 0.4 m: mean 0.25, RMS sqrt(0.3 / 4), max 0.4 at the last.
  std::vector<StampedPose> steps;
  for (int i = 1; i <= 4; ++i) steps.push_back({i * 1000000, Pose2(0.1 * 10 * i, 2.0 - 0.1 * i, 0.3)});
  const PoseErrorFigures s = ComparePoses(steps, truth, 500000);
  EXPECT_NEAR(s.mean_m, 0.25, 1e-9);
  EXPECT_NEAR(s.rms_m, std::sqrt(0.3 / 4), 1e-9);
  EXPECT_NEAR(s.max_m, 0.4, 1e-9);
  EXPECT_EQ(s.worst_utime, 4000000);
}

TEST(PoseError, DeadReckoningIsAlignedAtItsStart) {
  const std::vector<StampedPose> truth = StraightTruth(50, 100000);
  const Pose2 odom_T_world(5.0, -3.0, 1.2);  // the odometry frame, fixed where it started
  std::vector<StampedPose> odometry;
  for (const StampedPose& t : truth) odometry.push_back({t.utime, odom_T_world * t.pose});
  EXPECT_GT(ComparePoses(odometry, truth, 500000).max_m, 1.0);
  const PoseErrorFigures aligned = ComparePoses(AlignToTruthAtStart(odometry, truth, 500000), truth, 500000);
  EXPECT_EQ(aligned.compared, 50);
  EXPECT_NEAR(aligned.max_m, 0.0, 1e-9);
  EXPECT_NEAR(aligned.max_heading_rad, 0.0, 1e-9);
}

// ---------------------------------------------------------------------------------------

// An entry 6 m wide ending in a face at x = 20; after the cut a 3 m wide box 0.80 m deep.
struct CutWorlds {
  std::vector<Segment> before, after;
  Segment face;  // the part of the face the box cut takes
};
CutWorlds MakeCutWorlds(const Pose2& place) {
  auto moved = [&](std::vector<Eigen::Vector2d> pts) {
    for (auto& p : pts) p = place * p;
    return pts;
  };
  CutWorlds w;
  w.before = Loop(moved(Box(0, 0, 20, 6)), 4);
  w.after = Loop(moved({{0, 0}, {20, 0}, {20, 1.5}, {20.8, 1.5}, {20.8, 4.5}, {20, 4.5}, {20, 6}, {0, 6}}));
  w.face = Segment(place * Eigen::Vector2d(20, 1.5), place * Eigen::Vector2d(20, 4.5));
  return w;
}

TEST(CutDepth, AFaceMovedByExactly080) {
  for (const Pose2& place : {Pose2(), Pose2(3.0, -7.0, DegToRad(30.0)), Pose2(-2.0, 1.0, DegToRad(-135.0))}) {
    const CutWorlds w = MakeCutWorlds(place);
    const Eigen::Vector2d advance(std::cos(place.theta), std::sin(place.theta));
    const DepthFigures d = MeasureFaceAdvance(w.face, advance, StaticSegmentIndex(w.before), StaticSegmentIndex(w.after));
    EXPECT_EQ(d.rays, 17);
    EXPECT_EQ(d.hits, 17);
    EXPECT_NEAR(d.median, 0.80, 1e-9);
    EXPECT_NEAR(d.min, 0.80, 1e-9);
    EXPECT_NEAR(d.max, 0.80, 1e-9);
  }
}

TEST(CutDepth, CutsAreFlaggedOffTheirRequest) {
  const CutWorlds w = MakeCutWorlds(Pose2());
  MissionSubtask box;
  box.id = 7;
  box.kind = "box_cut";
  box.target = Pose2(14.2, 3.0, 0.0);
  box.depth = 0.80;
  box.face = w.face;
  MissionSubtask deeper = box;
  deeper.id = 8;
  deeper.depth = 0.90;  // 10 cm more than was cut
  MissionSubtask move = box;
  move.kind = "move";
  MissionSubtask no_face = box;
  no_face.face.reset();
  // The map followed the cut only halfway: its face at 20.4.
  const std::vector<Segment> map =
      Loop({{0, 0}, {20, 0}, {20, 1.5}, {20.4, 1.5}, {20.4, 4.5}, {20, 4.5}, {20, 6}, {0, 6}});
  const std::vector<CutFigures> cuts = MeasureCuts({box, deeper, move, no_face}, w.before, w.after, map, {}, 0.05);
  ASSERT_EQ(cuts.size(), 3u);  // the move is not a cut
  EXPECT_NEAR(cuts[0].truth.median, 0.80, 1e-9);
  EXPECT_FALSE(cuts[0].off_request);
  EXPECT_NEAR(cuts[0].map.median, 0.40, 1e-9);
  EXPECT_TRUE(cuts[0].map_off);
  EXPECT_TRUE(cuts[1].off_request);
  EXPECT_TRUE(cuts[2].off_request);
  EXPECT_FALSE(cuts[2].note.empty());
  // The map is judged against what was cut, not against the request: a cut 4 cm deeper than a
  // request of 0.76 m (within the tolerance), mapped 2 cm deeper than it was cut (6 cm off the
  // request), is a map that followed the cut.
  MissionSubtask near = box;
  near.depth = 0.76;
  const std::vector<Segment> map_deeper =
      Loop({{0, 0}, {20, 0}, {20, 1.5}, {20.82, 1.5}, {20.82, 4.5}, {20, 4.5}, {20, 6}, {0, 6}});
  const std::vector<CutFigures> followed = MeasureCuts({near}, w.before, w.after, map_deeper, {}, 0.05);
  ASSERT_EQ(followed.size(), 1u);
  EXPECT_NEAR(followed[0].truth.median, 0.80, 1e-9);
  EXPECT_NEAR(followed[0].map.median, 0.82, 1e-9);
  EXPECT_FALSE(followed[0].off_request);
  EXPECT_FALSE(followed[0].map_off);
  // Nothing cut: depth 0, flagged.
  const std::vector<CutFigures> none = MeasureCuts({box}, w.before, w.before, w.before, {}, 0.05);
  EXPECT_NEAR(none[0].truth.median, 0.0, 1e-12);
  EXPECT_TRUE(none[0].off_request);
}

// ---------------------------------------------------------------------------------------

TEST(PlannerStatus, ParsesAnswersAndRejectsEverythingElse) {
  const auto ok = ParsePlannerStatus("ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, 3.0 ms on map version 1");
  ASSERT_TRUE(ok);
  EXPECT_DOUBLE_EQ(ok->ms, 3.0);
  EXPECT_DOUBLE_EQ(ok->length_m, 26.0);
  EXPECT_EQ(ok->map_version, 1);
  EXPECT_FALSE(ok->replanned);
  const auto re = ParsePlannerStatus(
      "replanned: map version 3 blocks piece 2 of 5 (forward to (1.00, 2.00, 0.00)); from (1.00, 2.00, 0.10): "
      "ok: 12.50 m, 2 pieces, 0 reversals, 40 expansions, 0.7 ms on map version 3");
  ASSERT_TRUE(re);
  EXPECT_DOUBLE_EQ(re->ms, 0.7);
  EXPECT_EQ(re->map_version, 3);
  EXPECT_TRUE(re->replanned);
  for (const std::string bad :
       {"", "ok:", "ok: ", "no_path: no path in the known free space", "ok: abc m, 3 pieces, 3.0 ms on map version 1",
        "ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, ms on map version 1",
        "ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, 3.0 ms on map version",
        "ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, 1e999 ms on map version 1",
        "ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, -3.0 ms on map version 1",
        "ok: 26.00 m, 3 pieces, 0 reversals, 1200 expansions, 3.0 ms on map version 99999999999999999999",
        "ok: 99999999999999999999.0 m, 3.0 ms on map version 1", "OK: 26.00 m, 3.0 ms on map version 1",
        "ok: 26.00 m, 3 pieces, 3.0 ms on map version 1 and more"})
    EXPECT_FALSE(ParsePlannerStatus(bad)) << bad;
  EXPECT_FALSE(ParsePlannerStatus("ok: 1.0 m, " + std::string(10000, 'x') + ", 3.0 ms on map version 1"));
}

TEST(PlannerStatus, PlanningFiguresCountEachAnswerOnceAndTheLinesTheyCannotRead) {
  std::vector<LoggedPath> answers;
  auto add = [&](int64_t id, bool feasible, const std::string& status) {
    LoggedPath p;
    p.request_id = id;
    p.feasible = feasible;
    p.status = status;
    answers.push_back(p);
  };
  for (int i = 1; i <= 10; ++i)
    add(i, true, "ok: 5.00 m, 1 pieces, 0 reversals, 10 expansions, " + std::to_string(i) + ".0 ms on map version 2");
  add(3, true, "ok: 5.00 m, 1 pieces, 0 reversals, 10 expansions, 3.0 ms on map version 2");  // answered again
  add(11, false, "no_path: the goal is not in the known free space");
  add(11, false, "no_path: the goal is not in the known free space");
  add(12, true, "garbage");
  add(13, true, "ok: 5 m, took 7 ms");
  MissionReport mission;
  mission.drives = 4;
  mission.drives_planned_ahead = 2;
  mission.planning_waits_s = {0.0, 0.0, 1.5, 0.5};
  const PlanningFigures p = MeasurePlanning(answers, &mission);
  EXPECT_EQ(p.answers, 13);
  EXPECT_EQ(p.searches, 10);
  EXPECT_EQ(p.refused, 1);
  EXPECT_EQ(p.unparsed, 2);
  EXPECT_EQ(p.unparsed_examples.size(), 2u);
  EXPECT_DOUBLE_EQ(p.search_ms.median, 5.5);
  EXPECT_DOUBLE_EQ(p.search_ms.p95, 10.0);
  EXPECT_DOUBLE_EQ(p.search_ms.max, 10.0);
  EXPECT_TRUE(p.have_mission);
  EXPECT_EQ(p.waits_zero, 2);
  EXPECT_DOUBLE_EQ(p.waits_s.median, 0.25);
  EXPECT_DOUBLE_EQ(p.waits_s.max, 1.5);
  EXPECT_EQ(p.drives_planned_ahead, 2);
}

// ---------------------------------------------------------------------------------------

MissionStatusLine Status(double t, MissionState s, BtStatus explore) {
  MissionStatusLine l;
  l.utime = static_cast<int64_t>(t * 1e6);
  l.state = s;
  l.nodes = {{"mission m", BtStatus::kRunning}, {"wait for the fleet to be ready", BtStatus::kSuccess},
             {"explore the section", explore}};
  return l;
}

TEST(MissionTimes, ExplorationAndMissionFromTheStatusLines) {
  MissionRecord log;
  log.events = 5;
  log.first_utime = 0;
  log.last_utime = 90000000;
  log.mission_status = {Status(0, MissionState::kIdle, BtStatus::kIdle),
                        Status(1, MissionState::kWaiting, BtStatus::kIdle),
                        Status(2, MissionState::kRunning, BtStatus::kRunning),
                        Status(30, MissionState::kPaused, BtStatus::kRunning),
                        Status(50, MissionState::kRunning, BtStatus::kSuccess),
                        Status(80, MissionState::kDone, BtStatus::kSuccess),
                        Status(85, MissionState::kDone, BtStatus::kSuccess)};
  const TimeFigures t = MissionTimes(log);
  EXPECT_DOUBLE_EQ(t.log_s, 90.0);
  ASSERT_TRUE(t.mission_s);
  EXPECT_DOUBLE_EQ(*t.mission_s, 79.0);
  ASSERT_TRUE(t.exploration_s);
  EXPECT_DOUBLE_EQ(*t.exploration_s, 48.0);
  EXPECT_EQ(t.exploration_result, "success");
  EXPECT_EQ(t.final_state, "DONE");
  // Cut short: no end, the exploration unfinished.
  log.mission_status.resize(4);
  const TimeFigures u = MissionTimes(log);
  EXPECT_FALSE(u.mission_s);
  EXPECT_FALSE(u.exploration_s);
  EXPECT_EQ(u.exploration_result, "unfinished");
  EXPECT_EQ(u.final_state, "PAUSED");
  EXPECT_FALSE(MissionTimes(MissionRecord()).mission_s);
  // The log ended before the coordinator's last status (the logger stopped with the fleet):
  // the coordinator's report says how it ended (a mission that FAILED was reported RUNNING).
  log.mission_status.resize(3);
  MissionReport report;
  report.state = "FAILED";
  report.message = "mission failed: exploration: 3 stations in a row not reached";
  const TimeFigures v = MissionTimes(log, &report);
  EXPECT_EQ(v.final_state, "FAILED");
  EXPECT_EQ(v.final_message, report.message);
  ASSERT_TRUE(v.mission_s);
  EXPECT_DOUBLE_EQ(*v.mission_s, 89.0);  // from the first status past IDLE (1 s) to the log's end (90 s)
  // An end in the log wins over the report.
  log.mission_status.push_back(Status(60, MissionState::kAborted, BtStatus::kFailure));
  EXPECT_EQ(MissionTimes(log, &report).final_state, "ABORTED");
}

TEST(Refusals, EachProblemOnceWithItsFirstLine) {
  MissionRecord log;
  auto hb = [&](double t, const std::string& p, HeartbeatState s, const std::string& m) {
    HeartbeatSample h;
    h.process = p;
    h.state = s;
    h.message = m;
    h.utime = static_cast<int64_t>(t * 1e6);
    log.heartbeats.push_back(h);
  };
  hb(1, "contour_mapper", HeartbeatState::kOk, "fine");
  hb(2, "contour_mapper", HeartbeatState::kWarn, "3 scans refused");
  hb(3, "contour_mapper", HeartbeatState::kWarn, "4 scans refused");
  hb(4, "path_planner", HeartbeatState::kError, "worker stuck");
  hb(5, "contour_mapper", HeartbeatState::kOk, "fine");
  log.task_status = {{1, 5, TaskState::kActive, ""},
                     {2, 5, TaskState::kFailed, "blocked ahead"},
                     {3, 5, TaskState::kFailed, "blocked ahead"},
                     {4, 6, TaskState::kCanceled, "canceled by the coordinator"},
                     {5, 7, TaskState::kDone, "arrived"}};
  LoggedPath refused;
  refused.request_id = 9;
  refused.status = "no_path: boxed in";
  log.planner_paths = {refused, refused};
  LoggedPath cancel;
  log.drive_paths = {cancel};
  MissionReport mission;
  mission.events = {"retrying 'box cut' (attempt 2)"};
  mission.retries = 1;
  const RefusalFigures r = MeasureRefusals(log, &mission);
  ASSERT_EQ(r.heartbeat_problems.size(), 2u);
  EXPECT_EQ(r.heartbeat_problems[0].process, "contour_mapper");
  EXPECT_EQ(r.heartbeat_problems[0].count, 2);
  EXPECT_EQ(r.heartbeat_problems[0].first_message, "3 scans refused");
  EXPECT_EQ(r.heartbeat_problems[1].state, HeartbeatState::kError);
  ASSERT_EQ(r.task_failures.size(), 2u);
  EXPECT_EQ(r.task_failures[1].state, TaskState::kCanceled);
  ASSERT_EQ(r.path_refusals.size(), 1u);
  EXPECT_EQ(r.path_refusals[0].request_id, 9);
  EXPECT_EQ(r.drive_path_cancels, 1);
  EXPECT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.retries, 1);
}

TEST(Stations, WhereTheVehicleStoodLongEnough) {
  std::vector<StampedPose> truth;
  int64_t t = 0;
  auto go = [&](double x0, double x1, int steps) {
    for (int i = 0; i < steps; ++i, t += 100000) truth.push_back({t, Pose2(x0 + (x1 - x0) * i / steps, 0, 0)});
  };
  auto stand = [&](double x, double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 10); ++i, t += 100000) truth.push_back({t, Pose2(x, 0.001 * (i % 2), 0)});
  };
  go(0, 5, 50);
  stand(5, 3.0);
  go(5, 8, 30);
  stand(8, 1.0);  // too short
  go(8, 10, 20);
  stand(10, 2.5);
  const std::vector<Pose2> s = StandingPoses(truth, 2000000, 0.05);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(s[0].x, 5.0, 0.11);
  EXPECT_NEAR(s[1].x, 10.0, 0.11);
}

TEST(MissionReportJson, ReadsTheCoordinatorsReportAndRefusesOtherJson) {
  const std::string text = R"json({"mission_id": "m1", "state": "done", "message": "mission done", "seconds": 412.5,
    "stations_visited": 6, "stations_failed": 1, "drives": 9, "drives_planned_ahead": 3, "replans": 1,
    "retries": 2, "resends": 4, "pauses_for_lost_processes": 0, "planning_wait_median_s": 0.0,
    "planning_wait_max_s": 1.5, "planning_waits_s": [0.0, 1.5], "events": ["retrying 'x' (attempt 2)"],
    "subtasks": [{"id": 5, "kind": "box_cut", "description": "box cut 1.00 m", "target": [14.0, 3.0, 0.0],
                  "depth": 1.0, "width": 3.3, "face": [20.0, 1.35, 20.0, 4.65], "state": "success"},
                 {"id": 6, "kind": "back_out", "description": "back out", "target": [8.0, 3.0, 0.0],
                  "depth": 0.0, "width": 0.0}]})json";
  const MissionReport m = ParseMissionReportJson(text, "mission.json");
  EXPECT_EQ(m.mission_id, "m1");
  EXPECT_DOUBLE_EQ(m.seconds, 412.5);
  EXPECT_EQ(m.drives_planned_ahead, 3);
  EXPECT_EQ(m.planning_waits_s.size(), 2u);
  ASSERT_EQ(m.subtasks.size(), 2u);
  ASSERT_TRUE(m.subtasks[0].face);
  EXPECT_DOUBLE_EQ(m.subtasks[0].face->b.y(), 4.65);
  EXPECT_EQ(m.subtasks[0].state, "success");
  EXPECT_FALSE(m.subtasks[1].face);
  for (const std::string bad : {"", "[1, 2]", "{\"drives\": \"many\"}", "{\"subtasks\": [{\"face\": [1, 2]}]}",
                                "{\"planning_waits_s\": [0, \"x\"]}", "{\"events\": [3]}", "{\"subtasks\": {}}"}) {
    try {
      ParseMissionReportJson(bad, "bad.json");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("bad.json: ", 0), 0u) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------

TEST(Picture, APathIsSampledAlongItsMotions) {
  PlannedPath path;
  path.start = Pose2(1, 1, 0);
  Pose2 at = path.start;
  auto piece = [&](Motion m, double amount, double radius) {
    const Pose2 end = PoseAfter(at, m, amount, radius);
    path.pieces.push_back({m, amount, radius, end});
    at = end;
  };
  piece(Motion::kForward, 2.0, 0.0);
  piece(Motion::kArcLeft, kPi / 2 * 4.0, 4.0);  // a quarter circle of 4 m
  piece(Motion::kTurnInPlace, 1.0, 0.0);
  piece(Motion::kReverse, 1.0, 0.0);
  const std::vector<Pose2> s = SamplePath(path, 0.1);
  EXPECT_EQ(TranslationDistance(s.front(), path.start), 0.0);
  EXPECT_LT(TranslationDistance(s.back(), at), 1e-12);
  for (size_t i = 1; i < s.size(); ++i) EXPECT_LE(TranslationDistance(s[i - 1], s[i]), 0.1 + 1e-9);
  // The forward piece gives samples 1..20 (ending at (3, 1)), the 2 pi m arc 63 more, each 4 m
  // from the arc's centre (3, 5), left of its start pose.
  ASSERT_GT(s.size(), 84u);
  EXPECT_LT(TranslationDistance(s[20], Pose2(3, 1, 0)), 1e-12);
  for (size_t i = 21; i <= 83; ++i) EXPECT_NEAR((s[i].translation() - Eigen::Vector2d(3, 5)).norm(), 4.0, 1e-9) << i;
  EXPECT_LT(TranslationDistance(s[83], Pose2(7, 5, 0)), 1e-9);
}

TEST(Picture, TheSceneHasEveryLayerAndTheHeadline) {
  MissionInputs in;
  const CutWorlds w = MakeCutWorlds(Pose2());
  in.initial_world = w.before;
  in.final_world = w.after;
  in.map.Create({{0, 0}, {20, 0}, {20, 1.5}, {20.8, 1.5}, {20.8, 4.5}, {20, 4.5}, {20, 6}, {0, 6}}, true);
  in.log.truth = StraightTruth(40, 100000);
  in.log.estimates = in.log.truth;
  LoggedPath drive;
  drive.request_id = 4;
  drive.feasible = true;
  drive.status = "ok: 1.00 m, 1 pieces, 0 reversals, 1 expansions, 1.0 ms on map version 1";
  drive.path.start = Pose2(1, 3, 0);
  drive.path.pieces = {{Motion::kForward, 5.0, 0.0, Pose2(6, 3, 0)}};
  in.log.drive_paths = {drive};
  MissionReport mission;
  mission.mission_id = "m";
  mission.state = "done";
  MissionSubtask box;
  box.kind = "box_cut";
  box.depth = 0.8;
  box.target = Pose2(14, 3, 0);
  box.face = w.face;
  mission.subtasks = {box};
  in.mission = mission;
  in.notes = {"speed factor 4 (--fast)"};
  const MissionEvaluationOptions o;
  const MissionFigures f = EvaluateMission(in, o);
  ASSERT_EQ(f.cuts.size(), 1u);
  EXPECT_NEAR(f.cuts[0].truth.median, 0.8, 1e-9);
  EXPECT_NEAR(f.cuts[0].map.median, 0.8, 1e-6);
  const SvgScene scene = MissionScene(in, f, o);
  EXPECT_EQ(scene.notes.back(), "speed factor 4 (--fast)");
  const std::string svg = RenderSvg(scene);
  for (const std::string label : {"true walls at the start", "true walls at the end", "final contour map",
                                  "planned paths (DRIVE_PATH)", "driven (SIM_TRUTH)", "estimated (POSE)",
                                  "cut faces (as planned)", "stops of the vehicle (no TASK_PLAN)", "box_cut 0.80 m", "MINENAV mission: m (done)"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  const std::string md = MissionReportMarkdown(in, f, o);
  EXPECT_NE(md.find("| 0 box_cut | 0.80 m | 0.800 m"), std::string::npos) << md;
}

}  // namespace
}  // namespace minenav
