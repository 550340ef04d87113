#include "mapper/loop_closure.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <unordered_map>

#include "mapper/correspondence.h"
#include "pose_estimator/iconic/iconic_matcher.h"
#include "pose_estimator/iconic/lookup_table_correspondence.h"

namespace minenav::mapper {

std::string ValidateOptions(const LoopClosureOptions& o) {
  if (std::string why = ValidateOptions(o.graph); !why.empty()) return "graph: " + why;
  std::ostringstream why;
  if (!(o.max_pair_distance > 0.0))
    why << "max_pair_distance must be > 0 m, got " << o.max_pair_distance;
  else if (!(o.min_threshold > 0.0) || !(o.initial_threshold >= o.min_threshold))
    why << "need 0 < min_threshold <= initial_threshold, got " << o.min_threshold << " and " << o.initial_threshold;
  else if (!(o.min_overlap >= 0.0 && o.min_overlap <= 1.0))
    why << "min_overlap must be in [0, 1], got " << o.min_overlap;
  else if (!(o.max_residual > 0.0))
    why << "max_residual must be > 0 m, got " << o.max_residual;
  else if (o.max_recent_pairs < 1 || o.max_loop_pairs < 0 || o.loop_index_gap < 1)
    why << "need max_recent_pairs >= 1, max_loop_pairs >= 0, loop_index_gap >= 1";
  else if (!(o.max_rotation_change > 0.0))
    why << "max_rotation_change must be > 0 rad, got " << o.max_rotation_change;
  else if (o.point_stride < 1)
    why << "point_stride must be >= 1, got " << o.point_stride;
  else if (!(o.covariance_floor_translation > 0.0) || !(o.covariance_floor_rotation > 0.0))
    why << "covariance floors must be > 0";
  else if (!(o.prior_sigma_translation > 0.0) || !(o.prior_sigma_rotation > 0.0))
    why << "prior sigmas must be > 0";
  else if (!(o.gate_translation > 0.0) || !(o.gate_rotation > 0.0))
    why << "gates must be > 0";
  else if (o.max_gate_passes < 1)
    why << "max_gate_passes must be >= 1, got " << o.max_gate_passes;
  else if (!(o.loop_translation >= 0.0) || !(o.loop_rotation >= 0.0))
    why << "loop_translation and loop_rotation must be >= 0";
  else if (!(o.observation_threshold > 0.0))
    why << "observation_threshold must be > 0 m, got " << o.observation_threshold;
  return why.str();
}

void DeclareOptions(OptionScope s, LoopClosureOptions& o) {
  s.AddBool("enabled", &o.enabled,
            "run the pose-graph step before the alternating rounds: alternation alone passes a "
            "loop's correction around it one scan per round");
  s.AddDouble("max_pair_distance", &o.max_pair_distance, "m",
              "scans whose sensors are farther apart (at the current poses) are not registered: they seldom see "
              "enough of the same walls",
              0.001, 100000.0);
  s.AddInt("max_recent_pairs", &o.max_recent_pairs,
           "each scan is registered against at most this many nearest earlier scans; 4 keeps the cost "
           "linear in the scans where a robot scanning at 5-10 Hz crowds one place [scans]",
           1, 1000);
  s.AddInt("max_loop_pairs", &o.max_loop_pairs,
           "and against at most this many nearest scans at least loop_index_gap back (loop candidates) [scans]; 4",
           0, 1000);
  s.AddInt("loop_index_gap", &o.loop_index_gap,
           "scans at least this many back count as loop candidates [scans]; 8", 1, 1000000);
  s.AddDouble("initial_threshold", &o.initial_threshold, "m",
              "first threshold of a registration: how far two scans' relative pose may be off, the reach of each "
              "scan's lookup table and the largest accepted move; 1 m, the iconic matcher's basin",
              0.001, 100.0);
  s.AddDouble("coarse_threshold", &o.coarse_threshold, "m",
              "registration stages start with this threshold floor, so a crib or corner still this far off keeps "
              "pulling (one pass drops such points as outliers at once); 0.8 m",
              0.001, 100.0);
  s.AddDouble("coarse_factor", &o.coarse_factor, "1",
              "each stage's floor is the last one's times this, down to min_threshold; 0.6", 0.01, 0.99);
  s.AddDouble("min_threshold", &o.min_threshold, "m",
              "last floor of a registration's shrinking threshold, about 3 sigma of two noisy raw scans; 0.15 m",
              0.001, 100.0);
  s.AddDouble("min_overlap", &o.min_overlap, "1",
              "fraction of the registered scan's points that must match within the final threshold for the "
              "registration to count; 0.25",
              0.0, 1.0);
  s.AddDouble("max_residual", &o.max_residual, "m",
              "RMS residual of an accepted registration at most; 0.06 m, as the mapper's refusal test",
              0.0001, 10.0);
  s.AddInt("point_stride", &o.point_stride,
           "every k-th point of the registered scan is used (1 = all); 2 halves the cost of dense scans [points]",
           1, 1000);
  s.AddDouble("covariance_floor_translation", &o.covariance_floor_translation, "m",
              "added to each registration's covariance (the matcher's own is optimistic: raw polylines carry "
              "correlated range noise); 0.003",
              1e-12, 1000.0);
  s.AddDouble("covariance_floor_rotation", &o.covariance_floor_rotation, "rad",
              "heading part of the covariance floor; 0.0002", 1e-12, 1000.0);
  s.AddDouble("prior_sigma_translation", &o.prior_sigma_translation, "m",
              "sigma of the weak prior tying consecutive scans to their current relative pose, so the graph stays "
              "connected where registration fails; 0.2 m",
              1e-9, 1000.0);
  s.AddDouble("prior_sigma_rotation", &o.prior_sigma_rotation, "rad",
              "heading part of that prior; 0.02 rad", 1e-9, 100.0);
  s.AddDouble("gate_translation", &o.gate_translation, "m",
              "after optimisation a registration off the solution by more is dropped as a false match; 0.05 m",
              1e-9, 1000.0);
  s.AddDouble("gate_rotation", &o.gate_rotation, "rad", "heading part of the gate; 0.005 rad", 1e-9,
              10.0);
  s.AddInt("max_gate_passes", &o.max_gate_passes, "optimise / drop passes at most [passes]; 4", 1, 1000);
  s.AddDouble("loop_translation", &o.loop_translation, "m",
              "the solution is applied only if a kept registration disagrees with the current poses by more (a "
              "loop to close); otherwise raw-scan registrations (1-2 cm) would only add noise to a consistent "
              "map; 0.1 m",
              0.0, 1000.0);
  s.AddDouble("loop_rotation", &o.loop_rotation, "rad", "heading part of that trigger; 0.012 rad (0.69 degrees)",
              0.0, 10.0);
  s.AddDouble("observation_threshold", &o.observation_threshold, "m",
              "a scan point this close to a segment moves that segment's vertices with the scan when contours are "
              "carried along; 0.3 m",
              0.001, 100.0);
  s.AddDouble("max_rotation_change", &o.max_rotation_change, "rad",
              "a registration that turned the pair by more than this left its basin and is rejected (one entry of "
              "a room-and-pillar mine looks like the next); 0.1 rad",
              1e-6, kPi);
  DeclareOptions(s.Nested("graph"), o.graph);
}

namespace {

// The raw polylines of a scan (thesis 3.3): a segment between neighbouring points of each
// partial scan, vehicle frame.
std::vector<Segment> RawPolylines(const PreprocessedScan& scan) {
  std::vector<Segment> out;
  for (const PartialScan& p : scan.partial_scans)
    for (size_t k = 1; k < p.points.size(); ++k) out.emplace_back(p.points[k - 1], p.points[k]);
  return out;
}

std::vector<Eigen::Vector2d> StridedPoints(const PreprocessedScan& scan, int stride) {
  std::vector<Eigen::Vector2d> out;
  int k = 0;
  for (const PartialScan& p : scan.partial_scans)
    for (const Eigen::Vector2d& q : p.points)
      if (k++ % stride == 0) out.push_back(q);
  return out;
}

}  // namespace

std::vector<ScanPairEdge> RegisterScanPairs(const std::vector<MappedScan>& scans, const LoopClosureOptions& o,
                                            int* pairs_tried, const ShouldStop& should_stop) {
  std::vector<ScanPairEdge> out;
  int tried = 0;
  const size_t n = scans.size();
  std::vector<Eigen::Vector2d> sensor(n);
  std::vector<std::vector<Eigen::Vector2d>> points(n);
  for (size_t k = 0; k < n; ++k) {
    sensor[k] = scans[k].pose * scans[k].scan.sensor_position;
    points[k] = StridedPoints(scans[k].scan, o.point_stride);
  }
  IconicMatchOptions match;
  match.initial_threshold = o.initial_threshold;
  match.min_threshold = o.min_threshold;
  std::vector<double> floors;
  for (double f = o.coarse_threshold; f > o.min_threshold; f *= o.coarse_factor) floors.push_back(f);
  floors.push_back(o.min_threshold);
  // Partners of each later scan j: within max_pair_distance, the nearest max_recent_pairs
  // and the nearest max_loop_pairs that are at least loop_index_gap scans back (loop
  // candidates, which the recent ones would otherwise crowd out).
  std::vector<std::vector<bool>> pair(n);
  for (size_t j = 1; j < n; ++j) {
    std::vector<std::pair<double, size_t>> recent, loop;
    for (size_t i = 0; i < j; ++i) {
      const double d = (sensor[j] - sensor[i]).norm();
      if (d > o.max_pair_distance) continue;
      (j - i >= static_cast<size_t>(o.loop_index_gap) ? loop : recent).emplace_back(d, i);
    }
    std::sort(recent.begin(), recent.end());
    std::sort(loop.begin(), loop.end());
    if (recent.size() > static_cast<size_t>(o.max_recent_pairs)) recent.resize(static_cast<size_t>(o.max_recent_pairs));
    if (loop.size() > static_cast<size_t>(o.max_loop_pairs)) loop.resize(static_cast<size_t>(o.max_loop_pairs));
    for (const auto& r : {recent, loop})
      for (const auto& [d, i] : r) {
        if (pair[i].empty()) pair[i].assign(n, false);
        pair[i][j] = true;
      }
  }
  bool stopped = false;
  for (size_t i = 0; i < n && !stopped; ++i) {
    // One lookup table per scan, in its own frame, built only if some later scan pairs with it.
    std::unique_ptr<LookupTableCorrespondence> table;
    if (pair[i].empty()) continue;
    for (size_t j = i + 1; j < n; ++j) {
      if (!pair[i][j]) continue;
      // A registration takes milliseconds; thousands of them take minutes on a long run.
      if (should_stop && should_stop()) {
        stopped = true;
        break;
      }
      if (points[j].size() < 10) continue;
      if (!table) {
        std::vector<Segment> segments = RawPolylines(scans[i].scan);
        if (segments.empty()) break;
        table = std::make_unique<LookupTableCorrespondence>(std::move(segments), 0.1, o.initial_threshold);
      }
      ++tried;
      const Pose2 initial = Between(scans[i].pose, scans[j].pose);
      // Coarse to fine: the matcher shrinks its threshold to the median distance at once,
      // which drops the few points that pin the pose along a corridor (cribs, corners) while
      // they are still far off; lowering the floor in stages keeps them pulling.
      IconicMatchResult r;
      Pose2 start = initial;
      for (const double floor : floors) {
        IconicMatchOptions m = match;
        m.min_threshold = floor;
        r = MatchPointsToMap(points[j], *table, start, m);
        if (!r.converged) break;
        start = r.pose;
      }
      if (!r.converged) continue;
      const double overlap = static_cast<double>(r.num_inliers) / static_cast<double>(points[j].size());
      if (overlap < o.min_overlap || r.residual > o.max_residual) continue;
      if (TranslationDistance(r.pose, initial) > o.initial_threshold || HeadingDistance(r.pose, initial) > o.max_rotation_change)
        continue;
      ScanPairEdge e;
      e.edge.from = static_cast<int>(i);
      e.edge.to = static_cast<int>(j);
      e.edge.measurement = r.pose;
      const Eigen::Matrix3d floor = Eigen::Vector3d(o.covariance_floor_translation * o.covariance_floor_translation,
                                                    o.covariance_floor_translation * o.covariance_floor_translation,
                                                    o.covariance_floor_rotation * o.covariance_floor_rotation)
                                        .asDiagonal();
      // The matcher's covariance is of (x, y, θ) of i_T_j; the edge error is expressed in
      // the measurement's frame, so rotate the translation block into it.
      Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
      rot.topLeftCorner<2, 2>() = r.pose.rotation().transpose();
      const Eigen::Matrix3d cov = rot * r.covariance * rot.transpose() + floor;
      e.edge.information = cov.inverse();
      e.edge.information = 0.5 * (e.edge.information + e.edge.information.transpose()).eval();
      e.residual = r.residual;
      e.overlap = overlap;
      out.push_back(e);
    }
  }
  if (pairs_tried) *pairs_tried = tried;
  return out;
}

void CarryContoursWithScans(const std::vector<MappedScan>& scans, const std::vector<Pose2>& old_poses,
                            ContourMap& map, double observation_threshold) {
  std::vector<Pose2> corrections;  // world-frame: new * old^-1
  for (size_t k = 0; k < scans.size(); ++k) corrections.push_back(scans[k].pose * old_poses[k].inverse());
  struct Acc {
    std::vector<Eigen::Vector2d> sum;
    std::vector<double> weight;
  };
  std::unordered_map<int, Acc> acc;
  for (const auto& [id, c] : map.contours()) {
    acc[id].sum.assign(c.points.size(), Eigen::Vector2d::Zero());
    acc[id].weight.assign(c.points.size(), 0.0);
  }
  for (size_t k = 0; k < scans.size(); ++k) {
    const ScanCorrespondence corr = CorrespondScan(scans[k].scan, old_poses[k], map, observation_threshold);
    for (const ErrorPiece& p : corr.pieces) {
      const Contour& c = map.Get(p.segment.contour);
      Acc& a = acc[p.segment.contour];
      for (const int v : {c.SegmentStart(p.segment.segment), c.SegmentEnd(p.segment.segment)}) {
        a.sum[static_cast<size_t>(v)] += corrections[k] * c.points[static_cast<size_t>(v)];
        a.weight[static_cast<size_t>(v)] += 1.0;
      }
    }
  }
  for (const int id : map.Ids()) {
    const Contour& c = map.Get(id);
    const Acc& a = acc[id];
    const int n = c.NumPoints();
    std::vector<Eigen::Vector2d> shift(static_cast<size_t>(n), Eigen::Vector2d::Zero());
    std::vector<int> observed;
    for (int v = 0; v < n; ++v)
      if (a.weight[static_cast<size_t>(v)] > 0.0) {
        shift[static_cast<size_t>(v)] = a.sum[static_cast<size_t>(v)] / a.weight[static_cast<size_t>(v)] - c.points[static_cast<size_t>(v)];
        observed.push_back(v);
      }
    if (observed.empty()) {
      // No scan sees it any more: it moves with the scan whose sensor is nearest.
      const Eigen::Vector2d centre = c.points[static_cast<size_t>(n / 2)];
      size_t best = 0;
      double best_d = 1e300;
      for (size_t k = 0; k < scans.size(); ++k) {
        const double d = (old_poses[k] * scans[k].scan.sensor_position - centre).norm();
        if (d < best_d) best_d = d, best = k;
      }
      for (int v = 0; v < n; ++v)
        shift[static_cast<size_t>(v)] = corrections[best] * c.points[static_cast<size_t>(v)] - c.points[static_cast<size_t>(v)];
    } else {
      // Interpolate the shift of unobserved vertices between observed ones (by arc length,
      // wrapping around closed contours; open ends take the nearest observed shift).
      std::vector<double> s(static_cast<size_t>(n), 0.0);
      for (int v = 1; v < n; ++v)
        s[static_cast<size_t>(v)] = s[static_cast<size_t>(v - 1)] + (c.points[static_cast<size_t>(v)] - c.points[static_cast<size_t>(v - 1)]).norm();
      const double total = c.closed ? s.back() + (c.points.front() - c.points.back()).norm() : s.back();
      const size_t m = observed.size();
      for (size_t q = 0; q < m; ++q) {
        const int a0 = observed[q];
        const bool last = q + 1 == m;
        if (last && !c.closed) {
          for (int v = a0 + 1; v < n; ++v) shift[static_cast<size_t>(v)] = shift[static_cast<size_t>(a0)];
          break;
        }
        const int a1 = last ? observed[0] : observed[q + 1];
        const double s0 = s[static_cast<size_t>(a0)];
        double s1 = s[static_cast<size_t>(a1)];
        if (last || a1 <= a0) s1 += total;
        for (int v = (a0 + 1) % n; v != a1; v = (v + 1) % n) {
          double sv = s[static_cast<size_t>(v)];
          if (sv < s0) sv += total;
          const double f = s1 > s0 ? (sv - s0) / (s1 - s0) : 0.0;
          shift[static_cast<size_t>(v)] = (1.0 - f) * shift[static_cast<size_t>(a0)] + f * shift[static_cast<size_t>(a1)];
        }
      }
      if (!c.closed)
        for (int v = 0; v < observed[0]; ++v) shift[static_cast<size_t>(v)] = shift[static_cast<size_t>(observed[0])];
    }
    std::vector<Eigen::Vector2d> pts = c.points;
    for (int v = 0; v < n; ++v) pts[static_cast<size_t>(v)] += shift[static_cast<size_t>(v)];
    map.SetPoints(id, std::move(pts));
  }
}

LoopClosureResult CloseLoops(std::vector<MappedScan>& scans, ContourMap& map, const LoopClosureOptions& o,
                             const ContourFittingOptions& fitting, const RedundantContourOptions& redundant,
                             const ShouldStop& should_stop) {
  LoopClosureResult out;
  if (scans.size() < 2) {
    out.reason = "fewer than 2 scans";
    return out;
  }
  // Once it said yes, the answer is kept: asked again, a caller's test is not asked twice.
  bool said_yes = false;
  const ShouldStop stop_latched = [&] { return said_yes = said_yes || (should_stop && should_stop()); };
  auto stopped = [&](const char* where) {
    if (!stop_latched()) return false;
    out.stopped = true;
    out.reason = std::string("stopped ") + where + " (" + std::to_string(out.pairs_tried) +
                 " pairs registered): nothing changed";
    return true;
  };
  const std::vector<ScanPairEdge> registered = RegisterScanPairs(scans, o, &out.pairs_tried, stop_latched);
  if (stopped("while registering scan pairs")) return out;
  std::vector<Pose2> old_poses;
  std::vector<bool> fixed;
  bool any_fixed = false;
  for (const MappedScan& s : scans) {
    old_poses.push_back(s.pose);
    fixed.push_back(s.fixed);
    any_fixed = any_fixed || s.fixed;
  }
  if (!any_fixed) fixed[0] = true;
  std::vector<PoseGraphEdge> priors;
  const Eigen::Matrix3d prior_info =
      Eigen::Vector3d(1.0 / (o.prior_sigma_translation * o.prior_sigma_translation),
                      1.0 / (o.prior_sigma_translation * o.prior_sigma_translation),
                      1.0 / (o.prior_sigma_rotation * o.prior_sigma_rotation))
          .asDiagonal();
  for (size_t k = 1; k < scans.size(); ++k)
    priors.push_back({static_cast<int>(k - 1), static_cast<int>(k), Between(old_poses[k - 1], old_poses[k]), prior_info});

  std::vector<PoseGraphEdge> kept;
  for (const ScanPairEdge& e : registered) kept.push_back(e.edge);
  for (int pass = 1; pass <= o.max_gate_passes; ++pass) {
    if (stopped("between pose-graph passes")) return out;
    std::vector<PoseGraphEdge> edges = priors;
    edges.insert(edges.end(), kept.begin(), kept.end());
    out.graph = OptimizePoseGraph(old_poses, fixed, edges, o.graph);
    if (!out.graph.reason.empty() && out.graph.poses.size() != scans.size()) break;
    std::vector<PoseGraphEdge> next;
    for (const PoseGraphEdge& e : kept) {
      const Eigen::Vector3d err = ComputeEdgeResidual(out.graph.poses[static_cast<size_t>(e.from)],
                                                      out.graph.poses[static_cast<size_t>(e.to)], e.measurement)
                                      .error;
      if (err.head<2>().norm() <= o.gate_translation && std::abs(err.z()) <= o.gate_rotation) next.push_back(e);
    }
    out.edges_rejected += static_cast<int>(kept.size() - next.size());
    const bool stable = next.size() == kept.size();
    kept = std::move(next);
    if (stable) break;
  }
  out.edges = static_cast<int>(kept.size());
  for (size_t k = 0; k < scans.size(); ++k) {
    out.max_correction_translation = std::max(out.max_correction_translation, TranslationDistance(out.graph.poses[k], old_poses[k]));
    out.max_correction_rotation = std::max(out.max_correction_rotation, HeadingDistance(out.graph.poses[k], old_poses[k]));
  }
  for (const PoseGraphEdge& e : kept) {
    const Eigen::Vector3d err =
        ComputeEdgeResidual(old_poses[static_cast<size_t>(e.from)], old_poses[static_cast<size_t>(e.to)], e.measurement).error;
    out.max_disagreement_translation = std::max(out.max_disagreement_translation, err.head<2>().norm());
    out.max_disagreement_rotation = std::max(out.max_disagreement_rotation, std::abs(err.z()));
  }
  std::ostringstream why;
  why << out.edges << " registrations kept of " << out.pairs_tried << " pairs (" << out.edges_rejected
      << " gated out), largest correction " << out.max_correction_translation << " m, "
      << RadToDeg(out.max_correction_rotation) << " deg, largest disagreement " << out.max_disagreement_translation
      << " m, " << RadToDeg(out.max_disagreement_rotation) << " deg";
  // The iteration limit still leaves a solution that lowered the cost (LM accepts only
  // descending steps); anything else (bad edges, no anchor) is a failure.
  if (!out.graph.converged && out.graph.reason != "iteration limit") {
    out.reason = "pose graph failed: " + out.graph.reason;
    return out;
  }
  if (out.max_disagreement_translation <= o.loop_translation && out.max_disagreement_rotation <= o.loop_rotation) {
    out.reason = why.str() + ": no loop to close, map left as it is";
    return out;
  }
  if (stopped("before applying the pose graph")) return out;
  for (size_t k = 0; k < scans.size(); ++k) scans[k].pose = out.graph.poses[k];
  CarryContoursWithScans(scans, old_poses, map, o.observation_threshold);
  RemoveRedundantContours(map, redundant);
  FitContours(map.Ids(), scans, map, fitting);
  out.applied = true;
  out.reason = why.str() + ": applied";
  return out;
}

}  // namespace minenav::mapper
