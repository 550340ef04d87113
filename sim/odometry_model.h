#pragma once
// Initial pose estimates for simulated runs, two ways:
//
// 1. Dead reckoning (DESIGN.md "vehicle_sim": "dead-reckoning odometry with drift"): true
//    motion increments are corrupted by a systematic and random error model and integrated,
//    giving the drifting ODOMETRY stream a real miner would have.
// 2. The thesis way (5.2.1, 5.3): each station's truth plus independent Gaussian noise
//    ("sigma_x = 0.33, sigma_y = 0.33, sigma_theta = 3.33" deg for the research mine).
//
// Error model for an increment of arc length ds (m), heading change dtheta (rad), over dt (s):
//   ds'     = ds * (1 + scale_error) + N(0, translation_noise^2 * |ds|)
//   dtheta' = dtheta * (1 + rotation_scale_error) + heading_drift_per_metre * |ds|
//             + heading_drift_per_second * dt + N(0, rotation_noise^2 * (|dtheta| + |ds|))
// The noise variances grow linearly with the motion, so the result does not depend on how
// finely the motion is cut into increments (a random walk), and a standing vehicle gets
// only the per-second drift.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/pose2.h"
#include "common/vehicle_state.h"
#include "sim/skid_steer.h"

namespace minenav {

struct OdometryErrorOptions {
  double scale_error = 0.0;              // fraction: 0.02 = odometry reads 2% long
  double rotation_scale_error = 0.0;     // fraction of each heading change
  double heading_drift_per_metre = 0.0;  // rad/m travelled (signed: + drifts counter-clockwise)
  double heading_drift_per_second = 0.0; // rad/s (gyro bias)
  double translation_noise = 0.0;        // m/sqrt(m): std of ds after 1 m is this
  double rotation_noise = 0.0;           // rad/sqrt(rad or m)
};

std::string ValidateOdometryErrorOptions(const OdometryErrorOptions& options);

class OptionScope;
// Declares every field of OdometryErrorOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, OdometryErrorOptions& o);

class DeadReckoning {
 public:
  DeadReckoning(const OdometryErrorOptions& options, const Pose2& initial_pose, uint64_t seed);

  // An arc increment (as SkidSteerVehicle::Step returns). Returns the new estimate.
  const Pose2& AddIncrement(const MotionIncrement& increment);
  // An arbitrary relative motion (end pose in the start frame), e.g. from one survey
  // station to the next: decomposed as rotate, go straight, rotate, each part corrupted.
  const Pose2& AddRelativeMotion(const Pose2& delta, double dt);
  // The increment as an OdometryReading stamped `utime` (v, omega from the estimate).
  OdometryReading Reading(int64_t utime) const;

  const Pose2& pose() const { return pose_; }
  void Reset(const Pose2& pose) { pose_ = pose; }

 private:
  void Apply(double ds, double dtheta, double dt);

  OdometryErrorOptions options_;
  Pose2 pose_;
  std::mt19937_64 rng_;
  int64_t seq_ = 0;
  double last_v_ = 0.0;
  double last_omega_ = 0.0;
};

// Dead-reckoned estimates along a sequence of true poses (e.g. survey stations): the first
// estimate equals the first truth; each further one adds the true relative motion with the
// error model. times_s (seconds, same size as truth, or empty = 1 s per leg) sets dt.
std::vector<Pose2> DeadReckonAlong(const std::vector<Pose2>& truth, const std::vector<double>& times_s,
                                   const OdometryErrorOptions& options, uint64_t seed);

struct PoseNoise {
  double sigma_x = 0.0;      // m
  double sigma_y = 0.0;      // m
  double sigma_theta = 0.0;  // rad
};

// Truth plus independent Gaussian noise per pose (thesis 5.2.1, 5.3). Deterministic for a seed.
std::vector<Pose2> PerturbPoses(const std::vector<Pose2>& truth, const PoseNoise& noise, uint64_t seed);

}  // namespace minenav
