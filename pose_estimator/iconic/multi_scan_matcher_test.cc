#include "pose_estimator/iconic/multi_scan_matcher.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "common/angle.h"
#include "pose_estimator/iconic/iconic_test_world.h"

namespace minenav {
namespace {

using testing::ExactScan;
using testing::RoomWorld;

std::vector<Eigen::Vector2d> Points(const LadarScan& scan) {
  std::string problem;
  return ValidScanPoints(scan, &problem);
}

const std::vector<Pose2>& Truths() {
  static const std::vector<Pose2> truths = {{3, 2.5, 0.0}, {10, 3, 0.3}, {14, 6, -0.4}, {4, 9, 1.2}, {11, 10, 2.0}};
  return truths;
}

TEST(MultiScanMatcherTest, AllPosesMoveTogetherToTruth) {
  const std::vector<Eigen::Vector3d> errors = {
      {0, 0, 0}, {0.3, -0.2, DegToRad(3)}, {-0.25, 0.3, DegToRad(-4)}, {0.2, 0.25, DegToRad(2)}, {-0.3, -0.1, DegToRad(-3)}};
  std::vector<MultiScanInput> inputs;
  for (size_t k = 0; k < Truths().size(); ++k) {
    MultiScanInput in;
    in.points = Points(ExactScan(RoomWorld(), Truths()[k], 720));
    in.initial = Pose2::FromVector(Truths()[k].vector() + errors[k]);
    in.fixed = k == 0;
    inputs.push_back(in);
  }
  MultiScanOptions o;
  o.match.min_threshold = 0.05;
  const MultiScanResult r = MatchScansSimultaneously(inputs, o);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(r.poses[0].x, Truths()[0].x);  // the fixed scan stays put
  for (size_t k = 1; k < Truths().size(); ++k) {
    // Raw polylines cut corners by a few mm; the poses land within a centimetre.
    EXPECT_LT(TranslationDistance(r.poses[k], Truths()[k]), 0.01) << "scan " << k;
    EXPECT_LT(HeadingDistance(r.poses[k], Truths()[k]), DegToRad(0.1)) << "scan " << k;
    EXPECT_GT(r.covariances[k].determinant(), 0.0);
    EXPECT_GT(r.inliers[k], 100);
  }
  EXPECT_TRUE(r.covariances[0].isZero());
  EXPECT_LT(r.residual, 0.01);
}

TEST(MultiScanMatcherTest, RejectsProblemsWithAReason) {
  MultiScanInput a, b;
  a.points = Points(ExactScan(RoomWorld(), Truths()[0], 360));
  b.points = Points(ExactScan(RoomWorld(), Truths()[1], 360));
  a.initial = Truths()[0];
  b.initial = Truths()[1];
  MultiScanOptions o;
  EXPECT_NE(MatchScansSimultaneously({a, b}, o).status.find("no scan is fixed"), std::string::npos);
  EXPECT_NE(MatchScansSimultaneously({a}, o).status.find("at least 2 scans"), std::string::npos);
  a.fixed = true;
  // b placed 200 m away overlaps nothing.
  MultiScanInput far = b;
  far.initial = Pose2(200, 0, 0);
  o.max_pair_distance = 1000.0;
  const MultiScanResult lost = MatchScansSimultaneously({a, far}, o);
  EXPECT_FALSE(lost.converged);
  EXPECT_NE(lost.status.find("scan 1 has only 0 points"), std::string::npos) << lost.status;
  MultiScanInput empty = b;
  empty.points.clear();
  EXPECT_FALSE(MatchScansSimultaneously({a, empty}, o).converged);
  o.point_stride = 0;
  EXPECT_NE(MatchScansSimultaneously({a, b}, o).status.find("point_stride"), std::string::npos);
}

}  // namespace
}  // namespace minenav
