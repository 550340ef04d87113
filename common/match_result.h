#pragma once
// What every scan matcher reports about one scan, in the vocabulary of the published
// estimate (common/pose_estimate.h): the iconic matcher (IconicMatchResult), the feature
// estimator (FeaturePoseResult), the contour estimator (mapper::PoseEstimationResult) and
// the mapping session (mapper::ScanResult) each derive their result from this core and add
// their own extras. Recoverable failures are values: converged = false with a one-line
// status.

#include <Eigen/Core>
#include <string>

#include "common/pose2.h"

namespace minenav {

struct MatchResult {
  // Vehicle in the map frame. Do not trust it unless converged: a failed match reports
  // its last iterate, or the initial estimate when nothing was computed.
  Pose2 pose;
  // Covariance of (x, y, theta): m^2, m rad, rad^2. Zero when the matcher computes none.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // The estimate can be used: the matcher ended on its own tolerance and passed its checks.
  bool converged = false;
  // One line: how the match ended ("ok", "ok: fixed scan", "gradient small", "converged
  // with 5 correspondences") or why it failed ("no features in the scan").
  std::string status = "not run";
  int iterations = 0;  // of the matcher's minimisation
  int num_points = 0;  // usable scan points the matcher was given
  // What the estimate rests on: the points within the final correspondence threshold (the
  // iconic and contour matchers), or the feature correspondences the minimiser kept (the
  // feature estimator: features, not points).
  int num_inliers = 0;
  double residual = 0.0;  // m, RMS correspondence error at the final pose
};

}  // namespace minenav
