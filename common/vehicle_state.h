#pragma once
// Plain readings of the vehicle's motion, as algorithms see them (no LCM).

#include <Eigen/Core>
#include <cstdint>

#include "common/pose2.h"

namespace minenav {

// Dead-reckoned pose of the vehicle (channel ODOMETRY). In live runs the pose is in
// the odometry frame and drifts; in offline surveys it is the initial estimate of the
// scan with the same utime, in the map frame.
struct OdometryReading {
  int64_t utime = 0;  // us
  int64_t seq = 0;
  Pose2 pose;
  double v = 0.0;      // m/s forward
  double omega = 0.0;  // rad/s
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of (x, y, theta); zero = unknown
};

// Ground truth from the simulator (channel SIM_TRUTH): vehicle pose in the world frame.
struct TruthReading {
  int64_t utime = 0;  // us
  int64_t seq = 0;
  Pose2 pose;
  double v = 0.0;      // m/s
  double omega = 0.0;  // rad/s
};

// A command to the vehicle (channel DRIVE_COMMAND).
struct DriveCommand {
  enum class Mode { kStop = 0, kVelocity = 1, kTurnInPlace = 2 };
  int64_t utime = 0;  // us
  int64_t seq = 0;
  Mode mode = Mode::kStop;
  double v = 0.0;        // m/s, forward positive
  double omega = 0.0;    // rad/s, counter-clockwise positive
  double timeout = 0.5;  // s this command stays valid
};

}  // namespace minenav
