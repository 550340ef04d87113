#pragma once
// A rigid transform in the plane (SE(2)): rotation by theta, then translation.
// Pose2 a_T_b maps points from frame b into frame a: p_a = a_T_b * p_b.
// Composition follows the frames: a_T_c = a_T_b * b_T_c.

#include <Eigen/Core>
#include <cmath>
#include <ostream>

#include "common/angle.h"

namespace minenav {

struct Pose2 {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad, counter-clockwise, kept in (-pi, pi] by the operations below

  Pose2() = default;
  Pose2(double x_in, double y_in, double theta_in) : x(x_in), y(y_in), theta(theta_in) {}

  Eigen::Vector2d translation() const { return {x, y}; }
  Eigen::Matrix2d rotation() const {
    const double c = std::cos(theta), s = std::sin(theta);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    return r;
  }
  Eigen::Vector3d vector() const { return {x, y, theta}; }
  static Pose2 FromVector(const Eigen::Vector3d& v) { return {v.x(), v.y(), NormalizeAngle(v.z())}; }

  // p_a = a_T_b * p_b
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }

  Pose2 operator*(const Pose2& b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, NormalizeAngle(theta + b.theta)};
  }

  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, NormalizeAngle(-theta)};
  }
};

// The motion from `from` to `to` expressed in `from`'s frame: from^-1 * to.
inline Pose2 Between(const Pose2& from, const Pose2& to) { return from.inverse() * to; }

// The pose a fraction f of the way from a to b: position linearly, heading the shorter
// way round. f = 0 gives a, f = 1 gives b.
inline Pose2 InterpolatePose(const Pose2& a, const Pose2& b, double f) {
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
          NormalizeAngle(a.theta + f * NormalizeAngle(b.theta - a.theta))};
}

inline double TranslationDistance(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
inline double HeadingDistance(const Pose2& a, const Pose2& b) {
  return std::abs(NormalizeAngle(a.theta - b.theta));
}

inline std::ostream& operator<<(std::ostream& os, const Pose2& p) {
  return os << "(" << p.x << ", " << p.y << ", " << p.theta << ")";
}

}  // namespace minenav
