#include "common/geometry.h"

#include <cmath>
#include <limits>

namespace minenav {

namespace {
double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }
}  // namespace

SegmentProjection ProjectOntoSegment(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d d = s.b - s.a;
  const double len2 = d.squaredNorm();
  SegmentProjection out;
  if (len2 <= 0.0) {
    out.point = s.a;
    out.t = 0.0;
    out.region = SegmentRegion::kStartPoint;
  } else {
    const double t = (p - s.a).dot(d) / len2;
    if (t <= 0.0) {
      out.t = 0.0;
      out.region = SegmentRegion::kStartPoint;
    } else if (t >= 1.0) {
      out.t = 1.0;
      out.region = SegmentRegion::kEndPoint;
    } else {
      out.t = t;
      out.region = SegmentRegion::kInterior;
    }
    out.point = s.a + out.t * d;
  }
  out.distance = (p - out.point).norm();
  return out;
}

double SignedDistanceToLine(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d d = s.b - s.a;
  const double len = d.norm();
  if (len <= 0.0) return (p - s.a).norm();
  return Cross(d, p - s.a) / len;
}

std::optional<double> RaySegmentIntersection(const Eigen::Vector2d& origin,
                                             const Eigen::Vector2d& dir, const Segment& s) {
  // origin + r*dir = a + u*(b-a)  =>  solve with cross products.
  const Eigen::Vector2d e = s.b - s.a;
  const double denom = Cross(dir, e);
  if (denom == 0.0) return std::nullopt;
  const Eigen::Vector2d w = s.a - origin;
  const double r = Cross(w, e) / denom;
  const double u = Cross(w, dir) / denom;
  // A ray aimed exactly at the vertex two segments share must hit one of them: rounding
  // can put u a hair outside [0, 1] on both, so the ends get a tolerance of a few ulps.
  constexpr double kEndTolerance = 1e-12;
  if (r < 0.0 || u < -kEndTolerance || u > 1.0 + kEndTolerance) return std::nullopt;
  return r;
}

std::optional<Eigen::Vector2d> SegmentIntersection(const Segment& s1, const Segment& s2) {
  const Eigen::Vector2d d1 = s1.b - s1.a;
  const auto r = RaySegmentIntersection(s1.a, d1, s2);
  if (!r || *r > 1.0) return std::nullopt;
  return s1.a + *r * d1;
}

std::optional<RayHit> CastRay(const Eigen::Vector2d& origin, double bearing,
                              const std::vector<Segment>& segments, double max_range) {
  const Eigen::Vector2d dir(std::cos(bearing), std::sin(bearing));
  RayHit best{std::numeric_limits<double>::infinity(), -1};
  for (size_t i = 0; i < segments.size(); ++i) {
    const auto r = RaySegmentIntersection(origin, dir, segments[i]);
    if (r && *r < best.range) best = {*r, static_cast<int>(i)};
  }
  if (best.segment < 0 || best.range > max_range) return std::nullopt;
  return best;
}

double PolylineLength(const std::vector<Eigen::Vector2d>& points, bool closed) {
  double total = 0.0;
  for (size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  if (closed && points.size() > 2) total += (points.front() - points.back()).norm();
  return total;
}

double PointToPolylineDistance(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& points,
                               bool closed) {
  if (points.empty()) return std::numeric_limits<double>::infinity();
  if (points.size() == 1) return (p - points[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < points.size(); ++i)
    best = std::min(best, PointToSegmentDistance(p, Segment(points[i - 1], points[i])));
  if (closed && points.size() > 2)
    best = std::min(best, PointToSegmentDistance(p, Segment(points.back(), points.front())));
  return best;
}

bool SameSegments(const std::vector<Segment>& a, const std::vector<Segment>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].a != b[i].a || a[i].b != b[i].b) return false;
  return true;
}

}  // namespace minenav
