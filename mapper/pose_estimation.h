#pragma once
// Pose estimation against the contour map (thesis 4.3.3): minimise the integral error
// (integral_error.h) over the scan pose by line search, first on (x, y) along their
// gradient, then on θ, recomputing correspondence every iteration with a threshold that
// starts near the largest expected initial error and shrinks by a constant factor to the
// sensor noise level. Four termination conditions: small gradient, small step (λ), small
// change in pose, iteration limit.
//
// Front-end seam (7.2.2): EstimatePose takes any initial pose. A front end (the iconic
// estimator, odometry, an operator) brings the pose close first; the caller then lowers
// initial_threshold accordingly (e.g. to 0.5 m) so the contour metric only refines.

#include <string>

#include "common/config.h"
#include "common/match_result.h"
#include "common/pose2.h"
#include "mapper/contour_map.h"
#include "mapper/correspondence.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct PoseEstimationOptions {
  // m; correspondence threshold on the first iteration (≈ the largest initial error).
  double initial_threshold = 3.0;
  // m; the threshold it shrinks to (≈ a few sensor noise σ).
  double final_threshold = 0.1;
  // Per-iteration factor applied to the threshold (0 < f <= 1).
  double threshold_factor = 0.9;
  // Iteration limit (termination condition 4).
  int max_iterations = 120;
  // m; gradient small: |∂F/∂(x,y)| and |∂F/∂θ| / lever arm below this times the matched
  // length (i.e. a mean offset of this size) ends the search.
  double gradient_tolerance = 1e-6;
  // m; line-search resolution; a step below it counts as "λ small".
  double step_resolution = 1e-4;
  // m and rad; change in pose below both ends the search.
  double min_translation_change = 2e-5;
  double min_rotation_change = 2e-6;
  // Fewer error pieces than this: no estimate (not enough overlap with the map).
  int min_pieces = 20;
  // rad; heading search before the line searches (beyond the thesis): headings within
  // ±heading_search_range of the initial one, every heading_search_step, are scored by how
  // many scan points find a contour within initial_threshold, and the search starts from the
  // best (the initial heading unless another matches heading_search_margin more points). The
  // line searches descend to the nearest minimum; a heading error of 10° moves points 10 m
  // away by 1.7 m, beyond any threshold that keeps clutter out, so a robot whose odometry
  // lags its turns (MIT CSAIL's log: 0° then 50° between scans) needs the wider basin.
  // 0 = off (the thesis's estimator).
  double heading_search_range = 0.0;
  double heading_search_step = 0.0349065850398866;  // 2°
  // Fraction of the initial heading's matched points another heading must add to win.
  double heading_search_margin = 0.05;
};

std::string ValidateOptions(const PoseEstimationOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, PoseEstimationOptions& o);

// How well a scan at a pose fits the map under a threshold.
struct ScanFit {
  double error = 0.0;           // m^3, F: the sum of the pieces' integral errors
  double matched_length = 0.0;  // m, Σ |l| over the pieces
  int num_pieces = 0;
  int num_points = 0;
  int num_inliers = 0;          // points with a contour within the threshold
  // m^2, F / matched_length: mean squared distance along the matched scan.
  double MeanSquaredDistance() const { return matched_length > 0.0 ? error / matched_length : 0.0; }
  double MatchedFraction() const { return num_points > 0 ? static_cast<double>(num_inliers) / num_points : 0.0; }
};
ScanFit MeasureScanFit(const PreprocessedScan& scan, const Pose2& world_T_vehicle, const ContourMap& map,
                       double threshold);

// The core (common/match_result.h) as this estimator fills it: pose = world_T_vehicle;
// converged = ended on a tolerance, not on the iteration limit or a failure; status = which
// termination condition, or why no estimate; num_points, num_inliers and residual (the RMS
// distance, sqrt of fit.MeanSquaredDistance()) summarise `fit`; covariance stays zero (the
// line searches give none).
struct PoseEstimationResult : MatchResult {
  double threshold = 0.0;  // m, correspondence threshold at the end
  ScanFit fit;             // at `pose` under `threshold`
};

// The heading search alone: the initial pose with the best-matching heading (see
// PoseEstimationOptions::heading_search_range); the initial pose when the search is off.
Pose2 SearchHeading(const PreprocessedScan& scan, const Pose2& initial_world_T_vehicle, const ContourMap& map,
                    const PoseEstimationOptions& options);

PoseEstimationResult EstimatePose(const PreprocessedScan& scan, const Pose2& initial_world_T_vehicle,
                                  const ContourMap& map, const PoseEstimationOptions& options = {});

}  // namespace minenav::mapper
