#include "logger/carmen_log.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/angle.h"
#include "common/file_io.h"

namespace minenav {
namespace {

std::string DatasetsDir() {
#ifdef MINENAV_DATASETS_DIR
  return MINENAV_DATASETS_DIR;
#else
  return "";
#endif
}

// The real files are required: a missing folder fails here instead of skipping.
std::string Dataset(const std::string& name) {
  const std::string path = DatasetsDir() + "/" + name;
  if (!std::filesystem::exists(path))
    ADD_FAILURE() << "dataset " << path << " is missing (set MINENAV_DATASETS_DIR; see shared/datasets/SOURCES.md)";
  return path;
}

// Two FLASER lines of 4 readings, one ODOM, a comment, a PARAM and an ignored NEFF line.
constexpr const char* kSmall =
    "# CARMEN Logfile\n"
    "PARAM robot_front_laser_max 50.0 nohost 0\n"
    "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 100.25 host 0.1\n"
    "FLASER 4 1.0 2.5 81.91 0.0 1.04 2.0 0.5 1.0 2.0 0.5 100.5 host 0.2\n"
    "NEFF 12.0 100.6 host 0.3\n"
    "\n"
    "FLASER 4 3 3 3 3 1.1 2.0 0.5 1.1 2.0 0.5 100.400001 host 0.4\n";

TEST(CarmenLogTest, ParsesFlaserOdomAndParam) {
  const CarmenLog log = ParseCarmenLog(kSmall, "small.clf");
  ASSERT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.scan_odometry.size(), 2u);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.stats.lines, 7);
  EXPECT_EQ(log.stats.flaser_lines, 2);
  EXPECT_EQ(log.stats.odom_lines, 1);
  EXPECT_EQ(log.stats.param_lines, 1);
  EXPECT_EQ(log.stats.ignored_lines, 1);
  // 81.91 is beyond the PARAM maximum (50 m) and 0.0 is no return.
  EXPECT_EQ(log.stats.no_return_readings, 2);
  EXPECT_EQ(log.stats.scan_time_reversals, 1);

  const LadarScan& s = log.scans[0];
  EXPECT_EQ(s.utime, 100500000);
  EXPECT_EQ(s.scan_id, 0);
  EXPECT_EQ(s.sensor_id, "FLASER");
  EXPECT_DOUBLE_EQ(s.start_angle, -kPi / 2.0);
  EXPECT_DOUBLE_EQ(s.angle_step, kPi / 3.0);  // n = 4: pi / (n - 1)
  EXPECT_DOUBLE_EQ(s.max_range, 50.0);
  ASSERT_EQ(s.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(s.ranges[0], 1.0f);
  EXPECT_FLOAT_EQ(s.ranges[1], 2.5f);
  EXPECT_TRUE(std::isnan(s.ranges[2]));
  EXPECT_TRUE(std::isnan(s.ranges[3]));
  EXPECT_TRUE(s.IsValid(0));
  EXPECT_FALSE(s.IsValid(2));
  // The laser sits 0.04 m ahead along heading 0.5 rad: robot^-1 * laser = (0.04 * cos... ).
  // laser - robot = (0.04, 0) in the world; in the robot frame (heading 0.5):
  EXPECT_NEAR(s.sensor_offset.x, 0.04 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(s.sensor_offset.y, -0.04 * std::sin(0.5), 1e-12);
  EXPECT_NEAR(s.sensor_offset.theta, 0.0, 1e-12);
  EXPECT_EQ(log.scan_odometry[0].utime, 100500000);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].pose.x, 1.0);
  EXPECT_EQ(log.scans[1].utime, 100400001);
  EXPECT_EQ(log.scans[1].scan_id, 1);

  const OdometryReading& o = log.odometry[0];
  EXPECT_EQ(o.utime, 100250000);
  EXPECT_DOUBLE_EQ(o.pose.x, 1.0);
  EXPECT_DOUBLE_EQ(o.pose.y, 2.0);
  EXPECT_DOUBLE_EQ(o.pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(o.v, 0.3);
  EXPECT_DOUBLE_EQ(o.omega, 0.1);
}

TEST(CarmenLogTest, MonotonicTimesOption) {
  CarmenReadOptions options;
  options.monotonic_times = true;
  const CarmenLog log = ParseCarmenLog(kSmall, "small.clf", options);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.scans[0].utime, 100500000);
  EXPECT_EQ(log.scans[1].utime, 100500001);
  EXPECT_EQ(log.scan_odometry[1].utime, 100500001);
  EXPECT_EQ(log.stats.scan_time_reversals, 1);  // counted on the raw times

  std::vector<int64_t> t = {5, 3, 3, 10, 9};
  EXPECT_EQ(MakeStrictlyIncreasing(&t), 3);
  EXPECT_EQ(t, (std::vector<int64_t>{5, 6, 7, 10, 11}));
}

TEST(CarmenLogTest, FlaserAnglesFollowCarmen) {
  std::string line = "FLASER 180";
  for (int i = 0; i < 180; ++i) line += " 1.0";
  line += " 0 0 0 0 0 0 1.0 h 0\n";
  std::string line361 = "FLASER 361";
  for (int i = 0; i < 361; ++i) line361 += " 1.0";
  line361 += " 0 0 0 0 0 0 2.0 h 0\n";
  const CarmenLog log = ParseCarmenLog(line + line361, "angles.clf");
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_DOUBLE_EQ(log.scans[0].angle_step, DegToRad(1.0));
  EXPECT_NEAR(log.scans[0].Bearing(179), DegToRad(89.0), 1e-12);
  EXPECT_DOUBLE_EQ(log.scans[1].angle_step, DegToRad(0.5));
  EXPECT_NEAR(log.scans[1].Bearing(360), DegToRad(90.0), 1e-12);
  // Without a PARAM the cap applies: 80 m.
  EXPECT_DOUBLE_EQ(log.scans[0].max_range, 80.0);
}

TEST(CarmenLogTest, ParsesRobotLaser1) {
  // 3 readings, 0 remissions, laser 0.22 m ahead of a robot at (1, 1, pi/2), tv 0.5, rv 0.1.
  const std::string text =
      "ROBOTLASER1 0 -1.0 2.0 1.0 81.9 0.01 0 3 2.0 81.83 4.0 0 1.0 1.22 1.5707963267948966 "
      "1.0 1.0 1.5707963267948966 0.5 0.1 0 0 0 1232658478.161285 zoidberg2 -0.05\n";
  const CarmenLog log = ParseCarmenLog(text, "rl.clf");
  ASSERT_EQ(log.scans.size(), 1u);
  const LadarScan& s = log.scans[0];
  EXPECT_EQ(s.sensor_id, "ROBOTLASER1");
  EXPECT_EQ(s.utime, 1232658478161285);
  EXPECT_DOUBLE_EQ(s.start_angle, -1.0);
  EXPECT_DOUBLE_EQ(s.angle_step, 1.0);
  EXPECT_DOUBLE_EQ(s.max_range, 80.0);  // line says 81.9, capped
  EXPECT_TRUE(std::isnan(s.ranges[1]));  // 81.83: SICK no-return code
  EXPECT_FLOAT_EQ(s.ranges[2], 4.0f);
  EXPECT_NEAR(s.sensor_offset.x, 0.22, 1e-12);
  EXPECT_NEAR(s.sensor_offset.y, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].v, 0.5);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].omega, 0.1);
  EXPECT_EQ(log.stats.robotlaser1_lines, 1);
}

void ExpectError(const std::string& text, const std::string& fragment) {
  try {
    ParseCarmenLog(text, "bad.clf");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(CarmenLogTest, MalformedLinesNameFileAndLine) {
  ExpectError("# c\nFLASER 3 1 2 0 0 0 0 0 0 1.0 h 0\n", "bad.clf:2: FLASER: expected 14 fields");
  ExpectError("FLASER 2 1 x 0 0 0 0 0 0 1.0 h 0\n", "bad.clf:1: FLASER: range 'x' (field 4) is not a finite number");
  ExpectError("FLASER -2 0 0 0 0 0 0 1.0 h 0\n", "number of readings '-2'");
  ExpectError("ODOM 1 2 3 4 5 6 1x5 h 0\n", "bad.clf:1: ODOM: ipc timestamp '1x5'");
  ExpectError("ODOM 1 2 3 4 5 1.0 h 0\n", "expected 10 fields");
  ExpectError("ODOM 1 2 nan 4 5 6 1.0 h 0\n", "theta 'nan'");
  ExpectError("PARAM robot_front_laser_max -3 h 0\n", "robot_front_laser_max -3 m is not positive");
  ExpectError("ROBOTLASER1 0 -1 2 0 81.9 0.01 0 1 2.0 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 0\n",
              "angular resolution");
  ExpectError("ROBOTLASER1 0 -1 2 1 81.9 0.01 0 1 2.0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 0\n", "expected 25 fields");
}

TEST(CarmenLogTest, TimestampsAreExact) {
  int64_t t = 0;
  ASSERT_TRUE(ParseCarmenTimestamp("976052857.337530", &t));
  EXPECT_EQ(t, 976052857337530);
  ASSERT_TRUE(ParseCarmenTimestamp("32.9068", &t));
  EXPECT_EQ(t, 32906800);
  ASSERT_TRUE(ParseCarmenTimestamp("7", &t));
  EXPECT_EQ(t, 7000000);
  ASSERT_TRUE(ParseCarmenTimestamp("1.08499e-42", &t));
  EXPECT_EQ(t, 0);
  ASSERT_TRUE(ParseCarmenTimestamp("1.5e2", &t));
  EXPECT_EQ(t, 150000000);
  ASSERT_TRUE(ParseCarmenTimestamp("1.1234567", &t));  // 7 decimals: rounded
  EXPECT_EQ(t, 1123457);
  EXPECT_FALSE(ParseCarmenTimestamp("inf", &t));
  EXPECT_FALSE(ParseCarmenTimestamp("abc", &t));
  EXPECT_FALSE(ParseCarmenTimestamp("", &t));
}

TEST(CarmenLogTest, ReadsGzipAndPlainFiles) {
  const std::string dir = ::testing::TempDir();
  const std::string plain = dir + "/carmen_small_" + std::to_string(::getpid()) + ".clf";
  const std::string gz = plain + ".gz";
  {
    std::ofstream out(plain);
    out << kSmall;
  }
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, kSmall, static_cast<unsigned>(std::string(kSmall).size()));
  gzclose(f);
  const CarmenLog a = ReadCarmenLog(plain);
  const CarmenLog b = ReadCarmenLog(gz);
  EXPECT_EQ(a.scans.size(), 2u);
  EXPECT_EQ(b.scans.size(), 2u);
  EXPECT_EQ(b.odometry.size(), 1u);
  std::filesystem::remove(plain);
  std::filesystem::remove(gz);
  EXPECT_THROW(ReadCarmenLog(dir + "/no_such_file.clf"), InputError);
}

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
