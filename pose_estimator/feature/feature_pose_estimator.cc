#include "pose_estimator/feature/feature_pose_estimator.h"

#include <algorithm>
#include <cmath>

#include "common/config.h"
#include "common/range_noise.h"

namespace minenav {
namespace {

// Seconds of the caller's stage clock (0 when there is none: the library reads no clock).
class StageTimer {
 public:
  explicit StageTimer(const std::function<double()>& clock) : clock_(clock) { Restart(); }
  void Restart() { start_ = clock_ ? clock_() : 0.0; }
  double Seconds() const { return clock_ ? clock_() - start_ : 0.0; }

 private:
  const std::function<double()>& clock_;
  double start_ = 0.0;
};

// Covariance of map_T_vehicle = map_T_sensor * sensor_T_vehicle from that of map_T_sensor.
Eigen::Matrix3d VehicleCovariance(const Eigen::Matrix3d& sensor_cov, const Pose2& map_T_sensor,
                                  const Pose2& sensor_T_vehicle) {
  const double c = std::cos(map_T_sensor.theta), s = std::sin(map_T_sensor.theta);
  const double a = sensor_T_vehicle.x, b = sensor_T_vehicle.y;
  Eigen::Matrix3d j;
  j << 1, 0, -s * a - c * b,  //
      0, 1, c * a - s * b,    //
      0, 0, 1;
  return j * sensor_cov * j.transpose();
}

}  // namespace

PointSupport MeasureSupport(const LadarScan& scan, const Pose2& map_T_sensor,
                            const std::vector<Segment>& segments, double distance) {
  PointSupport out;
  const std::vector<ScanPoint> pts = ScanPointsInSensorFrame(scan);
  if (pts.empty()) return out;
  std::vector<double> near;
  // At most ~512 points: a fraction and a median need no more.
  const size_t stride = std::max<size_t>(1, pts.size() / 512);
  size_t used = 0;
  for (size_t k = 0; k < pts.size(); k += stride) {
    const ScanPoint& p = pts[k];
    ++used;
    const Eigen::Vector2d w = map_T_sensor * p.point;
    double best = distance;
    bool found = false;
    for (const Segment& s : segments) {
      const double d = PointToSegmentDistance(w, s);
      if (d <= best) {
        best = d;
        found = true;
      }
    }
    if (found) near.push_back(best);
  }
  out.fraction = static_cast<double>(near.size()) / static_cast<double>(used);
  if (!near.empty()) {
    std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(near.size() / 2), near.end());
    out.median_distance = near[near.size() / 2];
  }
  return out;
}

std::string ValidateOptions(const FeaturePoseEstimatorOptions& o) {
  if (!(o.prediction.max_range > 0.0)) return "prediction max_range must be > 0";
  if (!(o.extraction.corner.arm_length > 0.0)) return "corner arm_length must be > 0";
  if (!(o.extraction.corner.min_corner_angle < o.extraction.corner.max_corner_angle)) {
    return "min_corner_angle must be below max_corner_angle";
  }
  if (!(o.matching.angerr >= 0.0 && o.matching.poserr >= 0.0)) return "angerr and poserr must be >= 0";
  if (o.matching.angerr >= kPi / 2.0) return "angerr must be below 90 deg (2.1.6)";
  if (!(o.minimization.point_sigma > 0.0)) return "point_sigma must be > 0";
  if (!(o.extraction.noise_sigma > 0.0)) return "noise_sigma must be > 0";
  if (!(o.range_noise_floor > 0.0)) return "range_noise_floor must be > 0";
  if (o.min_matches < 1) return "min_matches must be >= 1";
  return "";
}

FeaturePoseEstimator::FeaturePoseEstimator(const std::vector<Segment>& map,
                                           const FeaturePoseEstimatorOptions& options)
    : options_(options) {
  FeatureMapBuild build = BuildFeatureMap(map, options.map);
  map_ = std::move(build.map);
  dropped_ = build.dropped;
}

FeaturePoseResult FeaturePoseEstimator::Estimate(const LadarScan& scan,
                                                 const Pose2& initial_map_T_vehicle) const {
  FeaturePoseResult result;
  result.pose = initial_map_T_vehicle;
  const std::string invalid = ValidateScan(scan);
  if (!invalid.empty()) {
    result.status = "invalid scan: " + invalid;
    return result;
  }
  const Pose2 initial_sensor = initial_map_T_vehicle * scan.sensor_offset;

  StageTimer t0(options_.stage_clock);
  PredictionOptions prediction = options_.prediction;
  prediction.max_range = std::min(prediction.max_range, scan.max_range);
  const PredictedFeatures predicted =
      PredictFeatures(map_, initial_sensor.translation(), prediction);
  result.timings.prediction = t0.Seconds();
  std::vector<Segment> predicted_segments;
  for (int i : predicted.visible_segments) predicted_segments.push_back(map_.segments[static_cast<size_t>(i)]);

  t0.Restart();
  ExtractionOptions extraction = options_.extraction;
  MinimizationOptions minimization = options_.minimization;
  if (options_.measure_range_noise) {
    if (const RangeNoise noise = MeasureRangeNoise(scan); noise.sigma > 0.0) {
      // At most 1 m (point_sigma's own bound): more is no sensor's noise but a scan of garbage.
      const double sigma = std::clamp(noise.sigma, options_.range_noise_floor, std::max(options_.range_noise_floor, 1.0));
      minimization.point_sigma = sigma;
      // The line fits' gates only ever narrow: wider than they were tuned (the mockup's clutter
      // at 10 cm) they let clutter and mixed pixels into a fit (the mockup measures 10.6 cm and
      // then converges once 9.7 cm off).
      extraction.noise_sigma = std::min(sigma, options_.extraction.noise_sigma);
    }
  }
  result.range_noise = minimization.point_sigma;
  const ExtractedFeatures sensed = ExtractFeatures(scan, extraction);
  result.timings.extraction = t0.Seconds();
  result.num_points = sensed.num_points;
  for (const Feature& f : sensed.features) {
    (f.type == FeatureType::kCorner ? result.sensed_corners : result.sensed_lines)++;
  }

  t0.Restart();
  // Model corners the corner operator cannot find (angles far outside its interval) only
  // cost matching time; occlusion corners are kept whatever their angle.
  const auto& corner = options_.extraction.corner;
  std::vector<Feature> model;
  for (const Feature& f : predicted.features) {
    if (f.type == FeatureType::kCorner && !f.occlusion &&
        (f.concave_angle < corner.min_corner_angle - options_.matching.concerr ||
         f.concave_angle > corner.max_corner_angle + options_.matching.concerr)) {
      continue;
    }
    model.push_back(f);
  }
  std::vector<Feature> model_in_sensor;
  model_in_sensor.reserve(model.size());
  for (const Feature& f : model) model_in_sensor.push_back(TransformFeature(f, initial_sensor));
  std::vector<size_t> order(model.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return model_in_sensor[a].Azimuth() < model_in_sensor[b].Azimuth();
  });
  std::vector<Feature> model_sorted, model_sorted_in_sensor;
  for (size_t i : order) {
    model_sorted.push_back(model[i]);
    model_sorted_in_sensor.push_back(model_in_sensor[i]);
    (model[i].type == FeatureType::kCorner ? result.predicted_corners : result.predicted_lines)++;
  }
  const FeatureMatchResult match = MatchFeatures(sensed.features, model_sorted_in_sensor, options_.matching);
  result.timings.matching = t0.Seconds();
  result.candidate_pairs = match.candidate_pairs;
  result.matches = static_cast<int>(match.pairs.size());
  result.search_complete = match.search_complete;

  if (sensed.features.empty()) {
    result.status = "no features in the scan";
    return result;
  }
  if (model.empty()) {
    result.status = "no map features predicted";
    return result;
  }
  if (result.matches == 0) {
    result.status = "no consistent matches";
    return result;
  }

  t0.Restart();
  std::vector<Correspondence> pairs;
  for (const FeaturePair& p : match.pairs) {
    pairs.push_back({sensed.features[static_cast<size_t>(p.sensed)], model_sorted[static_cast<size_t>(p.model)]});
  }
  const MinimizationResult min = MinimizeFeatureError(pairs, initial_sensor, minimization);
  result.timings.minimization = t0.Seconds();
  result.iterations = min.iterations;
  result.num_inliers = min.used;
  result.residual = min.rms_distance;
  const Pose2 sensor_T_vehicle = scan.sensor_offset.inverse();
  result.pose = min.pose * sensor_T_vehicle;
  result.covariance = VehicleCovariance(min.covariance, min.pose, sensor_T_vehicle);
  result.converged = min.converged;
  result.status = min.reason;
  // Too few correspondences: still report what they observe (pose and covariance), but
  // a set this small is too easily consistent by chance to be trusted.
  if (result.converged && result.num_inliers < options_.min_matches) {
    result.converged = false;
    result.status = "only " + std::to_string(result.num_inliers) + " consistent correspondences (need " +
                    std::to_string(options_.min_matches) + ")";
  }
  // The match assumed the pose within poserr and angerr of the estimate; a result beyond
  // that contradicts its own premises.
  const double moved = TranslationDistance(min.pose, initial_sensor);
  const double turned = HeadingDistance(min.pose, initial_sensor);
  const auto& m = options_.matching;
  if (result.converged && (moved > m.poserr + m.disterr || turned > m.angerr + m.binangerr)) {
    result.converged = false;
    result.status = "estimate moved beyond the matching bounds (" + std::to_string(moved) +
                    " m, " + std::to_string(RadToDeg(turned)) + " deg)";
  }
  // Our check beyond the thesis: at the estimate, enough of the scan must lie on the map.
  // The points on the map must lie as close to it as the range noise allows: a pose a
  // decimetre off (features of rounded walls, a map a little wrong) shows up here.
  if (result.converged && options_.min_support > 0.0) {
    t0.Restart();
    const PointSupport support = MeasureSupport(scan, min.pose, predicted_segments, options_.support_distance);
    result.support = support.fraction;
    result.support_median_distance = support.median_distance;
    result.timings.verification = t0.Seconds();
    const double max_median = options_.max_median_distance_factor * minimization.point_sigma;
    if (result.support < options_.min_support) {
      result.converged = false;
      result.status = "only " + std::to_string(static_cast<int>(100.0 * result.support)) +
                      "% of the scan lies on the map at the estimate";
    } else if (options_.max_median_distance_factor > 0.0 && support.median_distance > max_median) {
      result.converged = false;
      result.status = "scan points lie " + std::to_string(support.median_distance) +
                      " m from the map at the estimate (median; noise allows " + std::to_string(max_median) + ")";
    }
  }
  return result;
}

void DeclareOptions(OptionScope scope, FeaturePoseEstimatorOptions& o) {
  // Not "map": a process's `map` is the map file.
  DeclareOptions(scope.Nested("feature_map"), o.map);
  DeclareOptions(scope.Nested("prediction"), o.prediction);
  DeclareOptions(scope.Nested("extraction"), o.extraction);
  DeclareOptions(scope.Nested("matching"), o.matching);
  DeclareOptions(scope.Nested("minimization"), o.minimization);
  scope.AddInt("min_matches", &o.min_matches,
               "consistent correspondences needed to call a pose converged (3: three pin x, y and heading)", 1, 1000);
  scope.AddBool("measure_range_noise", &o.measure_range_noise,
                "measure each scan's range noise from its readings (common/range_noise.h) and use it for "
                "minimization.point_sigma and, where it is smaller, extraction.noise_sigma; both options serve "
                "as given when this is off or a scan is too sparse to measure (true: one option set for every "
                "sensor)");
  scope.AddDouble("range_noise_floor", &o.range_noise_floor, "m",
                  "least measured range noise used: below it the walls' roughness and the map's survey decide how "
                  "well a point fits (0.01 m)",
                  0.0001, 1.0);
  scope.AddDouble("min_support", &o.min_support, "1",
                  "fraction of scan points that must lie within support_distance of the map at the estimate "
                  "(ours: clutter lowers it, a wrong pose lowers it more); 0 = no check (0.4)",
                  0.0, 1.0);
  scope.AddDouble("support_distance", &o.support_distance, "m",
                  "how near the map a scan point must lie to support the estimate (0.3 m, ~3 sigma)", 0.0, 100.0);
  scope.AddDouble("max_median_distance_factor", &o.max_median_distance_factor, "1",
                  "the median point-to-map distance at the estimate must not exceed this many "
                  "minimization.point_sigma (a right pose gives ~0.7); 0 = no check (2)",
                  0.0, 1000.0);
}

}  // namespace minenav
