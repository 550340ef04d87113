#include "pose_estimator/iconic/scan_polylines.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/config.h"
#include "common/scan_split.h"

namespace minenav {

std::vector<std::vector<Eigen::Vector2d>> SplitIntoPartialScans(const std::vector<Eigen::Vector2d>& points,
                                                               const PartialScanOptions& options) {
  ScanSplitOptions split;
  split.break_distance = options.break_distance;
  split.min_points = options.min_points;
  // Points carry no bearing: a NaN point is skipped, not a break, and a ring is known by its
  // last point lying near its first.
  split.max_missing_readings = kAnyNumberOfMissingReadings;
  split.wrap_around = WrapAround::kWhenEndsMeet;
  split.seam_partial_scan_first = true;
  std::vector<std::vector<Eigen::Vector2d>> out;
  for (const PartialScanReadings& partial : SplitScan({.points = points, .ranges = {}, .angle_step = 0.0}, split)) {
    std::vector<Eigen::Vector2d>& run = out.emplace_back();
    run.reserve(partial.readings.size());
    for (const int i : partial.readings) run.push_back(points[static_cast<size_t>(i)]);
  }
  return out;
}

std::vector<Segment> PartialScansToSegments(const std::vector<std::vector<Eigen::Vector2d>>& partial_scans) {
  std::vector<Segment> out;
  for (const auto& run : partial_scans) {
    for (size_t i = 1; i < run.size(); ++i) {
      if ((run[i] - run[i - 1]).squaredNorm() > 0.0) out.emplace_back(run[i - 1], run[i]);
    }
  }
  return out;
}

namespace {
struct FitLine {
  Eigen::Vector2d centroid;
  Eigen::Vector2d direction;  // unit
  Eigen::Vector2d Project(const Eigen::Vector2d& p) const {
    return centroid + direction * direction.dot(p - centroid);
  }
};

FitLine FitTotalLeastSquares(const std::vector<Eigen::Vector2d>& run, size_t begin, size_t end) {
  FitLine line;
  line.centroid.setZero();
  for (size_t i = begin; i <= end; ++i) line.centroid += run[i];
  line.centroid /= static_cast<double>(end - begin + 1);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (size_t i = begin; i <= end; ++i) {
    const Eigen::Vector2d d = run[i] - line.centroid;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  line.direction = eig.eigenvectors().col(1);
  if (!(line.direction.squaredNorm() > 0.5)) line.direction = (run[end] - run[begin]).normalized();
  return line;
}
}  // namespace

std::vector<Segment> FitPolylines(const std::vector<std::vector<Eigen::Vector2d>>& partial_scans,
                                  const PolylineFitOptions& options) {
  std::vector<Segment> out;
  for (const auto& run : partial_scans) {
    if (run.size() < 2) continue;
    // Cut points: where the straight distance from the last cut reaches segment_length
    // (arc length would count the noise zigzag: 5 cm noise at 2 cm spacing triples it).
    std::vector<size_t> cuts = {0};
    for (size_t i = 1; i + 1 < run.size(); ++i) {
      if ((run[i] - run[cuts.back()]).norm() >= options.segment_length) cuts.push_back(i);
    }
    cuts.push_back(run.size() - 1);
    // A last piece much shorter than the rest joins its predecessor.
    if (cuts.size() > 2 && (run.back() - run[cuts[cuts.size() - 2]]).norm() < 0.5 * options.segment_length)
      cuts.erase(cuts.end() - 2);
    std::vector<FitLine> lines;
    for (size_t k = 0; k + 1 < cuts.size(); ++k) lines.push_back(FitTotalLeastSquares(run, cuts[k], cuts[k + 1]));
    std::vector<Eigen::Vector2d> vertices;
    vertices.push_back(lines.front().Project(run[cuts.front()]));
    for (size_t k = 1; k + 1 < cuts.size(); ++k)
      vertices.push_back(0.5 * (lines[k - 1].Project(run[cuts[k]]) + lines[k].Project(run[cuts[k]])));
    vertices.push_back(lines.back().Project(run[cuts.back()]));
    for (size_t k = 1; k < vertices.size(); ++k)
      if ((vertices[k] - vertices[k - 1]).squaredNorm() > 0.0) out.emplace_back(vertices[k - 1], vertices[k]);
  }
  return out;
}

std::vector<Segment> TransformSegments(const Pose2& pose, const std::vector<Segment>& segments) {
  std::vector<Segment> out;
  out.reserve(segments.size());
  for (const Segment& s : segments) out.emplace_back(pose * s.a, pose * s.b);
  return out;
}

void DeclareOptions(OptionScope scope, PartialScanOptions& o) {
  scope.AddDouble("break_distance", &o.break_distance, "m",
                  "consecutive points farther apart start a new partial scan: 0.5 m is well above twice the range "
                  "noise (3.3) and below the gaps occlusions leave",
                  0.01, 100.0);
  scope.AddInt("min_points", &o.min_points,
               "partial scans with fewer points are dropped as clutter or mixed pixels (3)", 1, 1000000);
}

void DeclareOptions(OptionScope scope, PolylineFitOptions& o) {
  scope.AddDouble("segment_length", &o.segment_length, "m",
                  "target segment length of the polylines fit to a scan (scan-map, 3.2.1): 0.5 m averages the "
                  "range noise of about ten points out at 5 m range",
                  0.05, 100.0);
}

}  // namespace minenav
