// vehicle_sim's simulation without the bus: its options, the world flags, the change
// times, the scenario, the world over time and the vehicle stepped over clock time.

#include "sim/vehicle_sim.h"

#include <gtest/gtest.h>

#include "common/angle.h"
#include "common/config_testing.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000;

std::vector<Segment> Square(double half) {
  return {Segment({-half, -half}, {half, -half}), Segment({half, -half}, {half, half}),
          Segment({half, half}, {-half, half}), Segment({-half, half}, {-half, -half})};
}

std::string UsageMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(VehicleSimOptionsTest, EveryFieldIsDeclaredAndReachable) {
  // SkidSteerOptions: speeds (2), turn radius, turn-in-place rate, accelerations (3),
  // min_speed, command_timeout.
  EXPECT_EQ(ExpectEveryOptionReachable<SkidSteerOptions>().size(), 9u);
  // OdometryErrorOptions: two scale errors, two drifts, two noises.
  EXPECT_EQ(ExpectEveryOptionReachable<OdometryErrorOptions>().size(), 6u);
  // VehicleSimOptions: 14 of its own (world, change times, line_map, the generator's 6,
  // the two outputs, start_pose, rate, map_period) and vehicle (9) and odometry (6) and cutterhead (9) nested.
  EXPECT_EQ(ExpectEveryOptionReachable<VehicleSimOptions>().size(), 14u + 9u + 6u + 9u);
}

TEST(VehicleSimOptionsTest, WorldFlagsAreTakenOutInOrder) {
  std::vector<std::string> args = {"--world", "a.json", "--rate", "5", "--world=b.json", "--seed", "2"};
  EXPECT_EQ(TakeWorldFlags(&args), (std::vector<std::string>{"a.json", "b.json"}));
  EXPECT_EQ(args, (std::vector<std::string>{"--rate", "5", "--seed", "2"}));
  std::vector<std::string> dangling = {"--world"};
  EXPECT_EQ(UsageMessage([&] { TakeWorldFlags(&dangling); }), "--world needs a file");
}

TEST(VehicleSimOptionsTest, ChangeTimesOnePerExtraWorldPositiveAndIncreasing) {
  EXPECT_EQ(ParseWorldChangeTimes("2,3.5", 3), (std::vector<int64_t>{2'000'000, 3'500'000}));
  EXPECT_TRUE(ParseWorldChangeTimes("", 1).empty());
  EXPECT_NE(UsageMessage([] { ParseWorldChangeTimes("2", 1); }).find("needs more than one --world"),
            std::string::npos);
  EXPECT_NE(UsageMessage([] { ParseWorldChangeTimes("", 2); }).find("need --world-change-at with 1 time"),
            std::string::npos);
  EXPECT_NE(UsageMessage([] { ParseWorldChangeTimes("1,2", 2); }).find("has 2 time(s), expected 1"),
            std::string::npos);
  EXPECT_NE(UsageMessage([] { ParseWorldChangeTimes("3,2", 3); }).find("times must increase"), std::string::npos);
  EXPECT_NE(UsageMessage([] { ParseWorldChangeTimes("0", 2); }).find("times must be in (0, 1e7] s"),
            std::string::npos);
}

TEST(VehicleSimScenarioTest, WorldsFromFilesOrTheGeneratorAndTheStartPose) {
  const SimScenario files =
      MakeSimScenario({{"a.json", Square(5)}, {"b.json", Square(4)}}, {2'000'000}, ScenarioOptions(), std::nullopt);
  EXPECT_EQ(files.name, "a.json");
  EXPECT_EQ(files.world.size(), 4u);
  EXPECT_EQ(files.map.size(), 4u);
  ASSERT_EQ(files.changes.size(), 1u);
  EXPECT_EQ(files.changes[0].at_us, 2'000'000);
  EXPECT_EQ(files.changes[0].name, "b.json");
  EXPECT_EQ(TranslationDistance(files.start, Pose2()), 0.0);
  EXPECT_THROW(MakeSimScenario({{"empty.json", {}}}, {}, ScenarioOptions(), std::nullopt), InputError);

  VehicleSimOptions o;
  o.seed = 3;
  const SimScenario mine = MakeSimScenario({}, {}, GeneratorOptions(o), StartPose(o));
  const GeneratedScenario expected = GenerateScenario(GeneratorOptions(o));
  EXPECT_EQ(mine.world.size(), expected.world.size());
  EXPECT_EQ(mine.name, "mine seed 3");
  EXPECT_EQ(TranslationDistance(mine.start, expected.stations.front().pose), 0.0) << "auto: the first station";
  o.start_pose = "3,3,90deg";
  EXPECT_NEAR(StartPose(o)->theta, kPi / 2, 1e-12);
  o.generate = "research";
  o.pillar_rows = 2;
  EXPECT_EQ(GeneratorOptions(o).research.pillar_rows, 2) << "the pillar counts serve research too";
}

TEST(WorldTimelineTest, ChangesApplyAtTheirTimeSinceTheFirstTick) {
  SimScenario sc = MakeSimScenario({{"a", Square(5)}, {"b", Square(4)}, {"c", Square(3)}}, {2'000'000, 3'000'000},
                                   ScenarioOptions(), std::nullopt);
  WorldTimeline first(sc, /*line_map_each=*/false);
  EXPECT_FALSE(first.Advance(kT0));
  EXPECT_FALSE(first.Advance(kT0 + 1'999'999));
  EXPECT_EQ(first.name(), "a");
  EXPECT_TRUE(first.Advance(kT0 + 2'000'000));
  EXPECT_EQ(first.name(), "b");
  EXPECT_DOUBLE_EQ(first.SecondsSinceStart(kT0 + 2'000'000), 2.0);
  EXPECT_NEAR(first.World().segments[0].a.x(), -4.0, 1e-12);
  EXPECT_EQ(first.LineMap().version, 0) << "LINE_MAP stays the surveyed first world";
  EXPECT_EQ(first.LineMap().name, "a (surveyed map)");
  EXPECT_NEAR(first.LineMap().segments[0].a.x(), -5.0, 1e-12);

  WorldTimeline each(sc, /*line_map_each=*/true);
  each.Advance(kT0);
  const uint64_t version = each.version();
  EXPECT_TRUE(each.Advance(kT0 + 5'000'000)) << "both changes at once";
  EXPECT_EQ(each.name(), "c");
  EXPECT_EQ(each.version(), version + 2);
  EXPECT_EQ(each.World().version, static_cast<int64_t>(each.version()));
  EXPECT_EQ(each.LineMap().version, 2);
  EXPECT_EQ(each.LineMap().name, "c");
}

TEST(SimulatedVehicleTest, DrivesUnderAFreshCommandAndStopsWhenItGoesStale) {
  VehicleSimOptions o;
  o.vehicle.max_acceleration = 0.0;
  o.vehicle.max_deceleration = 0.0;
  o.odometry = OdometryErrorOptions();  // exact odometry
  SimulatedVehicle vehicle(o, Pose2(1, 2, 0));
  SimulatedVehicle::Tick t = vehicle.Step(kT0, std::nullopt);
  EXPECT_TRUE(t.stale);
  EXPECT_FALSE(t.stale_changed);
  EXPECT_EQ(t.truth.seq, 0);
  EXPECT_EQ(t.odometry.seq, 0);
  EXPECT_EQ(t.truth.utime, kT0);
  DriveCommand forward;
  forward.utime = kT0;
  forward.mode = DriveCommand::Mode::kVelocity;
  forward.v = 0.05;
  forward.timeout = 10.0;
  t = vehicle.Step(kT0 + 100'000, forward);
  EXPECT_FALSE(t.stale);
  EXPECT_TRUE(t.stale_changed);
  EXPECT_NEAR(t.truth.pose.x, 1.0 + 0.005, 1e-9);
  EXPECT_NEAR(t.odometry.pose.x, t.truth.pose.x, 1e-12);
  EXPECT_EQ(t.truth.seq, 1);
  t = vehicle.Step(kT0 + 400'000, forward);  // 0.4 s old: still fresh
  EXPECT_NEAR(t.truth.pose.x, 1.005 + 0.015, 1e-9);
  t = vehicle.Step(kT0 + 1'400'000, forward);  // older than command_timeout (0.5 s): stale
  EXPECT_TRUE(t.stale);
  EXPECT_TRUE(t.stale_changed);
  EXPECT_NEAR(t.truth.pose.x, 1.02, 1e-9);
  forward.utime = kT0 + 2'900'000;
  t = vehicle.Step(kT0 + 3'000'000, forward);  // 1.6 s since the last tick, capped at 1 s
  EXPECT_NEAR(t.truth.pose.x, 1.02 + 0.05, 1e-9);
}

}  // namespace
}  // namespace minenav
