#include "common/pose2.h"

#include <gtest/gtest.h>

#include <random>

namespace minenav {
namespace {

TEST(Pose2Test, ComposeThenInverseIsIdentity) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 100; ++i) {
    const Pose2 a(u(rng), u(rng), u(rng));
    const Pose2 id = a * a.inverse();
    EXPECT_NEAR(id.x, 0, 1e-12);
    EXPECT_NEAR(id.y, 0, 1e-12);
    EXPECT_NEAR(id.theta, 0, 1e-12);
  }
}

TEST(Pose2Test, TransformPointMatchesMatrix) {
  const Pose2 a(1.0, 2.0, kPi / 2);
  const Eigen::Vector2d p = a * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  const Eigen::Vector2d q = a.rotation() * Eigen::Vector2d(3, -1) + a.translation();
  EXPECT_TRUE((a * Eigen::Vector2d(3, -1)).isApprox(q));
}

TEST(Pose2Test, CompositionIsAssociativeOnPoints) {
  const Pose2 a(1, -2, 0.7), b(-3, 0.5, 2.9), c(0.2, 0.1, -1.3);
  const Eigen::Vector2d p(0.3, -4);
  EXPECT_TRUE(((a * b) * c * p).isApprox(a * (b * (c * p))));
  EXPECT_TRUE((Between(a, a * b) * p).isApprox(b * p));
}

TEST(AngleTest, NormalizeWrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(NormalizeAngle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-kPi), kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(2 * kPi + 0.1), 0.1, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-0.1), -0.1, 1e-12);
}

}  // namespace
}  // namespace minenav
