#include "evaluation/relations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/angle.h"

namespace minenav {
namespace {

constexpr int64_t kSec = 1000000;

StampedPose At(double t, double x, double y, double theta) { return {std::llround(t * 1e6), Pose2(x, y, theta)}; }

TEST(RelationsTest, ParsesRelationsFile) {
  const auto r = ParseRelations(
      "# comment\n976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 -1.682210\n\n"
      "1 2 0.5 0.25 0 0 0 4.0\n",
      "r.txt");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].utime1, 976052905167303);
  EXPECT_EQ(r[0].utime2, 976052911885496);
  EXPECT_DOUBLE_EQ(r[0].delta.x, -0.05699);
  EXPECT_DOUBLE_EQ(r[0].delta.theta, -1.68221);
  EXPECT_NEAR(r[1].delta.theta, 4.0 - 2 * kPi, 1e-12);  // wrapped
}

TEST(RelationsTest, MalformedLinesNameFileAndLine) {
  auto message = [](const std::string& text) {
    try {
      ParseRelations(text, "r.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("1 2 3\n"), "r.txt:1: expected 8 fields (t1 t2 x y z roll pitch yaw), got 3");
  EXPECT_EQ(message("\n1 2 0 0 0 0 0 x\n"), "r.txt:2: yaw 'x' is not a finite number");
  EXPECT_EQ(message("a 2 0 0 0 0 0 0\n"), "r.txt:1: t1 'a' is not a time in seconds");
}

TEST(RelationsTest, ExactSmallCase) {
  // Estimates at 1, 2, 3 s; the relations disagree with them by known amounts.
  const std::vector<StampedPose> est = {At(3, 1, 1, kPi / 2), At(1, 0, 0, 0), At(2, 1, 0, kPi / 2)};
  std::vector<Relation> rel(2);
  rel[0] = {1 * kSec, 2 * kSec, Pose2(1.1, 0.0, kPi / 2 + 0.1)};  // estimate: (1, 0, pi/2)
  rel[1] = {2 * kSec, 3 * kSec, Pose2(1.0, 0.2, -0.05)};           // estimate: (1, 0, 0)
  const RelationScore s = ScoreRelations(rel, est, {});
  ASSERT_TRUE(s.ok) << s.reason;
  EXPECT_EQ(s.n, 2);
  EXPECT_EQ(s.skipped, 0);
  EXPECT_EQ(s.odometry_corrected, 0);
  EXPECT_NEAR(s.entries[0].translation_error, 0.1, 1e-12);
  EXPECT_NEAR(s.entries[0].rotation_error, 0.1, 1e-12);
  EXPECT_NEAR(s.entries[1].translation_error, 0.2, 1e-12);
  EXPECT_NEAR(s.entries[1].rotation_error, 0.05, 1e-12);
  EXPECT_NEAR(s.translation.mean, 0.15, 1e-12);
  EXPECT_NEAR(s.translation.std, std::sqrt(2 * 0.05 * 0.05), 1e-12);  // sample std, N - 1 = 1
  EXPECT_NEAR(s.translation_squared.mean, 0.025, 1e-12);
  EXPECT_NEAR(s.translation_squared.std, std::sqrt(2 * 0.015 * 0.015), 1e-12);
  const double r0 = RadToDeg(0.1), r1 = RadToDeg(0.05);
  EXPECT_NEAR(s.rotation.mean, (r0 + r1) / 2, 1e-9);
  EXPECT_NEAR(s.rotation.std, std::abs(r0 - r1) / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(s.rotation_squared.mean, (r0 * r0 + r1 * r1) / 2, 1e-9);
}

// Issue 18: a row marked not_converged (the guess a match started from) is no estimate: a
// relation at its time is scored from the estimate before it moved on by odometry, or skipped.
TEST(RelationsTest, RowsNotConvergedAreLeftOutAndCounted) {
  StampedPose guess = At(2.0, 5, 5, 1.0);  // far off: scored, it would cost metres
  guess.status = PoseStatus::kNotConverged;
  StampedPose tracked = At(1.0, 0, 0, 0);
  tracked.status = PoseStatus::kTracked;
  const std::vector<StampedPose> est = {tracked, guess};
  const std::vector<StampedPose> odo = {At(0.0, 0, 0, 0), At(3.0, 3, 0, 0)};
  const std::vector<Relation> rel = {{1 * kSec, 2 * kSec, Pose2(1.0, 0.0, 0.0)}};

  const RelationScore s = ScoreRelations(rel, est, odo);
  ASSERT_TRUE(s.ok) << s.reason;
  EXPECT_EQ(s.not_estimates, 1);
  EXPECT_EQ(s.n, 1);
  EXPECT_EQ(s.odometry_corrected, 1);  // the pose at 2 s came from 1 s through odometry
  EXPECT_NEAR(s.entries[0].translation_error, 0.0, 1e-12);

  const RelationScore none = ScoreRelations(rel, {guess}, {});
  EXPECT_FALSE(none.ok);
  EXPECT_EQ(none.reason, "no estimated poses (1 rows not converged)");
  const RelationScore skipped = ScoreRelations(rel, est, {});  // no odometry to bridge the gap
  EXPECT_FALSE(skipped.ok);
  EXPECT_EQ(skipped.skipped, 1);
}

TEST(RelationsTest, NearestWithinGapIsUsedUncorrected) {
  // 0.08 s off: within 0.1 s, used as is even though odometry says the robot moved.
  const std::vector<StampedPose> est = {At(1.0, 0, 0, 0), At(2.08, 2, 0, 0)};
  const std::vector<StampedPose> odo = {At(0.0, 0, 0, 0), At(3.0, 3, 0, 0)};
  const std::vector<Relation> rel = {{1 * kSec, 2 * kSec, Pose2(2.0, 0.0, 0.0)}};
  const RelationScore s = ScoreRelations(rel, est, odo);
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(s.odometry_corrected, 0);
  EXPECT_NEAR(s.entries[0].translation_error, 0.0, 1e-12);
}

TEST(RelationsTest, FarEstimateIsCorrectedWithOdometry) {
  // No estimate near t = 2 s: the nearest one (t = 1 s, a tie with t = 3 s goes to the
  // earlier) is moved on by the odometry from 1 s to 2 s. Odometry frame rotated against
  // the map: its motion (1, 0) in its own frame at heading 0 is the robot moving forward.
  const std::vector<StampedPose> est = {At(1, 5, 5, kPi / 2), At(3, 5, 7, kPi / 2)};
  const std::vector<StampedPose> odo = {At(0, 10, 0, 0), At(1, 11, 0, 0), At(3, 13, 0, 0.2)};
  // O(2) = interpolated (12, 0, 0.1); O(1)^-1 O(2) = (1, 0, 0.1); P(2) = (5, 6, pi/2 + 0.1).
  const std::vector<Relation> rel = {{1 * kSec, 2 * kSec, Pose2(1.0, 0.0, 0.1)},
                                     {1 * kSec, 2 * kSec, Pose2(1.3, 0.4, 0.0)}};
  const RelationScore s = ScoreRelations(rel, est, odo);
  ASSERT_TRUE(s.ok) << s.reason;
  EXPECT_EQ(s.odometry_corrected, 2);
  EXPECT_NEAR(s.entries[0].translation_error, 0.0, 1e-12);
  EXPECT_NEAR(s.entries[0].rotation_error, 0.0, 1e-12);
  EXPECT_NEAR(s.entries[1].translation_error, 0.5, 1e-12);
  EXPECT_NEAR(s.entries[1].rotation_error, 0.1, 1e-12);

  // Without odometry those relations cannot be scored.
  const RelationScore none = ScoreRelations(rel, est, {});
  EXPECT_FALSE(none.ok);
  EXPECT_EQ(none.skipped, 2);
  EXPECT_NE(none.reason.find("no odometry"), std::string::npos) << none.reason;
}

TEST(RelationsTest, EmptyInputsGiveReasons) {
  EXPECT_EQ(ScoreRelations({}, {At(1, 0, 0, 0)}, {}).reason, "no relations");
  EXPECT_EQ(ScoreRelations({{0, 1, Pose2()}}, {}, {}).reason, "no estimated poses");
  const ErrorStatistic one = MeanAndSampleStd({2.0});
  EXPECT_DOUBLE_EQ(one.mean, 2.0);
  EXPECT_DOUBLE_EQ(one.std, 0.0);
}

}  // namespace
}  // namespace minenav
