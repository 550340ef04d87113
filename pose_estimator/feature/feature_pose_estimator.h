#pragma once
// The feature-based pose estimator (thesis chapter 2, Figure 1): prediction, extraction,
// matching and minimisation composed. Given a line map, a scan and an approximate vehicle
// pose (dead reckoning), returns the vehicle pose in the map frame with its covariance.
//   1. Predict the features visible from the approximate sensor position (2.1.3).
//   2. Extract corners and lines from the scan (2.1.4).
//   3. Move the predicted features into the sensor frame with the approximate pose and
//      match (2.1.5).
//   4. Minimise the feature errors over the sensor pose (2.1.6, A.1); the vehicle pose
//      follows through the sensor offset.
// The result is never a pose claimed as converged without enough consistent
// correspondences that pin down all three directions and stay within the matching
// bounds of the initial estimate.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/match_result.h"
#include "common/pose2.h"
#include "common/range_noise.h"
#include "common/scan.h"
#include "pose_estimator/feature/feature_extraction.h"
#include "pose_estimator/feature/feature_map.h"
#include "pose_estimator/feature/feature_matching.h"
#include "pose_estimator/feature/feature_minimization.h"
#include "pose_estimator/feature/feature_prediction.h"

namespace minenav {

struct FeaturePoseEstimatorOptions {
  FeatureMapOptions map;
  PredictionOptions prediction;
  ExtractionOptions extraction;
  MatchingOptions matching;
  MinimizationOptions minimization;
  int min_matches = 3;  // consistent correspondences needed to call a pose converged
  // The range noise every estimate weighs and gates points by is measured from the scan
  // itself (common/range_noise.h), so one option set serves the Typhoon (4.4 cm), the
  // Cyclone (10 cm) and a SICK (1 cm) alike: it replaces minimization.point_sigma, and
  // extraction.noise_sigma where it is smaller (the line fits' gates only narrow: wider than
  // tuned they let clutter into a fit). Both options are used as given when this is off or a
  // scan has too few readings to measure. Never below range_noise_floor: under it the walls'
  // roughness and the map's survey, not the sensor, decide how well a point fits.
  bool measure_range_noise = true;
  double range_noise_floor = kLeastUsefulRangeNoise;  // m
  // Our check beyond the thesis: at the estimate, at least min_support of the scan points
  // must lie within support_distance of a map segment (clutter lowers it; a wrong pose
  // lowers it more). 0 switches it off.
  double min_support = 0.4;       // 1
  double support_distance = 0.3;  // m
  // The median distance of those points from the map must not exceed this many
  // minimization.point_sigma (a right pose gives ~0.7 sigma). 0 switches it off.
  double max_median_distance_factor = 2.0;  // 1
  // s: a clock for the per-stage timings (benchmarks pass a steady clock). The library
  // reads no clock itself; without one every timing is 0.
  std::function<double()> stage_clock;
};

struct FeaturePoseTimings {  // s of stage_clock spent in each stage (0 without one)
  double prediction = 0.0;
  double extraction = 0.0;
  double matching = 0.0;
  double minimization = 0.0;
  double verification = 0.0;  // the support check (ours)
  double total() const { return prediction + extraction + matching + minimization + verification; }
};

// The core (common/match_result.h) as this estimator fills it: pose = the initial estimate
// when nothing was computed; covariance of the vehicle pose, carried through the sensor
// offset; num_points = the valid scan readings; num_inliers = the feature correspondences
// kept by the minimiser (features, not points); residual = the RMS of their distance errors.
struct FeaturePoseResult : MatchResult {
  int sensed_corners = 0, sensed_lines = 0;
  int predicted_corners = 0, predicted_lines = 0;
  int candidate_pairs = 0;  // after the unary constraints
  int matches = 0;          // in the largest consistent set
  bool search_complete = true;
  double support = 0.0;     // fraction of scan points on the map at the estimate
  double support_median_distance = 0.0;  // m, their median distance from the map
  double range_noise = 0.0;  // m, the range noise the estimate used (measured, or the options')
  FeaturePoseTimings timings;
};

class FeaturePoseEstimator {
 public:
  // Segments with non-finite or coincident ends are dropped (see dropped_segments()).
  FeaturePoseEstimator(const std::vector<Segment>& map, const FeaturePoseEstimatorOptions& options = {});

  FeaturePoseResult Estimate(const LadarScan& scan, const Pose2& initial_map_T_vehicle) const;

  const FeatureMap& map() const { return map_; }
  int dropped_segments() const { return dropped_; }
  const FeaturePoseEstimatorOptions& options() const { return options_; }

 private:
  FeaturePoseEstimatorOptions options_;
  FeatureMap map_;
  int dropped_ = 0;
};

// The scan's valid points (every k-th, at most ~512) within `distance` of one of
// `segments` (the estimator passes the segments predicted visible), with the sensor at
// map_T_sensor: their fraction and their median distance.
struct PointSupport {
  double fraction = 0.0;
  double median_distance = 0.0;  // m
};
PointSupport MeasureSupport(const LadarScan& scan, const Pose2& map_T_sensor,
                            const std::vector<Segment>& segments, double distance);

// One-line reason if the options are inconsistent, else empty.
std::string ValidateOptions(const FeaturePoseEstimatorOptions& options);

class OptionScope;
// Declares every field of FeaturePoseEstimatorOptions under `scope`, the nested structs as
// feature_map.*, prediction.*, extraction.* (extraction.corner.*), matching.* and
// minimization.*; stage_clock is a function a program passes, not a parameter.
void DeclareOptions(OptionScope scope, FeaturePoseEstimatorOptions& o);

}  // namespace minenav
