#include "planner/footprint_collision.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {

double SegmentToSegmentDistance(const Segment& s, const Segment& t) {
  if (SegmentIntersection(s, t)) return 0.0;
  return std::min({PointToSegmentDistance(s.a, t), PointToSegmentDistance(s.b, t), PointToSegmentDistance(t.a, s),
                   PointToSegmentDistance(t.b, s)});
}

std::vector<Disc> DiscCover(const Footprint& footprint, int count) {
  Eigen::Vector2d lo = footprint.vertices.front(), hi = lo;
  for (const auto& v : footprint.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const int axis = hi.x() - lo.x() >= hi.y() - lo.y() ? 0 : 1;
  const Eigen::Vector2d size = hi - lo;
  Eigen::Vector2d slice = size;
  slice[axis] /= count;
  std::vector<Disc> discs;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector2d centre = 0.5 * (lo + hi);
    centre[axis] = lo[axis] + (i + 0.5) * slice[axis];
    discs.push_back({centre, 0.5 * slice.norm()});
  }
  return discs;
}

FootprintCollisionChecker::FootprintCollisionChecker(const StaticSegmentIndex& walls, const ClearanceField& field,
                                                     Footprint footprint, double margin, int discs)
    : walls_(walls),
      field_(field),
      footprint_(std::move(footprint)),
      margin_(margin),
      inscribed_(InscribedRadius(footprint_)),
      circumscribed_(CircumscribedRadius(footprint_)),
      discs_(DiscCover(footprint_, std::max(1, discs))) {
  const auto& v = footprint_.vertices;
  const auto inset = [&](const Eigen::Vector2d& q) {
    double e = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < v.size(); ++i) e = std::min(e, PointToSegmentDistance(q, {v[i], v[(i + 1) % v.size()]}));
    return e;
  };
  box_lo_ = box_hi_ = v.front();
  for (const auto& p : v) {
    box_lo_ = box_lo_.cwiseMin(p);
    box_hi_ = box_hi_.cwiseMax(p);
  }
  inside_.push_back({Eigen::Vector2d::Zero(), inscribed_});
  for (const Disc& d : discs_)
    if (PolygonContains(v, d.centre)) inside_.push_back({d.centre, inset(d.centre)});
}

PoseCheck FootprintCollisionChecker::Check(const Pose2& pose, double c, double s) const {
  const auto world = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(pose.x + c * p.x() - s * p.y(), pose.y + s * p.x() + c * p.y());
  };
  double spare = std::numeric_limits<double>::infinity();
  for (const Disc& d : discs_) {
    spare = std::min(spare, field_.LowerBound(world(d.centre)) - d.radius - margin_);
    if (!(spare > 0.0)) break;
  }
  if (spare > 0.0) {
    ++counters_.free_by_field;
    return {false, spare};
  }
  for (const Disc& q : inside_)
    if (field_.UpperBound(world(q.centre)) < q.radius + margin_) {
      ++counters_.blocked_by_field;
      return {true, 0.0};
    }
  return {CollidesExactly(pose, c, s), 0.0};
}

bool FootprintCollisionChecker::CollidesExactly(const Pose2& pose, double c, double s) const {
  // In the vehicle frame: each wall near the pose is turned into it (two rotations), and a
  // wall whose bounding box is more than the margin away from the polygon's bounding box
  // (in x or in y) is farther than the margin from every point of the polygon: skipped
  // without the polygon tests. Only the walls beside the box are tested edge by edge.
  ++counters_.exact_tests;
  const Eigen::Vector2d lo = box_lo_ - Eigen::Vector2d::Constant(margin_), hi = box_hi_ + Eigen::Vector2d::Constant(margin_);
  const auto& v = footprint_.vertices;
  bool hit = false;
  const auto& segments = walls_.segments();
  walls_.ForEachNear(pose.translation(), circumscribed_ + margin_, [&](int i) {
    if (hit) return;
    const Segment& w = segments[static_cast<size_t>(i)];
    const Eigen::Vector2d da = w.a - pose.translation(), db = w.b - pose.translation();
    const Eigen::Vector2d a(c * da.x() + s * da.y(), -s * da.x() + c * da.y());
    const Eigen::Vector2d b(c * db.x() + s * db.y(), -s * db.x() + c * db.y());
    if (std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x() || std::max(a.y(), b.y()) < lo.y() ||
        std::min(a.y(), b.y()) > hi.y())
      return;
    if (PolygonContains(v, a) || PolygonContains(v, b)) {
      hit = true;
      return;
    }
    const Segment local(a, b);
    const Eigen::Vector2d wlo = a.cwiseMin(b) - Eigen::Vector2d::Constant(margin_),
                          whi = a.cwiseMax(b) + Eigen::Vector2d::Constant(margin_);
    for (size_t k = 0; k < v.size() && !hit; ++k) {
      const Eigen::Vector2d& p = v[k];
      const Eigen::Vector2d& q = v[(k + 1) % v.size()];
      // An edge whose box is beyond the margin of the wall's box cannot come within it.
      if (std::max(p.x(), q.x()) < wlo.x() || std::min(p.x(), q.x()) > whi.x() || std::max(p.y(), q.y()) < wlo.y() ||
          std::min(p.y(), q.y()) > whi.y())
        continue;
      const Segment edge(p, q);
      hit = margin_ > 0.0 ? SegmentToSegmentDistance(edge, local) < margin_ : SegmentIntersection(edge, local).has_value();
    }
  });
  return hit;
}

}  // namespace minenav
