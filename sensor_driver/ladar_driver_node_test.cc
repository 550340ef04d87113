// ladar_driver's nodes through the fake bus: scans scheduled on the truth clock and cast in
// the world from SIM_WORLD, none before there is a world; the replay at the recorded pace,
// bad scans counted; the options and the flat flags of before.

#include "sensor_driver/ladar_driver_node.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/node/fake_runtime.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

// A 10 m x 10 m room around the origin.
std::vector<Segment> Room() {
  return {Segment({-5, -5}, {5, -5}), Segment({5, -5}, {5, 5}), Segment({5, 5}, {-5, 5}),
          Segment({-5, 5}, {-5, -5})};
}

vehicle_truth_t Truth(int64_t utime) {
  TruthReading t;
  t.utime = utime;
  t.pose = Pose2(0, 0, 0);
  return ToLcm(t);
}

// A clock that moves 1 ms every time it is read: lets a node wait for clock time in a test.
class SteppingClock final : public Clock {
 public:
  explicit SteppingClock(int64_t utime) : utime_(utime) {}
  int64_t NowUtime() const override { return utime_ += 1000; }

 private:
  mutable int64_t utime_;
};


LadarDriverOptions IdealTyphoon() {
  LadarDriverOptions o;
  o.model.range_sigma = "0";
  o.model.range_resolution = "0";
  o.model.mixed_pixel_probability = "0";
  return o;
}

// The simulation node on the fake bus, heartbeats every second; the clock started.
struct SimulationHarness {
  SimulationHarness() { fake.runtime().SpinOnce(0); }
  // The heartbeats so far, after one more second.
  std::vector<heartbeat_t> HeartbeatsAfterASecond() {
    clock.Advance(1'000'000);
    fake.runtime().SpinOnce(0);
    return fake.bus().Decoded<heartbeat_t>("HEARTBEAT");
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock, /*heartbeat_period=*/1.0};
  FakeBus& bus = fake.bus();
  LadarDriverOptions options = IdealTyphoon();
  LadarSimulationNode node{fake.runtime(), options, ResolveLadarDriver(options, NodeOptions())};
};

TEST(LadarSimulationNodeTest, ScansFollowTheTruthClockInTheWorldFromTheWorldChannel) {
  SimulationHarness h;
  h.bus.InjectMessage("SIM_TRUTH", Truth(kT0));  // due at once, but no world yet
  h.bus.HandleFor(0);
  EXPECT_TRUE(h.bus.PublishedOn("LADAR_SCAN").empty());
  h.bus.InjectMessage("SIM_WORLD", SegmentsToLcm(Room(), kT0, 1, "room"));
  for (int k = 1; k <= 5; ++k) h.bus.InjectMessage("SIM_TRUTH", Truth(kT0 + k * 50'000));  // 20 Hz truth
  h.bus.HandleFor(0);
  const auto scans = h.bus.Decoded<ladar_scan_t>("LADAR_SCAN");
  ASSERT_EQ(scans.size(), 2u);  // at t0 + 0.1 s and t0 + 0.2 s (10 Hz)
  for (size_t k = 0; k < scans.size(); ++k) {
    EXPECT_EQ(scans[k].scan_id, static_cast<int64_t>(k));
    EXPECT_EQ(scans[k].utime, kT0 + static_cast<int64_t>(k + 1) * 100'000);
    ASSERT_EQ(scans[k].num_ranges, 2048);
    EXPECT_NEAR(scans[k].ranges[0], 5.0, 1e-5) << "the wall 5 m ahead";
  }
  EXPECT_EQ(h.node.scans_published(), 2);
  const auto heartbeats = h.HeartbeatsAfterASecond();
  ASSERT_EQ(heartbeats.size(), 2u);
  EXPECT_EQ(heartbeats[0].state, heartbeat_t::WARN);
  EXPECT_EQ(heartbeats[0].message, "waiting for SIM_TRUTH");
  EXPECT_EQ(heartbeats[1].state, heartbeat_t::OK);
}

TEST(LadarSimulationNodeTest, WithoutAWorldTheHeartbeatSaysSo) {
  SimulationHarness h;
  h.bus.InjectMessage("SIM_TRUTH", Truth(kT0));
  h.bus.HandleFor(0);
  const auto heartbeats = h.HeartbeatsAfterASecond();
  ASSERT_EQ(heartbeats.size(), 2u);
  EXPECT_EQ(heartbeats[1].state, heartbeat_t::WARN);
  EXPECT_EQ(heartbeats[1].message, "no world");
  EXPECT_EQ(h.node.scans_published(), 0);
}

TEST(ScanReplayNodeTest, RepublishesTheLogsScansAtTheRecordedPaceAndSkipsBadOnes) {
  testing::TempDir dir("minenav_ladar_driver_node_test");
  const std::string log = dir / "scans.lcm";
  std::vector<std::vector<uint8_t>> recorded;
  {
    LogWriter w(log);
    const LadarSimulator simulator(LadarModel::Typhoon().Ideal(), 1);
    for (int k = 0; k < 3; ++k) {
      const LadarScan scan = simulator.Simulate(Room(), Pose2(), Pose2(), kT0 + k * 100'000, k);
      recorded.push_back(EncodeMessage(ToLcm(scan)));
      w.Write("LADAR_SCAN", ToLcm(scan));
      if (k == 1) {
        const uint8_t garbage[5] = {1, 2, 3, 4, 5};
        w.Write("LADAR_SCAN", scan.utime + 1, garbage, 5);
        w.Write("ODOMETRY", ToLcm(OdometryReading{}));  // another channel: not replayed
      }
    }
    w.Close();
  }
  SteppingClock clock(kT0);
  FakeRuntime fake(clock);
  LadarDriverOptions o;
  o.replay = log;
  o.replay_speed = 2.0;
  ScanReplayNode node(fake.runtime(), o);
  const int64_t start = clock.NowUtime();
  EXPECT_EQ(node.Run(), 0);
  const int64_t elapsed = clock.NowUtime() - start;
  EXPECT_GE(elapsed, 100'000) << "0.2 s of log at twice the speed";
  EXPECT_LT(elapsed, 150'000);
  const auto published = fake.bus().PublishedOn("LADAR_SCAN");
  ASSERT_EQ(published.size(), 3u);
  for (size_t k = 0; k < 3; ++k) EXPECT_EQ(published[k].data, recorded[k]) << "unchanged, scan " << k;
  EXPECT_TRUE(fake.bus().PublishedOn("ODOMETRY").empty());
  EXPECT_EQ(node.scans_published(), 3);
  EXPECT_EQ(node.scans_bad(), 1);
}

TEST(LadarDriverOptionsTest, ResolvingChecksTheModelThePoseAndTheModes) {
  LadarDriverOptions o;
  o.model.scan_rate = "4";
  o.sensor_pose = "0.5,0,90deg";
  const LadarSimulationSetup setup = ResolveLadarDriver(o, NodeOptions());
  EXPECT_EQ(setup.schedule.period_us, 250'000);
  EXPECT_NEAR(setup.sensor_offset.theta, kPi / 2, 1e-12);
  o.sensor_pose = "0.5,0";
  EXPECT_THROW(ResolveLadarDriver(o, NodeOptions()), UsageError);
  o.sensor_pose = "0,0,0";
  o.replay = "x.lcm";
  NodeOptions batch;
  batch.log = "in.lcm";
  EXPECT_THROW(ResolveLadarDriver(o, batch), UsageError);
}

TEST(LadarDriverOptionsTest, EveryOptionIsReachableAndTheFlatFlagsSetTheNestedKeys) {
  const auto keys = ExpectEveryOptionReachable<LadarDriverOptions>(
      LadarDriverOptions(), [](ConfigSchema& s, LadarDriverOptions& o) { DeclareOptions(s, o); });
  // model (14, LadarModelOptions), schedule (2), sensor_pose, seed, world, replay,
  // replay_speed and the three channels.
  EXPECT_EQ(keys.size(), 14u + 2u + 5u + 3u);
  LadarDriverOptions o;
  ConfigSchema s("ladar_driver", "test");
  DeclareOptions(s, o);
  const std::vector<FlagAndConfigLine> flags = {
      {"sensor", "model.sensor = cyclone"}, {"points", "model.points = 8192"}, {"sensor-id", "model.sensor_id = x"},
      {"min-range", "model.min_range = 1"}, {"max-range", "model.max_range = 40"},
      {"start-angle", "model.start_angle = -180deg"}, {"angular-resolution", "model.angular_resolution = 0.001"},
      {"range-resolution", "model.range_resolution = 0.01"}, {"range-sigma", "model.range_sigma = 0.05"},
      {"beam-divergence", "model.beam_divergence = 0.002"},
      {"mixed-pixel-probability", "model.mixed_pixel_probability = 0.1"},
      {"mixed-pixel-min-gap", "model.mixed_pixel_min_gap = 0.2"}, {"scan-rate", "model.scan_rate = 2"},
      {"truth-buffer", "schedule.history = 2"}, {"max-truth-gap", "schedule.max_gap = 0.5"}};
  ASSERT_EQ(s.Parse(FlagArgs(flags)), ParseOutcome::kRun);
  ExpectConfigLines(s.ConfigText(), flags);
  EXPECT_EQ(o.schedule.max_gap_us, 500'000);
}

}  // namespace
}  // namespace minenav
