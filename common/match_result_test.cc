#include "common/match_result.h"

#include <gtest/gtest.h>

#include "common/pose_estimate.h"

namespace minenav {
namespace {

// A result with every core field set to a value of its own.
MatchResult DistinctResult() {
  MatchResult r;
  r.pose = Pose2(1.5, -2.25, 0.75);
  r.covariance << 0.01, 0.002, 0.0003,  //
      0.002, 0.04, 0.0005,              //
      0.0003, 0.0005, 0.0009;
  r.converged = true;
  r.status = "ok: fixed scan";
  r.iterations = 7;
  r.num_points = 361;
  r.num_inliers = 298;
  r.residual = 0.042;
  return r;
}

TEST(MatchResultTest, MakePoseEstimateCarriesEveryFieldAcross) {
  const MatchResult r = DistinctResult();
  const PoseEstimate e = MakePoseEstimate(r, 1'234'567, 42, "ipe", 0.0125);
  EXPECT_EQ(e.utime, 1'234'567);
  EXPECT_EQ(e.scan_id, 42);
  EXPECT_EQ(e.source, "ipe");
  EXPECT_EQ(e.compute_time, 0.0125);
  EXPECT_EQ(e.pose.x, 1.5);
  EXPECT_EQ(e.pose.y, -2.25);
  EXPECT_EQ(e.pose.theta, 0.75);
  EXPECT_TRUE(e.converged);
  EXPECT_EQ(e.status, "ok: fixed scan");
  EXPECT_EQ(e.iterations, 7);
  EXPECT_EQ(e.num_points, 361);
  EXPECT_EQ(e.num_inliers, 298);
  EXPECT_EQ(e.residual, 0.042);
}

TEST(MatchResultTest, MakePoseEstimateCarriesTheWholeCovariance) {
  const MatchResult r = DistinctResult();
  const PoseEstimate e = MakePoseEstimate(r, 0, 0, "fpe", 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_EQ(e.covariance(i, j), r.covariance(i, j)) << i << "," << j;
}

TEST(MatchResultTest, ANonConvergedResultKeepsItsStatusAndLastPose) {
  MatchResult r = DistinctResult();
  r.converged = false;
  r.status = "no features in the scan";
  const PoseEstimate e = MakePoseEstimate(r, 5, 6, "fpe", 0.001);
  EXPECT_FALSE(e.converged);
  EXPECT_EQ(e.status, "no features in the scan");
  EXPECT_EQ(e.pose.x, r.pose.x);  // reported, not to be trusted
  EXPECT_EQ(e.num_inliers, r.num_inliers);
}

TEST(MatchResultTest, AMatchersOwnResultPublishesItsCoreOnly) {
  struct WithExtras : MatchResult {
    double final_threshold = 0.3;  // m
  };
  WithExtras r;
  static_cast<MatchResult&>(r) = DistinctResult();
  const PoseEstimate e = MakePoseEstimate(r, 9, 10, "clue", 0.5);
  EXPECT_EQ(e.status, "ok: fixed scan");
  EXPECT_EQ(e.num_points, 361);
  EXPECT_EQ(e.source, "clue");
}

TEST(MatchResultTest, ADefaultResultIsADefaultEstimate) {
  const MatchResult r;
  const PoseEstimate made = MakePoseEstimate(r, 0, 0, "", 0.0);
  const PoseEstimate plain;
  EXPECT_FALSE(made.converged);
  EXPECT_EQ(made.status, "not run");
  EXPECT_EQ(made.status, plain.status);
  EXPECT_TRUE(made.covariance.isZero());
  EXPECT_EQ(made.iterations, plain.iterations);
  EXPECT_EQ(made.num_points, plain.num_points);
  EXPECT_EQ(made.num_inliers, plain.num_inliers);
  EXPECT_EQ(made.residual, plain.residual);
}

}  // namespace
}  // namespace minenav
