#pragma once
// The result of estimating the vehicle pose for one scan (channels POSE_FPE, POSE_IPE,
// POSE). Recoverable failures are values: converged = false with a one-line status.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "common/pose2.h"

namespace minenav {

struct PoseEstimate {
  int64_t utime = 0;    // us, the scan's utime
  int64_t scan_id = 0;
  std::string source;   // "fpe", "ipe", "clue"
  Pose2 pose;           // vehicle in the map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // (x, y, theta): m^2, m rad, rad^2
  double residual = 0.0;  // m, RMS correspondence error at the end
  int num_points = 0;
  int num_inliers = 0;
  int iterations = 0;
  bool converged = false;
  std::string status = "not run";
  double compute_time = 0.0;  // s
};

}  // namespace minenav
