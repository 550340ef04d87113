#include "pose_estimator/iconic/iconic_matcher.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/config.h"

#include "pose_estimator/iconic/iconic_residual.h"

namespace minenav {

std::string ValidateIconicMatchOptions(const IconicMatchOptions& o) {
  std::ostringstream why;
  if (!(o.initial_threshold > 0.0)) why << "initial_threshold must be > 0 m";
  else if (!(o.min_threshold > 0.0)) why << "min_threshold must be > 0 m";
  else if (o.min_threshold > o.initial_threshold) why << "min_threshold is greater than initial_threshold";
  else if (!(o.epsilon_translation > 0.0) || !(o.epsilon_rotation > 0.0)) why << "epsilons must be > 0";
  else if (o.max_iterations < 1) why << "max_iterations must be >= 1";
  else if (o.min_correspondences < 3) why << "min_correspondences must be >= 3";
  else if (!(o.loss_scale > 0.0)) why << "loss_scale must be > 0 m";
  else if (!(o.max_step_translation > 0.0) || !(o.max_step_rotation > 0.0)) why << "max steps must be > 0";
  return why.str();
}

std::vector<Eigen::Vector2d> ValidScanPoints(const LadarScan& scan, std::string* problem) {
  problem->clear();
  const std::string bad = ValidateScan(scan);
  if (!bad.empty()) {
    *problem = "bad scan: " + bad;
    return {};
  }
  std::vector<Eigen::Vector2d> points;
  points.reserve(scan.ranges.size());
  for (const ScanPoint& p : ScanPointsInVehicleFrame(scan)) points.push_back(p.point);
  if (points.empty()) {
    std::ostringstream why;
    why << "scan has no valid reading (" << scan.ranges.size() << " readings, all NaN or outside ["
        << scan.min_range << ", " << scan.max_range << "] m)";
    *problem = why.str();
  }
  return points;
}

namespace {

struct Accumulated {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // J^T W J
  Eigen::Vector3d g = Eigen::Vector3d::Zero();  // J^T W f
  double weighted_sq = 0.0;                     // sum w f^2
  double sum_sq = 0.0;                          // sum f^2
  int count = 0;
};

// Correspondence at `pose` under `threshold`, the normal equations, and the distances.
Accumulated Linearise(const std::vector<Eigen::Vector2d>& points, const CorrespondenceSearch& map,
                      const Pose2& pose, double threshold, const IconicMatchOptions& options,
                      std::vector<double>* distances) {
  Accumulated acc;
  distances->clear();
  const Eigen::Matrix2d R = pose.rotation();
  const Eigen::Vector2d t = pose.translation();
  const std::vector<Segment>& segments = map.segments();
  const std::vector<uint8_t>* open_ends = options.reject_open_ends ? &map.open_ends() : nullptr;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d P = R * p + t;
    const SegmentMatch m = map.Nearest(P, threshold);
    if (!m.matched()) continue;
    if (open_ends && IsOpenEnd(*open_ends, m.segment, m.region)) continue;
    const IconicResidual r =
        ComputeMapResidual(P, t, segments[static_cast<size_t>(m.segment)], m.closest, m.region);
    const double w = RobustWeight(options.loss, r.f, options.loss_scale);
    acc.H.noalias() += w * r.d_pose_m.transpose() * r.d_pose_m;
    acc.g.noalias() += w * r.f * r.d_pose_m.transpose();
    acc.weighted_sq += w * r.f * r.f;
    acc.sum_sq += r.f * r.f;
    ++acc.count;
    distances->push_back(m.distance);
  }
  return acc;
}

double Median(std::vector<double>* v) {
  if (v->empty()) return 0.0;
  auto mid = v->begin() + static_cast<std::ptrdiff_t>(v->size() / 2);
  std::nth_element(v->begin(), mid, v->end());
  return *mid;
}

// True when H is too close to singular to trust (a corridor with no end in view).
bool Degenerate(const Eigen::Matrix3d& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ev = eig.eigenvalues();
  return !(ev(0) > 1e-9 * std::max(ev(2), 1e-300));
}

}  // namespace

IconicMatchResult MatchPointsToMap(const std::vector<Eigen::Vector2d>& all_points, const CorrespondenceSearch& map,
                                   const Pose2& initial, const IconicMatchOptions& options) {
  IconicMatchResult result;
  result.pose = initial;
  std::vector<Eigen::Vector2d> points;
  points.reserve(all_points.size());
  for (const Eigen::Vector2d& p : all_points)
    if (std::isfinite(p.x()) && std::isfinite(p.y())) points.push_back(p);
  result.num_points = static_cast<int>(points.size());

  if (const std::string bad = ValidateIconicMatchOptions(options); !bad.empty()) {
    result.status = "bad options: " + bad;
    return result;
  }
  if (!std::isfinite(initial.x) || !std::isfinite(initial.y) || !std::isfinite(initial.theta)) {
    result.status = "initial pose is not finite";
    return result;
  }
  if (map.segments().empty()) {
    result.status = "map has no segments";
    return result;
  }
  if (points.empty()) {
    result.status = "scan has no valid points";
    return result;
  }

  Pose2 pose = initial;
  double threshold = options.initial_threshold;
  std::vector<double> distances;
  distances.reserve(points.size());
  bool converged = false;
  int iteration = 0;
  while (iteration < options.max_iterations) {
    ++iteration;
    const Accumulated acc = Linearise(points, map, pose, threshold, options, &distances);
    if (acc.count < options.min_correspondences) {
      std::ostringstream why;
      why << "only " << acc.count << " of " << points.size() << " points within " << threshold
          << " m of the map (need " << options.min_correspondences << ")";
      result.status = why.str();
      result.iterations = iteration;
      return result;
    }
    if (Degenerate(acc.H)) {
      result.status = "degenerate geometry: the matched points do not constrain all of x, y, theta";
      result.iterations = iteration;
      return result;
    }
    // Gauss-Newton: F + J D = 0 in the least-squares sense, pose <- pose - D (EQ 17).
    Eigen::Vector3d D = acc.H.ldlt().solve(acc.g);
    const double step = std::hypot(D(0), D(1));
    if (step > options.max_step_translation) D.head<2>() *= options.max_step_translation / step;
    D(2) = std::clamp(D(2), -options.max_step_rotation, options.max_step_rotation);
    pose = Pose2(pose.x - D(0), pose.y - D(1), NormalizeAngle(pose.theta - D(2)));
    // 3.1.2: next threshold = max(median distance, floor); never grows again.
    threshold = std::min(threshold, std::max(Median(&distances), options.min_threshold));
    if (std::abs(D(0)) < options.epsilon_translation && std::abs(D(1)) < options.epsilon_translation &&
        std::abs(D(2)) < options.epsilon_rotation) {
      converged = true;
      break;
    }
  }

  // Statistics and covariance at the final pose.
  const Accumulated acc = Linearise(points, map, pose, threshold, options, &distances);
  result.iterations = iteration;
  result.final_threshold = threshold;
  result.num_inliers = acc.count;
  result.residual = acc.count > 0 ? std::sqrt(acc.sum_sq / acc.count) : 0.0;
  if (acc.count < options.min_correspondences || Degenerate(acc.H)) {
    result.status = "lost the map at the final pose";
    return result;
  }
  const double dof = std::max(1, acc.count - 3);
  result.covariance = (acc.weighted_sq / dof) * acc.H.inverse();
  result.pose = pose;
  if (!converged) {
    std::ostringstream why;
    why << "no convergence in " << options.max_iterations << " iterations";
    result.status = why.str();
    return result;
  }
  result.converged = true;
  result.status = "ok";
  return result;
}

IconicMatchResult MatchScanToMap(const LadarScan& scan, const CorrespondenceSearch& map, const Pose2& initial,
                                 const IconicMatchOptions& options) {
  std::string problem;
  const std::vector<Eigen::Vector2d> points = ValidScanPoints(scan, &problem);
  if (!problem.empty()) {
    IconicMatchResult result;
    result.pose = initial;
    result.num_points = static_cast<int>(points.size());
    result.status = problem;
    return result;
  }
  return MatchPointsToMap(points, map, initial, options);
}

void DeclareOptions(OptionScope scope, IconicMatchOptions& o) {
  scope.AddDouble("initial_threshold", &o.initial_threshold, "m",
                  "correspondence threshold of the first iteration: must cover what the initial pose error does "
                  "to the points (2 m: ~1 m and a few degrees of odometry error at 10 m range)",
                  0.01, 100.0);
  scope.AddDouble("min_threshold", &o.min_threshold, "m",
                  "floor of the threshold, which shrinks to the median correspondence distance each iteration: "
                  "~3 sigma of the range noise (0.3 m for the Cyclone's 0.1 m; 0.15 m for the Typhoon)",
                  0.001, 100.0);
  scope.AddDouble("epsilon_translation", &o.epsilon_translation, "m",
                  "converged when no x/y step is larger (0.1 mm: far below the range noise)", 1e-9, 1.0);
  scope.AddDouble("epsilon_rotation", &o.epsilon_rotation, "rad",
                  "converged when no heading step is larger (1e-5 rad moves a point at 10 m by 0.1 mm)", 1e-12, 1.0);
  scope.AddInt("max_iterations", &o.max_iterations,
               "Gauss-Newton iteration limit in case the epsilons are too small (3.1.2); 50 is several times "
               "what a converging match takes",
               1, 10000);
  scope.AddInt("min_correspondences", &o.min_correspondences,
               "fewer matched points = no estimate; 10 keeps the three unknowns well over-determined", 3, 1000000);
  scope.AddEnum("loss", &o.loss,
                "robust loss (IRLS): none is the thesis's plain least squares; huber or cauchy keep clutter and "
                "mixed pixels from pulling the estimate",
                {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy});
  scope.AddDouble("loss_scale", &o.loss_scale, "m",
                  "scale of the robust loss: residuals beyond it lose weight (0.1 m ~ the Cyclone's range noise)",
                  1e-4, 10.0);
  scope.AddBool("reject_open_ends", &o.reject_open_ends,
                "skip points nearest to the open end of a polyline: they see what the map does not hold, and "
                "pairing them with the end would pull the estimate along the wall");
  scope.AddDouble("max_step_translation", &o.max_step_translation, "m",
                  "a longer x/y step is cut to this: with a large first threshold Gauss-Newton can overshoot "
                  "(1 m: about the initial error it must recover)",
                  1e-6, 100.0);
  scope.AddDouble("max_step_rotation", &o.max_step_rotation, "rad",
                  "a larger heading step is cut to this, for the same reason (0.35 rad, 20 deg)", 1e-6, 3.2);
}

}  // namespace minenav
