#include "pose_estimator/iconic/iconic_estimator.h"

#include <gtest/gtest.h>

#include "common/angle.h"
#include "common/pose_estimate.h"
#include "pose_estimator/iconic/iconic_test_world.h"

namespace minenav {
namespace {

using testing::ExactScan;
using testing::RoomWorld;

TEST(IconicEstimatorTest, EveryModeTracksASequence) {
  const std::vector<Pose2> truths = {{3, 2.5, 0.0}, {5, 2.8, 0.1}, {7, 3.0, 0.2}, {9, 2.8, 0.3}, {11, 2.5, 0.25}};
  std::vector<LadarScan> scans;
  std::vector<Pose2> initials;
  for (size_t k = 0; k < truths.size(); ++k) {
    scans.push_back(ExactScan(RoomWorld(), truths[k], 720, 0.01, static_cast<uint32_t>(k + 1),
                              static_cast<int64_t>(k) * 1000000));
    // The first pose is known (it defines the map frame); the others carry odometry error.
    const double e = k == 0 ? 0.0 : 0.25;
    initials.push_back(Pose2(truths[k].x + e, truths[k].y - e, truths[k].theta + DegToRad(k == 0 ? 0 : 3)));
  }
  for (IconicMode mode : {IconicMode::kSurveyed, IconicMode::kScanMap, IconicMode::kFirstScan,
                          IconicMode::kAllPrevious, IconicMode::kSimultaneous}) {
    IconicEstimatorOptions o;
    o.mode = mode;
    o.match.min_threshold = 0.05;
    const auto results = EstimateSequence(scans, initials, RoomWorld(), o);
    ASSERT_EQ(results.size(), truths.size());
    for (size_t k = 0; k < truths.size(); ++k) {
      ASSERT_TRUE(results[k].converged) << ToString(mode) << " scan " << k << ": " << results[k].status;
      EXPECT_LT(TranslationDistance(results[k].pose, truths[k]), 0.02) << ToString(mode) << " scan " << k;
      EXPECT_LT(HeadingDistance(results[k].pose, truths[k]), DegToRad(0.2)) << ToString(mode) << " scan " << k;
    }
  }
}

TEST(IconicEstimatorTest, ModesParseAndBadMapIsReported) {
  IconicMode mode;
  for (const char* name : {"surveyed", "scan-map", "first-scan", "all-previous", "simultaneous"}) {
    ASSERT_TRUE(ParseIconicMode(name, &mode));
    EXPECT_STREQ(ToString(mode), name);
  }
  EXPECT_FALSE(ParseIconicMode("icp", &mode));

  IconicEstimator estimator(IconicEstimatorOptions{});
  EXPECT_NE(estimator.SetMap({{0, 0, 0, 0}}).find("no usable segments"), std::string::npos);
  const LadarScan scan = ExactScan(RoomWorld(), Pose2(3, 3, 0), 360);
  EXPECT_EQ(estimator.AddScan(scan, Pose2(3, 3, 0)).status, "no map yet");
  EXPECT_EQ(estimator.SetMap(RoomWorld()), "");
  const IconicMatchResult r = estimator.AddScan(scan, Pose2(3.2, 3.1, 0.02));
  EXPECT_TRUE(r.converged) << r.status;
  const PoseEstimate e = MakePoseEstimate(r, scan.utime, scan.scan_id, "ipe", 0.0);
  EXPECT_EQ(e.source, "ipe");
  EXPECT_EQ(e.num_inliers, r.num_inliers);
}

}  // namespace
}  // namespace minenav
