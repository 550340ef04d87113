// The cutter library alone: finding the face in a map, the refusals of Start with their
// one-line reasons, the first steps of the cycle against a hand-fed appendage state, and
// the options' validation.

#include "tracker/cutter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000;

// A dead-end entry 6 m wide with its face at x = 16.
std::vector<Segment> Entry() {
  return {Segment(-8, -3, 16, -3), Segment(16, -3, 16, 3), Segment(16, 3, -8, 3), Segment(-8, 3, -8, -3)};
}

CutterState StateAt(int64_t t, double boom, bool drum) {
  CutterState s;
  s.utime = t;
  s.boom_height = boom;
  s.drum_on = drum;
  return s;
}

TEST(CutterTest, FindsTheFaceStraightAheadAcrossTheDrumsWidth) {
  const auto face = FindFace(Entry(), Pose2(9, 0.3, 0.1), CutterOptions{});
  ASSERT_TRUE(face);
  EXPECT_NEAR(face->a.x(), 16.0, 1e-9);
  EXPECT_NEAR(face->b.x(), 16.0, 1e-9);
  EXPECT_GT(face->length(), 2.5);  // the drum's width, seen from the skewed heading
  // Nothing within reach: 11 m from the drum.
  EXPECT_FALSE(FindFace(Entry(), Pose2(0, 0, 0), CutterOptions{}));
  // A face whose line is oblique is fitted, not snapped.
  const std::vector<Segment> oblique = {Segment(15, -3, 17, 3)};
  const auto f = FindFace(oblique, Pose2(10, 0, 0), CutterOptions{});
  ASSERT_TRUE(f);
  EXPECT_NEAR((f->b - f->a).normalized().cwiseAbs().dot(Eigen::Vector2d(1, 3).normalized()), 1.0, 1e-9);
}

TEST(CutterTest, RefusesACutWithoutAFaceInReachOrAPose) {
  Cutter c{CutterOptions{}};
  const StampedPose pose{kT0, Pose2(0, 0, 0)};
  EXPECT_EQ(c.Start({1, 1.0, std::nullopt}, pose, Entry(), kT0),
            "refused: no face in reach: nothing in the map within 3.0 m ahead of the cutterhead");
  EXPECT_EQ(c.status().state, CutterStatus::State::kFailed);
  EXPECT_EQ(c.status().message, "refused: no face in reach: nothing in the map within 3.0 m ahead of the cutterhead");
  EXPECT_EQ(c.Start({2, 1.0, Segment(16, -3, 16, 3)}, pose, {}, kT0),
            "refused: no face in reach: the face is 11.00 m ahead of the cutterhead (reach 3.00 m)");
  EXPECT_EQ(c.Start({3, 1.0, Segment(16, 5, 16, 9)}, StampedPose{kT0, Pose2(10, 0, 0)}, {}, kT0),
            "refused: no face in reach: the face line does not lie ahead of the vehicle");
  EXPECT_EQ(c.Start({4, 1.0, Segment(16, -3, 16, 3)}, StampedPose{kT0, Pose2(10, 0, 0.8)}, {}, kT0),
            "refused: the face is 45.8 deg off the heading (at most 34.4 deg)");
  EXPECT_EQ(c.Start({5, 1.0, Segment(16, -3, 16, 3)}, std::nullopt, {}, kT0), "refused: no pose estimate yet");
  EXPECT_EQ(c.Start({6, 1.0, Segment(16, -3, 16, 3)}, StampedPose{kT0 - 5'000'000, Pose2(10, 0, 0)}, {}, kT0),
            "refused: the pose estimate is 5.0 s old (limit 2.0 s)");
  EXPECT_EQ(c.Start({7, 0.0, Segment(16, -3, 16, 3)}, StampedPose{kT0, Pose2(10, 0, 0)}, {}, kT0),
            "refused: the depth of cut must be positive");
  EXPECT_FALSE(c.active());
  EXPECT_FALSE(c.Update(kT0, pose, StateAt(kT0, 2.4, false)).drive);  // no cut, no drive command
}

// A slab cut (thesis 6.2.1): the face given is the part left beside a box cut, across only
// part of the drum (the vehicle's centre is not in front of it); its line gives the normal
// to square up to and the depth is measured from it.
TEST(CutterTest, TakesAFaceAcrossPartOfTheDrumAndSquaresUpToItsLine) {
  Cutter c{CutterOptions{}};  // drum 3.3 m wide: y in [-2.95, 0.35] at y = -1.3
  const StampedPose pose{kT0, Pose2(9, -1.3, 0.03)};
  ASSERT_EQ(c.Start({1, 1.0, Segment(16, -3, 16, -1.45)}, pose, {}, kT0), "");
  EXPECT_NEAR(c.DepthAt(Pose2(11, -1.3, 0)), 0.0, 1e-12);
  EXPECT_NEAR(c.DepthAt(Pose2(12, 0, 0)), 1.0, 1e-12);
  // A face line turned 5 deg: the heading to square up to is its normal.
  Cutter skew{CutterOptions{}};
  const Eigen::Vector2d dir(-std::sin(DegToRad(5.0)), std::cos(DegToRad(5.0)));
  const Eigen::Vector2d on(16, -2.2);
  ASSERT_EQ(skew.Start({2, 1.0, Segment(on - 0.8 * dir, on + 0.8 * dir)}, pose, {}, kT0), "");
  int64_t t = kT0;
  Cutter::Output out;
  for (int k = 0; k < 3; ++k) {
    t += 100'000;
    out = skew.Update(t, StampedPose{t, Pose2(9, -1.3, 0.03)}, StateAt(t, 2.4, false));
  }
  ASSERT_EQ(skew.status().step, "squaring up");
  EXPECT_GT(out.drive->omega, 0.0) << "towards 5 deg from 1.7 deg";
  for (int k = 0; k < 2; ++k) {
    t += 100'000;
    out = skew.Update(t, StampedPose{t, Pose2(9, -1.3, DegToRad(5.0))}, StateAt(t, 2.4, false));
  }
  EXPECT_EQ(skew.status().step, "approaching the face");
  // Beside the drum, not across it: refused.
  EXPECT_EQ(c.Start({3, 1.0, Segment(16, -3, 16, -2.96)}, StampedPose{kT0, Pose2(9, -1.3, 0)}, {}, kT0),
            "refused: no face in reach: the face line does not lie ahead of the vehicle");
}

TEST(CutterTest, SquaresUpByTurningInPlaceThenTramsToTheFace) {
  Cutter c{CutterOptions{}};
  int64_t t = kT0;
  ASSERT_EQ(c.Start({1, 1.0, Segment(16, -3, 16, 3)}, StampedPose{t, Pose2(10, 0, 0.05)}, {}, t), "");
  EXPECT_NEAR(c.DepthAt(Pose2(11, 0, 0)), 0.0, 1e-12);
  auto step = [&](const Pose2& p, double boom, int64_t dt = 100'000, int64_t state_age = 0) {
    t += dt;
    return c.Update(t, StampedPose{t, p}, StateAt(t - state_age, boom, false));
  };
  // The boom is raised first (SET_BOOM to the top) and nothing moves meanwhile.
  Cutter::Output out = step(Pose2(10, 0, 0.05), 1.0);
  ASSERT_TRUE(out.cutter);
  EXPECT_EQ(out.cutter->action, CutterCommand::Action::kSetBoom);
  EXPECT_DOUBLE_EQ(out.cutter->boom_height, 2.4);
  EXPECT_EQ(out.drive->mode, DriveCommand::Mode::kStop);
  out = step(Pose2(10, 0, 0.05), 2.4);
  EXPECT_EQ(c.status().step, "squaring up");
  out = step(Pose2(10, 0, 0.05), 2.4);
  EXPECT_EQ(out.drive->mode, DriveCommand::Mode::kTurnInPlace);
  EXPECT_LT(out.drive->omega, 0.0);  // clockwise, toward heading 0
  out = step(Pose2(10, 0, 0.001), 2.4);
  out = step(Pose2(10, 0, 0.001), 2.4);
  EXPECT_EQ(c.status().step, "approaching the face");
  EXPECT_EQ(out.drive->mode, DriveCommand::Mode::kVelocity);
  EXPECT_DOUBLE_EQ(out.drive->v, 0.05);
  EXPECT_DOUBLE_EQ(out.drive->timeout, CutterOptions{}.command_timeout);
  // No appendage state for longer than state_timeout: stopped.
  out = step(Pose2(10.5, 0, 0.001), 2.4, 2'500'000, 2'500'000);
  EXPECT_EQ(c.status().message, "stopped: no CUTTER_STATE for 2.0 s");
  EXPECT_EQ(out.drive->mode, DriveCommand::Mode::kStop);
  ASSERT_TRUE(out.cutter);
  EXPECT_EQ(out.cutter->action, CutterCommand::Action::kStop);
  t += 100'000;
  EXPECT_FALSE(c.Update(t, std::nullopt, std::nullopt).drive);  // and then silence
}

TEST(CutterTest, AVehicleRefusalStopsTheCut) {
  Cutter c{CutterOptions{}};
  int64_t t = kT0;
  ASSERT_EQ(c.Start({1, 1.0, Segment(16, -3, 16, 3)}, StampedPose{t, Pose2(10, 0, 0)}, {}, t), "");
  CutterState s = StateAt(t + 100'000, 2.4, false);
  s.message = "refused SUMP: the drum is not turning";
  c.Update(t + 100'000, StampedPose{t, Pose2(10, 0, 0)}, s);
  EXPECT_EQ(c.status().message, "stopped: the vehicle refused SUMP: the drum is not turning");
}

TEST(CutterTest, ValidatesItsOptions) {
  EXPECT_EQ(ValidateCutterOptions({}), "");
  CutterOptions o;
  o.sump_speed = 0.0;
  EXPECT_NE(ValidateCutterOptions(o), "");
  o = {};
  o.max_cycles = 0;
  EXPECT_EQ(ValidateCutterOptions(o), "cutter: max_cycles must be at least 1");
}

}  // namespace
}  // namespace minenav
