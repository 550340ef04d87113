#include "sim/skid_steer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/angle.h"

namespace minenav {
namespace {

DriveCommand Velocity(double v, double omega, int64_t utime = 0, double timeout = 1e9) {
  DriveCommand c;
  c.mode = DriveCommand::Mode::kVelocity;
  c.v = v;
  c.omega = omega;
  c.utime = utime;
  c.timeout = timeout;
  return c;
}

SkidSteerOptions Instant() {
  SkidSteerOptions o;
  o.max_acceleration = 0.0;
  o.max_deceleration = 0.0;
  o.max_yaw_acceleration = 0.0;
  return o;
}

// Runs `seconds` in steps of dt under one command.
void Drive(SkidSteerVehicle* v, const DriveCommand& c, double seconds, double dt) {
  const int n = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < n; ++i) v->Step(dt, c, c.utime);
}

TEST(SkidSteerTest, StraightAtCruiseSpeed) {
  SkidSteerVehicle v(Instant(), Pose2(1.0, 2.0, kPi / 2));
  Drive(&v, Velocity(0.076, 0.0), 100.0, 0.1);
  EXPECT_NEAR(v.pose().x, 1.0, 1e-12);
  EXPECT_NEAR(v.pose().y, 2.0 + 7.6, 1e-9);
  EXPECT_NEAR(v.pose().theta, kPi / 2, 1e-12);
  EXPECT_EQ(v.motion(), SkidSteerMotion::kStraight);
}

TEST(SkidSteerTest, ArcMatchesClosedFormCircle) {
  const SkidSteerOptions o = Instant();
  const double R = o.turn_radius, speed = 0.05;
  SkidSteerVehicle v(o);
  const double T = 200.0;  // 10 m of arc: 2.5 rad
  Drive(&v, Velocity(speed, speed / R), T, 0.1);
  const double phi = speed * T / R;
  EXPECT_NEAR(v.pose().x, R * std::sin(phi), 1e-9);
  EXPECT_NEAR(v.pose().y, R * (1.0 - std::cos(phi)), 1e-9);
  EXPECT_NEAR(v.pose().theta, NormalizeAngle(phi), 1e-9);
  EXPECT_NEAR(v.omega(), speed / R, 1e-15);
  // Backwards with omega > 0 (k = omega / v = -1/R): the rear swings right, the heading
  // turns counter-clockwise; the mirror image of the forward arc.
  SkidSteerVehicle back(o);
  Drive(&back, Velocity(-speed, speed / R), T, 0.25);
  EXPECT_NEAR(back.pose().x, -R * std::sin(phi), 1e-9);
  EXPECT_NEAR(back.pose().y, -R * (1.0 - std::cos(phi)), 1e-9);
  EXPECT_NEAR(back.pose().theta, phi, 1e-9);
  EXPECT_NEAR(back.omega(), speed / R, 1e-15);
}

TEST(SkidSteerTest, ClampingPicksStraightArcOrTurnInPlace) {
  const SkidSteerOptions o;  // R = 4 m
  auto clamp = [&](double v, double w) { return ClampDriveCommand(Velocity(v, w), o); };
  EXPECT_EQ(clamp(0.05, 0.05 / 10.0).motion, SkidSteerMotion::kStraight);  // R 10 m > 2R
  const ClampedCommand arc = clamp(0.05, 0.05 / 3.0);                     // R 3 m: the 4 m arc
  EXPECT_EQ(arc.motion, SkidSteerMotion::kArc);
  EXPECT_DOUBLE_EQ(arc.curvature, 0.25);
  EXPECT_DOUBLE_EQ(clamp(0.05, -0.05 / 7.0).curvature, -0.25);
  EXPECT_EQ(clamp(0.05, 0.05 / 1.0).motion, SkidSteerMotion::kTurnInPlace);  // R 1 m < R/2
  EXPECT_EQ(clamp(0.0, 0.02).motion, SkidSteerMotion::kTurnInPlace);
  EXPECT_DOUBLE_EQ(clamp(0.0, 1.0).yaw_rate, o.max_turn_in_place_rate);
  EXPECT_DOUBLE_EQ(clamp(0.0, -1.0).yaw_rate, -o.max_turn_in_place_rate);
  EXPECT_DOUBLE_EQ(clamp(1.0, 0.0).speed, o.max_forward_speed);
  EXPECT_DOUBLE_EQ(clamp(-1.0, 0.0).speed, -o.max_reverse_speed);
  EXPECT_EQ(clamp(0.0, 0.0).motion, SkidSteerMotion::kStopped);
  EXPECT_EQ(clamp(NAN, 0.0).motion, SkidSteerMotion::kStopped);
  DriveCommand stop = Velocity(0.05, 0.0);
  stop.mode = DriveCommand::Mode::kStop;
  EXPECT_EQ(ClampDriveCommand(stop, o).motion, SkidSteerMotion::kStopped);
  DriveCommand spin = Velocity(0.05, 0.03);
  spin.mode = DriveCommand::Mode::kTurnInPlace;
  EXPECT_EQ(ClampDriveCommand(spin, o).motion, SkidSteerMotion::kTurnInPlace);
  EXPECT_DOUBLE_EQ(ClampDriveCommand(spin, o).yaw_rate, 0.03);
}

TEST(SkidSteerTest, TurnInPlaceKeepsPosition) {
  SkidSteerVehicle v(Instant(), Pose2(3.0, 4.0, 0.0));
  DriveCommand spin = Velocity(0.0, 0.5);  // clamped to 0.05 rad/s
  Drive(&v, spin, 20.0, 0.05);
  EXPECT_DOUBLE_EQ(v.pose().x, 3.0);
  EXPECT_DOUBLE_EQ(v.pose().y, 4.0);
  EXPECT_NEAR(v.pose().theta, 1.0, 1e-12);
  EXPECT_EQ(v.motion(), SkidSteerMotion::kTurnInPlace);
}

TEST(SkidSteerTest, AccelerationIsIntegratedExactlyWhateverTheStep) {
  const SkidSteerOptions o;  // accel 0.05 m/s^2 up to 0.076 m/s: 1.52 s of ramp
  SkidSteerVehicle coarse(o), fine(o);
  const DriveCommand c = Velocity(0.076, 0.076 / 4.0);
  coarse.Step(1.0, c, 0);
  EXPECT_NEAR(coarse.speed(), 0.05, 1e-15);
  // s = a t^2 / 2 = 0.025 m on the 4 m arc.
  const Pose2 expect = ArcDelta(0.025, 0.25);
  EXPECT_NEAR(coarse.pose().x, expect.x, 1e-15);
  EXPECT_NEAR(coarse.pose().y, expect.y, 1e-15);
  coarse.Step(9.0, c, 0);
  Drive(&fine, c, 10.0, 0.01);
  // Ramp 1.52 s (0.05776 m), then 8.48 s at 0.076 m/s.
  const double s = 0.5 * 0.05 * 1.52 * 1.52 + 0.076 * 8.48;
  const Pose2 total = ArcDelta(s, 0.25);
  for (const SkidSteerVehicle* v : {&coarse, &fine}) {
    EXPECT_NEAR(v->pose().x, total.x, 1e-9);
    EXPECT_NEAR(v->pose().y, total.y, 1e-9);
    EXPECT_NEAR(v->pose().theta, total.theta, 1e-9);
  }
}

TEST(SkidSteerTest, StaleCommandStops) {
  const SkidSteerOptions o;  // decel 0.1 m/s^2
  SkidSteerVehicle v(o);
  DriveCommand c = Velocity(0.076, 0.0, /*utime=*/0, /*timeout=*/0.5);
  for (int i = 0; i < 5; ++i) v.Step(0.1, c, i * 100000);  // fresh: 0 .. 0.4 s
  EXPECT_FALSE(v.stale());
  EXPECT_GT(v.speed(), 0.0);
  const double x_before = v.pose().x;
  const double speed = v.speed();
  v.Step(0.1, c, 600000);  // 0.6 s old: stale
  EXPECT_TRUE(v.stale());
  // Decelerates: v0 = speed, a = -0.1 for min(0.1, v0 / 0.1) s.
  const double t = std::min(0.1, speed / 0.1);
  EXPECT_NEAR(v.pose().x - x_before, speed * t - 0.05 * t * t, 1e-12);
  for (int i = 0; i < 20; ++i) v.Step(0.1, c, 700000 + i * 100000);
  EXPECT_EQ(v.speed(), 0.0);
  const Pose2 stopped = v.pose();
  v.Step(1.0, c, 5000000);
  EXPECT_EQ(v.pose().x, stopped.x);
  // A fresh command starts it again; no command at all stops it.
  c.utime = 5000000;
  v.Step(1.0, c, 5100000);
  EXPECT_GT(v.speed(), 0.0);
  v.StepWithoutCommand(5.0);
  EXPECT_EQ(v.speed(), 0.0);
  // A command whose timeout is 0 falls back to options.command_timeout (0.5 s).
  DriveCommand no_timeout = Velocity(0.05, 0.0, 0, 0.0);
  SkidSteerVehicle w(o);
  w.Step(0.1, no_timeout, 400000);
  EXPECT_FALSE(w.stale());
  w.Step(0.1, no_timeout, 600000);
  EXPECT_TRUE(w.stale());
}

// Issue 11: one command with timeout = 1e9, then silence, drove the vehicle for ever. The
// vehicle's own stale limit (command_timeout) caps the command's: whichever is shorter.
TEST(SkidSteerTest, TheVehiclesStaleLimitCapsALongCommandTimeout) {
  SkidSteerOptions o = Instant();
  o.command_timeout = 0.5;
  SkidSteerVehicle v(o);
  const DriveCommand forever = Velocity(0.05, 0.0, /*utime=*/0, /*timeout=*/1e9);
  v.Step(0.1, forever, 400000);  // 0.4 s old: within both limits
  EXPECT_FALSE(v.stale());
  EXPECT_DOUBLE_EQ(v.speed(), 0.05);
  v.Step(0.1, forever, 600000);  // 0.6 s old: past the vehicle's 0.5 s
  EXPECT_TRUE(v.stale());
  EXPECT_EQ(v.speed(), 0.0);
  const double x_stopped = v.pose().x;
  for (int i = 0; i < 100; ++i) v.Step(0.1, forever, 700000 + i * 100000);  // 10 s more of silence
  EXPECT_EQ(v.pose().x, x_stopped) << "a stale command moved the vehicle";

  // A command's shorter timeout still wins over the vehicle's limit.
  SkidSteerVehicle w(o);
  const DriveCommand brief = Velocity(0.05, 0.0, /*utime=*/0, /*timeout=*/0.2);
  w.Step(0.1, brief, 150000);
  EXPECT_FALSE(w.stale());
  w.Step(0.1, brief, 250000);
  EXPECT_TRUE(w.stale());
  // Infinite or NaN timeouts count as none: the vehicle's limit applies.
  for (const double odd : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    SkidSteerVehicle u(o);
    u.Step(0.1, Velocity(0.05, 0.0, 0, odd), 400000);
    EXPECT_FALSE(u.stale()) << odd;
    u.Step(0.1, Velocity(0.05, 0.0, 0, odd), 600000);
    EXPECT_TRUE(u.stale()) << odd;
  }
}

TEST(SkidSteerTest, StopsBeforeSwitchingBetweenDrivingAndSpinning) {
  SkidSteerOptions o;
  o.max_deceleration = 0.076;  // 1 s to stop from cruise
  SkidSteerVehicle v(o);
  Drive(&v, Velocity(0.076, 0.0), 5.0, 0.1);
  ASSERT_NEAR(v.speed(), 0.076, 1e-12);
  const double x0 = v.pose().x;
  v.Step(0.5, Velocity(0.0, 0.05), 0);  // wants to spin: first brakes for 1 s
  EXPECT_NEAR(v.speed(), 0.038, 1e-12);
  EXPECT_NEAR(v.pose().theta, 0.0, 1e-15);
  v.Step(1.5, Velocity(0.0, 0.05), 0);  // 0.5 s braking, then 1 s spin ramping at 0.05 rad/s^2
  EXPECT_NEAR(v.pose().x - x0, 0.076 * 1.0 - 0.5 * 0.076 * 1.0, 1e-12);
  EXPECT_NEAR(v.pose().theta, 0.5 * 0.05 * 1.0, 1e-12);
  EXPECT_EQ(v.motion(), SkidSteerMotion::kTurnInPlace);
}

TEST(SkidSteerTest, ValidateOptions) {
  EXPECT_EQ(ValidateSkidSteerOptions(SkidSteerOptions()), "");
  SkidSteerOptions o;
  o.turn_radius = 0.0;
  EXPECT_NE(ValidateSkidSteerOptions(o).find("turn_radius"), std::string::npos);
  o = SkidSteerOptions();
  o.max_acceleration = -1.0;
  EXPECT_NE(ValidateSkidSteerOptions(o).find("max_acceleration"), std::string::npos);
}

}  // namespace
}  // namespace minenav
