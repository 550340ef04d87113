// The CARMEN reader on the real logs of the datasets folder (dataset_readers/dataset_path.h); built
// only when the datasets are there (MINENAV_HAVE_DATASETS). The inline and hostile-input
// cases are in carmen_log_test.cc.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/scan.h"
#include "dataset_readers/carmen_log.h"
#include "dataset_readers/dataset_path.h"

namespace minenav {
namespace {

using logger_test::Dataset;

// ---- The real logs (counts from shared/datasets/SOURCES.md).

TEST(CarmenLogRealTest, Intel) {
  const CarmenLog log = ReadCarmenLog(Dataset("intel.clf.bz2"));
  EXPECT_EQ(log.stats.flaser_lines, 13631);
  EXPECT_EQ(log.scans.size(), 13631u);
  EXPECT_EQ(log.odometry.size(), 26915u);
  EXPECT_EQ(log.stats.scan_time_reversals, 631);
  EXPECT_EQ(log.scans.front().utime, 976052857337530);
  EXPECT_EQ(log.scans.front().ranges.size(), 180u);
  EXPECT_NEAR(log.scans.front().sensor_offset.x, 0.0, 1e-9);
  // Duration 2691 s (SOURCES.md).
  EXPECT_NEAR(static_cast<double>(log.scans.back().utime - log.scans.front().utime) * 1e-6, 2691.0, 1.0);
  for (size_t i = 0; i < log.scans.size(); ++i) EXPECT_EQ(log.scans[i].scan_id, static_cast<int64_t>(i));
  EXPECT_TRUE(ValidateScan(log.scans[100]).empty());

  CarmenReadOptions mono;
  mono.monotonic_times = true;
  const CarmenLog m = ReadCarmenLog(Dataset("intel.clf.bz2"), mono);
  for (size_t i = 1; i < m.scans.size(); ++i) ASSERT_GT(m.scans[i].utime, m.scans[i - 1].utime);
  for (size_t i = 1; i < m.odometry.size(); ++i) ASSERT_GT(m.odometry[i].utime, m.odometry[i - 1].utime);
}

TEST(CarmenLogRealTest, Fr079LaserOffset) {
  const CarmenLog log = ReadCarmenLog(Dataset("fr079.clf.bz2"));
  EXPECT_EQ(log.scans.size(), 4934u);
  EXPECT_EQ(log.odometry.size(), 8951u);
  EXPECT_EQ(log.stats.param_lines, 187);
  EXPECT_EQ(log.scans.front().ranges.size(), 360u);
  EXPECT_DOUBLE_EQ(log.scans.front().max_range, 80.0);  // PARAM 80.99, capped
  // PARAM robot_frontlaser_offset -0.04: the laser 4 cm behind the robot centre.
  for (size_t i = 0; i < log.scans.size(); i += 97) {
    EXPECT_NEAR(log.scans[i].sensor_offset.x, -0.04, 2e-5) << i;
    EXPECT_NEAR(log.scans[i].sensor_offset.y, 0.0, 2e-5) << i;
  }
  EXPECT_NEAR(static_cast<double>(log.scans.back().utime - log.scans.front().utime) * 1e-6, 1061.0, 1.0);
}

TEST(CarmenLogRealTest, MitCsailHasOnlyLaserOdometry) {
  const CarmenLog log = ReadCarmenLog(Dataset("mit-csail.clf.bz2"));
  EXPECT_EQ(log.scans.size(), 1988u);
  EXPECT_EQ(log.odometry.size(), 0u);
  EXPECT_EQ(log.scan_odometry.size(), 1988u);
  EXPECT_EQ(log.scans.front().ranges.size(), 361u);
  EXPECT_NEAR(static_cast<double>(log.scans.back().utime - log.scans.front().utime) * 1e-6, 424.0, 1.0);
}

TEST(CarmenLogRealTest, FreiburgHospitalRobotLaser1) {
  const CarmenLog log = ReadCarmenLog(Dataset("fr-clinic_robotlaser.clf.bz2"));
  EXPECT_EQ(log.stats.robotlaser1_lines, 6917);
  EXPECT_EQ(log.scans.size(), 6917u);
  EXPECT_NEAR(log.scans[2000].sensor_offset.x, 0.22, 1e-4);
  EXPECT_NEAR(static_cast<double>(log.scans.back().utime - log.scans.front().utime) * 1e-6, 4820.0, 1.0);
}

TEST(CarmenLogRealTest, IntelCorrectedGzip) {
  const CarmenLog log = ReadCarmenLog(Dataset("intel-corrected.log.gz"));
  EXPECT_EQ(log.scans.size(), 910u);
  EXPECT_EQ(log.stats.ignored_lines, 910);  // NEFF
}

}  // namespace
}  // namespace minenav
