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
  return {CollidesExactly(pose), 0.0};
}

bool FootprintCollisionChecker::CollidesExactly(const Pose2& pose) const {
  ++counters_.exact_tests;
  world_.clear();
  for (const auto& v : footprint_.vertices) world_.push_back(pose * v);
  bool hit = false;
  const auto& segments = walls_.segments();
  walls_.ForEachNear(pose.translation(), circumscribed_ + margin_, [&](int i) {
    if (hit) return;
    const Segment& w = segments[static_cast<size_t>(i)];
    if (PolygonContains(world_, w.a) || PolygonContains(world_, w.b)) {
      hit = true;
      return;
    }
    for (size_t k = 0; k < world_.size() && !hit; ++k) {
      const Segment edge(world_[k], world_[(k + 1) % world_.size()]);
      hit = margin_ > 0.0 ? SegmentToSegmentDistance(edge, w) < margin_ : SegmentIntersection(edge, w).has_value();
    }
  });
  return hit;
}

}  // namespace minenav
