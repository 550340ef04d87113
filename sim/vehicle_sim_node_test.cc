// vehicle_sim's node through the fake bus: the world first, truth and odometry every tick,
// a changed world published at once before that tick's truth, commands aged from when they
// arrive; the scenario from files; the options and the flat flags of before.

#include "sim/vehicle_sim_node.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

std::vector<Segment> Square(double half) {
  return {Segment({-half, -half}, {half, -half}), Segment({half, -half}, {half, half}),
          Segment({half, half}, {-half, half}), Segment({-half, half}, {-half, -half})};
}

// A door opens 0.25 s after the first tick: world b replaces world a.
SimScenario DoorOpens() {
  return MakeSimScenario({{"a", Square(5)}, {"b", Square(4)}}, {250'000}, ScenarioOptions(), Pose2(1, 0, 0));
}

struct Harness {
  explicit Harness(const VehicleSimNodeOptions& o) : node(fake.runtime(), o, DoorOpens()) {}
  // The channels one pass of the loop publishes on, in order.
  std::vector<std::string> SpinChannels() {
    bus->ClearPublished();
    fake.runtime().SpinOnce(0);
    std::vector<std::string> out;
    for (const FakeBus::Message& m : bus->published()) out.push_back(m.channel);
    return out;
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  FakeBus* bus = &fake.bus();
  VehicleSimNode node;
};

VehicleSimNodeOptions TenHertz() {
  VehicleSimNodeOptions o;
  o.sim.rate = 10.0;
  return o;
}

using Channels = std::vector<std::string>;

TEST(VehicleSimNodeTest, TheWorldGoesOutFirstThenTruthAndOdometryEveryTick) {
  Harness h(TenHertz());
  EXPECT_EQ(h.SpinChannels(), (Channels{"SIM_WORLD", "LINE_MAP", "SIM_TRUTH", "ODOMETRY", "CUTTER_STATE"}));
  const auto world = h.bus->Decoded<line_map_t>("SIM_WORLD");
  ASSERT_EQ(world.size(), 1u);
  EXPECT_EQ(world[0].name, "a");
  h.clock.Advance(100'000);
  EXPECT_EQ(h.SpinChannels(), (Channels{"SIM_TRUTH", "ODOMETRY"}));
  const auto truth = h.bus->Decoded<vehicle_truth_t>("SIM_TRUTH");
  const auto odometry = h.bus->Decoded<odometry_t>("ODOMETRY");
  ASSERT_EQ(truth.size(), 1u);
  EXPECT_EQ(truth[0].seq, 1);
  EXPECT_EQ(odometry[0].seq, 1);
  EXPECT_EQ(truth[0].utime, kT0 + 100'000);
  EXPECT_DOUBLE_EQ(truth[0].pose.x, 1.0) << "no command: standing at the start";
}

TEST(VehicleSimNodeTest, AChangedWorldIsPublishedAtOnceBeforeThatTicksTruth) {
  Harness h(TenHertz());
  h.SpinChannels();
  h.clock.Advance(100'000);
  h.SpinChannels();
  h.clock.Advance(100'000);
  h.SpinChannels();  // 0.2 s: still world a
  h.clock.Advance(100'000);
  EXPECT_EQ(h.SpinChannels(), (Channels{"SIM_WORLD", "LINE_MAP", "SIM_TRUTH", "ODOMETRY"}));  // 0.3 s
  const auto world = h.bus->Decoded<line_map_t>("SIM_WORLD");
  ASSERT_EQ(world.size(), 1u);
  EXPECT_EQ(world[0].name, "b");
  EXPECT_NEAR(world[0].segments[0].x1, -4.0, 1e-12);
  const auto map = h.bus->Decoded<line_map_t>("LINE_MAP");
  EXPECT_EQ(map[0].version, 0) << "LINE_MAP stays the first world";
  EXPECT_EQ(map[0].name, "a (surveyed map)");
}

TEST(VehicleSimNodeTest, DrivesUnderACommandAgedFromWhenItArrived) {
  Harness h(TenHertz());
  h.SpinChannels();
  DriveCommand c;
  c.utime = 0;  // a sender's clock far off: the age counts from the arrival
  c.mode = DriveCommand::Mode::kVelocity;
  c.v = 0.05;
  c.timeout = 10.0;
  h.bus->InjectMessage("DRIVE_COMMAND", ToLcm(c));
  h.bus->HandleFor(0);
  for (int k = 0; k < 4; ++k) {
    h.clock.Advance(100'000);
    h.SpinChannels();
  }
  const double moved = h.bus->Decoded<vehicle_truth_t>("SIM_TRUTH").back().pose.x - 1.0;
  EXPECT_GT(moved, 0.0);
  for (int k = 0; k < 20; ++k) {  // 2 s without a fresh command: stale after 0.5 s, stopped
    h.clock.Advance(100'000);
    h.SpinChannels();
  }
  EXPECT_EQ(h.bus->Decoded<vehicle_truth_t>("SIM_TRUTH").back().v, 0.0);
}

TEST(VehicleSimNodeTest, PrepareScenarioReadsTheWorldsAndWritesTheOutputs) {
  testing::TempDir dir("minenav_vehicle_sim_node_test");
  SaveSegmentsJson(dir / "a.json", Square(5));
  SaveSegmentsJson(dir / "b.json", Square(4));
  VehicleSimOptions o;
  o.world = dir / "a.json";  // a config file's line: used when no flag gives a world
  o.world_out = dir / "world_out.json";
  o.map_out = dir / "map_out.json";
  const SimScenario from_config = PrepareScenario(o, {});
  EXPECT_EQ(from_config.name, dir / "a.json");
  EXPECT_EQ(LoadSegmentsJson(dir / "world_out.json").size(), 4u);
  EXPECT_EQ(LoadSegmentsJson(dir / "map_out.json").size(), 4u);
  o.world_change_at = "2";
  const SimScenario from_flags = PrepareScenario(o, {dir / "b.json", dir / "a.json"});
  EXPECT_EQ(from_flags.name, dir / "b.json") << "flags beat the config file";
  ASSERT_EQ(from_flags.changes.size(), 1u);
  EXPECT_EQ(from_flags.changes[0].at_us, 2'000'000);
  EXPECT_THROW(PrepareScenario(o, {dir / "missing.json", dir / "a.json"}), InputError);
  o.vehicle.turn_radius = -1.0;
  EXPECT_THROW(PrepareScenario(o, {}), UsageError);
}

TEST(VehicleSimNodeTest, EveryOptionIsReachableAndTheFlatFlagsSetTheNestedKeys) {
  const auto keys = ExpectEveryOptionReachable<VehicleSimNodeOptions>(
      VehicleSimNodeOptions(), [](ConfigSchema& s, VehicleSimNodeOptions& o) { DeclareOptions(s, o); });
  // VehicleSimOptions (29 + the cutterhead's 9), the seven channels, cutter_state_period.
  EXPECT_EQ(keys.size(), 38u + 7u + 1u);
  VehicleSimNodeOptions o;
  ConfigSchema s("vehicle_sim", "test");
  DeclareOptions(s, o);
  const std::vector<FlagAndConfigLine> flags = {
      {"max-forward-speed", "vehicle.max_forward_speed = 0.3"},
      {"max-reverse-speed", "vehicle.max_reverse_speed = 0.2"}, {"turn-radius", "vehicle.turn_radius = 5"},
      {"max-turn-in-place-rate", "vehicle.max_turn_in_place_rate = 0.1"},
      {"max-acceleration", "vehicle.max_acceleration = 0.2"},
      {"max-deceleration", "vehicle.max_deceleration = 0.3"},
      {"max-yaw-acceleration", "vehicle.max_yaw_acceleration = 0.4"}, {"min-speed", "vehicle.min_speed = 0.01"},
      {"command-timeout", "vehicle.command_timeout = 0.7"},
      {"odometry-scale-error", "odometry.scale_error = 0.02"},
      {"odometry-rotation-scale-error", "odometry.rotation_scale_error = 0.03"},
      {"odometry-heading-drift-per-metre", "odometry.heading_drift_per_metre = 0.004"},
      {"odometry-heading-drift-per-second", "odometry.heading_drift_per_second = 0.001"},
      {"odometry-translation-noise", "odometry.translation_noise = 0.01"},
      {"odometry-rotation-noise", "odometry.rotation_noise = 0.003"}};
  ASSERT_EQ(s.Parse(FlagArgs(flags)), ParseOutcome::kRun);
  ExpectConfigLines(s.ConfigText(), flags);
}


// The cutterhead on the bus: a SUMP without the drum is refused on CUTTER_STATE; with the drum
// turning the miner sumps, and the shear reaching the floor publishes the cut world at once.
TEST(VehicleSimNodeTest, CutterCommandsDriveTheAppendagesAndAShearCutsTheWorld) {
  VehicleSimNodeOptions o = TenHertz();
  o.sim.odometry = {};
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  // The drum's front (5 m ahead of the pose) touches the wall at x = 5.
  VehicleSimNode node(fake.runtime(), o, MakeSimScenario({{"a", Square(5)}}, {}, ScenarioOptions(), Pose2(0, 0, 0)));
  FakeBus& bus = fake.bus();
  auto command = [&](int8_t action) {
    cutter_command_t c{};
    c.utime = clock.NowUtime();
    c.action = action;
    bus.InjectMessage("CUTTER_COMMAND", c);
  };
  auto spin = [&](int ticks, double v) {
    for (int k = 0; k < ticks; ++k) {
      drive_command_t d{};
      d.utime = clock.NowUtime();
      d.mode = drive_command_t::VELOCITY;
      d.v = v;
      d.timeout = 0.5;
      bus.InjectMessage("DRIVE_COMMAND", d);
      clock.Advance(100'000);
      fake.runtime().SpinOnce(0);
    }
  };
  fake.runtime().SpinOnce(0);
  command(cutter_command_t::SUMP);
  spin(1, 0.0);
  EXPECT_EQ(bus.Decoded<cutter_state_t>("CUTTER_STATE").back().message, "refused SUMP: the drum is not turning");
  spin(20, 0.05);  // the drum touches the wall: it may not be driven into it
  EXPECT_EQ(bus.Decoded<cutter_state_t>("CUTTER_STATE").back().message,
            "refused DRIVE: no sump without the drum turning (the drum touches the face)");
  EXPECT_NEAR(bus.Decoded<vehicle_truth_t>("SIM_TRUTH").back().pose.x, 0.0, 1e-9);
  command(cutter_command_t::DRUM_ON);
  spin(1, 0.0);
  command(cutter_command_t::SUMP);
  spin(1, 0.0);
  EXPECT_EQ(bus.Decoded<cutter_state_t>("CUTTER_STATE").back().phase, cutter_state_t::SUMPING);
  spin(60, 0.05);
  spin(10, 0.0);
  const double x = bus.Decoded<vehicle_truth_t>("SIM_TRUTH").back().pose.x;
  EXPECT_GT(x, 0.2);
  command(cutter_command_t::SHEAR);
  const size_t worlds = bus.Decoded<line_map_t>("SIM_WORLD").size();
  spin(115, 0.0);  // 11.5 s of the 12 s shear
  EXPECT_EQ(bus.Decoded<line_map_t>("SIM_WORLD").size(), worlds + 11);  // the periodic ones only
  spin(10, 0.0);
  const cutter_state_t state = bus.Decoded<cutter_state_t>("CUTTER_STATE").back();
  EXPECT_EQ(state.phase, cutter_state_t::CLEANING);
  EXPECT_DOUBLE_EQ(state.boom_height, 0.0);
  EXPECT_NEAR(state.sumped_depth, x, 1e-9);
  EXPECT_NEAR(state.coal_removed, 3.3 * x, 0.03);
  const std::vector<Segment> cut = SegmentsFromLcm(bus.Decoded<line_map_t>("SIM_WORLD").back());
  const auto hit = CastRay(Eigen::Vector2d(0, 0), 0.0, cut, 100.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range, 5.0 + x, 1e-9);
  EXPECT_GT(bus.Decoded<line_map_t>("SIM_WORLD").back().version, bus.Decoded<line_map_t>("SIM_WORLD").front().version);
}

}  // namespace
}  // namespace minenav
