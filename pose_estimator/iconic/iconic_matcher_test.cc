#include "pose_estimator/iconic/iconic_matcher.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <limits>
#include <random>

#include "common/angle.h"
#include "pose_estimator/iconic/iconic_test_world.h"
#include "pose_estimator/iconic/segment_map.h"

namespace minenav {
namespace {

using testing::ExactScan;
using testing::RoomWorld;

std::unique_ptr<CorrespondenceSearch> Map(const std::vector<Segment>& world,
                                          CorrespondenceMethod method = CorrespondenceMethod::kLookupTable) {
  CorrespondenceOptions o;
  o.method = method;
  o.cell_size = 0.25;
  o.max_distance = 3.0;
  return MakeCorrespondenceSearch(world, o);
}

TEST(IconicMatcherTest, ExactScanConvergesToTruthWithEveryMethod) {
  const Pose2 truth(4.0, 8.5, DegToRad(30));
  const LadarScan scan = ExactScan(RoomWorld(), truth);
  for (auto method : {CorrespondenceMethod::kBruteForce, CorrespondenceMethod::kGridSearch,
                      CorrespondenceMethod::kLookupTable}) {
    const auto map = Map(RoomWorld(), method);
    IconicMatchOptions o;
    o.min_threshold = 0.05;
    const IconicMatchResult r = MatchScanToMap(scan, *map, Pose2(4.5, 8.1, DegToRad(35)), o);
    ASSERT_TRUE(r.converged) << map->name() << ": " << r.status;
    EXPECT_EQ(r.status, "ok");
    EXPECT_LT(TranslationDistance(r.pose, truth), 1e-5) << map->name();
    EXPECT_LT(HeadingDistance(r.pose, truth), 1e-6) << map->name();
    EXPECT_LT(r.residual, 1e-4);
    EXPECT_EQ(r.num_points, 720);
    EXPECT_GT(r.num_inliers, 700);
    EXPECT_DOUBLE_EQ(r.final_threshold, 0.05);  // shrank to the floor (3.1.2)
    EXPECT_GT(r.iterations, 1);
  }
}

TEST(IconicMatcherTest, NoisyScanIsAccurateAndCovarianceIsHonest) {
  const auto map = Map(RoomWorld());
  IconicMatchOptions o;
  o.min_threshold = 0.15;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int within_3_sigma = 0;
  const int trials = 20;
  for (int k = 0; k < trials; ++k) {
    // Anywhere in the open part of the room, above the pillar.
    const Pose2 truth(8.5 + 6.0 * u(rng), 9.0 + 1.5 * u(rng), 3.0 * u(rng));
    const LadarScan scan = ExactScan(RoomWorld(), truth, 1024, 0.03, 100 + k);
    const Pose2 initial(truth.x + 0.5 * u(rng), truth.y + 0.5 * u(rng), truth.theta + DegToRad(5) * u(rng));
    const IconicMatchResult r = MatchScanToMap(scan, *map, initial, o);
    ASSERT_TRUE(r.converged) << r.status;
    EXPECT_LT(TranslationDistance(r.pose, truth), 0.01);
    EXPECT_LT(HeadingDistance(r.pose, truth), DegToRad(0.1));
    EXPECT_NEAR(r.residual, 0.03, 0.01);
    // Covariance: symmetric positive definite, and the error mostly within 3 sigma.
    EXPECT_LT((r.covariance - r.covariance.transpose()).norm(), 1e-12);
    EXPECT_GT(r.covariance.determinant(), 0.0);
    const Eigen::Vector3d e(r.pose.x - truth.x, r.pose.y - truth.y, NormalizeAngle(r.pose.theta - truth.theta));
    if (e.dot(r.covariance.inverse() * e) < 14.2) ++within_3_sigma;  // chi2(3) at 99.7 %
  }
  EXPECT_GE(within_3_sigma, trials - 2);
}

TEST(IconicMatcherTest, RobustLossIgnoresClutter) {
  const Pose2 truth(10.0, 6.0, 0.2);
  // Clutter the map does not hold: a crate and a person-sized post near the vehicle.
  std::vector<Segment> world = RoomWorld();
  const std::vector<Segment> clutter = {{11, 7.5, 12.5, 7.5}, {12.5, 7.5, 12.5, 8.2}, {9, 4.6, 9.3, 4.6}};
  world.insert(world.end(), clutter.begin(), clutter.end());
  const LadarScan scan = ExactScan(world, truth, 1024, 0.02, 9);
  const auto map = Map(RoomWorld());
  for (RobustLoss loss : {RobustLoss::kHuber, RobustLoss::kCauchy}) {
    IconicMatchOptions o;
    o.loss = loss;
    o.loss_scale = 0.05;
    o.min_threshold = 0.1;
    const IconicMatchResult r = MatchScanToMap(scan, *map, Pose2(10.4, 5.7, 0.25), o);
    ASSERT_TRUE(r.converged) << ToString(loss) << ": " << r.status;
    EXPECT_LT(TranslationDistance(r.pose, truth), 0.01) << ToString(loss);
    EXPECT_LT(HeadingDistance(r.pose, truth), DegToRad(0.1)) << ToString(loss);
  }
  RobustLoss parsed;
  EXPECT_TRUE(ParseRobustLoss("cauchy", &parsed));
  EXPECT_FALSE(ParseRobustLoss("tukey", &parsed));
  EXPECT_DOUBLE_EQ(RobustWeight(RobustLoss::kHuber, 0.2, 0.1), 0.5);
  EXPECT_DOUBLE_EQ(RobustWeight(RobustLoss::kCauchy, 0.1, 0.1), 0.5);
}

TEST(IconicMatcherTest, BadInputGivesAReasonNotACrash) {
  const auto map = Map(RoomWorld());
  const IconicMatchOptions o;
  const Pose2 pose(5, 5, 0);

  LadarScan empty = ExactScan(RoomWorld(), pose, 8);
  empty.ranges.clear();
  IconicMatchResult r = MatchScanToMap(empty, *map, pose, o);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("no valid reading"), std::string::npos) << r.status;

  LadarScan nan = ExactScan(RoomWorld(), pose, 360);
  for (float& x : nan.ranges) x = std::numeric_limits<float>::quiet_NaN();
  r = MatchScanToMap(nan, *map, pose, o);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("no valid reading"), std::string::npos) << r.status;

  LadarScan far = ExactScan(RoomWorld(), pose, 360);
  for (float& x : far.ranges) x = 500.0f;  // beyond max_range
  EXPECT_FALSE(MatchScanToMap(far, *map, pose, o).converged);

  LadarScan malformed = ExactScan(RoomWorld(), pose, 360);
  malformed.max_range = -1.0;
  r = MatchScanToMap(malformed, *map, pose, o);
  EXPECT_NE(r.status.find("bad scan"), std::string::npos) << r.status;

  // A scan that matches nothing: taken 100 m away from the mapped room.
  const std::vector<Segment> elsewhere = {{100, 100, 110, 100}, {110, 100, 110, 110}, {110, 110, 100, 100}};
  const LadarScan lost = ExactScan(elsewhere, Pose2(105, 102, 0), 360);
  r = MatchScanToMap(lost, *map, Pose2(105, 102, 0), o);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("points within"), std::string::npos) << r.status;

  // A map of only zero-length and duplicate segments never reaches the matcher.
  const SegmentMap bad_map = PrepareSegmentMap({{1, 1, 1, 1}, {1, 1, 1, 1}});
  EXPECT_FALSE(bad_map.problem.empty());
  const auto empty_map = MakeCorrespondenceSearch(bad_map.segments, {});
  r = MatchScanToMap(ExactScan(RoomWorld(), pose, 360), *empty_map, pose, o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, "map has no segments");

  IconicMatchOptions bad = o;
  bad.min_threshold = 5.0;
  r = MatchScanToMap(ExactScan(RoomWorld(), pose, 360), *map, pose, bad);
  EXPECT_NE(r.status.find("bad options"), std::string::npos) << r.status;

  r = MatchScanToMap(ExactScan(RoomWorld(), pose, 360), *map, Pose2(std::nan(""), 0, 0), o);
  EXPECT_EQ(r.status, "initial pose is not finite");
}

TEST(IconicMatcherTest, CorridorWithoutEndsIsDegenerate) {
  // Two long parallel walls and nothing else in range: x along the corridor is free.
  const std::vector<Segment> corridor = {{-1000, 0, 1000, 0}, {-1000, 4, 1000, 4}};
  LadarScan scan = ExactScan(corridor, Pose2(0, 2, 0), 720);
  scan.max_range = 40.0;
  for (float& x : scan.ranges)
    if (!(x <= 40.0f)) x = std::numeric_limits<float>::quiet_NaN();
  const auto map = Map(corridor, CorrespondenceMethod::kBruteForce);
  const IconicMatchResult r = MatchScanToMap(scan, *map, Pose2(0.3, 2.2, 0.05), IconicMatchOptions{});
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("degenerate"), std::string::npos) << r.status;
}

TEST(IconicMatcherTest, IterationLimitIsReported) {
  const auto map = Map(RoomWorld());
  IconicMatchOptions o;
  o.max_iterations = 1;
  const IconicMatchResult r =
      MatchScanToMap(ExactScan(RoomWorld(), Pose2(5, 9, 0)), *map, Pose2(5.5, 8.7, 0.1), o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NE(r.status.find("no convergence in 1 iterations"), std::string::npos) << r.status;
}

}  // namespace
}  // namespace minenav
