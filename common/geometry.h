#pragma once
// Segment and polyline geometry in the plane: distances, projections, intersections and
// ray casting. Plain functions over Eigen vectors; lengths in metres.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace minenav {

struct Segment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();

  Segment() = default;
  Segment(const Eigen::Vector2d& a_in, const Eigen::Vector2d& b_in) : a(a_in), b(b_in) {}
  Segment(double x1, double y1, double x2, double y2) : a(x1, y1), b(x2, y2) {}

  double length() const { return (b - a).norm(); }
  Eigen::Vector2d direction() const { return b - a; }
};

// Where on a segment the closest point to a query lies.
enum class SegmentRegion { kStartPoint, kInterior, kEndPoint };

struct SegmentProjection {
  Eigen::Vector2d point;  // closest point on the segment
  double t = 0.0;         // its parameter in [0, 1] along a -> b
  double distance = 0.0;  // m from the query to `point`
  SegmentRegion region = SegmentRegion::kInterior;
};

// Closest point on segment s to p (a degenerate segment projects to its start point).
SegmentProjection ProjectOntoSegment(const Eigen::Vector2d& p, const Segment& s);

inline double PointToSegmentDistance(const Eigen::Vector2d& p, const Segment& s) {
  return ProjectOntoSegment(p, s).distance;
}

// Signed distance from p to the infinite line through s; positive on the left of a -> b.
double SignedDistanceToLine(const Eigen::Vector2d& p, const Segment& s);

// Distance along the ray origin + r * dir (dir need not be unit; r is in units of |dir|)
// to its first crossing of s, if r >= 0. Parallel rays do not hit.
std::optional<double> RaySegmentIntersection(const Eigen::Vector2d& origin,
                                             const Eigen::Vector2d& dir, const Segment& s);

// Intersection point of two segments, if they cross (touching endpoints counts).
std::optional<Eigen::Vector2d> SegmentIntersection(const Segment& s1, const Segment& s2);

// The nearest hit of a ray against many segments: range in metres along the unit
// direction at `bearing` (rad, world frame), and the index of the segment hit.
struct RayHit {
  double range = 0.0;
  int segment = -1;
};
std::optional<RayHit> CastRay(const Eigen::Vector2d& origin, double bearing,
                              const std::vector<Segment>& segments, double max_range);

// Polylines: consecutive points joined by segments, optionally closed.
double PolylineLength(const std::vector<Eigen::Vector2d>& points, bool closed);
double PointToPolylineDistance(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& points,
                               bool closed);

// True when both lists hold the same segments, end for end, in the same order (a map
// message that repeats the map in force needs no rebuild).
bool SameSegments(const std::vector<Segment>& a, const std::vector<Segment>& b);

}  // namespace minenav
