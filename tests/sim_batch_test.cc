// vehicle_sim and ladar_driver run in batch over logs (--log/--log-out): no network, so
// these run directly under CTest. They check the processes end to end with exact
// numbers: ladar ranges from poses interpolated between SIM_TRUTH samples, vehicle motion
// from commands and the stale-command stop, and bit-for-bit repeatable output.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/node/event_log.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/child_process.h"
#include "tests/log_contents.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadChannel;
using testing::ReadPayloads;

constexpr int64_t kT0 = 1'700'000'000'000'000;

int RunToCompletion(const std::vector<std::string>& argv, const std::string& output) {
  ChildProcess p(argv, output);
  const auto code = p.Wait(120.0);
  return code.value_or(-1);
}

// A 20 x 20 m room centred on the origin.
line_map_t Room(int64_t utime) {
  const std::vector<Segment> walls = {Segment(-10, -10, 10, -10), Segment(10, -10, 10, 10),
                                      Segment(10, 10, -10, 10), Segment(-10, 10, -10, -10)};
  return SegmentsToLcm(walls, utime, 1, "room");
}

// Truth at 7 Hz (so scan times fall between samples): x = -3 + 0.5 t, theta = 0.1 t.
double TrueX(double t) { return -3.0 + 0.5 * t; }
double TrueTheta(double t) { return 0.1 * t; }

std::string WriteTruthLog(const std::string& path) {
  LogWriter w(path);
  w.Write("SIM_WORLD", Room(kT0 - 1000));
  const int64_t period = 142'857;
  for (int64_t j = 0; j * period <= 3'000'000; ++j) {
    const double t = static_cast<double>(j * period) * 1e-6;
    vehicle_truth_t m{};
    m.utime = kT0 + j * period;
    m.seq = j;
    m.pose.x = TrueX(t);
    m.pose.theta = TrueTheta(t);
    m.v = 0.5;
    m.omega = 0.1;
    w.Write("SIM_TRUTH", m);
  }
  w.Close();
  return path;
}

TEST(LadarDriverBatch, ScansOnScheduleWithInterpolatedPoses) {
  testing::TempDir dir("minenav_sim_batch_test");
  const std::string in = WriteTruthLog(dir / "truth.lcm");
  const std::string out = dir / "scans.lcm";
  ASSERT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--log", in, "--log-out", out, "--range-sigma", "0",
                             "--range-resolution", "0", "--mixed-pixel-probability", "0", "--beam-divergence", "0"},
                            dir / "ladar.txt"),
            0)
      << testing::ReadTextFile(dir / "ladar.txt");
  const auto scans = ReadChannel<ladar_scan_t>(out, "LADAR_SCAN");
  // Truth covers [0, 2.999997] s: scans at 0, 0.1, ..., 2.9 s.
  ASSERT_EQ(scans.size(), 30u);
  for (size_t k = 0; k < scans.size(); ++k) {
    const ladar_scan_t& s = scans[k].msg;
    EXPECT_EQ(s.scan_id, static_cast<int64_t>(k));
    EXPECT_EQ(s.utime, kT0 + static_cast<int64_t>(k) * 100'000);
    ASSERT_EQ(s.num_ranges, 2048);
    EXPECT_EQ(s.sensor_id, "typhoon");
    const double t = static_cast<double>(k) * 0.1;
    // Reading 0 looks along the heading at the x = 10 wall; reading 512 (90 deg) at y = 10.
    const double expected0 = (10.0 - TrueX(t)) / std::cos(TrueTheta(t));
    const double expected90 = 10.0 / std::cos(TrueTheta(t));
    EXPECT_NEAR(s.ranges[0], expected0, 2e-4) << "scan " << k;
    EXPECT_NEAR(s.ranges[512], expected90, 2e-4) << "scan " << k;
  }
}

TEST(LadarDriverBatch, RepeatableForASeedAndDifferentForAnother) {
  testing::TempDir dir("minenav_sim_batch_test");
  const std::string in = WriteTruthLog(dir / "truth.lcm");
  for (const char* name : {"a.lcm", "b.lcm"})
    ASSERT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--log", in, "--log-out", dir / name, "--seed", "9"},
                              dir / "out.txt"),
              0);
  ASSERT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--log", in, "--log-out", dir / "c.lcm", "--seed", "10"},
                            dir / "out.txt"),
            0);
  const auto a = ReadPayloads(dir / "a.lcm", "LADAR_SCAN");
  const auto b = ReadPayloads(dir / "b.lcm", "LADAR_SCAN");
  const auto c = ReadPayloads(dir / "c.lcm", "LADAR_SCAN");
  ASSERT_EQ(a.size(), 30u);
  EXPECT_EQ(a, b);
  ASSERT_EQ(c.size(), a.size());
  EXPECT_NE(a[5], c[5]);  // different noise
}

TEST(LadarDriverBatch, BadFlagsExitWithUsageCode) {
  testing::TempDir dir("minenav_sim_batch_test");
  EXPECT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--min-range", "far"}, dir / "o.txt"), 2);
  EXPECT_NE(testing::ReadTextFile(dir / "o.txt").find("--min-range"), std::string::npos);
  EXPECT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--min-range", "50", "--max-range", "10"}, dir / "o.txt"), 2);
  EXPECT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--log", dir / "missing.lcm"}, dir / "o.txt"), 2);
  EXPECT_EQ(RunToCompletion({MINENAV_LADAR_DRIVER_BIN, "--world", dir / "missing.json", "--log", dir / "x"}, dir / "o.txt"),
            2);
  EXPECT_EQ(testing::LinesContaining(testing::ReadTextFile(dir / "o.txt"), "error").size(), 1u);
}

// Commands: forward 0.3 m/s every 0.1 s for 2 s (timeout 0.5 s), then silence, then a STOP
// at 4 s that only extends the log.
std::string WriteCommandLog(const std::string& path) {
  LogWriter w(path);
  for (int k = 0; k < 20; ++k) {
    drive_command_t c{};
    c.utime = kT0 + k * 100'000;
    c.seq = k;
    c.mode = drive_command_t::VELOCITY;
    c.v = 0.3;
    c.timeout = 0.5;
    w.Write("DRIVE_COMMAND", c);
  }
  drive_command_t stop{};
  stop.utime = kT0 + 4'000'000;
  stop.mode = drive_command_t::STOP;
  stop.timeout = 0.5;
  w.Write("DRIVE_COMMAND", stop);
  w.Close();
  return path;
}

std::vector<std::string> VehicleArgs(const std::string& in, const std::string& out) {
  return {MINENAV_VEHICLE_SIM_BIN, "--log", in, "--log-out", out, "--start-pose", "1,2,90deg",
          "--rate", "20", "--max-forward-speed", "0.5", "--max-acceleration", "0", "--max-deceleration", "0",
          "--odometry-scale-error", "0", "--odometry-rotation-scale-error", "0",
          "--odometry-heading-drift-per-metre", "0", "--odometry-translation-noise", "0",
          "--odometry-rotation-noise", "0"};
}

TEST(VehicleSimBatch, DrivesOnCommandsAndStopsWhenTheyGoStale) {
  testing::TempDir dir("minenav_sim_batch_test");
  const std::string in = WriteCommandLog(dir / "commands.lcm");
  const std::string out = dir / "run.lcm";
  ASSERT_EQ(RunToCompletion(VehicleArgs(in, out), dir / "sim.txt"), 0) << testing::ReadTextFile(dir / "sim.txt");
  const auto truth = ReadChannel<vehicle_truth_t>(out, "SIM_TRUTH");
  const auto odom = ReadChannel<odometry_t>(out, "ODOMETRY");
  ASSERT_EQ(truth.size(), 81u);  // 20 Hz over [0, 4] s
  ASSERT_EQ(odom.size(), truth.size());
  double last_y = 2.0;
  for (size_t j = 0; j < truth.size(); ++j) {
    const vehicle_truth_t& m = truth[j].msg;
    EXPECT_EQ(m.seq, static_cast<int64_t>(j));
    EXPECT_EQ(m.utime, kT0 + static_cast<int64_t>(j) * 50'000);
    const double t = static_cast<double>(j) * 0.05;
    // Heading 90 deg: the vehicle drives along +y at 0.3 m/s from t = 0 (the command at
    // t0 arrives just after the first tick) until the command goes stale 0.5 s after the
    // last one (t = 2.4 s; the tick that notices may still finish its step: 2.45 s).
    EXPECT_NEAR(m.pose.x, 1.0, 1e-9);
    EXPECT_NEAR(m.pose.theta, M_PI / 2, 1e-9);
    if (t <= 2.4 + 1e-9) {
      EXPECT_NEAR(m.pose.y, 2.0 + 0.3 * t, 1e-9) << "t = " << t;
    }
    if (t >= 2.5) {
      EXPECT_NEAR(m.pose.y, last_y, 1e-12) << "still moving at t = " << t;
    }
    last_y = m.pose.y;
    // Odometry without errors equals truth.
    EXPECT_NEAR(odom[j].msg.pose.y, m.pose.y, 1e-9);
  }
  EXPECT_GE(last_y, 2.0 + 0.72 - 1e-9);
  EXPECT_LE(last_y, 2.0 + 0.735 + 1e-9);
  // The world and the map went out too, and heartbeats ended with STOPPING.
  EXPECT_FALSE(ReadChannel<line_map_t>(out, "SIM_WORLD").empty());
  EXPECT_FALSE(ReadChannel<line_map_t>(out, "LINE_MAP").empty());
  const auto hb = ReadChannel<heartbeat_t>(out, "HEARTBEAT");
  ASSERT_FALSE(hb.empty());
  EXPECT_EQ(hb.back().msg.state, heartbeat_t::STOPPING);
  EXPECT_EQ(hb.back().msg.messages_in, 21);
  EXPECT_EQ(hb.back().msg.messages_bad, 0);
}

TEST(VehicleSimBatch, RepeatableBitForBit) {
  testing::TempDir dir("minenav_sim_batch_test");
  const std::string in = WriteCommandLog(dir / "commands.lcm");
  std::vector<std::string> a = VehicleArgs(in, dir / "a.lcm"), b = VehicleArgs(in, dir / "b.lcm");
  a.insert(a.end(), {"--odometry-translation-noise", "0.01"});
  b.insert(b.end(), {"--odometry-translation-noise", "0.01"});
  ASSERT_EQ(RunToCompletion(a, dir / "a.txt"), 0);
  ASSERT_EQ(RunToCompletion(b, dir / "b.txt"), 0);
  EXPECT_EQ(ReadPayloads(dir / "a.lcm", "ODOMETRY"), ReadPayloads(dir / "b.lcm", "ODOMETRY"));
  EXPECT_EQ(ReadPayloads(dir / "a.lcm", "SIM_TRUTH"), ReadPayloads(dir / "b.lcm", "SIM_TRUTH"));
}

TEST(VehicleSimBatch, WorldGeneratorsAndBadInput) {
  testing::TempDir dir("minenav_sim_batch_test");
  const std::string in = WriteCommandLog(dir / "commands.lcm");
  for (const char* gen : {"mine", "research", "mockup"}) {
    const std::string world = dir / (std::string(gen) + ".json");
    ASSERT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--log", in, "--generate", gen, "--world-out", world,
                               "--heartbeat-period", "0"},
                              dir / "o.txt"),
              0)
        << gen << ": " << testing::ReadTextFile(dir / "o.txt");
    EXPECT_GT(fs::file_size(world), 100u) << gen;
    // The saved world loads back as --world.
    EXPECT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--log", in, "--world", world}, dir / "o.txt"), 0);
  }
  {
    std::ofstream bad(dir / "bad.json");
    bad << "{\"segments\": [[1, 2, 3]]}";
  }
  EXPECT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--log", in, "--world", dir / "bad.json"}, dir / "o.txt"), 2);
  EXPECT_EQ(testing::LinesContaining(testing::ReadTextFile(dir / "o.txt"), "bad.json").size(), 1u);
  EXPECT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--rate", "0"}, dir / "o.txt"), 2);
  EXPECT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--start-pose", "1,2"}, dir / "o.txt"), 2);
  EXPECT_EQ(RunToCompletion({MINENAV_VEHICLE_SIM_BIN, "--log-out", dir / "x.lcm"}, dir / "o.txt"), 2);
}

}  // namespace
}  // namespace minenav
