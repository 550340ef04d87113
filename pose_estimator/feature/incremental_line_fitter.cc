#include "pose_estimator/feature/incremental_line_fitter.h"

#include <cmath>

namespace minenav {

void IncrementalLineFitter::Add(const Eigen::Vector2d& p) {
  const Eigen::Vector2d q = p - origin_;
  ++n_;
  sx_ += q.x();
  sy_ += q.y();
  sxx_ += q.x() * q.x();
  sxy_ += q.x() * q.y();
  syy_ += q.y() * q.y();
  if (ray_variance_ > 0.0 && p.norm() > 0.0) {
    const Eigen::Vector2d d = p.normalized();
    dxx_ += d.x() * d.x();
    dxy_ += d.x() * d.y();
    dyy_ += d.y() * d.y();
  }
}

void IncrementalLineFitter::Remove(const Eigen::Vector2d& p) {
  const Eigen::Vector2d q = p - origin_;
  --n_;
  sx_ -= q.x();
  sy_ -= q.y();
  sxx_ -= q.x() * q.x();
  sxy_ -= q.x() * q.y();
  syy_ -= q.y() * q.y();
  if (ray_variance_ > 0.0 && p.norm() > 0.0) {
    const Eigen::Vector2d d = p.normalized();
    dxx_ -= d.x() * d.x();
    dxy_ -= d.x() * d.y();
    dyy_ -= d.y() * d.y();
  }
  if (n_ <= 0) Clear();
}

void IncrementalLineFitter::Clear() {
  n_ = 0;
  sx_ = sy_ = sxx_ = sxy_ = syy_ = 0.0;
  dxx_ = dxy_ = dyy_ = 0.0;
}

LineFit IncrementalLineFitter::Fit() const {
  LineFit f;
  f.count = n_;
  if (n_ < 2) return f;
  const double n = static_cast<double>(n_);
  const double mx = sx_ / n, my = sy_ / n;
  const double cxx = sxx_ / n - mx * mx;
  const double cyy = syy_ / n - my * my;
  const double cxy = sxy_ / n - mx * my;
  const double half_trace = 0.5 * (cxx + cyy);
  const double root = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
  const double lambda_max = half_trace + root;
  if (lambda_max <= 1e-18) return f;  // all points coincide
  // Direction from the scatter without the expected ray-noise scatter.
  const double k = ray_variance_ / n;
  const double angle = 0.5 * std::atan2(2.0 * (cxy - k * dxy_), (cxx - k * dxx_) - (cyy - k * dyy_));
  f.valid = true;
  f.centroid = origin_ + Eigen::Vector2d(mx, my);
  f.direction = {std::cos(angle), std::sin(angle)};
  f.rms = std::sqrt(std::max(0.0, half_trace - root));
  return f;
}

}  // namespace minenav
