#include "common/scan.h"

#include <gtest/gtest.h>

#include <cmath>

namespace minenav {
namespace {

LadarScan FourBeamScan() {
  LadarScan s;
  s.start_angle = 0.0;
  s.angle_step = kPi / 2;
  s.min_range = 0.5;
  s.max_range = 10.0;
  s.ranges = {1.0f, 2.0f, std::nanf(""), 0.2f};
  return s;
}

TEST(ScanTest, OnlyValidReadingsBecomePoints) {
  const auto pts = ScanPointsInSensorFrame(FourBeamScan());
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_TRUE(pts[0].point.isApprox(Eigen::Vector2d(1, 0)));
  EXPECT_NEAR(pts[1].point.x(), 0.0, 1e-12);
  EXPECT_NEAR(pts[1].point.y(), 2.0, 1e-6);
  EXPECT_EQ(pts[1].index, 1);
}

TEST(ScanTest, WorldPointsGoThroughSensorOffsetAndVehiclePose) {
  LadarScan s = FourBeamScan();
  s.sensor_offset = Pose2(0.5, 0.0, 0.0);
  const auto pts = ScanPointsInWorld(s, Pose2(10, 0, kPi / 2));
  ASSERT_EQ(pts.size(), 2u);
  // Sensor at (10, 0.5) facing +y; reading 0 (1 m ahead) lands at (10, 1.5).
  EXPECT_NEAR(pts[0].x(), 10.0, 1e-9);
  EXPECT_NEAR(pts[0].y(), 1.5, 1e-9);
}

TEST(ScanTest, ValidateNamesTheProblem) {
  LadarScan s = FourBeamScan();
  EXPECT_EQ(ValidateScan(s), "");
  s.min_range = 20;
  EXPECT_NE(ValidateScan(s).find("range limits"), std::string::npos);
  s = FourBeamScan();
  s.intensities = {1.0f};
  EXPECT_NE(ValidateScan(s).find("intensities"), std::string::npos);
  s = FourBeamScan();
  s.angle_step = 1.0;
  s.ranges.resize(10, 1.0f);
  EXPECT_NE(ValidateScan(s).find("360"), std::string::npos);
}

}  // namespace
}  // namespace minenav
