// vehicle_sim's safety limits on a real LCM bus, inside a private network namespace
// (tests/bus/private_net.sh sets MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL):
//   - issue 11: one DRIVE_COMMAND with timeout = 1e9, then silence (a sender that died or a
//     lost link), must not drive the vehicle for ever: it stops at its own stale limit
//     (--command-timeout), whichever of the two is shorter (lcmtypes/drive_command_t.lcm).
//   - issue 16: vehicle_sim driven by path_tracker stops within 200 ms of losing its pose
//     estimates, its path or its commands, measured in the simulation's time (SIM_TRUTH
//     stamps) and on the test's wall clock.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/sanitizer.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

using testing::ChildProcess;
using testing::ReadTextFile;

using VehicleSafetyBusTest = testing::PrivateBusTest;

TEST_F(VehicleSafetyBusTest, OneCommandWithAHugeTimeoutStopsAtTheVehiclesStaleLimit) {
  testing::TempDir dir("minenav_vehicle_safety_test");
  constexpr double kStaleLimit = 0.5;  // s, vehicle_sim --command-timeout
  constexpr double kRate = 20.0;       // Hz, vehicle_sim --rate: one tick is 0.05 s
  constexpr double kSpeed = 1.0;       // m/s, commanded and allowed
  // Instant acceleration and braking, so the stop comes exactly at the first stale tick.
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "90", "--generate", "mine", "--seed", "3", "--rate", "20",
                    "--command-timeout", "0.5", "--max-forward-speed", "1", "--max-acceleration", "0",
                    "--max-deceleration", "0"},
                   dir / "sim.txt");
  LcmBus bus(url_, 10000);
  std::vector<vehicle_truth_t> truth;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(m); });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return truth.size() >= 5; }))
      << "no SIM_TRUTH within 20 s\nsim: " << ReadTextFile(dir / "sim.txt");
  const size_t before = truth.size();

  drive_command_t forever{};
  forever.utime = 1;
  forever.seq = 1;
  forever.mode = drive_command_t::VELOCITY;
  forever.v = kSpeed;
  forever.omega = 0.0;
  forever.timeout = 1e9;  // "valid for 31 years"
  ASSERT_TRUE(Publish(bus, "DRIVE_COMMAND", forever));
  // Silence: 3 s, six times the stale limit.
  Pump(bus, 3.0);
  EXPECT_TRUE(sim.Running()) << ReadTextFile(dir / "sim.txt");
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");

  // The samples after the command: it moved, then stopped for good.
  std::vector<vehicle_truth_t> after(truth.begin() + static_cast<std::ptrdiff_t>(before), truth.end());
  ASSERT_GT(after.size(), 20u) << "SIM_TRUTH stopped flowing";
  size_t first_moving = after.size(), last_moving = after.size();
  for (size_t i = 0; i < after.size(); ++i) {
    if (std::abs(after[i].v) > 0.0) {
      if (first_moving == after.size()) first_moving = i;
      last_moving = i;
    }
  }
  ASSERT_LT(first_moving, after.size()) << "the vehicle never moved: the command was lost?\n"
                                        << ReadTextFile(dir / "sim.txt");
  // Ticks are stamped with vehicle_sim's clock, the same clock that timed the command's
  // receipt: every moving tick is at most the stale limit after the receipt, and the
  // receipt precedes the first moving tick.
  const double moving_s = static_cast<double>(after[last_moving].utime - after[first_moving].utime) * 1e-6;
  EXPECT_LE(moving_s, kStaleLimit + 1e-6) << "still driving " << moving_s << " s after the command";
  ASSERT_LT(last_moving + 1, after.size()) << "still driving at the end of the 3 s of silence";
  // The first moving tick integrates at most one tick before the receipt (more if the
  // process was held up: the tick is capped at 1 s, so allow a held-up tick of 0.1 s).
  const double distance = std::hypot(after.back().pose.x - after[first_moving].pose.x,
                                     after.back().pose.y - after[first_moving].pose.y);
  EXPECT_LE(distance, kSpeed * (kStaleLimit + 1.0 / kRate + 0.1)) << "drove " << distance << " m";
  // ...and it drove for the stale limit, not a shorter time (two ticks short nominally;
  // half the limit leaves room for a machine so loaded that a tick comes late).
  EXPECT_GE(distance, kSpeed * kStaleLimit / 2) << "stopped too early: " << distance << " m";
  // Stopped, it stays put: no motion in the samples after the stop.
  for (size_t i = last_moving + 1; i < after.size(); ++i) {
    EXPECT_EQ(after[i].v, 0.0) << "sample " << i;
    EXPECT_EQ(after[i].pose.x, after[last_moving + 1].pose.x) << "sample " << i;
    EXPECT_EQ(after[i].pose.y, after[last_moving + 1].pose.y) << "sample " << i;
  }
  // At least 2 s of standing still were observed.
  EXPECT_GE(static_cast<double>(after.back().utime - after[last_moving].utime) * 1e-6, 2.0);
}


// Issue 16: "the vehicle is stopped within 200 ms of losing pose, path or commands, measured
// in simulation time and wall time". vehicle_sim (instant braking, so that the stop is the
// fleet's reaction and not the miner's 0.1 m/s^2 brakes) driven by path_tracker along a
// straight path; the test stands in for the pose estimator (every ODOMETRY republished as an
// exact POSE estimate: a perfect estimator; nothing reads SIM_TRUTH but the judge). Three
// losses, each while driving at cruise:
//   pose:     the estimates stop; lost when the tracker's limit (--pose-timeout, by the last
//             estimate's stamp) passes;
//   path:     the sender cancels the path (the same request id, feasible = false);
//   commands: the tracker is killed (-9); lost when its next command is overdue (one control
//             period, 0.1 s, after the last one heard).
// Stopped = the first SIM_TRUTH sample with speed 0. Sim time: SIM_TRUTH stamps (vehicle_sim's
// clock) minus the loss's stamp; wall: the test's clock when that sample arrived minus when
// the loss happened (pose, commands: the stamp it derives from, on the same clock; path:
// the cancel's publication).
class VehicleStopBusTest : public testing::PrivateBusTest {
 protected:
  using SteadyClock = std::chrono::steady_clock;
  static constexpr double kPoseTimeout = 1.0;  // s, path_tracker --pose-timeout
  static constexpr double kControlPeriod = 0.1;  // s, path_tracker --rate 10
  static constexpr double kCruise = 0.3;       // m/s

  struct Sample {
    vehicle_truth_t truth;
    SteadyClock::time_point arrived;
  };

  static int64_t WallUtime() {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
  }
  static double SteadySeconds(SteadyClock::time_point t) {
    return std::chrono::duration<double>(t.time_since_epoch()).count();
  }

  // A straight path 40 m ahead of the odometry pose, which the estimates also report.
  path_t StraightPath(int64_t request_id) const {
    path_t p{};
    p.utime = WallUtime();
    p.request_id = request_id;
    p.feasible = true;
    p.status = "ok";
    p.start = odometry_.back().pose;
    path_segment_t piece{};
    piece.motion = path_segment_t::FORWARD;
    piece.end = p.start;
    piece.end.x += 40.0 * std::cos(p.start.theta);
    piece.end.y += 40.0 * std::sin(p.start.theta);
    piece.speed = kCruise;
    p.segments = {piece};
    p.num_segments = 1;
    p.length = 40.0;
    return p;
  }

  // Index of the first truth sample from `from` on with speed 0 (truth_.size() when none).
  size_t FirstStopped(size_t from) const {
    for (size_t i = from; i < truth_.size(); ++i)
      if (truth_[i].truth.v == 0.0) return i;
    return truth_.size();
  }
  bool Cruising() const { return !truth_.empty() && truth_.back().truth.v > 0.9 * kCruise; }

  std::vector<Sample> truth_;
  std::vector<odometry_t> odometry_;
  std::vector<std::pair<int64_t, SteadyClock::time_point>> commands_;  // utime, arrival
  bool feed_pose_ = true;
  int64_t last_pose_utime_ = 0;
  SteadyClock::time_point last_pose_sent_{};
};

TEST_F(VehicleStopBusTest, TheVehicleStopsWithin200MsOfLosingPosePathOrCommands) {
  testing::TempDir dir("minenav_vehicle_stop_test");
  {  // An empty 200 m hall: nothing to stop for but the losses.
    std::ofstream world(dir / "hall.json");
    world << R"({"segments": [[-100,-100,100,-100],[100,-100,100,100],[100,100,-100,100],[-100,100,-100,-100]]})";
  }
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--world", dir / "hall.json", "--start-pose", "0,0,0",
                    "--rate", "20", "--max-forward-speed", "0.5", "--max-acceleration", "0", "--max-deceleration", "0"},
                   dir / "sim.txt");
  const std::vector<std::string> tracker_argv = {MINENAV_PATH_TRACKER_BIN, "--rate", "10", "--pose-timeout", "1",
                                                 "--tracker.cruise-speed", "0.3"};
  auto tracker = std::make_unique<ChildProcess>(tracker_argv, dir / "tracker.txt");
  auto logs = [&] { return "sim: " + ReadTextFile(dir / "sim.txt") + "\ntracker: " + ReadTextFile(dir / "tracker.txt"); };

  LcmBus bus(url_, 10000);
  int64_t scan_id = 0;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) {
    truth_.push_back({m, SteadyClock::now()});
  });
  Subscribe<drive_command_t>(bus, "DRIVE_COMMAND", [&](const drive_command_t& m) {
    commands_.push_back({m.utime, SteadyClock::now()});
  });
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t& m) {
    odometry_.push_back(m);
    if (!feed_pose_) return;
    pose_estimate_t e{};
    e.utime = m.utime;
    e.scan_id = ++scan_id;
    e.source = "test";
    e.pose = m.pose;
    e.covariance[0] = e.covariance[4] = 1e-4;
    e.covariance[8] = 1e-6;
    e.converged = true;
    e.status = "ok: inserted";
    e.num_points = e.num_inliers = 100;
    Publish(bus, "POSE", e);
    last_pose_utime_ = m.utime;
    last_pose_sent_ = SteadyClock::now();
  });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return odometry_.size() >= 10 && !commands_.empty(); }))
      << "no ODOMETRY or no DRIVE_COMMAND within 20 s\n" << logs();

  int64_t request_id = 0;
  auto drive = [&]() -> bool {
    Publish(bus, "PATH", StraightPath(++request_id));
    return Pump(bus, 15.0, [&] { return Cruising(); });
  };
  struct Loss {
    std::string what;
    double sim_ms, wall_ms;
  };
  std::vector<Loss> losses;
  // From the loss (its stamp on the sim's clock, its moment on the test's) to the stop.
  auto measure = [&](const std::string& what, size_t from, int64_t lost_utime, SteadyClock::time_point lost_at) {
    ASSERT_TRUE(Pump(bus, 5.0, [&] { return FirstStopped(from) < truth_.size(); }))
        << what << ": still driving 5 s after the loss\n" << logs();
    const Sample& stop = truth_[FirstStopped(from)];
    losses.push_back({what, static_cast<double>(stop.truth.utime - lost_utime) * 1e-3,
                      1e3 * (SteadySeconds(stop.arrived) - SteadySeconds(lost_at))});
  };

  // 1. Pose lost: the estimates stop.
  ASSERT_TRUE(drive()) << "never reached cruise\n" << logs();
  feed_pose_ = false;
  const size_t pose_from = truth_.size();
  Pump(bus, 0.01);
  const auto pose_deadline = last_pose_sent_ + std::chrono::duration_cast<SteadyClock::duration>(
                                                   std::chrono::duration<double>(kPoseTimeout));
  measure("pose", pose_from, last_pose_utime_ + static_cast<int64_t>(kPoseTimeout * 1e6), pose_deadline);
  // It drove on odometry until the limit, not less.
  EXPECT_GT(truth_[FirstStopped(pose_from)].truth.utime - truth_[pose_from].truth.utime, 800'000) << "stopped early";
  feed_pose_ = true;  // estimates back: the path resumes
  ASSERT_TRUE(Pump(bus, 10.0, [&] { return Cruising(); })) << "did not resume after the estimates came back\n"
                                                            << logs();

  // 2. Path lost: canceled by its sender.
  path_t cancel = StraightPath(request_id);
  cancel.feasible = false;
  cancel.status = "canceled";
  const size_t path_from = truth_.size();
  const int64_t cancel_utime = WallUtime();
  const auto cancel_at = SteadyClock::now();
  Publish(bus, "PATH", cancel);
  measure("path", path_from, cancel_utime, cancel_at);

  // 3. Commands lost: the tracker killed while driving.
  ASSERT_TRUE(drive()) << "never reached cruise on the second path\n" << logs();
  tracker->Signal(SIGKILL);
  tracker->Wait(5.0);
  const size_t commands_from = truth_.size();
  Pump(bus, 0.02);  // a command already on its way
  ASSERT_FALSE(commands_.empty());
  const auto [last_utime, last_arrival] = commands_.back();
  const auto overdue = last_arrival + std::chrono::duration_cast<SteadyClock::duration>(
                                          std::chrono::duration<double>(kControlPeriod));
  measure("commands", commands_from, last_utime + static_cast<int64_t>(kControlPeriod * 1e6), overdue);
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << logs();

  for (const Loss& l : losses) {
    std::printf("stop after losing %-8s: %6.1f ms sim time, %6.1f ms wall\n", l.what.c_str(), l.sim_ms, l.wall_ms);
    RecordProperty("stop_ms_sim_" + l.what, static_cast<int>(std::lround(l.sim_ms)));
    RecordProperty("stop_ms_wall_" + l.what, static_cast<int>(std::lround(l.wall_ms)));
    // The requirement; under ASan/UBSan (kSlowdown) the processes are slower, not the design.
    EXPECT_LE(l.sim_ms, 200.0 * testing::kSlowdown) << l.what;
    EXPECT_LE(l.wall_ms, 200.0 * testing::kSlowdown) << l.what;
    EXPECT_GE(l.sim_ms, -60.0) << l.what << ": stopped before the loss (one sim tick of slack)";
  }
}

}  // namespace
}  // namespace minenav
