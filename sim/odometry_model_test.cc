#include "sim/odometry_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.h"

namespace minenav {
namespace {

MotionIncrement Straight(double ds, double dt) {
  MotionIncrement m;
  m.delta = Pose2(ds, 0.0, 0.0);
  m.distance = ds;
  m.dt = dt;
  return m;
}

// Drives 100 m straight in `steps` increments; returns the estimate.
Pose2 Drive100(const OdometryErrorOptions& o, uint64_t seed, int steps = 1000) {
  DeadReckoning dr(o, Pose2(), seed);
  for (int i = 0; i < steps; ++i) dr.AddIncrement(Straight(100.0 / steps, 1300.0 / steps));
  return dr.pose();
}

TEST(OdometryModelTest, NoErrorsReproducesTruth) {
  SkidSteerOptions so;
  so.max_acceleration = 0.0;
  SkidSteerVehicle v(so, Pose2(1, 2, 0.3));
  DeadReckoning dr(OdometryErrorOptions(), v.pose(), 1);
  DriveCommand c;
  c.mode = DriveCommand::Mode::kVelocity;
  c.v = 0.076;
  c.omega = 0.076 / 4.0;
  c.timeout = 1e9;
  for (int i = 0; i < 500; ++i) dr.AddIncrement(v.Step(0.2, c, 0));
  EXPECT_NEAR(dr.pose().x, v.pose().x, 1e-9);
  EXPECT_NEAR(dr.pose().y, v.pose().y, 1e-9);
  EXPECT_NEAR(dr.pose().theta, v.pose().theta, 1e-9);
  const OdometryReading r = dr.Reading(123);
  EXPECT_EQ(r.utime, 123);
  EXPECT_EQ(r.seq, 500);
  EXPECT_NEAR(r.v, 0.076, 1e-12);
  EXPECT_NEAR(r.omega, 0.019, 1e-12);
}

TEST(OdometryModelTest, ScaleErrorIsTheExpectedBias) {
  OdometryErrorOptions o;
  o.scale_error = 0.02;
  EXPECT_NEAR(Drive100(o, 1).x, 102.0, 1e-9);
  o.translation_noise = 0.01;  // m/sqrt(m): 0.1 m after 100 m
  double sum = 0.0, sum2 = 0.0;
  const int n = 400;
  for (int seed = 0; seed < n; ++seed) {
    const double x = Drive100(o, seed, 100).x;
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 102.0, 4 * 0.1 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.1, 0.01);
}

TEST(OdometryModelTest, NoiseDoesNotDependOnStepSize) {
  OdometryErrorOptions o;
  o.rotation_noise = 0.002;  // rad/sqrt(m) on a straight drive: 0.02 rad after 100 m
  for (int steps : {10, 1000}) {
    double sum2 = 0.0;
    const int n = 300;
    for (int seed = 0; seed < n; ++seed) {
      const double th = Drive100(o, 1000 + seed, steps).theta;
      sum2 += th * th;
    }
    EXPECT_NEAR(std::sqrt(sum2 / n), 0.02, 0.002) << steps << " steps";
  }
}

TEST(OdometryModelTest, HeadingDriftPerMetreAndPerSecond) {
  OdometryErrorOptions o;
  o.heading_drift_per_metre = 0.001;  // 0.1 rad over 100 m: an arc of radius 1000 m
  const Pose2 p = Drive100(o, 1);
  EXPECT_NEAR(p.theta, 0.1, 1e-9);
  EXPECT_NEAR(p.x, 1000.0 * std::sin(0.1), 1e-3);
  EXPECT_NEAR(p.y, 1000.0 * (1 - std::cos(0.1)), 1e-3);
  // A standing vehicle only drifts with time.
  OdometryErrorOptions g;
  g.heading_drift_per_second = 1e-4;
  DeadReckoning dr(g, Pose2(), 1);
  for (int i = 0; i < 100; ++i) dr.AddIncrement(Straight(0.0, 10.0));
  EXPECT_NEAR(dr.pose().theta, 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(dr.pose().x, 0.0);
}

TEST(OdometryModelTest, DeadReckonAlongStations) {
  const std::vector<Pose2> truth{Pose2(0, 0, 0), Pose2(5, 0, 0.5), Pose2(8, 3, 1.5), Pose2(8, 9, 1.6)};
  const auto exact = DeadReckonAlong(truth, {}, OdometryErrorOptions(), 3);
  ASSERT_EQ(exact.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(exact[i].x, truth[i].x, 1e-12);
    EXPECT_NEAR(exact[i].y, truth[i].y, 1e-12);
    EXPECT_NEAR(exact[i].theta, truth[i].theta, 1e-12);
  }
  OdometryErrorOptions o;
  o.scale_error = 0.1;
  const auto line = DeadReckonAlong({Pose2(0, 0, 0), Pose2(10, 0, 0), Pose2(20, 0, 0)}, {0, 1, 2}, o, 3);
  EXPECT_NEAR(line[2].x, 22.0, 1e-12);
  o = OdometryErrorOptions();
  o.heading_drift_per_second = 0.01;
  const auto drift = DeadReckonAlong({Pose2(0, 0, 0), Pose2(0, 0, 0)}, {0.0, 10.0}, o, 3);
  EXPECT_NEAR(drift[1].theta, 0.1, 1e-12);
  EXPECT_NE(ValidateOdometryErrorOptions(OdometryErrorOptions{-2.0, 0, 0, 0, 0, 0}), "");
  EXPECT_EQ(ValidateOdometryErrorOptions(OdometryErrorOptions()), "");
}

TEST(OdometryModelTest, PerturbPosesHasTheThesisStatistics) {
  const PoseNoise noise{0.33, 0.33, DegToRad(3.33)};
  std::vector<Pose2> truth(4000, Pose2(10.0, -5.0, 0.2));
  const auto noisy = PerturbPoses(truth, noise, 7);
  double sx = 0, sy = 0, st = 0, mx = 0;
  for (const Pose2& p : noisy) {
    sx += (p.x - 10.0) * (p.x - 10.0);
    sy += (p.y + 5.0) * (p.y + 5.0);
    st += (p.theta - 0.2) * (p.theta - 0.2);
    mx += p.x - 10.0;
  }
  const double n = static_cast<double>(noisy.size());
  EXPECT_NEAR(std::sqrt(sx / n), 0.33, 0.033);
  EXPECT_NEAR(std::sqrt(sy / n), 0.33, 0.033);
  EXPECT_NEAR(std::sqrt(st / n), DegToRad(3.33), DegToRad(0.333));
  EXPECT_NEAR(mx / n, 0.0, 4 * 0.33 / std::sqrt(n));
  const auto again = PerturbPoses(truth, noise, 7);
  EXPECT_EQ(again[17].x, noisy[17].x);
  EXPECT_NE(PerturbPoses(truth, noise, 8)[17].x, noisy[17].x);
}

}  // namespace
}  // namespace minenav
