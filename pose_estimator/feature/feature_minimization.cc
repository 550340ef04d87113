#include "pose_estimator/feature/feature_minimization.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/config.h"

namespace minenav {

FeatureResidual ComputeResidual(const Feature& sensed, const Feature& model, const Pose2& pose) {
  FeatureResidual out;
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  if (model.type == FeatureType::kCorner) {
    const double dx = model.position.x() - pose.x, dy = model.position.y() - pose.y;
    const double xp = dx * c + dy * s;
    const double yp = -dx * s + dy * c;
    out.f = {xp - sensed.position.x(), yp - sensed.position.y()};
    out.jacobian << -c, -s, yp,  //
        s, -c, -xp;
    return out;
  }
  const double cp = std::cos(model.orientation), sp = std::sin(model.orientation);
  const double rp = model.distance - pose.x * cp - pose.y * sp;
  const double php = model.orientation - pose.theta;
  out.f = {rp - sensed.distance, NormalizeAngle(php - sensed.orientation)};
  out.jacobian << -cp, -sp, 0.0,  //
      0.0, 0.0, -1.0;
  return out;
}

Eigen::Matrix2d FeatureInformation(const Feature& sensed, const MinimizationOptions& o) {
  const double n = std::max(1, sensed.num_points);
  const double s2 = o.point_sigma * o.point_sigma;
  Eigen::Matrix2d cov;
  if (sensed.type == FeatureType::kCorner) {
    const double v = std::max(o.corner_variance_factor * s2 / n, o.min_variance) + sensed.position_variance;
    cov << v, 0.0, 0.0, v;
  } else {
    const double len = std::max(sensed.length, 0.1);
    const double v_phi = std::max(12.0 * s2 / (n * len * len), o.min_angle_variance);
    const double v_off = std::max(s2 / n, o.min_variance);
    // r = n . c for the centroid c; turning the normal by d_phi moves r by (t . c) d_phi.
    const Eigen::Vector2d mid = 0.5 * (sensed.start + sensed.end);
    const Eigen::Vector2d t(-std::sin(sensed.orientation), std::cos(sensed.orientation));
    const double k = t.dot(mid);
    cov << v_off + k * k * v_phi, k * v_phi, k * v_phi, v_phi;
  }
  return cov.inverse();
}

namespace {

// Model lines with the sense of the perpendicular fixed so that the sensor, at the initial
// pose, sees the line from the origin side (r_p >= 0), as the sensed lines are.
std::vector<Correspondence> FixLineSense(std::vector<Correspondence> pairs, const Pose2& pose) {
  for (Correspondence& c : pairs) {
    if (c.model.type != FeatureType::kLine) continue;
    const double rp = c.model.distance - pose.x * std::cos(c.model.orientation) -
                      pose.y * std::sin(c.model.orientation);
    if (rp < 0.0) {
      c.model.distance = -c.model.distance;
      c.model.orientation = NormalizeAngle(c.model.orientation + kPi);
    }
  }
  return pairs;
}

struct Solve {
  Pose2 pose;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  bool converged = false;
  int iterations = 0;
};

Solve GaussNewton(const std::vector<Correspondence>& pairs, const std::vector<Eigen::Matrix2d>& w,
                  const Pose2& initial, const MinimizationOptions& o) {
  Solve s;
  s.pose = initial;
  for (int it = 0; it < o.max_iterations; ++it) {
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < pairs.size(); ++i) {
      const FeatureResidual r = ComputeResidual(pairs[i].sensed, pairs[i].model, s.pose);
      h += r.jacobian.transpose() * w[i] * r.jacobian;
      g += r.jacobian.transpose() * w[i] * r.f;
    }
    s.information = h;
    // Solve in the observable subspace only: a pseudo-inverse over the eigenvalues that
    // are not negligible, so an unconstrained direction stays where it started.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(h);
    const double floor = 1e-9 * std::max(eig.eigenvalues().maxCoeff(), 1e-300);
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const double l = eig.eigenvalues()(k);
      if (l > floor) {
        const Eigen::Vector3d v = eig.eigenvectors().col(k);
        d -= v * (v.dot(g) / l);
      }
    }
    s.pose = Pose2(s.pose.x + d.x(), s.pose.y + d.y(), NormalizeAngle(s.pose.theta + d.z()));
    s.iterations = it + 1;
    if (d.head<2>().norm() < o.step_tolerance && std::abs(d.z()) < o.step_tolerance) {
      s.converged = true;
      break;
    }
  }
  // The information at the final pose.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < pairs.size(); ++i) {
    const FeatureResidual r = ComputeResidual(pairs[i].sensed, pairs[i].model, s.pose);
    h += r.jacobian.transpose() * w[i] * r.jacobian;
  }
  s.information = h;
  return s;
}

// The gate excess of a correspondence (> 1 means beyond its gate).
double GateRatio(const Correspondence& c, const Pose2& pose, const MinimizationOptions& o) {
  const FeatureResidual r = ComputeResidual(c.sensed, c.model, pose);
  if (c.model.type == FeatureType::kCorner) return r.f.norm() / o.max_corner_error;
  return std::max(std::abs(r.f.x()) / o.max_line_distance_error,
                  std::abs(r.f.y()) / o.max_line_angle_error);
}

}  // namespace

MinimizationResult MinimizeFeatureError(const std::vector<Correspondence>& input,
                                        const Pose2& initial, const MinimizationOptions& o) {
  MinimizationResult result;
  result.pose = initial;
  std::vector<Correspondence> pairs = FixLineSense(input, initial);
  if (pairs.empty()) {
    result.reason = "no correspondences";
    result.covariance = Eigen::Matrix3d::Identity() * o.unobservable_variance;
    return result;
  }
  Solve s;
  int dropped = 0;
  bool all_gated = false;
  for (;;) {
    std::vector<Eigen::Matrix2d> w;
    for (const Correspondence& c : pairs) w.push_back(FeatureInformation(c.sensed, o));
    s = GaussNewton(pairs, w, initial, o);
    result.iterations += s.iterations;
    // Drop the worst mismatch, if any, and solve again. A mismatch with many points can
    // pull the estimate onto itself, so each pair is judged at the pose the others give
    // (leave one out), where they pin the pose down on their own.
    size_t worst = 0;
    double worst_ratio = 0.0;
    const double min_information = 1.0 / (o.max_std * o.max_std);
    for (size_t i = 0; i < pairs.size(); ++i) {
      Pose2 judge = s.pose;
      if (pairs.size() > 2) {
        std::vector<Correspondence> others = pairs;
        std::vector<Eigen::Matrix2d> wo = w;
        others.erase(others.begin() + static_cast<std::ptrdiff_t>(i));
        wo.erase(wo.begin() + static_cast<std::ptrdiff_t>(i));
        const Solve loo = GaussNewton(others, wo, s.pose, o);
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(loo.information);
        if (eig.eigenvalues().minCoeff() >= min_information) judge = loo.pose;
      }
      const double ratio = GateRatio(pairs[i], judge, o);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = i;
      }
    }
    all_gated = worst_ratio <= 1.0;
    if (all_gated || static_cast<int>(pairs.size()) <= o.min_kept) break;
    pairs.erase(pairs.begin() + static_cast<std::ptrdiff_t>(worst));
    ++dropped;
  }
  result.pose = s.pose;
  result.used = static_cast<int>(pairs.size());
  double sum = 0.0;
  int count = 0;
  for (const Correspondence& c : pairs) {
    const FeatureResidual r = ComputeResidual(c.sensed, c.model, s.pose);
    if (c.model.type == FeatureType::kCorner) {
      sum += r.f.squaredNorm();
      count += 2;
    } else {
      sum += r.f.x() * r.f.x();
      count += 1;
    }
  }
  result.rms_distance = count > 0 ? std::sqrt(sum / count) : 0.0;

  // Covariance and observability. Heading is compared in metres at 1 m lever arm.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s.information);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  const double min_information = 1.0 / (o.max_std * o.max_std);
  std::string weak;
  // When the features disagree more than their weights say (fractal mine walls, a map a
  // little off), scale the covariance by the a-posteriori variance factor so it stays
  // honest; never below the a-priori one.
  double chi2 = 0.0;
  for (const Correspondence& c : pairs) {
    const FeatureResidual r = ComputeResidual(c.sensed, c.model, s.pose);
    chi2 += r.f.dot(FeatureInformation(c.sensed, o) * r.f);
  }
  const int dof = 2 * static_cast<int>(pairs.size()) - 3;
  result.variance_factor = dof > 0 ? std::max(1.0, chi2 / dof) : 1.0;
  double worst_std = 0.0;
  std::string loose;
  for (int k = 0; k < 3; ++k) {
    const double l = eig.eigenvalues()(k);
    const Eigen::Vector3d v = eig.eigenvectors().col(k);
    std::ostringstream os;
    os.precision(2);
    os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    if (l < min_information) {
      cov += v * v.transpose() * o.unobservable_variance;
      weak += (weak.empty() ? "" : ", ") + os.str();
      worst_std = std::numeric_limits<double>::infinity();
    } else {
      const double variance = result.variance_factor / l;
      cov += v * v.transpose() * variance;
      worst_std = std::max(worst_std, std::sqrt(variance));
      if (std::sqrt(variance) > o.max_converged_std) loose += (loose.empty() ? "" : ", ") + os.str();
    }
  }
  result.covariance = cov;
  result.min_std_direction = worst_std;
  if (!weak.empty()) {
    result.reason = "unobservable direction (x, y, theta) " + weak + " from " +
                    std::to_string(pairs.size()) + " correspondences";
  } else if (!s.converged) {
    result.reason = "did not converge in " + std::to_string(o.max_iterations) + " iterations";
  } else if (!all_gated) {
    result.reason = "correspondences disagree beyond the gates after dropping " +
                    std::to_string(dropped);
  } else if (!loose.empty()) {
    result.reason = "weakly constrained direction (x, y, theta) " + loose + ": std " +
                    std::to_string(worst_std) + " > " + std::to_string(o.max_converged_std);
  } else {
    result.converged = true;
    result.reason = "converged with " + std::to_string(pairs.size()) + " correspondences";
  }
  return result;
}

void DeclareOptions(OptionScope scope, MinimizationOptions& o) {
  scope.AddInt("max_iterations", &o.max_iterations, "Gauss-Newton iteration limit (30)", 1, 10000);
  scope.AddDouble("step_tolerance", &o.step_tolerance, "m, rad",
                  "converged when a step is smaller in x, y and heading (1e-6)", 1e-12, 1.0);
  scope.AddDouble("point_sigma", &o.point_sigma, "m",
                  "range noise per scan point, for the feature weights, when it is not measured from the scan "
                  "(measure_range_noise): 0.1 m, the Cyclone's", 0.001, 1.0);
  scope.AddDouble("corner_variance_factor", &o.corner_variance_factor, "1",
                  "a corner's variance per axis is this x sigma^2 / points: a vertex is pinned less well than a "
                  "line by the same points (8)",
                  0.01, 1000.0);
  scope.AddDouble("min_variance", &o.min_variance, "m^2",
                  "floor of corner-axis and line-distance variances: a fit of many points is only as good as the "
                  "wall is straight and the map surveyed (4e-4: 2 cm)",
                  0.0, 1.0);
  scope.AddDouble("min_angle_variance", &o.min_angle_variance, "rad^2",
                  "floor of line-orientation variances (7.6e-5: 0.5 deg)", 0.0, 1.0);
  scope.AddDouble("max_std", &o.max_std, "m",
                  "a direction less certain than this (rad x 1 m for heading) counts as unobservable: only "
                  "parallel walls, one corner (0.5 m)",
                  1e-6, 1000.0);
  scope.AddDouble("unobservable_variance", &o.unobservable_variance, "m^2",
                  "variance put into the covariance along an unobservable direction (1e6: unknown)", 1.0, 1e12);
  scope.AddDouble("max_converged_std", &o.max_converged_std, "m",
                  "a converged pose needs every direction's std below this: a corridor pinned by one weak corner "
                  "is not converged (0.1 m)",
                  1e-6, 1000.0);
  scope.AddDouble("max_corner_error", &o.max_corner_error, "m",
                  "after convergence a corner pair farther apart is a mismatch: the worst is dropped and the "
                  "minimisation repeated (0.15 m; the matcher's 0.5 m tolerances let near-alternatives through)",
                  0.001, 100.0);
  scope.AddDouble("max_line_distance_error", &o.max_line_distance_error, "m",
                  "the same gate for a line's distance (0.15 m)", 0.001, 100.0);
  scope.AddDouble("max_line_angle_error", &o.max_line_angle_error, "rad",
                  "the same gate for a line's orientation (2 deg)", 1e-4, 3.2);
  scope.AddInt("min_kept", &o.min_kept,
               "mismatched correspondences are dropped one at a time while more than this remain (2)", 0, 1000);
}

}  // namespace minenav
