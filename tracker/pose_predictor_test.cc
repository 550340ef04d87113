// The pose between estimates: the latest estimate composed with the odometry since (checked
// against the composition written out), the odometry interpolated at the estimate's time,
// the gate against a jump with the reanchoring policy, and the ignored estimates.

#include "tracker/pose_predictor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000;

OdometryReading Odo(int64_t t, const Pose2& p) {
  OdometryReading r;
  r.utime = t;
  r.pose = p;
  return r;
}

PoseEstimate Est(int64_t t, const Pose2& p, double sigma = 0.02) {
  PoseEstimate e;
  e.utime = t;
  e.pose = p;
  e.converged = true;
  e.covariance = Eigen::Vector3d(sigma * sigma, sigma * sigma, 0.005 * 0.005).asDiagonal();
  return e;
}

// Odometry in its own frame: straight along x at 0.1 m per second, one reading a second.
void DriveOdometry(PosePredictor& p, int from_s, int to_s) {
  for (int s = from_s; s <= to_s; ++s) p.AddOdometry(Odo(kT0 + s * 1'000'000, Pose2(0.1 * s, 0, 0)));
}

TEST(PosePredictorTest, ComposesTheLatestEstimateWithTheOdometrySince) {
  PosePredictor p;
  EXPECT_FALSE(p.Predict());
  DriveOdometry(p, 0, 2);
  EXPECT_FALSE(p.Predict()) << "no estimate yet";
  // The map frame is the odometry frame turned by 90 deg and shifted; estimate at t = 1.5 s,
  // between two readings (odometry 0.15, 0, 0 there).
  const Pose2 at(10, 20, kPi / 2);
  EXPECT_TRUE(p.AddEstimate(Est(kT0 + 1'500'000, at)).trusted);
  DriveOdometry(p, 3, 5);  // 0.35 m more along the odometry's x = the map's +y
  const Pose2 predicted = *p.Predict();
  EXPECT_NEAR(predicted.x, 10.0, 1e-9);
  EXPECT_NEAR(predicted.y, 20.35, 1e-9);
  EXPECT_NEAR(predicted.theta, kPi / 2, 1e-12);
  // Uncertainty grows with the distance driven.
  EXPECT_GT(p.PredictionCovariance()(0, 0), 0.02 * 0.02);
}

TEST(PosePredictorTest, AJumpIsReportedAndNotObeyedUntilEstimatesAgreeOnIt) {
  PosePredictorOptions o;
  o.reanchor_after = 3;
  PosePredictor p(o);
  DriveOdometry(p, 0, 1);
  ASSERT_TRUE(p.AddEstimate(Est(kT0, Pose2(0, 0, 0))).trusted);
  // A consistent estimate 1 cm off: trusted.
  DriveOdometry(p, 2, 2);
  const EstimateVerdict fine = p.AddEstimate(Est(kT0 + 1'000'000, Pose2(0.11, 0.0, 0)));
  EXPECT_TRUE(fine.trusted) << fine.reason;
  EXPECT_LT(fine.sigmas, 1.0);
  // A 1 m jump sideways: reported, the prediction stays on the odometry.
  const EstimateVerdict jump = p.AddEstimate(Est(kT0 + 2'000'000, Pose2(0.21, 1.0, 0)));
  EXPECT_FALSE(jump.trusted);
  EXPECT_TRUE(jump.jump);
  EXPECT_GT(jump.sigmas, 20.0);
  EXPECT_NE(jump.reason.find("pose jump"), std::string::npos) << jump.reason;
  EXPECT_NEAR(p.Predict()->y, 0.0, 1e-9);
  EXPECT_EQ(*p.last_trusted_utime(), kT0 + 1'000'000);
  // Two more that agree with it (moved by the odometry): the third consistent one re-anchors.
  DriveOdometry(p, 3, 4);
  EXPECT_FALSE(p.AddEstimate(Est(kT0 + 3'000'000, Pose2(0.31, 1.0, 0))).trusted);
  const EstimateVerdict third = p.AddEstimate(Est(kT0 + 4'000'000, Pose2(0.41, 1.0, 0)));
  EXPECT_TRUE(third.trusted) << third.reason;
  EXPECT_TRUE(third.reanchored);
  EXPECT_NEAR(p.Predict()->y, 1.0, 1e-9);
  EXPECT_EQ(p.jumps(), 3);
}

TEST(PosePredictorTest, JumpsThatDisagreeWithEachOtherAreNeverObeyed) {
  PosePredictor p;
  DriveOdometry(p, 0, 10);
  ASSERT_TRUE(p.AddEstimate(Est(kT0, Pose2(0, 0, 0))).trusted);
  for (int k = 1; k <= 6; ++k) {
    const double y = k % 2 == 0 ? 2.0 : -2.0;
    EXPECT_FALSE(p.AddEstimate(Est(kT0 + k * 1'000'000, Pose2(0.1 * k, y, 0))).trusted) << k;
  }
  EXPECT_NEAR(p.Predict()->y, 0.0, 1e-9);
}

TEST(PosePredictorTest, IgnoresUnconvergedOldAndUnmatchableEstimates) {
  PosePredictor p;
  DriveOdometry(p, 0, 3);
  PoseEstimate bad = Est(kT0, Pose2());
  bad.converged = false;
  bad.status = "too few points";
  EXPECT_NE(p.AddEstimate(bad).reason.find("not converged"), std::string::npos);
  ASSERT_TRUE(p.AddEstimate(Est(kT0 + 2'000'000, Pose2(0.2, 0, 0))).trusted);
  EXPECT_NE(p.AddEstimate(Est(kT0 + 1'000'000, Pose2())).reason.find("older"), std::string::npos);
  // Newer than the odometry: it waits for the odometry of its time, then is decided.
  EXPECT_NE(p.AddEstimate(Est(kT0 + 3'500'000, Pose2(0.35, 0, 0))).reason.find("waiting"), std::string::npos);
  EXPECT_FALSE(p.TakeDeferredVerdict());
  DriveOdometry(p, 4, 4);
  const std::optional<EstimateVerdict> later = p.TakeDeferredVerdict();
  ASSERT_TRUE(later);
  EXPECT_TRUE(later->trusted) << later->reason;
  EXPECT_EQ(*p.last_trusted_utime(), kT0 + 3'500'000);
  // Across a gap in the odometry longer than max_odometry_gap: not matchable.
  p.AddOdometry(Odo(kT0 + 60'000'000, Pose2(0.4, 0, 0)));
  EXPECT_NE(p.AddEstimate(Est(kT0 + 30'000'000, Pose2())).reason.find("no odometry"), std::string::npos);
  EXPECT_FALSE(p.AddOdometry(Odo(kT0, Pose2())));  // out of order
  // An estimate without covariance gets the default sigmas (trusted when it agrees).
  PoseEstimate bare = Est(kT0 + 60'000'000, Pose2(0.4, 0.01, 0));
  bare.covariance.setZero();
  EXPECT_TRUE(p.AddEstimate(bare).trusted);
  EXPECT_EQ(ValidatePosePredictorOptions({}), "");
}

}  // namespace
}  // namespace minenav
