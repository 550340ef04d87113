// path_tracker's node through the fake bus and the test's clock: a path taken and driven,
// done with TASK_STATUS DONE for its request, the watchdog's STOP within 200 ms of each limit
// (pose, odometry, path age) said on TASK_STATUS and HEARTBEAT, a path through a known wall
// refused, a malformed path refused in one line, a pose jump reported; every option reachable.

#include "tracker/path_tracker_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "common/config_testing.h"
#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/path_message.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

struct Harness {
  explicit Harness(const PathTrackerNodeOptions& o = {})
      : node(fake.runtime(), o, Footprint::Rectangle(3.3, 10.0)) {}
  // Odometry at the clock's time (the vehicle standing at `odo`), then dt_us on and a spin.
  void Step(int64_t dt_us, const Pose2& odo = Pose2(), bool with_odometry = true) {
    if (with_odometry) {
      OdometryReading r;
      r.utime = clock.NowUtime();
      r.pose = odo;
      bus->InjectMessage("ODOMETRY", ToLcm(r));
    }
    clock.Advance(dt_us);
    runtime->SpinOnce(0);
  }
  void Pose(const Pose2& p, int64_t utime) {
    PoseEstimate e;
    e.utime = utime;
    e.pose = p;
    e.converged = true;
    e.status = "ok";
    e.source = "clue";
    e.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal();
    bus->InjectMessage("POSE", ToLcm(e));
  }
  void Path(const PlannedPath& p, int64_t request_id) {
    bus->InjectMessage("PATH", PathToLcm(p, request_id, clock.NowUtime(), 0.076, "ok"));
  }
  // Ticks (real time passing for the map worker) until `n` maps were taken.
  void WaitForMaps(int64_t n) {
    for (int k = 0; k < 10000 && node.maps_applied() < n; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      Step(100'000, Pose2(), false);
    }
    ASSERT_GE(node.maps_applied(), n) << "no map built";
  }
  // A pose at the origin and the path of request `id`, taken and driving after two ticks.
  void Begin(const PlannedPath& p, int64_t id) {
    Pose(Pose2(0, 0, 0), clock.NowUtime());
    Path(p, id);
    Step(100'000);
    Step(100'000);
  }
  std::vector<task_status_t> Statuses() const { return bus->Decoded<task_status_t>("TASK_STATUS"); }
  drive_command_t LastCommand() const { return bus->Decoded<drive_command_t>("DRIVE_COMMAND").back(); }

  ManualClock clock{kT0};
  FakeRuntime fake{clock, 0.1, "path_tracker"};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  PathTrackerNode node;
};

PlannedPath Straight(double from, double to) {
  PlannedPath p;
  p.start = Pose2(from, 0, 0);
  p.pieces.push_back({Motion::kForward, to - from, 0.0, Pose2(to, 0, 0)});
  return p;
}

// One driver at a time on DRIVE_COMMAND: idle, the tracker repeats its STOP for
// idle_stop_time and then falls silent (the cutter drives the vehicle through a cut on the
// same channel); a new path makes it the driver again.
TEST(PathTrackerNodeTest, AnIdleTrackerStopsThenFallsSilent) {
  Harness h;
  auto count = [&] { return h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").size(); };
  for (int k = 0; k < 20; ++k) h.Step(100'000);
  const size_t at_start = count();
  EXPECT_GE(at_start, 9u) << "STOPs for the first second";
  EXPECT_LE(at_start, 12u) << "then nothing";
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.Path(Straight(0, 2), 7);
  h.Step(100'000);
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  h.Step(100'000, Pose2(2.0, 0, 0));
  h.Step(100'000, Pose2(2.0, 0, 0));
  h.Step(100'000, Pose2(2.0, 0, 0));
  ASSERT_EQ(h.Statuses().back().state, task_status_t::DONE);
  const size_t at_done = count();
  for (int k = 0; k < 30; ++k) h.Step(100'000, Pose2(2.0, 0, 0));
  EXPECT_GE(count() - at_done, 8u) << "the last word: STOP for a second";
  EXPECT_LE(count() - at_done, 12u) << "then silence for the cutter";
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
}

TEST(PathTrackerNodeTest, DrivesAPathAndSaysDoneForItsRequest) {
  Harness h;
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP) << "no path";
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.Path(Straight(0, 2), 41);
  h.Step(100'000);
  h.Step(100'000);
  ASSERT_FALSE(h.Statuses().empty());
  EXPECT_EQ(h.Statuses().front().task_id, 41);
  EXPECT_EQ(h.Statuses().front().state, task_status_t::ACTIVE);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  EXPECT_GT(h.LastCommand().v, 0.0);
  EXPECT_FLOAT_EQ(static_cast<float>(h.LastCommand().timeout), static_cast<float>(PathTrackerOptions{}.command_timeout));
  // The odometry says the vehicle went the 2 m: done.
  h.Step(100'000, Pose2(2.0, 0, 0));
  h.Step(100'000, Pose2(2.0, 0, 0));  // the timer runs before the messages of a spin
  h.Step(100'000, Pose2(2.0, 0, 0));
  const task_status_t last = h.Statuses().back();
  EXPECT_EQ(last.state, task_status_t::DONE) << last.message;
  EXPECT_EQ(last.task_id, 41);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
  const auto commands = h.bus->Decoded<drive_command_t>("DRIVE_COMMAND");
  for (size_t k = 0; k < commands.size(); ++k) EXPECT_EQ(commands[k].seq, static_cast<int64_t>(k));
}


TEST(PathTrackerNodeTest, AStalePoseStopsTheMinerWithin200msAndSaysWhy) {
  PathTrackerNodeOptions o;
  o.pose_timeout = 3.0;
  Harness h(o);
  const int64_t pose_at = h.clock.NowUtime();
  h.Pose(Pose2(0, 0, 0), pose_at);
  h.Path(Straight(0, 20), 7);
  h.Step(100'000);  // the first tick (before the messages are handled)
  h.Step(100'000);
  ASSERT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY) << h.Statuses().back().message;
  // Odometry keeps coming, estimates do not: every command before the limit drives.
  int64_t stop_at = -1;
  while (h.clock.NowUtime() < pose_at + 5'000'000) {
    h.Step(20'000);
    const drive_command_t c = h.LastCommand();
    if (c.mode == drive_command_t::STOP) {
      stop_at = c.utime;
      break;
    }
  }
  const int64_t limit = pose_at + 3'000'000;
  ASSERT_GT(stop_at, 0);
  EXPECT_GT(stop_at, limit) << "not before the limit";
  EXPECT_LE(stop_at - limit, 200'000) << "within 200 ms of it";
  const task_status_t s = h.Statuses().back();
  EXPECT_EQ(s.task_id, 7);
  EXPECT_NE(s.message.find("pose stale"), std::string::npos) << s.message;
  h.Step(100'000);  // the next heartbeat says it too
  const heartbeat_t hb = h.bus->Decoded<heartbeat_t>("HEARTBEAT").back();
  EXPECT_EQ(hb.state, heartbeat_t::WARN);
  EXPECT_NE(hb.message.find("pose stale"), std::string::npos) << hb.message;
  // A fresh estimate: it drives again.
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.Step(100'000);
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  EXPECT_EQ(h.Statuses().back().message, "resumed");
}

TEST(PathTrackerNodeTest, StaleOdometryStopsTheMinerWithin200ms) {
  Harness h;  // odometry_timeout 0.5 s
  h.Begin(Straight(0, 20), 8);
  ASSERT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  const int64_t last_odometry = h.clock.NowUtime();
  h.Step(20'000);  // the last reading, stamped last_odometry
  int64_t stop_at = -1;
  while (h.clock.NowUtime() < last_odometry + 2'000'000) {
    h.Step(20'000, Pose2(), false);
    if (h.LastCommand().mode == drive_command_t::STOP) {
      stop_at = h.LastCommand().utime;
      break;
    }
  }
  ASSERT_GT(stop_at, 0);
  EXPECT_GT(stop_at, last_odometry + 500'000);
  EXPECT_LE(stop_at - (last_odometry + 500'000), 200'000);
  EXPECT_NE(h.Statuses().back().message.find("odometry stale"), std::string::npos) << h.Statuses().back().message;
}

TEST(PathTrackerNodeTest, AnOldPathIsAbandoned) {
  PathTrackerNodeOptions o;
  o.path_max_age = 2.0;
  o.pose_timeout = 100.0;
  Harness h(o);
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.Path(Straight(0, 20), 9);
  const int64_t planned = h.clock.NowUtime();
  h.Step(100'000);
  h.Step(100'000);
  ASSERT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  int64_t stop_at = -1;
  for (int k = 0; k < 200 && stop_at < 0; ++k) {
    h.Step(20'000);
    if (h.LastCommand().mode == drive_command_t::STOP) stop_at = h.LastCommand().utime;
  }
  EXPECT_GT(stop_at, planned + 2'000'000);
  ASSERT_GT(stop_at, 0);
  EXPECT_LE(stop_at - (planned + 2'000'000), 200'000);
  EXPECT_EQ(h.Statuses().back().state, task_status_t::FAILED);
  EXPECT_NE(h.Statuses().back().message.find("path stale"), std::string::npos);
}

TEST(PathTrackerNodeTest, RefusesAPathThroughAWallOfTheMapAndAMalformedPath) {
  Harness h;
  ContourMapMessage map;
  map.version = 1;
  map.contours.push_back({1, true, {{-8, -4}, {40, -4}, {40, 4}, {-8, 4}}});
  map.contours.push_back({2, false, {{12, -4}, {12, 4}}});  // across the way
  h.bus->InjectMessage("CONTOUR_MAP", ContourMapToLcm(map));
  h.WaitForMaps(1);  // built on the worker, taken by a tick
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.Step(100'000);
  h.Path(Straight(0, 20), 10);
  h.Step(100'000);
  ASSERT_FALSE(h.Statuses().empty());
  EXPECT_EQ(h.Statuses().back().state, task_status_t::FAILED);
  EXPECT_EQ(h.Statuses().back().task_id, 10);
  EXPECT_NE(h.Statuses().back().message.find("refused"), std::string::npos) << h.Statuses().back().message;
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
  // An arc of the wrong radius.
  path_t bad = PathToLcm(Straight(0, 3), 11, h.clock.NowUtime(), 0.076, "ok");
  bad.segments[0].motion = path_segment_t::ARC_LEFT;
  bad.segments[0].radius = 2.0;
  h.bus->InjectMessage("PATH", bad);
  h.Step(100'000);
  EXPECT_EQ(h.Statuses().back().task_id, 11);
  EXPECT_EQ(h.Statuses().back().state, task_status_t::FAILED);
  EXPECT_NE(h.Statuses().back().message.find("radius"), std::string::npos) << h.Statuses().back().message;
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
}

TEST(PathTrackerNodeTest, APoseJumpIsReportedNotObeyed) {
  Harness h;
  h.Begin(Straight(0, 20), 12);
  h.Pose(Pose2(0, 2.0, 0), h.clock.NowUtime() - 100'000);  // 2 m sideways
  h.Step(100'000);
  const task_status_t s = h.Statuses().back();
  EXPECT_NE(s.message.find("pose jump"), std::string::npos) << s.message;
  const drive_command_t c = h.LastCommand();
  EXPECT_EQ(c.mode, drive_command_t::VELOCITY) << "still on the prediction: straight on";
  EXPECT_DOUBLE_EQ(c.omega, 0.0);
}

// The coordinator re-sends each path until it is acknowledged (on DRIVE_PATH): a repeat of
// the active request changes nothing and re-publishes its latest status; a repeat of a
// finished one re-publishes its end (DONE) and never drives it again.
TEST(PathTrackerNodeTest, ARepeatedPathIsAcknowledgedAndNotRestarted) {
  PathTrackerNodeOptions o;
  o.path_channel = "DRIVE_PATH";
  Harness h(o);
  // 2 m forward, then 1 m back: two runs.
  PlannedPath p = Straight(0, 2);
  p.pieces.push_back({Motion::kReverse, 1.0, 0.0, Pose2(1, 0, 0)});
  h.Pose(Pose2(0, 0, 0), h.clock.NowUtime());
  h.bus->InjectMessage("DRIVE_PATH", PathToLcm(p, 51, h.clock.NowUtime(), 0.076, "ok"));
  h.Step(100'000);
  h.Step(100'000);
  h.Step(100'000, Pose2(2.0, 0, 0));  // the first run driven
  h.Step(100'000, Pose2(2.0, 0, 0));
  h.Step(100'000, Pose2(2.0, 0, 0));
  ASSERT_EQ(h.node.tracker().run_index(), 1);
  ASSERT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  ASSERT_LT(h.LastCommand().v, 0.0) << "reversing the second run";
  const task_status_t latest = h.Statuses().back();
  const size_t statuses = h.Statuses().size();
  h.bus->InjectMessage("DRIVE_PATH", PathToLcm(p, 51, h.clock.NowUtime(), 0.076, "ok"));  // the repeat
  h.Step(100'000, Pose2(1.9, 0, 0));
  ASSERT_EQ(h.Statuses().size(), statuses + 1);
  const task_status_t ack = h.Statuses().back();
  EXPECT_EQ(ack.task_id, 51);
  EXPECT_EQ(ack.state, latest.state);
  EXPECT_EQ(ack.message, latest.message);
  EXPECT_GT(ack.progress, 0.5f) << "the progress of the path under way";
  EXPECT_EQ(h.node.tracker().run_index(), 1) << "not restarted";
  h.Step(100'000, Pose2(1.8, 0, 0));
  EXPECT_LT(h.LastCommand().v, 0.0) << "still reversing";
  // Done; the repeat after it re-publishes DONE and the miner stays put.
  for (int k = 0; k < 5; ++k) h.Step(100'000, Pose2(1.0, 0, 0));
  ASSERT_EQ(h.Statuses().back().state, task_status_t::DONE) << h.Statuses().back().message;
  const task_status_t done = h.Statuses().back();
  const size_t after_done = h.Statuses().size();
  for (int k = 0; k < 3; ++k) {
    h.bus->InjectMessage("DRIVE_PATH", PathToLcm(p, 51, h.clock.NowUtime(), 0.076, "ok"));
    h.Step(100'000, Pose2(1.0, 0, 0));
  }
  ASSERT_EQ(h.Statuses().size(), after_done + 3);
  for (size_t k = after_done; k < h.Statuses().size(); ++k) {
    EXPECT_EQ(h.Statuses()[k].task_id, 51);
    EXPECT_EQ(h.Statuses()[k].state, task_status_t::DONE);
    EXPECT_EQ(h.Statuses()[k].message, done.message);
  }
  EXPECT_EQ(h.node.tracker().state(), TrackState::kDone);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
}

// path_planner replans the active path when the map blocks it and publishes the new path with
// the same request_id: a different path of the active request is taken (not a repeat).
TEST(PathTrackerNodeTest, AReplannedPathOfTheActiveRequestReplacesIt) {
  Harness h;
  h.Begin(Straight(0, 20), 71);
  h.Step(100'000, Pose2(1.0, 0, 0));
  const size_t n = h.Statuses().size();
  h.Path(Straight(1, 3), 71);  // the replan: from where the vehicle is, to another end
  h.Step(100'000, Pose2(1.0, 0, 0));
  ASSERT_EQ(h.Statuses().size(), n + 1);
  EXPECT_EQ(h.Statuses().back().task_id, 71);
  EXPECT_EQ(h.Statuses().back().state, task_status_t::ACTIVE);
  EXPECT_EQ(h.Statuses().back().message.rfind("replanned path taken", 0), 0u) << h.Statuses().back().message;
  for (int k = 0; k < 4; ++k) h.Step(100'000, Pose2(3.0, 0, 0));
  EXPECT_EQ(h.Statuses().back().state, task_status_t::DONE) << "the replanned path's end: " << h.Statuses().back().message;
  EXPECT_EQ(h.Statuses().back().task_id, 71);
}

// feasible = false with the active request's id cancels it: STOP, CANCELED "canceled by the
// sender"; its repeats (and a repeat of the path itself) only re-publish that; an infeasible
// answer to another request does not touch the active path.
TEST(PathTrackerNodeTest, AnInfeasiblePathOfTheActiveRequestCancelsIt) {
  Harness h;
  h.Begin(Straight(0, 20), 61);
  ASSERT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  h.bus->InjectMessage("PATH", NoPathToLcm(99, h.clock.NowUtime(), "no path"));  // another request's
  h.Step(100'000);
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  EXPECT_EQ(h.Statuses().back().task_id, 61);
  EXPECT_EQ(h.Statuses().back().state, task_status_t::ACTIVE);
  h.bus->InjectMessage("PATH", NoPathToLcm(61, h.clock.NowUtime(), "cancel"));
  h.Step(100'000);
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
  const task_status_t canceled = h.Statuses().back();
  EXPECT_EQ(canceled.task_id, 61);
  EXPECT_EQ(canceled.state, task_status_t::CANCELED);
  EXPECT_EQ(canceled.message, "canceled by the sender");
  const size_t n = h.Statuses().size();
  h.bus->InjectMessage("PATH", NoPathToLcm(61, h.clock.NowUtime(), "cancel"));
  h.Step(100'000);
  h.Path(Straight(0, 20), 61);  // the path itself, late
  h.Step(100'000);
  h.Step(100'000);
  ASSERT_EQ(h.Statuses().size(), n + 2);
  for (size_t k = n; k < n + 2; ++k) {
    EXPECT_EQ(h.Statuses()[k].state, task_status_t::CANCELED);
    EXPECT_EQ(h.Statuses()[k].message, "canceled by the sender");
  }
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::STOP);
  // A new request drives again.
  h.Path(Straight(0, 20), 62);
  h.Step(100'000);
  h.Step(100'000);
  EXPECT_EQ(h.LastCommand().mode, drive_command_t::VELOCITY);
  EXPECT_EQ(h.Statuses().back().task_id, 62);
}

TEST(PathMessageTest, AmountsComeBackFromThePoses) {
  // Every motion, arcs both ways in both directions and longer than a half turn.
  PlannedPath p;
  p.start = Pose2(1, 2, 0.3);
  Pose2 at = p.start;
  const std::vector<std::pair<Motion, double>> pieces = {
      {Motion::kForward, 2.0},        {Motion::kArcLeft, 1.5},           {Motion::kArcRight, 14.0},
      {Motion::kTurnInPlace, -1.2},   {Motion::kReverse, 0.7},           {Motion::kArcLeftReverse, 2.5},
      {Motion::kArcRightReverse, 3.0}};
  for (const auto& [m, amount] : pieces) {
    const double radius = IsArc(m) ? 4.0 : 0.0;
    at = PoseAfter(at, m, amount, radius);
    p.pieces.push_back({m, amount, radius, at});
  }
  const PathMessage back = PathFromLcm(PathToLcm(p, 5, kT0, 0.076, "ok"), 4.0);
  EXPECT_EQ(back.request_id, 5);
  EXPECT_EQ(back.speeds, std::vector<double>(p.pieces.size(), 0.076));
  ASSERT_EQ(back.path.pieces.size(), p.pieces.size());
  for (size_t k = 0; k < p.pieces.size(); ++k) {
    EXPECT_EQ(back.path.pieces[k].motion, p.pieces[k].motion) << k;
    EXPECT_NEAR(back.path.pieces[k].amount, p.pieces[k].amount, 1e-5) << k;
  }
  // A speed that is not a speed: refused, named.
  path_t fast = PathToLcm(p, 6, kT0, 0.076, "ok");
  fast.segments[2].speed = -1.0;
  EXPECT_THROW(PathFromLcm(fast, 4.0), InputError);
  // A piece that cannot reach its end: refused, named.
  path_t bad = PathToLcm(p, 6, kT0, 0.076, "ok");
  bad.segments[1].end.y += 0.5;
  try {
    PathFromLcm(bad, 4.0);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("segment 1"), std::string::npos) << e.what();
  }
}

TEST(PathTrackerNodeTest, EveryOptionIsReachable) {
  const auto keys = ExpectEveryOptionReachable<PathTrackerNodeOptions>(
      PathTrackerNodeOptions(), [](ConfigSchema& s, PathTrackerNodeOptions& o) { DeclareOptions(s, o); });
  // 7 channels, rate, 4 limits (pose, odometry, path age, idle STOPs), the footprint's 3, the tracker's 28, the prediction's 10.
  EXPECT_EQ(keys.size(), 7u + 1u + 4u + 3u + 28u + 10u);
  for (const std::string& k : keys) EXPECT_EQ(k.find("truth"), std::string::npos) << k;
  PathTrackerNodeOptions bad;
  bad.tracker.command_timeout = 0.05;
  EXPECT_THROW(LoadTrackerFootprint(bad), UsageError);
}

}  // namespace
}  // namespace minenav
