#include "tracker/station_tour.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.h"
#include "common/config_testing.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000;
constexpr int64_t kTick = 100'000;  // 10 Hz

// Ideal unicycle over one tick.
Pose2 Move(const Pose2& p, const DriveCommand& c) {
  const double dt = 1e-6 * static_cast<double>(kTick);
  const double v = c.mode == DriveCommand::Mode::kVelocity ? c.v : 0.0;
  const double w = c.mode == DriveCommand::Mode::kStop ? 0.0 : c.omega;
  const double th = p.theta + 0.5 * w * dt;
  return {p.x + v * dt * std::cos(th), p.y + v * dt * std::sin(th), NormalizeAngle(p.theta + w * dt)};
}

WaypointFollowerOptions Fast() { return {.cruise_speed = 0.5, .turn_rate = 0.5, .command_timeout = 0.3}; }

TEST(StationTourTest, StandsStillUntilThereIsAPose) {
  StationTour tour(Fast(), {Pose2(2, 0, 0)}, 1.0);
  const StationTour::Step step = tour.Update(kT0, std::nullopt);
  EXPECT_EQ(step.command.mode, DriveCommand::Mode::kStop);
  EXPECT_DOUBLE_EQ(step.command.timeout, 0.3);
  EXPECT_FALSE(step.arrived);
  EXPECT_FALSE(tour.Finished(kT0));
}

TEST(StationTourTest, DwellsAtEachStationThenDrivesOnAndFinishesAfterTheLastDwell) {
  const std::vector<Pose2> stations = {Pose2(2, 0, 0), Pose2(2, 2, kPi / 2)};
  StationTour tour(Fast(), stations, 1.0);
  Pose2 pose(0, 0, 0);
  std::vector<int64_t> arrivals;
  int64_t now = kT0;
  for (; now < kT0 + 600 * 1'000'000 && !tour.Finished(now); now += kTick) {
    const StationTour::Step step = tour.Update(now, pose);
    if (step.arrived) {
      arrivals.push_back(now);
      EXPECT_LT(TranslationDistance(pose, stations[arrivals.size() - 1]), 0.15);
    }
    if (!arrivals.empty() && now > arrivals.back() && now < arrivals.back() + 1'000'000) {
      EXPECT_EQ(step.command.mode, DriveCommand::Mode::kStop) << "dwelling at " << now;
      EXPECT_DOUBLE_EQ(step.command.timeout, 0.3);
    }
    pose = Move(pose, step.command);
  }
  ASSERT_EQ(arrivals.size(), 2u);
  EXPECT_EQ(tour.station_count(), 2);
  EXPECT_TRUE(tour.Finished(now));
  EXPECT_EQ(now, arrivals.back() + 1'000'000) << "finished when the last dwell is over";
}

TEST(StationTourTest, EveryFollowerOptionIsDeclared) {
  // WaypointFollowerOptions: cruise_speed, turn_rate, position/heading/align tolerances,
  // steering_gain, command_timeout.
  EXPECT_EQ(ExpectEveryOptionReachable<WaypointFollowerOptions>().size(), 7u);
}

}  // namespace
}  // namespace minenav
