// iconic_pose_estimator as users run it in batch: a log in, a poses CSV out, for every
// mode; bad flags, bad files and bad messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "common/angle.h"
#include "common/config_testing.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "pose_estimator/iconic/iconic_test_world.h"
#include "tests/child_process.h"
#include "tests/log_contents.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using minenav::testing::ReadTextFile;

testing::ProgramRun Ipe(const std::vector<std::string>& args, const testing::TempDir& dir) {
  return testing::RunProgram(MINENAV_IPE_BIN, args, dir / "out.txt", 120.0);
}

// A survey of the test room: 6 stations a couple of metres apart, odometry with the
// scan's utime carrying the initial estimate (truth + error, the first one exact).
std::vector<StampedPose> WriteSurveyLog(const std::string& path, bool with_line_map) {
  const std::vector<Pose2> truths = {{3, 2.5, 0.0}, {5, 2.8, 0.1}, {7, 3.0, 0.2}, {9, 2.8, 0.3}, {11, 2.5, 0.25}, {12, 9.5, 1.0}};
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> e(-1.0, 1.0);
  std::vector<StampedPose> truth;
  LogWriter log(path);
  if (with_line_map) log.Write("LINE_MAP", SegmentsToLcm(testing::RoomWorld(), 1, 1, "room"));
  for (size_t k = 0; k < truths.size(); ++k) {
    const int64_t utime = 1'000'000 + static_cast<int64_t>(k) * 1'000'000;
    LadarScan scan = testing::ExactScan(testing::RoomWorld(), truths[k], 720, 0.01, static_cast<uint32_t>(k + 1), utime);
    scan.scan_id = static_cast<int64_t>(k);
    OdometryReading odo;
    odo.utime = utime;
    odo.seq = static_cast<int64_t>(k);
    const double s = k == 0 ? 0.0 : 1.0;
    odo.pose = Pose2(truths[k].x + 0.2 * s * e(rng), truths[k].y + 0.2 * s * e(rng),
                     truths[k].theta + s * DegToRad(2) * e(rng));
    // Odometry after the scan for odd k: the scan must wait for it.
    if (k % 2 == 0) log.Write("ODOMETRY", ToLcm(odo));
    log.Write("LADAR_SCAN", ToLcm(scan));
    if (k % 2 == 1) log.Write("ODOMETRY", ToLcm(odo));
    if (k == 2) {
      const uint8_t garbage[5] = {1, 2, 3, 4, 5};
      log.Write("LADAR_SCAN", utime + 1, garbage, 5);  // does not decode: counted, skipped
    }
    truth.push_back({utime, truths[k]});
  }
  log.Close();
  return truth;
}

void ExpectPosesNearTruth(const std::string& csv, const std::vector<StampedPose>& truth, double tol_m,
                          const std::string& what) {
  const std::vector<StampedPose> est = LoadPosesCsv(csv);
  ASSERT_EQ(est.size(), truth.size()) << what;
  for (size_t k = 0; k < truth.size(); ++k) {
    EXPECT_EQ(est[k].utime, truth[k].utime) << what;
    EXPECT_LT(TranslationDistance(est[k].pose, truth[k].pose), tol_m) << what << " scan " << k;
    EXPECT_LT(HeadingDistance(est[k].pose, truth[k].pose), DegToRad(0.3)) << what << " scan " << k;
  }
}

TEST(IconicProcessTest, EveryModeWritesOnePosePerScan) {
  testing::TempDir dir("minenav_ipe_process_test");
  const auto truth = WriteSurveyLog(dir / "in.lcm", false);
  SaveSegmentsJson(dir / "map.json", testing::RoomWorld());
  for (const std::string mode : {"surveyed", "scan-map", "first-scan", "all-previous", "simultaneous"}) {
    std::vector<std::string> args = {"--log", dir / "in.lcm", "--mode", mode, "--poses-out", dir / "est.csv",
                                     "--min-threshold", "0.05", "--log-out", dir / "out.lcm"};
    if (mode == "surveyed") args.insert(args.end(), {"--map", dir / "map.json"});
    const testing::ProgramRun r = Ipe(args, dir);
    ASSERT_EQ(r.exit_code, 0) << mode << ": " << r.output;
    SCOPED_TRACE(r.output);
    ExpectPosesNearTruth(dir / "est.csv", truth, 0.03, mode);
    const auto published = testing::ReadChannel<pose_estimate_t>(dir / "out.lcm", "POSE_IPE");
    ASSERT_EQ(published.size(), truth.size()) << mode;
    for (const auto& e : published) {
      EXPECT_TRUE(e.msg.converged) << mode << ": " << e.msg.status;
      EXPECT_EQ(e.msg.source, "ipe");
      EXPECT_GT(e.msg.num_inliers, 100);
    }
    // Surveyed estimates carry a covariance from the normal equations.
    if (mode == "surveyed") {
      EXPECT_GT(published.back().msg.covariance[0], 0.0);
    }
  }
}

TEST(IconicProcessTest, MapFromTheLineMapChannel) {
  testing::TempDir dir("minenav_ipe_process_test");
  const auto truth = WriteSurveyLog(dir / "in.lcm", true);
  const testing::ProgramRun r = Ipe({"--log", dir / "in.lcm", "--poses-out", dir / "est.csv", "--min-threshold", "0.05"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectPosesNearTruth(dir / "est.csv", truth, 0.03, "LINE_MAP");
}

TEST(IconicProcessTest, BadFlagsAndFilesExitWithTwoAndOneLine) {
  testing::TempDir dir("minenav_ipe_process_test");
  WriteSurveyLog(dir / "in.lcm", false);
  testing::ProgramRun r = Ipe({"--log", dir / "in.lcm", "--mode", "icp"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = Ipe({"--log", dir / "in.lcm", "--map", dir / "missing.json"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.json"), std::string::npos) << r.output;
  SaveSegmentsJson(dir / "degenerate.json", {{1, 1, 1, 1}, {2, 2, 2, 2}});
  r = Ipe({"--log", dir / "in.lcm", "--map", dir / "degenerate.json"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no usable segments"), std::string::npos) << r.output;
  r = Ipe({"--mode", "simultaneous"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("needs the whole sequence"), std::string::npos) << r.output;
  r = Ipe({"--poses-out", dir / "x.csv"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = Ipe({"--log", dir / "in.lcm", "--min-threshold", "5", "--initial-threshold", "1"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(IconicProcessTest, ScansThatMatchNothingAreReportedNotFatal) {
  testing::TempDir dir("minenav_ipe_process_test");
  WriteSurveyLog(dir / "in.lcm", false);
  // A map 100 m away from where the scans were taken.
  SaveSegmentsJson(dir / "far.json", {{100, 100, 110, 100}, {110, 100, 110, 110}, {110, 110, 100, 110}});
  const testing::ProgramRun r = Ipe({"--log", dir / "in.lcm", "--map", dir / "far.json", "--poses-out", dir / "est.csv",
                           "--log-out", dir / "out.lcm"},
                          dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto published = testing::ReadChannel<pose_estimate_t>(dir / "out.lcm", "POSE_IPE");
  ASSERT_EQ(published.size(), 6u);
  for (const auto& e : published) {
    EXPECT_FALSE(e.msg.converged);
    EXPECT_NE(e.msg.status.find("points within"), std::string::npos) << e.msg.status;
  }
  // Initial estimates, one per scan, each marked as no estimate (issue 18).
  const std::vector<StampedPose> est = LoadPosesCsv(dir / "est.csv");
  EXPECT_EQ(est.size(), 6u);
  for (const StampedPose& p : est) EXPECT_EQ(p.status, PoseStatus::kNotConverged) << p.utime;
}

// Issue 12: the estimator's options nested (match.*, correspondence.*, ...); the flat flags
// scripts and tests have always used set the nested keys.
TEST(IconicProcessTest, TheFlatFlagsOfBeforeSetTheNestedKeys) {
  testing::TempDir dir("minenav_ipe_process_test");
  const std::vector<FlagAndConfigLine> flags = {
      {"initial-threshold", "match.initial_threshold = 1.5"}, {"min-threshold", "match.min_threshold = 0.2"},
      {"epsilon-translation", "match.epsilon_translation = 0.001"},
      {"epsilon-rotation", "match.epsilon_rotation = 0.0002"}, {"max-iterations", "match.max_iterations = 40"},
      {"min-correspondences", "match.min_correspondences = 12"}, {"loss", "match.loss = cauchy"},
      {"loss-scale", "match.loss_scale = 0.2"}, {"reject-open-ends", "match.reject_open_ends = false"},
      {"method", "correspondence.method = brute"}, {"cell-size", "correspondence.cell_size = 0.05"},
      {"break-distance", "partial.break_distance = 0.6"}, {"fit-segment-length", "fit.segment_length = 0.4"},
      {"max-pair-distance", "simultaneous.max_pair_distance = 30"},
      {"point-stride", "simultaneous.point_stride = 2"},
      {"every-overlapping-scan", "simultaneous.every_overlapping_scan = false"}};
  const testing::ProgramRun r = Ipe(PrintConfigArgs(flags), dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectConfigLines(r.output, flags);
}

}  // namespace
}  // namespace minenav
