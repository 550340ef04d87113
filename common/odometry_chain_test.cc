#include "common/odometry_chain.h"

#include <gtest/gtest.h>

#include <cmath>

namespace minenav {
namespace {

TEST(OdometryChainTest, WithoutAnAnchorTheOdometryIsTheGuess) {
  OdometryChain chain;
  const Pose2 odo(1.0, 2.0, 0.3);
  EXPECT_FALSE(chain.anchored());
  EXPECT_NEAR(chain.Predict(odo).x, 1.0, 1e-12);
  EXPECT_NEAR(chain.Predict(odo).theta, 0.3, 1e-12);
}

// The motion measured by odometry since the anchor, applied in the estimate's frame: with
// odometry rotated 90 degrees from the map, a 1 m forward move in odometry is a 1 m
// forward move of the estimate, whatever direction that is in either frame.
TEST(OdometryChainTest, MovesTheAnchorByTheOdometryIncrementInTheVehicleFrame) {
  OdometryChain chain;
  chain.Trust(Pose2(10.0, 5.0, M_PI / 2), Pose2(0.0, 0.0, 0.0));
  const Pose2 guess = chain.Predict(Pose2(1.0, 0.0, 0.1));  // 1 m forward, turned 0.1 rad
  EXPECT_NEAR(guess.x, 10.0, 1e-12);
  EXPECT_NEAR(guess.y, 6.0, 1e-12);
  EXPECT_NEAR(guess.theta, M_PI / 2 + 0.1, 1e-12);
  // Brute force: estimate * odometry_anchor^-1 * odometry_now, composed by hand.
  const Pose2 a(10.0, 5.0, M_PI / 2), o0(3.0, -1.0, 0.7), o1(4.0, 0.5, 1.1);
  chain.Trust(a, o0);
  const Pose2 g = chain.Predict(o1);
  const double dx = o1.x - o0.x, dy = o1.y - o0.y;
  const double lx = std::cos(o0.theta) * dx + std::sin(o0.theta) * dy;
  const double ly = -std::sin(o0.theta) * dx + std::cos(o0.theta) * dy;
  EXPECT_NEAR(g.x, a.x + std::cos(a.theta) * lx - std::sin(a.theta) * ly, 1e-12);
  EXPECT_NEAR(g.y, a.y + std::sin(a.theta) * lx + std::cos(a.theta) * ly, 1e-12);
  EXPECT_NEAR(g.theta, a.theta + (o1.theta - o0.theta), 1e-12);
  chain.Reset();
  EXPECT_FALSE(chain.anchored());
}

}  // namespace
}  // namespace minenav
