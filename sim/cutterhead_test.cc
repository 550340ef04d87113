// The simulated cutterhead: the order constraints of 6.2.1 refused with their reasons, the
// shear's timing, and the cut taken out of the world (checked with brute-force ray casts
// against the world's segments, and the removed area against the rectangle's).

#include "sim/cutterhead.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/geometry.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000;

// A dead-end entry 6 m wide closed at x = 16 (the face) and x = -8.
World Entry() { return World({Segment(-8, -3, 16, -3), Segment(16, -3, 16, 3), Segment(16, 3, -8, 3), Segment(-8, 3, -8, -3)}); }

CutterCommand Cmd(CutterCommand::Action a, double boom = 0.0) {
  CutterCommand c;
  c.action = a;
  c.boom_height = boom;
  return c;
}

DriveCommand Forward(double v) {
  DriveCommand d;
  d.mode = DriveCommand::Mode::kVelocity;
  d.v = v;
  return d;
}

double FaceAt(const World& w, double y) {
  const auto hit = CastRay(Eigen::Vector2d(0, y), 0.0, w.Segments(), 100.0);
  return hit ? hit->range : -1.0;
}

TEST(CutterheadTest, SumpAndShearNeedTheDrumTurning) {
  Cutterhead head({}, 2.4);
  head.Command(Cmd(CutterCommand::Action::kSump), Pose2(), kT0);
  EXPECT_EQ(head.State(kT0).message, "refused SUMP: the drum is not turning");
  EXPECT_EQ(head.State(kT0).phase, CutterState::Phase::kIdle);
  head.Command(Cmd(CutterCommand::Action::kShear), Pose2(), kT0);
  EXPECT_EQ(head.State(kT0).message, "refused SHEAR: the drum is not turning");
  head.Command(Cmd(CutterCommand::Action::kDrumOn), Pose2(), kT0);
  EXPECT_EQ(head.State(kT0).message, "");
  head.Command(Cmd(CutterCommand::Action::kSump), Pose2(), kT0);
  EXPECT_EQ(head.State(kT0).phase, CutterState::Phase::kSumping);
}

TEST(CutterheadTest, NoTrammingWithTheHeadDownButBackingOverTheCuspIsAllowed) {
  const World w = Entry();
  Cutterhead head({}, 2.4);
  head.Command(Cmd(CutterCommand::Action::kSetBoom, 0.0), Pose2(), kT0);
  for (int k = 0; k < 200; ++k) head.Step(0.1, Pose2(), nullptr, kT0);
  EXPECT_DOUBLE_EQ(head.State(kT0).boom_height, 0.0);
  const DriveCommand out = head.FilterDrive(Forward(0.05), Pose2(), w, kT0);
  EXPECT_EQ(out.mode, DriveCommand::Mode::kStop);
  EXPECT_EQ(head.State(kT0).message, "refused DRIVE: no tramming with the head down (boom 0.00 m, below 0.50 m)");
  head.Command(Cmd(CutterCommand::Action::kDrumOn), Pose2(), kT0);
  EXPECT_EQ(head.FilterDrive(Forward(-0.03), Pose2(), w, kT0).mode, DriveCommand::Mode::kVelocity);
  EXPECT_EQ(head.FilterDrive(Forward(0.03), Pose2(), w, kT0).mode, DriveCommand::Mode::kStop);
}

TEST(CutterheadTest, TheDrumCannotBeDrivenIntoTheFaceWithoutTurning) {
  const World w = Entry();
  Cutterhead head({}, 2.4);
  // Not engaged yet (no cutter command): the plain kinematics of before.
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(11, 0, 0), w, kT0).mode, DriveCommand::Mode::kVelocity);
  head.Command(Cmd(CutterCommand::Action::kDrumOff), Pose2(11, 0, 0), kT0);
  // Drum front at x = 11 + 5 = 16: touching the face.
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(11, 0, 0), w, kT0).mode, DriveCommand::Mode::kStop);
  EXPECT_EQ(head.State(kT0).message, "refused DRIVE: no sump without the drum turning (the drum touches the face)");
  // 10 cm short of it: free to tram.
  Cutterhead free({}, 2.4);
  free.Command(Cmd(CutterCommand::Action::kDrumOff), Pose2(10.9, 0, 0), kT0);
  EXPECT_EQ(free.FilterDrive(Forward(0.02), Pose2(10.9, 0, 0), w, kT0).mode, DriveCommand::Mode::kVelocity);
  EXPECT_EQ(free.State(kT0).message, "");
  head.Command(Cmd(CutterCommand::Action::kDrumOn), Pose2(11, 0, 0), kT0);
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(11, 0, 0), w, kT0).mode, DriveCommand::Mode::kVelocity);
}

TEST(CutterheadTest, AShearToTheFloorCutsTheSweptAreaOutOfTheWorld) {
  World w = Entry();
  Cutterhead head({}, 2.4);  // width 3.3, drum radius 0.5, reach 5, shear 12 s from 2.4 m
  head.Command(Cmd(CutterCommand::Action::kDrumOn), Pose2(11, 0, 0), kT0);
  head.Command(Cmd(CutterCommand::Action::kSump), Pose2(11, 0, 0), kT0);
  // Sumped 0.6 m: the drum front at x = 16.6.
  EXPECT_FALSE(head.Step(0.1, Pose2(11.6, 0, 0), &w, kT0));
  EXPECT_NEAR(head.State(kT0).sumped_depth, 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(FaceAt(w, 0.0), 16.0);  // a sump alone does not move the 2D face
  head.Command(Cmd(CutterCommand::Action::kShear), Pose2(11.6, 0, 0), kT0);
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(11.6, 0, 0), w, kT0).mode, DriveCommand::Mode::kStop);
  EXPECT_EQ(head.State(kT0).message, "refused DRIVE: the tracks stay stopped while shearing");
  bool changed = false;
  int steps = 0;
  while (!changed && steps < 1000) {
    changed = head.Step(0.1, Pose2(11.6, 0, 0), &w, kT0);
    ++steps;
  }
  ASSERT_TRUE(changed);
  EXPECT_NEAR(steps * 0.1, 12.0, 0.11);  // the shear time
  const CutterState s = head.State(kT0);
  EXPECT_EQ(s.phase, CutterState::Phase::kCleaning);
  EXPECT_NEAR(s.coal_removed, 3.3 * 0.6, 0.02);
  // The face advanced 0.6 m across the drum's width and stayed put outside it.
  for (double y : {-1.6, -1.0, 0.0, 1.0, 1.6}) EXPECT_NEAR(FaceAt(w, y), 16.6, 1e-9) << y;
  for (double y : {-2.5, 2.5}) EXPECT_NEAR(FaceAt(w, y), 16.0, 1e-9) << y;
}

// Sump 0.6 m from `pose` (drum front at pose.x + 5), then shear to the floor.
void SumpAndShear(Cutterhead& head, World& w, const Pose2& pose, double depth, int64_t t) {
  head.Command(Cmd(CutterCommand::Action::kDrumOn), pose, t);
  head.Command(Cmd(CutterCommand::Action::kSump), pose, t);
  const Pose2 in(pose.x + depth, pose.y, pose.theta);
  head.Step(0.1, in, &w, t);
  head.Command(Cmd(CutterCommand::Action::kShear), in, t);
  for (int k = 0; k < 1000 && !head.Step(0.1, in, &w, t); ++k) {
  }
  head.Command(Cmd(CutterCommand::Action::kSetBoom, 2.4), in, t);
  for (int k = 0; k < 200; ++k) head.Step(0.1, in, &w, t);
}

// Thesis 6.2.1, Figure 40: the slab cut takes the rest of the entry's width beside the box
// cut. The drum overlaps the box cut's free space: it removes only the coal there is (the
// box cut's rib and the uncut strip), and the face ends at one depth across its width.
TEST(CutterheadTest, ASlabCutBesideABoxCutCutsOnlyTheCoalLeft) {
  World w = Entry();
  Cutterhead head({}, 2.4);
  SumpAndShear(head, w, Pose2(11, 0, 0), 0.6, kT0);  // the box cut: y in [-1.65, 1.65]
  EXPECT_NEAR(head.State(kT0).coal_removed, 3.3 * 0.6, 0.02);
  EXPECT_NEAR(FaceAt(w, -2.3), 16.0, 1e-9);
  // The slab: the miner 1.3 m to the right, its drum (y in [-2.95, 0.35]) 2 m over the box cut.
  // Beforehand the drum, off, may come up to the uncut strip but not touch it.
  head.Command(Cmd(CutterCommand::Action::kDrumOff), Pose2(10.95, -1.3, 0), kT0);
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(10.95, -1.3, 0), w, kT0).mode, DriveCommand::Mode::kVelocity);
  EXPECT_EQ(head.FilterDrive(Forward(0.02), Pose2(11.0, -1.3, 0), w, kT0).mode, DriveCommand::Mode::kStop)
      << "the uncut strip touches the drum";
  const double before = head.State(kT0).coal_removed;
  SumpAndShear(head, w, Pose2(11, -1.3, 0), 0.6, kT0);
  // Only the strip y in [-2.95, -1.65] was coal: 1.3 m x 0.6 m.
  EXPECT_NEAR(head.State(kT0).coal_removed - before, 1.3 * 0.6, 0.02);
  for (double y : {-2.9, -2.3, -1.7, -1.6, -1.0, 0.0, 1.0, 1.6}) EXPECT_NEAR(FaceAt(w, y), 16.6, 1e-9) << y;
  EXPECT_NEAR(FaceAt(w, 2.5), 16.0, 1e-9);  // the other side was not in the drum's way
  EXPECT_NEAR(FaceAt(w, -2.98), 16.0, 1e-9);  // nor the 5 cm by the rib
  // The box cut's right rib is gone: nothing across y = -1.65 between x = 16 and 16.6.
  EXPECT_FALSE(CastRay(Eigen::Vector2d(16.3, -1.0), -kPi / 2, w.Segments(), 1.5));
}

TEST(CutterheadTest, EveryOptionIsDeclaredAndReachable) {
  EXPECT_EQ(ExpectEveryOptionReachable<CutterheadOptions>().size(), 9u);
}

TEST(CutterheadTest, ValidatesItsOptions) {
  EXPECT_EQ(ValidateCutterheadOptions({}), "");
  CutterheadOptions o;
  o.tram_height = 3.0;
  EXPECT_EQ(ValidateCutterheadOptions(o), "cutterhead.tram_height must not exceed max_boom_height");
  o = {};
  o.shear_time = 0.0;
  EXPECT_NE(ValidateCutterheadOptions(o), "");
}

}  // namespace
}  // namespace minenav
