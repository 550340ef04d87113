#include "planner/testing/path_checker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace minenav::testing {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double Wrap(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// Winding-number test (points on the boundary count as inside).
bool Inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  int winding = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    if (PointToSegmentDistance(p, {a, b}) < 1e-12) return true;
    const double cross = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && cross > 0) ++winding;
    } else if (b.y() <= p.y() && cross < 0) {
      --winding;
    }
  }
  return winding != 0;
}

double PolygonToSegment(const std::vector<Eigen::Vector2d>& poly, const Segment& s) {
  if (Inside(poly, s.a) || Inside(poly, s.b)) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Segment e(poly[i], poly[(i + 1) % poly.size()]);
    if (SegmentIntersection(e, s)) return 0.0;
    d = std::min({d, PointToSegmentDistance(e.a, s), PointToSegmentDistance(s.a, e), PointToSegmentDistance(s.b, e)});
  }
  return d;
}

// Pose at fraction f of a checked piece, given its geometry.
struct PieceGeometry {
  int kind = 0;  // 0 straight, 1 arc, 2 turn in place
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double signed_angle = 0.0;  // rad the heading turns
  double length = 0.0;        // m driven
};

Pose2 At(const Pose2& a, const Pose2& b, const PieceGeometry& g, double f) {
  if (g.kind == 0) return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), a.theta};
  const double turn = f * g.signed_angle;
  if (g.kind == 2) return {a.x, a.y, Wrap(a.theta + turn)};
  const Eigen::Vector2d r = a.translation() - g.centre;
  const double c = std::cos(turn), s = std::sin(turn);
  return {g.centre.x() + c * r.x() - s * r.y(), g.centre.y() + s * r.x() + c * r.y(), Wrap(a.theta + turn)};
}

}  // namespace

double PoseClearance(const std::vector<Segment>& map, const std::vector<Eigen::Vector2d>& polygon, const Pose2& pose) {
  std::vector<Eigen::Vector2d> poly(polygon.size());
  for (size_t v = 0; v < poly.size(); ++v) poly[v] = pose * polygon[v];
  double d = std::numeric_limits<double>::infinity();
  for (const Segment& s : map) d = std::min(d, PolygonToSegment(poly, s));
  return d;
}

PathCheckReport CheckPath(const std::vector<Segment>& map, const Pose2& start, const std::vector<CheckedPiece>& pieces,
                          const PathCheckSettings& st) {
  PathCheckReport report;
  report.min_clearance = std::numeric_limits<double>::infinity();
  double reach = 0.0;
  for (const auto& v : st.polygon) reach = std::max(reach, v.norm());
  const double tol = st.pose_tolerance, R = st.turn_radius;
  const auto fail = [&](size_t i, const std::string& what) {
    report.ok = false;
    report.problem = "piece " + std::to_string(i) + ": " + what;
    return report;
  };
  std::vector<Eigen::Vector2d> poly(st.polygon.size());
  // The least distance from the polygon at p to the map; false on contact.
  const auto sample = [&](const Pose2& p) {
    for (size_t v = 0; v < poly.size(); ++v) poly[v] = p * st.polygon[v];
    ++report.samples;
    for (const Segment& s : map) {
      const double d = PolygonToSegment(poly, s);
      report.min_clearance = std::min(report.min_clearance, d);
      if (d < st.clearance) return false;
    }
    return true;
  };
  if (!sample(start)) {
    report.problem = "the start pose is in contact";
    return report;
  }
  Pose2 a = start;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Pose2 b = pieces[i].end;
    const int m = pieces[i].motion;
    PieceGeometry g;
    const Eigen::Vector2d heading(std::cos(a.theta), std::sin(a.theta));
    const Eigen::Vector2d move = b.translation() - a.translation();
    double sweep = 0.0;
    if (m == 0 || m == 1) {
      if (std::abs(Wrap(b.theta - a.theta)) > tol) return fail(i, "a straight move changes the heading");
      const double along = move.dot(heading), across = heading.x() * move.y() - heading.y() * move.x();
      if (std::abs(across) > tol) return fail(i, "a straight move leaves the heading line");
      if ((m == 0 && along < -tol) || (m == 1 && along > tol)) return fail(i, "a straight move goes the wrong way");
      g.length = std::abs(along);
      sweep = g.length;
    } else if (m == 4) {
      if (move.norm() > tol) return fail(i, "a turn in place moves");
      g.kind = 2;
      g.signed_angle = Wrap(b.theta - a.theta);
      sweep = reach * std::abs(g.signed_angle);
    } else if (m == 2 || m == 3 || m == 5 || m == 6) {
      const int side = (m == 2 || m == 5) ? 1 : -1;
      const int dir = (m == 2 || m == 3) ? 1 : -1;
      g.kind = 1;
      g.centre = a.translation() + side * R * Eigen::Vector2d(-heading.y(), heading.x());
      const Eigen::Vector2d end_centre =
          b.translation() + side * R * Eigen::Vector2d(-std::sin(b.theta), std::cos(b.theta));
      if ((end_centre - g.centre).norm() > tol)
        return fail(i, "the arc's ends are not on one circle of the turning radius on its side");
      // Heading turns side * dir * (arc angle); the arc angle is in [0, 2 pi).
      double angle = std::fmod(side * dir * (b.theta - a.theta), kTwoPi);
      if (angle < 0) angle += kTwoPi;
      g.signed_angle = side * dir * angle;
      g.length = R * angle;
      sweep = (R + reach) * angle;
    } else {
      return fail(i, "unknown motion " + std::to_string(m));
    }
    report.length += g.length;
    const int n = std::max(1, static_cast<int>(std::ceil(sweep / st.sample_step)));
    for (int k = 1; k <= n; ++k) {
      const Pose2 p = At(a, b, g, static_cast<double>(k) / n);
      if (!sample(p))
        return fail(i, "contact at pose (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                           std::to_string(p.theta) + "): less than " + std::to_string(st.clearance) + " m from a segment");
    }
    a = b;
  }
  report.ok = true;
  return report;
}

}  // namespace minenav::testing
