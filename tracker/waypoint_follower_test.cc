#include "tracker/waypoint_follower.h"

#include <gtest/gtest.h>

#include <cmath>

namespace minenav {
namespace {

// Ideal unicycle integration, exact for constant (v, omega) over dt.
Pose2 Integrate(const Pose2& p, const DriveCommand& c, double dt) {
  double v = c.v, w = c.omega;
  if (c.mode == DriveCommand::Mode::kStop) v = w = 0;
  if (c.mode == DriveCommand::Mode::kTurnInPlace) v = 0;
  if (std::abs(w) < 1e-12) return {p.x + v * dt * std::cos(p.theta), p.y + v * dt * std::sin(p.theta), p.theta};
  const double r = v / w, th = p.theta + w * dt;
  return {p.x + r * (std::sin(th) - std::sin(p.theta)), p.y - r * (std::cos(th) - std::cos(p.theta)),
          NormalizeAngle(th)};
}

TEST(WaypointFollowerTest, ReachesEveryStationWithinTolerance) {
  WaypointFollowerOptions o;
  o.cruise_speed = 0.5;
  o.turn_rate = 0.5;
  const std::vector<Waypoint> wps = {{{5, 0, kPi / 2}, true}, {{5, 5, kPi}, true}, {{0, 5, -kPi / 2}, true}};
  WaypointFollower f(o, wps);
  Pose2 pose(0, 0, 0.3);
  std::vector<Pose2> arrivals;
  for (int step = 0; step < 20000 && !f.Done(); ++step) {
    const DriveCommand c = f.Update(pose);
    if (f.JustArrived()) arrivals.push_back(pose);
    pose = Integrate(pose, c, 0.05);
  }
  ASSERT_TRUE(f.Done());
  ASSERT_EQ(arrivals.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_LT(TranslationDistance(arrivals[i], wps[i].pose), o.position_tolerance + 0.03) << i;
    EXPECT_LT(HeadingDistance(arrivals[i], wps[i].pose), o.heading_tolerance + 0.03) << i;
  }
}

TEST(WaypointFollowerTest, TurnsInPlaceWhenFacingAway) {
  WaypointFollower f({}, {{{-3, 0, 0}, true}});
  const DriveCommand c = f.Update(Pose2(0, 0, 0));
  EXPECT_EQ(c.mode, DriveCommand::Mode::kTurnInPlace);
  EXPECT_GT(std::abs(c.omega), 0.0);
}

TEST(WaypointFollowerTest, EmptyListIsDoneAndStops) {
  WaypointFollower f({}, {});
  EXPECT_TRUE(f.Done());
  EXPECT_EQ(f.Update(Pose2()).mode, DriveCommand::Mode::kStop);
}

}  // namespace
}  // namespace minenav
