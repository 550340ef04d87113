#include "pose_estimator/feature/feature_extraction.h"

#include <gtest/gtest.h>

#include "pose_estimator/feature/feature_test_util.h"

namespace minenav {
namespace {

using testing::AddBox;
using testing::RoomWithPillar;
using testing::SimulateScan;

// Nearest sensed corner to a world point, in the sensor frame of `sensor`.
const Feature* NearestCorner(const ExtractedFeatures& ex, const Pose2& sensor, const Eigen::Vector2d& world) {
  const Eigen::Vector2d q = sensor.inverse() * world;
  const Feature* best = nullptr;
  for (const Feature& f : ex.features) {
    if (f.type != FeatureType::kCorner) continue;
    if (!best || (f.position - q).norm() < (best->position - q).norm()) best = &f;
  }
  return best;
}

TEST(FeatureExtraction, ExactScanOfARoomGivesItsCornersAndWalls) {
  std::vector<Segment> room;
  AddBox(&room, 0, 0, 10, 6);
  const Pose2 pose(4, 2, 0.3);
  const ExtractedFeatures ex = ExtractFeatures(SimulateScan(room, pose, 1000));
  int corners = 0, lines = 0;
  for (const Feature& f : ex.features) (f.type == FeatureType::kCorner ? corners : lines)++;
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(lines, 4);
  for (const Eigen::Vector2d& w : {Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0), Eigen::Vector2d(10, 6), Eigen::Vector2d(0, 6)}) {
    const Feature* c = NearestCorner(ex, pose, w);
    ASSERT_NE(c, nullptr);
    EXPECT_LT((c->position - pose.inverse() * w).norm(), 0.01) << w.transpose();
    EXPECT_NEAR(c->concave_angle, kPi / 2, DegToRad(0.5));
    EXPECT_FALSE(c->occlusion);
  }
  // Wall y = 0 in the sensor frame: distance 2 from the sensor, perpendicular at -90 deg
  // in the map, so at -90 deg - 0.3 rad in the sensor frame.
  bool found = false;
  for (const Feature& f : ex.features) {
    if (f.type == FeatureType::kLine && std::abs(f.distance - 2.0) < 0.01) {
      found = true;
      EXPECT_NEAR(NormalizeAngle(f.orientation - (-kPi / 2 - 0.3)), 0.0, 1e-3);
      EXPECT_NEAR(f.length, 10.0, 0.05);
      EXPECT_GT(f.num_points, 100);
    }
  }
  EXPECT_TRUE(found);
  // Ordered by azimuth.
  for (size_t i = 1; i < ex.features.size(); ++i) {
    EXPECT_LE(ex.features[i - 1].Azimuth(), ex.features[i].Azimuth());
  }
}

TEST(FeatureExtraction, NoisyScanStillLocatesCornersWithinFewCentimetres) {
  std::vector<Segment> room;
  AddBox(&room, 0, 0, 10, 6);
  const Pose2 pose(3, 3.5, -0.4);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ExtractedFeatures ex = ExtractFeatures(SimulateScan(room, pose, 1000, 0.1, seed));
    for (const Eigen::Vector2d& w : {Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0), Eigen::Vector2d(10, 6), Eigen::Vector2d(0, 6)}) {
      const Feature* c = NearestCorner(ex, pose, w);
      ASSERT_NE(c, nullptr);
      EXPECT_LT((c->position - pose.inverse() * w).norm(), 0.08) << "seed " << seed << " corner " << w.transpose();
    }
  }
}

TEST(FeatureExtraction, OccludingEndsOfAPillarBecomeOcclusionCorners) {
  const std::vector<Segment> world = RoomWithPillar();
  const Pose2 pose(3, 3.5, 0.0);
  const ExtractedFeatures ex = ExtractFeatures(SimulateScan(world, pose, 2000));
  // The pillar's west face (7, 3)-(7, 4) ends in two occlusion corners.
  for (const Eigen::Vector2d& w : {Eigen::Vector2d(7, 3), Eigen::Vector2d(7, 4)}) {
    const Feature* c = NearestCorner(ex, pose, w);
    ASSERT_NE(c, nullptr);
    EXPECT_TRUE(c->occlusion);
    EXPECT_LT((c->position - w + Eigen::Vector2d(3, 3.5)).norm(), 0.03);
  }
  // The shadow's ends on the east wall are not corners (they move with the viewpoint):
  // every corner found is a map vertex.
  for (const Feature& f : ex.features) {
    if (f.type != FeatureType::kCorner) continue;
    double nearest = 1e9;
    for (const Segment& s : world) nearest = std::min(nearest, (pose * f.position - s.a).norm());
    EXPECT_LT(nearest, 0.2) << ToString(f);  // (10, 5) has a face seen at 12 deg
  }
}

TEST(FeatureExtraction, CurvedWallsGiveNoFeatures) {
  std::vector<Segment> circle;
  const int n = 120;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
    circle.emplace_back(6 * std::cos(a0), 6 * std::sin(a0), 6 * std::cos(a1), 6 * std::sin(a1));
  }
  const ExtractedFeatures ex = ExtractFeatures(SimulateScan(circle, Pose2(0.5, 0, 0), 1000, 0.02));
  EXPECT_EQ(ex.num_pieces, 1);
  int corners = 0;
  for (const Feature& f : ex.features) corners += f.type == FeatureType::kCorner;
  EXPECT_EQ(corners, 0);
  EXPECT_TRUE(ex.features.empty());
}

TEST(FeatureExtraction, EmptyScanGivesNothing) {
  LadarScan scan;
  scan.start_angle = -kPi;
  scan.angle_step = 0.01;
  scan.min_range = 0.1;
  scan.max_range = 50;
  scan.ranges.assign(600, std::nanf(""));
  const ExtractedFeatures ex = ExtractFeatures(scan);
  EXPECT_EQ(ex.num_points, 0);
  EXPECT_TRUE(ex.features.empty());
}

}  // namespace
}  // namespace minenav
