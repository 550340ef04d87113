#include "pose_estimator/feature/feature_minimization.h"

#include <gtest/gtest.h>

#include <random>

namespace minenav {
namespace {

Feature Corner(double x, double y, int points = 100) {
  Feature f = MakeCorner({x, y}, {1, 0}, {0, 1}, false);
  f.num_points = points;
  return f;
}

Feature Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int points = 200) {
  Feature f = MakeLine(a, b);
  f.num_points = points;
  return f;
}

// Sensed features = map features seen from `truth` (exactly).
std::vector<Correspondence> Observe(const std::vector<Feature>& map, const Pose2& truth) {
  std::vector<Correspondence> out;
  for (const Feature& m : map) out.push_back({TransformFeature(m, truth), m});
  return out;
}

TEST(FeatureMinimization, JacobiansMatchNumericalDerivatives) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-5, 5), ua(-kPi, kPi);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 pose(u(rng), u(rng), ua(rng));
    Feature corner = Corner(u(rng), u(rng));
    Feature line;
    line.type = FeatureType::kLine;
    line.distance = u(rng);  // any sign: the derivative does not care
    line.orientation = ua(rng);
    const Feature sensed_corner = Corner(u(rng), u(rng));
    Feature sensed_line = line;
    sensed_line.distance = std::abs(u(rng));
    sensed_line.orientation = ua(rng);
    for (const auto& [s, m] : {std::pair{sensed_corner, corner}, std::pair{sensed_line, line}}) {
      const FeatureResidual r = ComputeResidual(s, m, pose);
      for (int k = 0; k < 3; ++k) {
        const double h = 1e-6;
        Eigen::Vector3d dp = Eigen::Vector3d::Zero();
        dp(k) = h;
        const Pose2 plus(pose.x + dp.x(), pose.y + dp.y(), pose.theta + dp.z());
        const Pose2 minus(pose.x - dp.x(), pose.y - dp.y(), pose.theta - dp.z());
        Eigen::Vector2d diff = ComputeResidual(s, m, plus).f - ComputeResidual(s, m, minus).f;
        diff.y() = s.type == FeatureType::kLine ? NormalizeAngle(diff.y()) : diff.y();
        const Eigen::Vector2d numeric = diff / (2 * h);
        EXPECT_NEAR((numeric - r.jacobian.col(k)).norm(), 0.0, 1e-6) << "trial " << trial << " column " << k;
      }
    }
  }
}

// The thesis' EQ 6 for a line, r_p = r' - x cos(theta) - y sin(theta), is an OCR/print
// error: the perpendicular distance of a map line seen from the pose must use the line's
// own orientation. Check the form used against geometry.
TEST(FeatureMinimization, LineTransformMatchesGeometry) {
  const Eigen::Vector2d a(2, 7), b(9, 4);
  const Feature world = MakeLine(a, b);
  const Pose2 pose(1.5, -2, 0.8);
  const Feature seen = TransformFeature(world, pose);
  const Feature direct = MakeLine(pose.inverse() * a, pose.inverse() * b);
  EXPECT_NEAR(seen.distance, direct.distance, 1e-12);
  EXPECT_NEAR(NormalizeAngle(seen.orientation - direct.orientation), 0.0, 1e-12);
}

TEST(FeatureMinimization, RecoversThePoseFromCornersAndLines) {
  const std::vector<Feature> map = {Corner(0, 0), Corner(10, 0), Corner(10, 6),
                                    Line({0, 0}, {10, 0}), Line({10, 0}, {10, 6}),
                                    Line({10, 6}, {0, 6})};
  const Pose2 truth(4, 2.5, 0.6);
  const auto pairs = Observe(map, truth);
  const MinimizationResult r = MinimizeFeatureError(pairs, Pose2(4.8, 1.9, 0.2));
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.pose.x, truth.x, 1e-6);
  EXPECT_NEAR(r.pose.y, truth.y, 1e-6);
  EXPECT_NEAR(r.pose.theta, truth.theta, 1e-6);
  EXPECT_LT(r.iterations, 15);
  // A confident covariance: a few millimetres.
  EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.02);
  EXPECT_LT(std::sqrt(r.covariance(2, 2)), 0.01);
}

TEST(FeatureMinimization, DropsAMismatchedCorrespondence) {
  std::vector<Feature> map = {Corner(0, 0), Corner(10, 0), Corner(10, 6), Corner(0, 6),
                              Line({0, 0}, {10, 0}), Line({10, 0}, {10, 6})};
  const Pose2 truth(4, 2.5, 0.1);
  auto pairs = Observe(map, truth);
  pairs[3].sensed.position += Eigen::Vector2d(1.0, 0.5);  // a clutter corner
  const MinimizationResult r = MinimizeFeatureError(pairs, Pose2(4.3, 2.2, 0.05));
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_EQ(r.used, 5);
  EXPECT_LT(TranslationDistance(r.pose, truth), 1e-6);
}

TEST(FeatureMinimization, ParallelWallsLeaveTheirDirectionUnobservable) {
  // A corridor along x: two walls y = 0 and y = 4; nothing fixes x.
  const std::vector<Feature> map = {Line({-20, 0}, {20, 0}), Line({20, 4}, {-20, 4})};
  const Pose2 truth(3, 1.5, 0.2);
  const MinimizationResult r = MinimizeFeatureError(Observe(map, truth), Pose2(3.4, 1.2, 0.1));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("unobservable"), std::string::npos) << r.reason;
  EXPECT_GE(r.covariance(0, 0), 1e5);  // along the corridor: unknown
  EXPECT_LT(r.covariance(1, 1), 0.01);  // across it and the heading: known
  EXPECT_LT(r.covariance(2, 2), 0.01);
  EXPECT_NEAR(r.pose.y, truth.y, 1e-6);
  EXPECT_NEAR(r.pose.theta, truth.theta, 1e-6);
  EXPECT_NEAR(r.pose.x, 3.4, 1e-6);  // untouched, not invented
}

TEST(FeatureMinimization, ASingleCornerDoesNotFixTheHeading) {
  const MinimizationResult r = MinimizeFeatureError(Observe({Corner(5, 5)}, Pose2(1, 1, 0.3)), Pose2(1.2, 0.9, 0.3));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("unobservable"), std::string::npos);
}

TEST(FeatureMinimization, NoCorrespondencesIsNotConverged) {
  const MinimizationResult r = MinimizeFeatureError({}, Pose2(1, 2, 3));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.pose.x, 1.0);
}

TEST(FeatureMinimization, WeightsFollowThePointsBehindAFeature) {
  MinimizationOptions o;
  Feature few = Line({1, -2}, {1, 2}, 5), many = Line({1, -2}, {1, 2}, 20);
  const Eigen::Matrix2d wf = FeatureInformation(few, o), wm = FeatureInformation(many, o);
  // Above the variance floors, information grows with the points.
  EXPECT_NEAR(wm(0, 0) / wf(0, 0), 4.0, 1e-9);
  EXPECT_NEAR(wm(1, 1) / wf(1, 1), 4.0, 1e-9);
}

}  // namespace
}  // namespace minenav
