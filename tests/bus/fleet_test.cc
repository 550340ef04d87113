// The fleet on a real LCM bus, inside a private network namespace (tests/bus/private_net.sh
// sets MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL with a port of its own):
//   - LcmBus itself: round trip, timeouts, decode errors;
//   - vehicle_sim + ladar_driver + lcm-logger with a scripted drive; the log is checked
//     (scans complete and consecutive, truth consistent with the commands, scans lying on
//     the world's walls at the true poses), then replayed with lcm-logplayer to a
//     subscriber that must receive the same messages;
//   - a process fed garbage logs one line per bad message, counts it in HEARTBEAT and
//     goes on.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "common/angle.h"
#include "common/file_io.h"
#include "common/geometry.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/node/lcm_bus.h"
#include "common/scan.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/log_contents.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::ChildProcess;
using testing::ReadChannel;
using testing::ReadPayloads;
using testing::ReadTextFile;

// Processes stop by themselves after this long even if the test dies without killing them.
constexpr const char* kSafetyStop = "--run-for";

using BusTest = testing::PrivateBusTest;

drive_command_t Command(int8_t mode, double v, double omega, int64_t seq) {
  drive_command_t c{};
  c.utime = seq;
  c.seq = seq;
  c.mode = mode;
  c.v = v;
  c.omega = omega;
  c.timeout = 0.5;
  return c;
}

TEST_F(BusTest, LcmBusRoundTripTimeoutAndBadMessages) {
  LcmBus bus(url_, 100);
  std::vector<odometry_t> got;
  Subscribe<odometry_t>(bus, "ODOMETRY_RT", [&](const odometry_t& m) { got.push_back(m); });
  // Nothing published yet: HandleFor returns 0 after about the timeout.
  const auto t0 = Clock::now();
  EXPECT_EQ(bus.HandleFor(50'000), 0);
  const double waited = std::chrono::duration<double>(Clock::now() - t0).count();
  EXPECT_GE(waited, 0.04);
  EXPECT_LT(waited, 1.0);

  for (int i = 0; i < 20; ++i) {
    odometry_t m{};
    m.utime = i;
    m.pose.x = 0.5 * i;
    ASSERT_TRUE(Publish(bus, "ODOMETRY_RT", m));
  }
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  bus.Publish("ODOMETRY_RT", garbage, 5);
  Publish(bus, "ODOMETRY_RT", Command(drive_command_t::STOP, 0, 0, 1));  // wrong type
  EXPECT_TRUE(Pump(bus, 5.0, [&] { return bus.counters().messages_bad == 2; }));
  ASSERT_EQ(got.size(), 20u);  // loopback delivery, in order, nothing lost
  for (int i = 0; i < 20; ++i) EXPECT_DOUBLE_EQ(got[static_cast<size_t>(i)].pose.x, 0.5 * i);
  EXPECT_EQ(bus.counters().messages_in, 20);
  EXPECT_EQ(bus.counters().published, 22);
}

// Nearest distance from p to any segment (brute force: the reference).
double DistanceToWorld(const Eigen::Vector2d& p, const std::vector<Segment>& world) {
  double best = 1e300;
  for (const Segment& s : world) best = std::min(best, PointToSegmentDistance(p, s));
  return best;
}

// Truth interpolated at t from samples sorted by utime.
Pose2 TruthAt(const std::vector<testing::Logged<vehicle_truth_t>>& truth, int64_t t) {
  auto it = std::lower_bound(truth.begin(), truth.end(), t,
                             [](const auto& l, int64_t u) { return l.msg.utime < u; });
  if (it == truth.end()) return FromLcm(truth.back().msg.pose);
  if (it == truth.begin() || it->msg.utime == t) return FromLcm(it->msg.pose);
  const auto& a = (it - 1)->msg;
  const auto& b = it->msg;
  const double f = static_cast<double>(t - a.utime) / static_cast<double>(b.utime - a.utime);
  return Pose2(a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
               NormalizeAngle(a.pose.theta + f * NormalizeAngle(b.pose.theta - a.pose.theta)));
}

// The truth sample at or just before log timestamp `ts` (the receive time of a command).
Pose2 TruthAtReceive(const std::vector<testing::Logged<vehicle_truth_t>>& truth, int64_t ts) {
  Pose2 p = FromLcm(truth.front().msg.pose);
  for (const auto& l : truth) {
    if (l.timestamp > ts) break;
    p = FromLcm(l.msg.pose);
  }
  return p;
}

TEST_F(BusTest, ScriptedDriveIsRecordedCompletelyAndReplaysIdentically) {
  testing::TempDir dir("minenav_fleet_test");
  const std::string log = dir / "run.lcm";
  constexpr double kSpeed = 0.3, kTurnRate = 0.3;  // m/s, rad/s

  ChildProcess logger({"lcm-logger", "--lcm-url=" + url_, "-f", "-q", log}, dir / "logger.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // logger subscribed first
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, kSafetyStop, "90", "--sensor", "typhoon", "--seed", "5"}, dir / "ladar.txt");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, kSafetyStop, "90", "--generate", "mine", "--seed", "3", "--max-forward-speed", "0.5",
                    "--max-acceleration", "0", "--max-deceleration", "0", "--max-yaw-acceleration", "0",
                    "--max-turn-in-place-rate", "0.5"},
                   dir / "sim.txt");

  LcmBus bus(url_, 1000);
  int scans_seen = 0;
  Subscribe<ladar_scan_t>(bus, "LADAR_SCAN", [&](const ladar_scan_t&) { ++scans_seen; });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return scans_seen >= 3; }))
      << "no scans within 20 s\nladar: " << ReadTextFile(dir / "ladar.txt") << "\nsim: " << ReadTextFile(dir / "sim.txt");

  // The drive: forward 3 s, stop 1 s, turn in place 2 s, stop 1 s; commands at 10 Hz.
  struct Phase {
    int8_t mode;
    double v, omega, seconds;
  };
  const std::vector<Phase> script = {{drive_command_t::VELOCITY, kSpeed, 0.0, 3.0},
                                     {drive_command_t::STOP, 0.0, 0.0, 1.0},
                                     {drive_command_t::TURN_IN_PLACE, 0.0, kTurnRate, 2.0},
                                     {drive_command_t::STOP, 0.0, 0.0, 1.0}};
  int64_t seq = 0;
  for (const Phase& phase : script) {
    const auto end = Clock::now() + std::chrono::duration<double>(phase.seconds);
    auto next = Clock::now();
    while (Clock::now() < end) {
      Publish(bus, "DRIVE_COMMAND", Command(phase.mode, phase.v, phase.omega, seq++));
      next += std::chrono::milliseconds(100);
      while (Clock::now() < next) bus.HandleFor(5'000);
    }
  }
  ladar.Signal(SIGTERM);
  sim.Signal(SIGTERM);
  EXPECT_EQ(ladar.Wait(10.0), 0) << ReadTextFile(dir / "ladar.txt");
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");
  Pump(bus, 0.5);
  logger.Signal(SIGINT);
  ASSERT_TRUE(logger.Wait(10.0).has_value());

  // --- What the log holds.
  const auto scans = ReadChannel<ladar_scan_t>(log, "LADAR_SCAN");
  auto truth = ReadChannel<vehicle_truth_t>(log, "SIM_TRUTH");
  const auto commands = ReadChannel<drive_command_t>(log, "DRIVE_COMMAND");
  const auto worlds = ReadChannel<line_map_t>(log, "SIM_WORLD");
  const auto heartbeats = ReadChannel<heartbeat_t>(log, "HEARTBEAT");
  ASSERT_FALSE(worlds.empty());
  ASSERT_GT(truth.size(), 100u);
  EXPECT_EQ(commands.size(), static_cast<size_t>(seq)) << "the logger lost drive commands";

  // Scans: right size, ids from 0 with no gap up to the last one the driver published.
  ASSERT_GE(scans.size(), 70u);  // 7 s of driving at 10 Hz plus the start-up
  const auto published_line = testing::LinesContaining(ReadTextFile(dir / "ladar.txt"), "scans published");
  ASSERT_EQ(published_line.size(), 1u);
  const long published = std::strtol(published_line[0].substr(published_line[0].find("info: ") + 6).c_str(), nullptr, 10);
  EXPECT_EQ(static_cast<long>(scans.size()), published) << "scans lost between ladar_driver and lcm-logger";
  for (size_t k = 0; k < scans.size(); ++k) {
    const ladar_scan_t& s = scans[k].msg;
    EXPECT_EQ(s.scan_id, static_cast<int64_t>(k));
    ASSERT_EQ(s.num_ranges, 2048);
    ASSERT_EQ(s.ranges.size(), 2048u);
    if (k > 0) {
      EXPECT_EQ(s.utime - scans[k - 1].msg.utime, 100'000) << "scan " << k;
    }
  }

  // Truth: no sample lost, time increasing.
  for (size_t j = 1; j < truth.size(); ++j) {
    EXPECT_EQ(truth[j].msg.seq, truth[j - 1].msg.seq + 1) << "SIM_TRUTH lost before sample " << j;
    EXPECT_GT(truth[j].msg.utime, truth[j - 1].msg.utime);
  }

  // Truth against the commands, timed by when the logger (like the vehicle) received them.
  auto first_of = [&](int8_t mode, size_t from) {
    for (size_t i = from; i < commands.size(); ++i)
      if (commands[i].msg.mode == mode) return i;
    return commands.size();
  };
  const size_t go = first_of(drive_command_t::VELOCITY, 0);
  const size_t stop1 = first_of(drive_command_t::STOP, go);
  const size_t turn = first_of(drive_command_t::TURN_IN_PLACE, stop1);
  const size_t stop2 = first_of(drive_command_t::STOP, turn);
  ASSERT_LT(stop2, commands.size());
  const Pose2 before = TruthAtReceive(truth, commands[go].timestamp);
  const Pose2 after_forward = TruthAtReceive(truth, commands[turn].timestamp);
  const Pose2 after_turn = FromLcm(truth.back().msg.pose);
  const double forward_s = static_cast<double>(commands[stop1].timestamp - commands[go].timestamp) * 1e-6;
  const double distance = TranslationDistance(before, after_forward);
  // One 50 ms integration tick of slack at each end, plus scheduling jitter on a loaded
  // machine (a vehicle_sim held up for 0.1 s keeps the old command 0.1 s longer).
  EXPECT_NEAR(distance, kSpeed * forward_s, 0.06) << "forward for " << forward_s << " s";
  EXPECT_NEAR(distance, kSpeed * 3.0, 0.09);
  EXPECT_NEAR(after_forward.theta, before.theta, 1e-6) << "a straight drive must not turn";
  const double direction = std::atan2(after_forward.y - before.y, after_forward.x - before.x);
  EXPECT_NEAR(NormalizeAngle(direction - before.theta), 0.0, 1e-3) << "moved along the heading";
  const double turn_s = static_cast<double>(commands[stop2].timestamp - commands[turn].timestamp) * 1e-6;
  const double turned = NormalizeAngle(after_turn.theta - after_forward.theta);
  EXPECT_NEAR(turned, kTurnRate * turn_s, 0.06) << "turn in place for " << turn_s << " s";
  // While moving, the truth reports exactly the commanded speed and yaw rate.
  for (const auto& l : truth) {
    if (std::abs(l.msg.v) > 1e-9) {
      EXPECT_NEAR(l.msg.v, kSpeed, 1e-9);
    } else if (std::abs(l.msg.omega) > 1e-9) {
      EXPECT_NEAR(l.msg.omega, kTurnRate, 1e-9);
    }
  }
  EXPECT_NEAR(turned, kTurnRate * 2.0, 0.09);
  EXPECT_LT(TranslationDistance(after_forward, after_turn), 1e-6) << "turning in place must not move";

  // Poses at scan times advance by speed x 0.1 s while driving forward.
  std::vector<Pose2> forward_poses;
  for (const auto& s : scans)
    if (s.msg.utime > truth.front().msg.utime && s.msg.utime >= commands[go].timestamp + 200'000 &&
        s.msg.utime + 200'000 <= commands[stop1].timestamp)
      forward_poses.push_back(TruthAt(truth, s.msg.utime));
  ASSERT_GE(forward_poses.size(), 20u);
  for (size_t k = 1; k < forward_poses.size(); ++k)
    EXPECT_NEAR(TranslationDistance(forward_poses[k - 1], forward_poses[k]), kSpeed * 0.1, 2e-3);

  // Every 5th scan, re-projected at its true pose, lies on the world's walls.
  const std::vector<Segment> world = SegmentsFromLcm(worlds.back().msg);
  for (size_t k = 0; k < scans.size(); k += 5) {
    const LadarScan scan = FromLcm(scans[k].msg);
    const Pose2 pose = TruthAt(truth, scan.utime);
    std::vector<double> d;
    for (const Eigen::Vector2d& p : ScanPointsInWorld(scan, pose)) d.push_back(DistanceToWorld(p, world));
    ASSERT_GT(d.size(), 1000u) << "scan " << k << " has few returns";
    std::sort(d.begin(), d.end());
    EXPECT_LT(d[d.size() / 2], 0.06) << "scan " << k << " median distance to the walls";
    EXPECT_LT(d[d.size() * 9 / 10], 0.15) << "scan " << k << " 90th percentile";
  }

  // Both processes stopped cleanly and saw no bad message.
  std::map<std::string, heartbeat_t> last;
  for (const auto& h : heartbeats) last[h.msg.process] = h.msg;
  for (const char* process : {"vehicle_sim", "ladar_driver"}) {
    ASSERT_TRUE(last.count(process)) << process << " sent no heartbeat";
    EXPECT_EQ(last[process].state, heartbeat_t::STOPPING) << process;
    EXPECT_EQ(last[process].messages_bad, 0) << process;
  }
  EXPECT_EQ(last["vehicle_sim"].messages_in, seq);

  // --- Replay: lcm-logplayer must deliver the same scans and truth, byte for byte.
  const auto logged_scans = ReadPayloads(log, "LADAR_SCAN");
  const auto logged_truth = ReadPayloads(log, "SIM_TRUTH");
  std::vector<std::vector<uint8_t>> got_scans, got_truth;
  LcmBus listener(url_, 10000);
  listener.Subscribe("LADAR_SCAN|SIM_TRUTH", [&](const RawMessage& m) {
    (m.channel == "LADAR_SCAN" ? got_scans : got_truth).emplace_back(m.data, m.data + m.size);
  });
  ChildProcess player({"lcm-logplayer", "--lcm-url=" + url_, "-s", "4", log}, dir / "player.txt");
  Pump(listener, 60.0, [&] { return !player.Running(); });
  Pump(listener, 1.0, [&] { return got_scans.size() == logged_scans.size() && got_truth.size() == logged_truth.size(); });
  EXPECT_EQ(player.Wait(1.0), 0) << ReadTextFile(dir / "player.txt");
  EXPECT_EQ(got_scans.size(), logged_scans.size());
  EXPECT_EQ(got_truth.size(), logged_truth.size());
  EXPECT_TRUE(got_scans == logged_scans) << "replayed scans differ from the log";
  EXPECT_TRUE(got_truth == logged_truth) << "replayed truth differs from the log";
}

TEST_F(BusTest, BadMessagesAreLoggedCountedAndSurvived) {
  testing::TempDir dir("minenav_fleet_test");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, kSafetyStop, "90", "--generate", "mine", "--heartbeat-period", "0.2",
                    "--max-forward-speed", "0.5", "--max-acceleration", "0"},
                   dir / "sim.txt");
  {
    std::ofstream world(dir / "room.json");
    world << "{\"segments\": [[-10,-10,10,-10],[10,-10,10,10],[10,10,-10,10],[-10,10,-10,-10]]}";
  }
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, kSafetyStop, "90", "--world", dir / "room.json", "--heartbeat-period", "0.2",
                      "--truth-channel", "FAKE_TRUTH"},
                     dir / "ladar.txt");
  LcmBus bus(url_, 1000);
  std::map<std::string, heartbeat_t> hb;
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) { hb[m.process] = m; });
  std::vector<vehicle_truth_t> truth;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(m); });
  int scans = 0;
  Subscribe<ladar_scan_t>(bus, "LADAR_SCAN", [&](const ladar_scan_t&) { ++scans; });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return hb.count("vehicle_sim") && hb.count("ladar_driver"); }))
      << ReadTextFile(dir / "sim.txt") << ReadTextFile(dir / "ladar.txt");

  // Three bad DRIVE_COMMANDs: garbage, another type, truncated; then one invalid content.
  const uint8_t garbage[7] = {0xde, 0xad, 0xbe, 0xef, 0, 1, 2};
  bus.Publish("DRIVE_COMMAND", garbage, sizeof(garbage));
  odometry_t wrong{};
  Publish(bus, "DRIVE_COMMAND", wrong);
  const std::vector<uint8_t> good = EncodeMessage(Command(drive_command_t::VELOCITY, 0.3, 0, 1));
  bus.Publish("DRIVE_COMMAND", good.data(), static_cast<int>(good.size()) - 3);
  drive_command_t unknown_mode = Command(drive_command_t::VELOCITY, 0.3, 0, 2);
  unknown_mode.mode = 9;
  Publish(bus, "DRIVE_COMMAND", unknown_mode);
  // Bad truth for the ladar driver: garbage and a NaN pose; good truth around them.
  int64_t t_us = 1'000'000'000;
  auto send_truth = [&](double x) {
    vehicle_truth_t m{};
    m.utime = t_us;
    m.pose.x = x;
    t_us += 50'000;
    Publish(bus, "FAKE_TRUTH", m);
  };
  for (int i = 0; i < 10; ++i) send_truth(0.0);
  bus.Publish("FAKE_TRUTH", garbage, sizeof(garbage));
  send_truth(std::nan(""));
  // ...and the processes go on: good commands move the vehicle, good truth makes scans.
  const size_t truth_before = truth.size();
  for (int i = 0; i < 10; ++i) {
    bus.Publish("DRIVE_COMMAND", good.data(), static_cast<int>(good.size()));
    send_truth(0.01 * i);
    Pump(bus, 0.1);
  }
  ASSERT_TRUE(Pump(bus, 5.0, [&] {
    return hb["vehicle_sim"].messages_bad == 4 && hb["ladar_driver"].messages_bad == 2 &&
           hb["vehicle_sim"].messages_in >= 10;
  })) << "vehicle_sim bad " << hb["vehicle_sim"].messages_bad << " in " << hb["vehicle_sim"].messages_in
      << ", ladar_driver bad " << hb["ladar_driver"].messages_bad;
  ASSERT_GT(truth.size(), truth_before + 2);
  EXPECT_GT(TranslationDistance(FromLcm(truth[truth_before].pose), FromLcm(truth.back().pose)), 0.1) << "vehicle did not move";
  EXPECT_GT(scans, 5);
  EXPECT_TRUE(sim.Running());
  EXPECT_TRUE(ladar.Running());
  sim.Signal(SIGTERM);
  ladar.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0);
  EXPECT_EQ(ladar.Wait(10.0), 0);

  // One warning line per bad message, naming the channel.
  const std::string sim_log = ReadTextFile(dir / "sim.txt");
  EXPECT_EQ(testing::LinesContaining(sim_log, "warning").size(), 4u) << sim_log;
  EXPECT_EQ(testing::LinesContaining(sim_log, "channel DRIVE_COMMAND").size(), 4u) << sim_log;
  const std::string ladar_log = ReadTextFile(dir / "ladar.txt");
  EXPECT_EQ(testing::LinesContaining(ladar_log, "channel FAKE_TRUTH").size(), 2u) << ladar_log;
}

TEST_F(BusTest, ReplayRepublishesRecordedScansAtTheRecordedRate) {
  testing::TempDir dir("minenav_fleet_test");
  const std::string log = dir / "dataset.lcm";
  std::vector<std::vector<uint8_t>> expected;
  {
    LogWriter w(log);
    const int64_t t0 = 1'600'000'000'000'000;
    for (int k = 0; k < 10; ++k) {
      ladar_scan_t s{};
      s.utime = t0 + k * 100'000;
      s.scan_id = 1000 + k;
      s.sensor_id = "carmen-front";
      s.angle_step = 0.01f;
      s.max_range = 50.0f;
      s.num_ranges = 3;
      s.ranges = {1.0f, 2.0f, static_cast<float>(k)};
      expected.push_back(EncodeMessage(s));
      w.Write("LADAR_SCAN", s.utime, expected.back().data(), static_cast<int>(expected.back().size()));
      odometry_t other{};
      other.utime = s.utime + 1;
      w.Write("ODOMETRY", other);  // not replayed
      if (k == 4) {
        const uint8_t garbage[9] = {9, 9, 9, 9, 9, 9, 9, 9, 9};
        w.Write("LADAR_SCAN", s.utime + 2, garbage, 9);  // skipped and counted
      }
    }
    w.Close();
  }
  LcmBus bus(url_, 1000);
  std::vector<std::vector<uint8_t>> got;
  std::vector<Clock::time_point> arrival;
  int odometry = 0;
  bus.Subscribe("LADAR_SCAN", [&](const RawMessage& m) {
    got.emplace_back(m.data, m.data + m.size);
    arrival.push_back(Clock::now());
  });
  bus.Subscribe("ODOMETRY", [&](const RawMessage&) { ++odometry; });
  std::map<std::string, heartbeat_t> hb;
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) { hb[m.process] = m; });
  ChildProcess driver({MINENAV_LADAR_DRIVER_BIN, kSafetyStop, "90", "--replay", log, "--replay-speed", "1"}, dir / "driver.txt");
  Pump(bus, 20.0, [&] { return !driver.Running(); });
  Pump(bus, 0.3);
  EXPECT_EQ(driver.Wait(1.0), 0) << ReadTextFile(dir / "driver.txt");
  ASSERT_EQ(got.size(), expected.size()) << ReadTextFile(dir / "driver.txt");
  EXPECT_TRUE(got == expected) << "replayed scans differ from the recorded ones";
  EXPECT_EQ(odometry, 0);
  // Recorded 0.1 s apart: 0.9 s from first to last (generous bounds for a loaded machine).
  const double span = std::chrono::duration<double>(arrival.back() - arrival.front()).count();
  EXPECT_GT(span, 0.85);
  EXPECT_LT(span, 1.5);
  ASSERT_TRUE(hb.count("ladar_driver"));
  EXPECT_EQ(hb["ladar_driver"].state, heartbeat_t::STOPPING);
  EXPECT_EQ(hb["ladar_driver"].messages_bad, 1);
  EXPECT_EQ(hb["ladar_driver"].messages_in, 10);
}

}  // namespace
}  // namespace minenav
