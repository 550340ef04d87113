// waypoint_driver's node through the fake bus: one DRIVE_COMMAND per tick stamped with the
// clock, standing still without a pose, the dwell at a station, the stop after the last
// one; its options and the flat flags of before.

#include "tracker/waypoint_driver_node.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

struct Harness {
  Harness(const WaypointDriverOptions& o, const std::vector<Station>& stations)
      : node(fake.runtime(), o, stations) {}
  // Advances the clock by one control period and runs the loop once.
  void Tick(int64_t dt_us = 100'000) {
    clock.Advance(dt_us);
    runtime->SpinOnce(0);
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  WaypointDriverNode node;
};

odometry_t OdometryAt(const Pose2& pose) {
  OdometryReading o;
  o.utime = kT0;
  o.pose = pose;
  return ToLcm(o);
}

TEST(WaypointDriverNodeTest, StandsStillWithoutAPoseWithCommandsValidForThreePeriods) {
  WaypointDriverOptions o = WaypointDriverDefaults({"--rate", "20"});
  o.rate = 20.0;
  o.stations = "test";
  Harness h(o, {Station{Pose2(5, 0, 0)}});
  h.runtime->SpinOnce(0);  // the first tick, at once
  h.Tick(50'000);
  const auto commands = h.bus->Decoded<drive_command_t>("DRIVE_COMMAND");
  ASSERT_EQ(commands.size(), 2u);
  for (size_t k = 0; k < commands.size(); ++k) {
    EXPECT_EQ(commands[k].seq, static_cast<int64_t>(k));
    EXPECT_EQ(commands[k].utime, kT0 + static_cast<int64_t>(k) * 50'000);
    EXPECT_EQ(commands[k].mode, drive_command_t::STOP);
    EXPECT_FLOAT_EQ(static_cast<float>(commands[k].timeout), 0.15f);
  }
  EXPECT_FALSE(h.runtime->StopRequested());
}

TEST(WaypointDriverNodeTest, DwellsAtTheLastStationThenStopsTheProcess) {
  WaypointDriverOptions o;
  o.stations = "test";
  o.dwell = 0.5;
  Harness h(o, {Station{Pose2(2, 0, 0)}});
  h.bus->InjectMessage("ODOMETRY", OdometryAt(Pose2(2, 0, 0)));  // already there
  h.runtime->SpinOnce(0);  // tick without a pose, then the odometry arrives
  h.Tick();                // arrives: the dwell starts
  EXPECT_FALSE(h.runtime->StopRequested());
  for (int k = 0; k < 4; ++k) {
    h.Tick();
    EXPECT_FALSE(h.runtime->StopRequested()) << "still dwelling at tick " << k;
  }
  h.Tick();  // 0.5 s after the arrival
  EXPECT_TRUE(h.runtime->StopRequested());
  for (const drive_command_t& c : h.bus->Decoded<drive_command_t>("DRIVE_COMMAND"))
    EXPECT_EQ(c.mode, drive_command_t::STOP);
}

TEST(WaypointDriverNodeTest, SteersByOdometryNeverByTheTruth) {
  WaypointDriverOptions o;
  o.stations = "test";
  Harness h(o, {Station{Pose2(5, 0, 0)}});
  TruthReading truth;
  truth.utime = kT0;
  h.bus->InjectMessage("SIM_TRUTH", ToLcm(truth));  // not subscribed
  h.runtime->SpinOnce(0);
  h.Tick();
  EXPECT_EQ(h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").back().mode, drive_command_t::STOP);
  OdometryReading odometry;
  odometry.utime = kT0;
  h.bus->InjectMessage("ODOMETRY", ToLcm(odometry));
  h.runtime->SpinOnce(0);
  h.Tick();
  const drive_command_t last = h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").back();
  EXPECT_EQ(last.mode, drive_command_t::VELOCITY) << "facing the station: drives";
  EXPECT_GT(last.v, 0.0);
}

TEST(WaypointDriverNodeTest, NeedsStations) {
  EXPECT_THROW(LoadDriverStations(WaypointDriverOptions()), UsageError);
}

TEST(WaypointDriverNodeTest, EveryOptionIsReachableAndTheFlatFlagsSetTheFollower) {
  const auto keys = ExpectEveryOptionReachable<WaypointDriverOptions>(
      WaypointDriverOptions(), [](ConfigSchema& s, WaypointDriverOptions& o) { DeclareOptions(s, o); });
  // stations, the two channels, rate, dwell, exit_when_done, and the follower's 7
  // (WaypointFollowerOptions).
  EXPECT_EQ(keys.size(), 6u + 7u);
  for (const std::string& k : keys) EXPECT_EQ(k.find("truth"), std::string::npos) << k;
  WaypointDriverOptions o;
  ConfigSchema s("waypoint_driver", "test");
  DeclareOptions(s, o);
  const std::vector<FlagAndConfigLine> flags = {
      {"cruise-speed", "follower.cruise_speed = 0.3"}, {"turn-rate", "follower.turn_rate = 0.2"},
      {"position-tolerance", "follower.position_tolerance = 0.2"},
      {"heading-tolerance", "follower.heading_tolerance = 0.1"},
      {"align-tolerance", "follower.align_tolerance = 0.3"}};
  ASSERT_EQ(s.Parse(FlagArgs(flags)), ParseOutcome::kRun);
  ExpectConfigLines(s.ConfigText(), flags);
  EXPECT_DOUBLE_EQ(WaypointDriverDefaults({}).follower.command_timeout, 0.3);  // 3 periods of 10 Hz
  EXPECT_DOUBLE_EQ(WaypointDriverDefaults({"--rate=5"}).follower.command_timeout, 0.6);
}

}  // namespace
}  // namespace minenav
