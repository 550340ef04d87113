#pragma once
// Error minimisation of the feature-based estimator (thesis 2.1.6, Appendix A.1).
// Gauss-Newton over the sensor pose (x, y, theta) in the map frame. The predicted (map)
// features are moved into the sensor frame (EQ 6) and compared with the sensed ones
// (EQ 7): corners by their x and y differences, lines by the differences of perpendicular
// distance and orientation.
//
// The equations of A.1 came through OCR with errors; what is used here, derived again
// (tested against numerical derivatives in feature_minimization_test.cc):
//   EQ 6 for lines:  r_p = r' - x cos(phi') - y sin(phi'),  phi_p = phi' - theta
//                    (the thesis prints cos/sin of theta: it must be the line's phi').
//   EQ 8:  d f_x/d theta =  y_p,  d f_y/d theta = -x_p  (as printed, rewritten),
//          d f_r/d x = -cos(phi'), d f_r/d y = -sin(phi'), d f_r/d theta = 0,
//          d f_phi/d theta = -1.
//   EQ 9:  the step solves J D = -F in the least-squares sense, D = -(J^T W J)^-1 J^T W F
//          (the printed D lacks the minus sign).
// Features are weighted by the points behind them (2.1.6), through the information of
// each fit: a line of n points over length L with per-point noise sigma has
// var(offset) = sigma^2 / n and var(phi) = 12 sigma^2 / (n L^2); a corner gets
// var = corner_variance_factor * sigma^2 / n per axis. The covariance of the result is
// (J^T W J)^-1, scaled up by chi^2 / dof when the residuals are larger than the weights
// expect. A direction the features do not constrain (only parallel walls, one
// corner) shows up as an eigenvalue of J^T W J near zero: the result is then not
// converged, and the covariance carries unobservable_variance along that direction.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "pose_estimator/feature/feature_types.h"

namespace minenav {

struct MinimizationOptions {
  int max_iterations = 30;
  double step_tolerance = 1e-6;         // m and rad: converged when a step is smaller
  double point_sigma = 0.1;             // m, range noise per scan point (weights)
  double corner_variance_factor = 8.0;  // 1, corner variance = this * sigma^2 / points
  // Floors per feature: a fit of many points is only as good as the wall is straight and
  // the map is surveyed.
  double min_variance = 4e-4;           // m^2 (2 cm) for corner axes and line distances
  double min_angle_variance = 7.6e-5;   // rad^2 (0.5 deg) for line orientations
  double max_std = 0.5;                 // m (rad x 1 m for heading): beyond this a
                                        // direction counts as unobservable
  double unobservable_variance = 1e6;   // m^2, put into the covariance along such directions
  // m (rad x 1 m): a converged pose needs every direction's std (after the variance
  // factor) below this; a corridor pinned by one weak corner is not converged.
  double max_converged_std = 0.1;
  // Gates after convergence: a pair beyond them is a mismatch; the worst is dropped and
  // the minimisation repeated.
  // The matcher's tolerances (bindisterr 0.5 m) let near-alternatives through, e.g. a
  // column's foot 0.3 m from the corner it was taken for.
  double max_corner_error = 0.15;        // m
  double max_line_distance_error = 0.15; // m
  double max_line_angle_error = DegToRad(2.0);  // rad
  int min_kept = 2;  // correspondences are dropped one at a time while more than this remain
};

class OptionScope;
// Declares every field of MinimizationOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, MinimizationOptions& o);

struct Correspondence {
  Feature sensed;  // sensor frame
  Feature model;   // map frame
};

struct MinimizationResult {
  Pose2 pose;  // sensor in the map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // (x, y, theta)
  bool converged = false;
  std::string reason;
  int iterations = 0;
  int used = 0;                // correspondences kept
  double rms_distance = 0.0;   // m, RMS of corner and line distance errors at the end
  double min_std_direction = 0.0;  // informative only: largest std over directions (m)
  double variance_factor = 1.0;    // chi^2 / dof at the end (>= 1), applied to the covariance
};

// The residual vector of one correspondence (EQ 7) and its Jacobian with respect to the
// sensor pose (x, y, theta), for a map line whose world parameters are (r', phi') as given
// (no flipping: the caller fixes the sense once).
struct FeatureResidual {
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 2, 3> jacobian = Eigen::Matrix<double, 2, 3>::Zero();
};
FeatureResidual ComputeResidual(const Feature& sensed, const Feature& model, const Pose2& pose);

// Information (inverse covariance) of the residual of a sensed feature.
Eigen::Matrix2d FeatureInformation(const Feature& sensed, const MinimizationOptions& options);

MinimizationResult MinimizeFeatureError(const std::vector<Correspondence>& pairs,
                                        const Pose2& initial_map_T_sensor,
                                        const MinimizationOptions& options = {});

}  // namespace minenav
