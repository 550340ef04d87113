#include "logger/test_logs.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/pose_estimate.h"
#include "tests/temp_dir.h"

namespace minenav::logger_test {

TestRun MakeTestRun(int stations, int points) {
  TestRun run;
  run.world = {Segment(0, 0, 10, 0), Segment(10, 0, 10, 8), Segment(10, 8, 0, 8), Segment(0, 8, 0, 0),
               Segment(4, 3, 5, 3), Segment(5, 3, 5, 4), Segment(5, 4, 4, 4), Segment(4, 4, 4, 3)};
  for (int k = 0; k < stations; ++k) {
    const int64_t utime = 1'000'000'000 + int64_t{k} * 1'000'000;
    const Pose2 truth(2.0 + 1.2 * k, 1.5 + 0.3 * k, 0.2 * k - 0.4);
    run.truth.push_back({utime, truth});
    run.odometry.push_back({utime, Pose2(truth.x + 0.2, truth.y - 0.1, truth.theta + 0.03)});
    run.estimates.push_back({utime, Pose2(truth.x + 0.01, truth.y, truth.theta)});
    LadarScan scan;
    scan.utime = utime;
    scan.scan_id = k;
    scan.sensor_id = "test";
    scan.start_angle = -kPi;
    scan.angle_step = 2.0 * kPi / points;
    scan.min_range = 0.1;
    scan.max_range = 30.0;
    scan.scan_duration = 0.1;
    for (int i = 0; i < points; ++i) {
      const auto hit = CastRay(truth.translation(), truth.theta + scan.Bearing(static_cast<size_t>(i)), run.world,
                               scan.max_range);
      scan.ranges.push_back(hit ? static_cast<float>(hit->range) : 0.0f);
    }
    run.scans.push_back(scan);
  }
  return run;
}

void WriteTestLog(const std::string& path, const TestRun& run) {
  LogWriter writer(path);
  for (size_t k = 0; k < run.scans.size(); ++k) {
    OdometryReading o;
    o.utime = run.odometry[k].utime;
    o.seq = static_cast<int64_t>(k);
    o.pose = run.odometry[k].pose;
    TruthReading t;
    t.utime = run.truth[k].utime;
    t.seq = static_cast<int64_t>(k);
    t.pose = run.truth[k].pose;
    MatchResult match;
    match.pose = run.estimates[k].pose;
    match.converged = true;
    match.status = "ok";
    const PoseEstimate e = MakePoseEstimate(match, run.estimates[k].utime, static_cast<int64_t>(k), "ipe", 0.0);
    writer.WriteMessage("ODOMETRY", o.utime, ToLcm(o));
    writer.WriteMessage("SIM_TRUTH", t.utime, ToLcm(t));
    writer.WriteMessage("LADAR_SCAN", run.scans[k].utime, ToLcm(run.scans[k]));
    writer.WriteMessage("POSE_IPE", e.utime + 50'000, ToLcm(e));
  }
  writer.Close();
}

namespace {

// This process's temporary files, removed when the binary exits.
const std::filesystem::path& TempRoot() {
  static const minenav::testing::TempDir root("minenav_logger");
  return root.path();
}

}  // namespace

std::string TempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = TempRoot() / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool FileExists(const std::string& path) { return std::filesystem::exists(path); }

}  // namespace minenav::logger_test
