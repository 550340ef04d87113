#include "pose_estimator/iconic/iconic_estimator.h"

#include <algorithm>

#include "common/config.h"

namespace minenav {

const char* ToString(IconicMode mode) {
  switch (mode) {
    case IconicMode::kSurveyed: return "surveyed";
    case IconicMode::kScanMap: return "scan-map";
    case IconicMode::kFirstScan: return "first-scan";
    case IconicMode::kAllPrevious: return "all-previous";
    case IconicMode::kSimultaneous: return "simultaneous";
  }
  return "?";
}

bool ParseIconicMode(const std::string& text, IconicMode* out) {
  for (IconicMode m : {IconicMode::kSurveyed, IconicMode::kScanMap, IconicMode::kFirstScan,
                       IconicMode::kAllPrevious, IconicMode::kSimultaneous}) {
    if (text == ToString(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

IconicEstimator::IconicEstimator(IconicEstimatorOptions options) : options_(std::move(options)) {
  options_.correspondence.max_distance =
      std::max(options_.correspondence.max_distance, options_.match.initial_threshold);
  if (options_.mode == IconicMode::kAllPrevious)
    scans_ = std::make_unique<ScanSetMap>(options_.scan_map_cell_size, options_.correspondence.max_distance);
}

std::string IconicEstimator::SetMap(const std::vector<Segment>& segments) {
  SegmentMap clean = PrepareSegmentMap(segments, options_.map);
  if (!clean.problem.empty()) return clean.problem;
  map_ = MakeCorrespondenceSearch(std::move(clean.segments), options_.correspondence);
  return "";
}

IconicMatchResult IconicEstimator::AddScan(const LadarScan& scan, const Pose2& initial) {
  IconicMatchResult result;
  result.pose = initial;
  std::string problem;
  const std::vector<Eigen::Vector2d> points = ValidScanPoints(scan, &problem);
  result.num_points = static_cast<int>(points.size());
  if (!problem.empty()) {
    result.status = problem;
    return result;
  }
  const bool first = scans_seen_ == 0;
  switch (options_.mode) {
    case IconicMode::kSurveyed:
      if (!map_) {
        result.status = "no map yet";
        return result;
      }
      ++scans_seen_;
      return MatchPointsToMap(points, *map_, initial, options_.match);
    case IconicMode::kScanMap:
    case IconicMode::kFirstScan:
    case IconicMode::kAllPrevious: {
      if (!first) {
        ++scans_seen_;
        const CorrespondenceSearch& search =
            options_.mode == IconicMode::kAllPrevious ? static_cast<const CorrespondenceSearch&>(*scans_) : *map_;
        result = MatchPointsToMap(points, search, initial, options_.match);
        if (options_.mode == IconicMode::kAllPrevious && result.converged)
          scans_->AddScan(PartialScansToSegments(SplitIntoPartialScans(points, options_.partial)), result.pose);
        return result;
      }
      // The first scan defines the map at its given pose.
      const auto partial = SplitIntoPartialScans(points, options_.partial);
      std::vector<Segment> local = options_.mode == IconicMode::kScanMap ? FitPolylines(partial, options_.fit)
                                                                          : PartialScansToSegments(partial);
      if (local.empty()) {
        result.status = "first scan gave no polylines to map with";
        return result;
      }
      ++scans_seen_;
      if (options_.mode == IconicMode::kAllPrevious) {
        scans_->AddScan(std::move(local), initial);
      } else {
        SegmentMap clean = PrepareSegmentMap(TransformSegments(initial, local), options_.map);
        CorrespondenceOptions correspondence = options_.correspondence;
        if (options_.mode == IconicMode::kFirstScan) correspondence.cell_size = options_.scan_map_cell_size;
        map_ = MakeCorrespondenceSearch(std::move(clean.segments), correspondence);
      }
      result.converged = true;
      result.status = "ok: first scan defines the map";
      result.num_inliers = result.num_points;
      return result;
    }
    case IconicMode::kSimultaneous:
      result.status = "simultaneous mode needs the whole sequence (EstimateSequence)";
      return result;
  }
  return result;
}

std::vector<IconicMatchResult> EstimateSequence(const std::vector<LadarScan>& scans,
                                                const std::vector<Pose2>& initial_poses,
                                                const std::vector<Segment>& map,
                                                const IconicEstimatorOptions& options) {
  std::vector<IconicMatchResult> results;
  if (options.mode != IconicMode::kSimultaneous) {
    IconicEstimator estimator(options);
    std::string map_problem;
    if (options.mode == IconicMode::kSurveyed) map_problem = estimator.SetMap(map);
    int last_good = -1;  // index of the last converged estimate, for chain_odometry
    for (size_t k = 0; k < scans.size(); ++k) {
      if (!map_problem.empty()) {
        IconicMatchResult r;
        r.pose = initial_poses[k];
        r.status = map_problem;
        results.push_back(r);
        continue;
      }
      Pose2 initial = initial_poses[k];
      if (options.chain_odometry && last_good >= 0) {
        const size_t j = static_cast<size_t>(last_good);
        initial = results[j].pose * Between(initial_poses[j], initial_poses[k]);
      }
      results.push_back(estimator.AddScan(scans[k], initial));
      if (results.back().converged) last_good = static_cast<int>(k);
    }
    return results;
  }
  // Simultaneous: scans with usable points join; the first usable one is fixed.
  std::vector<Pose2> start = initial_poses;
  if (options.seed_simultaneous) {
    IconicEstimatorOptions seed = options;
    seed.mode = IconicMode::kAllPrevious;
    const std::vector<IconicMatchResult> seeded = EstimateSequence(scans, initial_poses, map, seed);
    for (size_t k = 0; k < scans.size(); ++k)
      if (seeded[k].converged) start[k] = seeded[k].pose;
  }
  std::vector<MultiScanInput> inputs;
  std::vector<int> input_of(scans.size(), -1);
  results.resize(scans.size());
  for (size_t k = 0; k < scans.size(); ++k) {
    std::string problem;
    MultiScanInput in;
    in.points = ValidScanPoints(scans[k], &problem);
    in.initial = start[k];
    results[k].pose = start[k];
    results[k].num_points = static_cast<int>(in.points.size());
    if (!problem.empty()) {
      results[k].status = problem;
      continue;
    }
    in.fixed = inputs.empty();
    input_of[k] = static_cast<int>(inputs.size());
    inputs.push_back(std::move(in));
  }
  MultiScanOptions multi;
  multi.match = options.match;
  multi.partial = options.partial;
  multi.cell_size = options.scan_map_cell_size;
  multi.max_pair_distance = options.max_pair_distance;
  multi.point_stride = options.point_stride;
  multi.every_overlapping_scan = options.every_overlapping_scan;
  multi.epsilon_translation = options.simultaneous_epsilon_translation;
  multi.epsilon_rotation = options.simultaneous_epsilon_rotation;
  const MultiScanResult out = MatchScansSimultaneously(inputs, multi);
  for (size_t k = 0; k < scans.size(); ++k) {
    const int i = input_of[k];
    if (i < 0) continue;
    IconicMatchResult& r = results[k];
    r.pose = out.poses[static_cast<size_t>(i)];
    r.covariance = out.covariances[static_cast<size_t>(i)];
    r.residual = out.residual;
    r.num_inliers = out.inliers[static_cast<size_t>(i)];
    r.iterations = out.iterations;
    r.final_threshold = out.final_threshold;
    r.converged = out.converged;
    r.status = inputs[static_cast<size_t>(i)].fixed && out.converged ? "ok: fixed scan" : out.status;
  }
  return results;
}

void DeclareOptions(OptionScope scope, IconicEstimatorOptions& o) {
  scope.AddEnum("mode", &o.mode,
                "which map each scan is matched to: surveyed (3.1, a surveyed line map), scan-map (3.2, polylines "
                "fit to the first scan), first-scan (3.3, its raw polylines), all-previous (3.4, every earlier "
                "scan), simultaneous (3.5, all scans to each other at once; batch only)",
                {IconicMode::kSurveyed, IconicMode::kScanMap, IconicMode::kFirstScan, IconicMode::kAllPrevious,
                 IconicMode::kSimultaneous});
  DeclareOptions(scope.Nested("match"), o.match);
  DeclareOptions(scope.Nested("correspondence"), o.correspondence);
  // Not "map": a process's `map` is the map file.
  DeclareOptions(scope.Nested("segment_map"), o.map);
  DeclareOptions(scope.Nested("partial"), o.partial);
  DeclareOptions(scope.Nested("fit"), o.fit);
  scope.AddDouble("scan_map_cell_size", &o.scan_map_cell_size, "m",
                  "lookup table cell of maps made of raw scans (first-scan, all-previous, simultaneous); 0 = "
                  "automatic, finer: faster queries, much slower builds (0.1 m)",
                  0.0, 10.0);
  scope.AddBool("chain_odometry", &o.chain_odometry,
                "sequential modes over a whole sequence: the given initial poses are drifting odometry, and each "
                "scan starts from the last converged estimate moved by the odometry since (false: offline "
                "surveys give initial estimates in the map frame)");
  scope.AddBool("seed_simultaneous", &o.seed_simultaneous,
                "simultaneous: start from the all-previous estimates, which tolerate dead-reckoning error, rather "
                "than from the given poses");
  DeclareMultiScanParameters(scope.Nested("simultaneous"),
                             {&o.simultaneous_epsilon_translation, &o.simultaneous_epsilon_rotation,
                              &o.max_pair_distance, &o.every_overlapping_scan, &o.point_stride});
}

}  // namespace minenav
