#include "pose_estimator/feature/feature_types.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/angle.h"

namespace minenav {

double Feature::Azimuth() const {
  if (type == FeatureType::kCorner) return std::atan2(position.y(), position.x());
  const Eigen::Vector2d mid = 0.5 * (start + end);
  return std::atan2(mid.y(), mid.x());
}

double Feature::Range() const {
  if (type == FeatureType::kCorner) return position.norm();
  return (0.5 * (start + end)).norm();
}

Eigen::Vector2d Feature::Normal() const { return {std::cos(orientation), std::sin(orientation)}; }

double Feature::SignedDistance(const Eigen::Vector2d& p) const { return Normal().dot(p) - distance; }

Feature MakeCorner(const Eigen::Vector2d& vertex, const Eigen::Vector2d& arm1,
                   const Eigen::Vector2d& arm2, bool occlusion) {
  Feature f;
  f.type = FeatureType::kCorner;
  f.position = vertex;
  const Eigen::Vector2d u1 = arm1.normalized(), u2 = arm2.normalized();
  f.concave_angle = std::acos(std::clamp(u1.dot(u2), -1.0, 1.0));
  Eigen::Vector2d b = u1 + u2;
  // Nearly straight "corners" have no well-defined bisector; take the left normal of arm1.
  if (b.norm() < 1e-9) b = Eigen::Vector2d(-u1.y(), u1.x());
  f.bisector = std::atan2(b.y(), b.x());
  f.occlusion = occlusion;
  return f;
}

Feature MakeLine(const Eigen::Vector2d& start, const Eigen::Vector2d& end) {
  Feature f;
  f.type = FeatureType::kLine;
  f.start = start;
  f.end = end;
  f.length = (end - start).norm();
  const Eigen::Vector2d d = (end - start).normalized();
  Eigen::Vector2d n(d.y(), -d.x());
  double r = n.dot(start);
  if (r < 0.0) {
    n = -n;
    r = -r;
  }
  f.distance = r;
  f.orientation = std::atan2(n.y(), n.x());
  return f;
}

Feature TransformFeature(const Feature& f, const Pose2& a_T_b) {
  const Pose2 b_T_a = a_T_b.inverse();
  Feature g = f;
  if (f.type == FeatureType::kCorner) {
    g.position = b_T_a * f.position;
    g.bisector = NormalizeAngle(f.bisector - a_T_b.theta);
    return g;
  }
  g.start = b_T_a * f.start;
  g.end = b_T_a * f.end;
  // EQ 6 (with the line's own orientation, not the pose's, in the cosine and sine).
  double r = f.distance - a_T_b.x * std::cos(f.orientation) - a_T_b.y * std::sin(f.orientation);
  double phi = f.orientation - a_T_b.theta;
  if (r < 0.0) {
    r = -r;
    phi += kPi;
  }
  g.distance = r;
  g.orientation = NormalizeAngle(phi);
  return g;
}

void SortByAzimuth(std::vector<Feature>* features) {
  std::stable_sort(features->begin(), features->end(),
                   [](const Feature& a, const Feature& b) { return a.Azimuth() < b.Azimuth(); });
}

std::string ToString(const Feature& f) {
  std::ostringstream os;
  os.precision(3);
  if (f.type == FeatureType::kCorner) {
    os << (f.occlusion ? "occlusion corner (" : "corner (") << f.position.x() << ", "
       << f.position.y() << ") concave " << RadToDeg(f.concave_angle) << " deg bisector "
       << RadToDeg(f.bisector) << " deg";
  } else {
    os << "line r " << f.distance << " m phi " << RadToDeg(f.orientation) << " deg length "
       << f.length << " m";
  }
  return os.str();
}

}  // namespace minenav
