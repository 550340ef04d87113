#pragma once
// Kinematics of the continuous miner as the Locomotion Emulator emulated it (thesis App. D,
// 6.4, 6.4.2): a skid-steer (tracked) vehicle that can drive straight, drive on ONE fixed
// turning radius ("the miner is currently capable of only one turning radius other than
// zero"), or turn in place; cruise about three inches per second.
//
// A command (v, omega) is clamped to what the vehicle can do:
//   - mode kStop, or a stale command (older than min(its timeout, command_timeout)): stop,
//     decelerating.
//   - mode kTurnInPlace, or |v| < min_speed with omega != 0: turn in place.
//   - otherwise the requested curvature k = omega / v picks the nearest motion on a log
//     scale: straight if |k| < 1 / (2 R), the fixed arc (k = +-1/R) if 1/(2R) <= |k| <= 2/R,
//     turn in place if |k| > 2 / R.
//   - speeds are clipped to max_forward_speed / max_reverse_speed / max_turn_in_place_rate.
// Between motions with different track patterns (moving <-> turning in place) the vehicle
// first stops; between straight and arc the curvature switches at once.
//
// Step() integrates exactly: within a step the curvature is constant and the speed ramps
// linearly (acceleration limits), so the pose is a closed-form arc of length
// s = v0 t + a t^2 / 2 (or a closed-form rotation in place).

#include <cstdint>
#include <string>

#include "common/pose2.h"
#include "common/vehicle_state.h"

namespace minenav {

struct SkidSteerOptions {
  double max_forward_speed = 0.076;     // m/s, cruise ~3 in/s (6.4.2)
  double max_reverse_speed = 0.076;     // m/s (magnitude)
  double turn_radius = 4.0;             // m, the one turning radius besides 0
  double max_turn_in_place_rate = 0.05; // rad/s (magnitude) when turning in place
  double max_acceleration = 0.05;       // m/s^2, raising |speed|; 0 = instantaneous
  double max_deceleration = 0.1;        // m/s^2, lowering |speed|; 0 = instantaneous
  double max_yaw_acceleration = 0.05;   // rad/s^2, turning in place; 0 = instantaneous
  double min_speed = 1e-3;              // m/s, below this a (v, omega) command turns in place or stops
  // s: the vehicle's own stale limit. A command is stale (and the vehicle stops) when it is
  // older than min(its own timeout field, this); a timeout field that is <= 0 or not finite
  // counts as absent. A sender can shorten the validity but never extend it, so one command
  // with timeout = 1e9 followed by silence cannot keep the vehicle driving.
  double command_timeout = 0.5;
};

std::string ValidateSkidSteerOptions(const SkidSteerOptions& options);

class OptionScope;
// Declares every field of SkidSteerOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, SkidSteerOptions& o);

// What the vehicle will actually do.
enum class SkidSteerMotion { kStopped = 0, kStraight = 1, kArc = 2, kTurnInPlace = 3 };

struct ClampedCommand {
  SkidSteerMotion motion = SkidSteerMotion::kStopped;
  double speed = 0.0;      // m/s along the path, signed (straight/arc)
  double curvature = 0.0;  // 1/m, 0 or +-1/turn_radius (straight/arc)
  double yaw_rate = 0.0;   // rad/s (turn in place)
};

// The pure clamping rule above (no staleness, no acceleration).
ClampedCommand ClampDriveCommand(const DriveCommand& command, const SkidSteerOptions& options);

// One integration step's exact motion.
struct MotionIncrement {
  Pose2 delta;            // end pose in the frame of the start pose
  double distance = 0.0;  // m travelled along the path, signed (forward +)
  double rotation = 0.0;  // rad of heading change
  double dt = 0.0;        // s
};

class SkidSteerVehicle {
 public:
  explicit SkidSteerVehicle(const SkidSteerOptions& options, const Pose2& initial_pose = Pose2());

  // Advances by dt seconds (>= 0) under `command`, evaluated at time `now_utime` (us) for
  // staleness. Returns the exact motion over the step.
  MotionIncrement Step(double dt, const DriveCommand& command, int64_t now_utime);
  // Same, with no command at all (stale by definition: the vehicle stops).
  MotionIncrement StepWithoutCommand(double dt);

  const Pose2& pose() const { return pose_; }
  void set_pose(const Pose2& pose) { pose_ = pose; }
  double speed() const { return speed_; }            // m/s along the path, signed
  double curvature() const { return curvature_; }    // 1/m
  double yaw_rate() const { return yaw_rate_; }      // rad/s when turning in place
  // Forward speed and yaw rate of the vehicle right now.
  double v() const { return speed_; }
  double omega() const { return turning_in_place_ ? yaw_rate_ : speed_ * curvature_; }
  bool stale() const { return stale_; }  // last Step found the command stale
  SkidSteerMotion motion() const;
  const SkidSteerOptions& options() const { return options_; }

 private:
  MotionIncrement Advance(double dt, const ClampedCommand& target);

  SkidSteerOptions options_;
  Pose2 pose_;
  double speed_ = 0.0;
  double curvature_ = 0.0;
  double yaw_rate_ = 0.0;
  bool turning_in_place_ = false;
  bool stale_ = true;
};

// The pose reached by moving a distance s (signed) on curvature k from the origin:
// the closed-form arc (straight line for k = 0).
Pose2 ArcDelta(double s, double curvature);

}  // namespace minenav
