#pragma once
// One scan matched to a segment map by Gauss-Newton (thesis 3.1.2, A.2): correspondence is
// recomputed every iteration; the distance threshold starts at initial_threshold and then
// shrinks to the median correspondence distance of the previous iteration, never below
// min_threshold; iteration stops when no degree of freedom changes by more than epsilon,
// or at max_iterations. The map is whatever CorrespondenceSearch holds: a surveyed map,
// polylines fit to a scan, or raw scans (variants 1-4 of chapter 3).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/match_result.h"
#include "common/pose2.h"
#include "common/scan.h"
#include "pose_estimator/iconic/correspondence.h"
#include "pose_estimator/iconic/robust_loss.h"

namespace minenav {

struct IconicMatchOptions {
  // Correspondence threshold of the first iteration (m). Must cover the initial pose
  // error's effect on the points; must not exceed the lookup table's reach. Default 2 m.
  double initial_threshold = 2.0;
  // Floor of the shrinking threshold (m); set from the range noise (about 3 sigma).
  // Default 0.3 m (Cyclone sigma ~ 10 cm).
  double min_threshold = 0.3;
  // Converged when |dx|, |dy| < epsilon_translation (m) and |dtheta| < epsilon_rotation (rad).
  double epsilon_translation = 1e-4;
  double epsilon_rotation = 1e-5;
  // Iteration limit, in case epsilon is too small (3.1.2). Default 50.
  int max_iterations = 50;
  // Fewer matched points than this = failure (no estimate). Default 10.
  int min_correspondences = 10;
  // Robust loss and its scale (m). Default none (the thesis's plain least squares).
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 0.1;
  // Skip pairs of a point with an open polyline end (see ComputeOpenEnds): such points see
  // what the map does not hold. Default true.
  bool reject_open_ends = true;
  // A step longer than this (m, or rad for heading) is cut to it: Gauss-Newton can
  // overshoot on the first iterations with a large threshold. Default 1 m / 0.35 rad.
  double max_step_translation = 1.0;
  double max_step_rotation = 0.35;
};

// Returns "" if the options are consistent, else a one-line reason.
std::string ValidateIconicMatchOptions(const IconicMatchOptions& options);

class OptionScope;
// Declares every field of IconicMatchOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, IconicMatchOptions& o);

// The core (common/match_result.h) as this matcher fills it: pose = the last iterate;
// covariance = sigma^2 (J^T W J)^-1 from the normal equations, sigma^2 the weighted residual
// variance (zero when not converged); num_points = the points given; num_inliers = the
// points within the final threshold; residual = their RMS error at the final pose.
struct IconicMatchResult : MatchResult {
  double final_threshold = 0.0;  // m, the correspondence threshold of the last iteration
};

// points: scan points in the vehicle frame (NaN points are ignored). initial: vehicle
// pose in the map frame.
IconicMatchResult MatchPointsToMap(const std::vector<Eigen::Vector2d>& points, const CorrespondenceSearch& map,
                                   const Pose2& initial, const IconicMatchOptions& options);

// The same for a scan: validates it and takes its valid readings (through sensor_offset).
IconicMatchResult MatchScanToMap(const LadarScan& scan, const CorrespondenceSearch& map, const Pose2& initial,
                                 const IconicMatchOptions& options);

// Valid readings of a scan as vehicle-frame points; *problem is set ("" if fine) when the
// scan is malformed or has no valid reading.
std::vector<Eigen::Vector2d> ValidScanPoints(const LadarScan& scan, std::string* problem);

}  // namespace minenav
