#include "mapper/pose_estimation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "mapper/integral_error.h"
#include "mapper/line_search.h"

namespace minenav::mapper {

std::string ValidateOptions(const PoseEstimationOptions& o) {
  std::ostringstream why;
  if (!(o.final_threshold > 0.0) || !(o.initial_threshold >= o.final_threshold))
    why << "need 0 < final_threshold <= initial_threshold, got " << o.final_threshold << " and "
        << o.initial_threshold << " m";
  else if (!(o.threshold_factor > 0.0 && o.threshold_factor <= 1.0))
    why << "threshold_factor must be in (0, 1], got " << o.threshold_factor;
  else if (o.max_iterations < 1)
    why << "max_iterations must be >= 1, got " << o.max_iterations;
  else if (!(o.step_resolution > 0.0) || !(o.gradient_tolerance >= 0.0))
    why << "step_resolution must be > 0 and gradient_tolerance >= 0";
  else if (o.min_pieces < 1)
    why << "min_pieces must be >= 1, got " << o.min_pieces;
  else if (!(o.heading_search_range >= 0.0 && o.heading_search_range <= kPi))
    why << "heading_search_range must be in [0, pi] rad, got " << o.heading_search_range;
  else if (o.heading_search_range > 0.0 && !(o.heading_search_step > 0.0))
    why << "heading_search_step must be > 0 rad, got " << o.heading_search_step;
  else if (!(o.heading_search_margin >= 0.0))
    why << "heading_search_margin must be >= 0, got " << o.heading_search_margin;
  return why.str();
}

void DeclareOptions(OptionScope s, PoseEstimationOptions& o) {
  s.AddDouble("initial_threshold", &o.initial_threshold, "m",
              "correspondence threshold of the first iteration, about the largest initial error expected: 3 m "
              "covers dead-reckoned survey stations (thesis 5.2), 0.5 m a pose already close (refinement, "
              "tracking with odometry), where a larger one lets far clutter pull the estimate",
              0.001, 100.0);
  s.AddDouble("final_threshold", &o.final_threshold, "m",
              "the threshold shrinks to this, a few sigma of the range noise: 0.1 m for the Typhoon's "
              "4.4 cm, 0.05 m for a SICK's 1 cm",
              0.001, 100.0);
  s.AddDouble("threshold_factor", &o.threshold_factor, "1",
              "factor applied to the threshold every iteration (0 < f <= 1); 0.9 takes 3 m to 0.1 m in "
              "about 32 iterations, slowly enough that the matches follow the pose",
              0.01, 1.0);
  s.AddInt("max_iterations", &o.max_iterations,
           "iteration limit (termination 4); 120 leaves room for the shrinking iterations and the "
           "descent at the final threshold [iterations]",
           1, 100000);
  s.AddDouble("gradient_tolerance", &o.gradient_tolerance, "m",
              "termination 1: the gradient per matched length (a mean offset) below this ends the search once "
              "the threshold is final; 1e-6 m is far below the sensor noise",
              0.0, 1.0);
  s.AddDouble("step_resolution", &o.step_resolution, "m",
              "line-search resolution; both steps below it end the search (termination 2); 1e-4 m, "
              "far below the sensor noise",
              1e-9, 1.0);
  s.AddDouble("min_translation_change", &o.min_translation_change, "m",
              "termination 3: a pose change below this and min_rotation_change ends the search; 2e-5 m",
              0.0, 1.0);
  s.AddDouble("min_rotation_change", &o.min_rotation_change, "rad",
              "termination 3, heading part; 2e-6 rad: 2e-5 m at 10 m", 0.0, 1.0);
  s.AddInt("min_pieces", &o.min_pieces,
           "fewer error pieces than this: no estimate (too little overlap with the map to determine three pose "
           "parameters); 20 for a new scan, 10 in refinement, where the pose is already close [pieces]",
           1, 1000000);
  s.AddDouble("heading_search_range", &o.heading_search_range, "rad",
              "before the line searches, score headings within +- this of the initial one by the points that find "
              "a contour within initial_threshold and start from the best; 0 = off, the thesis's "
              "estimator; odometry that lags turns (MIT CSAIL) needs 20 degrees",
              0.0, kPi);
  s.AddDouble("heading_search_step", &o.heading_search_step, "rad",
              "step of the heading search; 2 degrees moves points at 10 m by 0.35 m, within the "
              "threshold that then refines them",
              1e-6, kPi);
  s.AddDouble("heading_search_margin", &o.heading_search_margin, "1",
              "another heading must match this fraction more points than the initial one to win; 0.05 "
              "keeps noise from moving a good start",
              0.0, 10.0);
}

namespace {

// The pieces of one correspondence, with their geometry copied out for fast re-evaluation.
struct PosePiece {
  Eigen::Vector2d q_i, q_j;  // vehicle frame
  Eigen::Vector2d s, e;      // contour segment, world frame
  Eigen::Vector2d u, n;      // its unit direction and left normal (fixed while the map is)
};

std::vector<PosePiece> CollectPieces(const PreprocessedScan& scan, const ScanCorrespondence& corr,
                                     const ContourMap& map) {
  std::vector<PosePiece> out;
  out.reserve(corr.pieces.size());
  for (const ErrorPiece& p : corr.pieces) {
    const auto& pts = scan.partial_scans[static_cast<size_t>(p.partial)].points;
    const Contour& c = map.Get(p.segment.contour);
    const Segment seg = c.GetSegment(p.segment.segment);
    const Eigen::Vector2d d = seg.b - seg.a;
    const double h = d.norm();
    if (h <= 0.0) continue;
    const Eigen::Vector2d u = d / h;
    out.push_back({pts[static_cast<size_t>(p.i)], pts[static_cast<size_t>(p.j)], seg.a, seg.b, u, {-u.y(), u.x()}});
  }
  return out;
}

// Σ PieceError with the rotation computed once and the segment frames precomputed (the
// line searches call this thousands of times per scan).
double Error(const std::vector<PosePiece>& pieces, const Pose2& pose) {
  const Eigen::Matrix2d r = pose.rotation();
  const Eigen::Vector2d t = pose.translation();
  double f = 0.0;
  for (const PosePiece& p : pieces) {
    const Eigen::Vector2d pi = r * p.q_i + t, pj = r * p.q_j + t;
    const double di = p.n.dot(pi - p.s), dj = p.n.dot(pj - p.s);
    f += std::abs(p.u.dot(pj - pi)) * (di * di + di * dj + dj * dj) / 3.0;
  }
  return f;
}

Eigen::Vector3d Gradient(const std::vector<PosePiece>& pieces, const Pose2& pose, double* value) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double f = 0.0;
  for (const PosePiece& p : pieces) {
    const PosePieceGradient pg = PieceErrorPoseGradient(p.q_i, p.q_j, pose, p.s, p.e);
    g += pg.gradient;
    f += pg.value;
  }
  if (value) *value = f;
  return g;
}

double MatchedLength(const std::vector<PosePiece>& pieces, const Pose2& pose) {
  double len = 0.0;
  for (const PosePiece& p : pieces) len += std::abs((p.e - p.s).normalized().dot(pose * p.q_j - pose * p.q_i));
  return len;
}

// RMS distance of the matched points from the vehicle origin: converts an angle step into
// the distance the points move.
double LeverArm(const std::vector<PosePiece>& pieces) {
  double sum = 0.0;
  for (const PosePiece& p : pieces) sum += p.q_i.squaredNorm();
  return std::max(1.0, std::sqrt(sum / static_cast<double>(std::max<size_t>(1, pieces.size()))));
}

}  // namespace

ScanFit MeasureScanFit(const PreprocessedScan& scan, const Pose2& pose, const ContourMap& map, double threshold) {
  const ScanCorrespondence corr = CorrespondScan(scan, pose, map, threshold);
  const std::vector<PosePiece> pieces = CollectPieces(scan, corr, map);
  ScanFit fit;
  fit.error = Error(pieces, pose);
  fit.matched_length = MatchedLength(pieces, pose);
  fit.num_pieces = static_cast<int>(pieces.size());
  fit.num_points = corr.num_points;
  fit.num_inliers = corr.num_matched;
  return fit;
}

Pose2 SearchHeading(const PreprocessedScan& scan, const Pose2& initial, const ContourMap& map,
                    const PoseEstimationOptions& o) {
  if (!(o.heading_search_range > 0.0) || !(o.heading_search_step > 0.0)) return initial;
  const auto score = [&](double dtheta) {
    const ScanCorrespondence c = CorrespondScan(scan, Pose2(initial.x, initial.y, initial.theta + dtheta), map,
                                                o.initial_threshold);
    return c.num_matched;
  };
  const int base = score(0.0);
  int best = base;
  double best_dtheta = 0.0;
  const int steps = static_cast<int>(std::floor(o.heading_search_range / o.heading_search_step + 1e-9));
  for (int k = 1; k <= steps; ++k)
    for (const double sign : {-1.0, 1.0}) {
      const double dtheta = sign * k * o.heading_search_step;
      const int n = score(dtheta);
      if (n > best) {
        best = n;
        best_dtheta = dtheta;
      }
    }
  if (static_cast<double>(best) <= static_cast<double>(base) * (1.0 + o.heading_search_margin)) return initial;
  return Pose2(initial.x, initial.y, NormalizeAngle(initial.theta + best_dtheta));
}

namespace {

// The fit at the result's pose, and the core's summary of it.
void SetFit(const ScanFit& fit, PoseEstimationResult* out) {
  out->fit = fit;
  out->num_points = fit.num_points;
  out->num_inliers = fit.num_inliers;
  out->residual = std::sqrt(fit.MeanSquaredDistance());
}

// The thesis estimator (4.3.3) from one start.
PoseEstimationResult EstimateFrom(const PreprocessedScan& scan, const Pose2& initial, const ContourMap& map,
                                  const PoseEstimationOptions& o) {
  PoseEstimationResult out;
  out.pose = initial;
  double threshold = o.initial_threshold;
  for (int iter = 1; iter <= o.max_iterations; ++iter) {
    out.iterations = iter;
    out.threshold = threshold;
    const ScanCorrespondence corr = CorrespondScan(scan, out.pose, map, threshold);
    const std::vector<PosePiece> pieces = CollectPieces(scan, corr, map);
    if (static_cast<int>(pieces.size()) < o.min_pieces) {
      out.status = "too few correspondences (" + std::to_string(pieces.size()) + " pieces within " +
                   std::to_string(threshold) + " m)";
      SetFit(MeasureScanFit(scan, out.pose, map, threshold), &out);
      return out;
    }
    const double length = std::max(1e-9, MatchedLength(pieces, out.pose));
    const double lever = LeverArm(pieces);
    const Pose2 before = out.pose;

    // Line search on x, y along the negative gradient; λ is metres.
    double f0 = 0.0;
    const Eigen::Vector3d g = Gradient(pieces, out.pose, &f0);
    const Eigen::Vector2d gxy = g.head<2>();
    bool small_step_xy = true;
    if (gxy.norm() > 0.0) {
      const Eigen::Vector2d dir = -gxy.normalized();
      const Pose2 base = out.pose;
      // With correspondence fixed the error is exactly quadratic in the translation.
      const LineSearchResult ls = QuadraticLineSearch(
          [&](double l) { return Error(pieces, Pose2(base.x + l * dir.x(), base.y + l * dir.y(), base.theta)); }, f0,
          -gxy.norm(), threshold, o.step_resolution);
      if (ls.lambda > 0.0) {
        out.pose = Pose2(base.x + ls.lambda * dir.x(), base.y + ls.lambda * dir.y(), base.theta);
        f0 = ls.value;
      }
      small_step_xy = ls.lambda < o.step_resolution * 2.0;
    }
    // Line search on θ; λ is radians, bounded so no point moves more than the threshold.
    double f1 = 0.0;
    const double gt = Gradient(pieces, out.pose, &f1).z();
    bool small_step_t = true;
    if (gt != 0.0) {
      const double dir = gt > 0.0 ? -1.0 : 1.0;
      const Pose2 base = out.pose;
      const LineSearchResult ls =
          LineSearch([&](double l) { return Error(pieces, Pose2(base.x, base.y, base.theta + dir * l)); }, f1,
                     threshold / lever, o.step_resolution / lever);
      if (ls.lambda > 0.0) out.pose = Pose2(base.x, base.y, NormalizeAngle(base.theta + dir * ls.lambda));
      small_step_t = ls.lambda < 2.0 * o.step_resolution / lever;
    }

    const bool at_final = threshold <= o.final_threshold;
    const double grad_xy = gxy.norm() / length, grad_t = std::abs(gt) / (lever * length);
    if (at_final) {
      if (grad_xy < o.gradient_tolerance && grad_t < o.gradient_tolerance) {
        out.converged = true;
        out.status = "gradient small";
      } else if (small_step_xy && small_step_t) {
        out.converged = true;
        out.status = "step (lambda) small";
      } else if (TranslationDistance(before, out.pose) < o.min_translation_change &&
                 HeadingDistance(before, out.pose) < o.min_rotation_change) {
        out.converged = true;
        out.status = "pose change small";
      }
      if (out.converged) break;
    }
    threshold = std::max(o.final_threshold, threshold * o.threshold_factor);
  }
  if (!out.converged) out.status = "iteration limit";
  SetFit(MeasureScanFit(scan, out.pose, map, out.threshold), &out);
  return out;
}

}  // namespace

PoseEstimationResult EstimatePose(const PreprocessedScan& scan, const Pose2& initial, const ContourMap& map,
                                  const PoseEstimationOptions& o) {
  PoseEstimationResult from_initial = EstimateFrom(scan, initial, map, o);
  const Pose2 searched = SearchHeading(scan, initial, map, o);
  if (searched.theta == initial.theta) return from_initial;
  // The searched heading only seeds a second descent; the final fits decide (more points
  // matched at the final threshold, then the smaller mean squared distance), so a scan the
  // initial heading already explains is never pulled away by a look-alike heading.
  PoseEstimationResult from_searched = EstimateFrom(scan, searched, map, o);
  const auto better = [](const PoseEstimationResult& a, const PoseEstimationResult& b) {
    if (a.fit.num_inliers != b.fit.num_inliers) return a.fit.num_inliers > b.fit.num_inliers;
    return a.fit.MeanSquaredDistance() < b.fit.MeanSquaredDistance();
  };
  return better(from_searched, from_initial) ? from_searched : from_initial;
}

}  // namespace minenav::mapper
