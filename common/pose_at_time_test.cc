#include "common/pose_at_time.h"

#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "common/file_io.h"
#include "common/vehicle_state.h"

namespace minenav {
namespace {

std::deque<OdometryReading> Readings() {
  std::deque<OdometryReading> r(3);
  r[0].utime = 1'000'000;
  r[0].pose = Pose2(0, 0, 3.0);
  r[1].utime = 2'000'000;
  r[1].pose = Pose2(2, 4, -3.0);  // heading crosses +-pi
  r[2].utime = 5'000'000;
  r[2].pose = Pose2(2, 10, 0);
  return r;
}

TEST(PoseAtTimeTest, ExactInterpolatedAndEnds) {
  const auto r = Readings();
  EXPECT_DOUBLE_EQ(PoseAtTime(r, 2'000'000, 100)->y, 4.0);
  const Pose2 mid = *PoseAtTime(r, 1'500'000, 1'000'000);
  EXPECT_NEAR(mid.x, 1.0, 1e-12);
  EXPECT_NEAR(mid.y, 2.0, 1e-12);
  // Halfway from 3.0 to -3.0 the short way round is pi, not 0.
  EXPECT_NEAR(std::abs(mid.theta), kPi, 1e-12);
  EXPECT_NEAR(PoseAtTime(r, 900'000, 200'000)->x, 0.0, 1e-12);     // before the first
  EXPECT_FALSE(PoseAtTime(r, 500'000, 200'000));                   // too far before
  EXPECT_NEAR(PoseAtTime(r, 5'100'000, 200'000)->y, 10.0, 1e-12);  // after the last
  EXPECT_FALSE(PoseAtTime(r, 6'000'000, 200'000));
  EXPECT_FALSE(PoseAtTime(r, 3'000'000, 1'000'000));  // 3 s gap > 2 x 1 s
  EXPECT_TRUE(PoseAtTime(r, 3'000'000, 1'500'000));
  EXPECT_FALSE(PoseAtTime(std::deque<OdometryReading>{}, 0, 1'000'000));
}

// Issue 11, item 5: a scan stamped INT64_MIN overflowed `after->utime - utime` and got the
// first reading's pose although it is 292,000 years before it.
TEST(PoseAtTimeTest, GapLimitsHoldForExtremeStamps) {
  const std::vector<StampedPose> poses = {{-5, {0, 0, 0}}, {1'000'000, {1, 0, 0}}};
  EXPECT_FALSE(PoseAtTime(poses, INT64_MIN, 1'000'000));
  EXPECT_FALSE(PoseAtTime(poses, INT64_MAX, 1'000'000));
  const std::vector<StampedPose> extremes = {{INT64_MIN, {0, 0, 0}}, {INT64_MAX, {1, 0, 0}}};
  EXPECT_FALSE(PoseAtTime(extremes, 0, 1'000'000));
  EXPECT_EQ(TimeGap(INT64_MAX, INT64_MIN), UINT64_MAX);
}

TEST(PoseAtTimeTest, WorksOnStampedPosesAndFindsExactStamps) {
  const std::vector<StampedPose> poses = {{10, {0, 0, 0}}, {20, {1, 0, 0}}};
  EXPECT_NEAR(PoseAtTime(poses, 15, 10)->x, 0.5, 1e-12);
  EXPECT_TRUE(HasReadingAt(poses, 20));
  EXPECT_FALSE(HasReadingAt(poses, 15));
}

}  // namespace
}  // namespace minenav
