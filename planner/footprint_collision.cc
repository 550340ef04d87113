#include "planner/footprint_collision.h"

#include <algorithm>

namespace minenav {

double SegmentToSegmentDistance(const Segment& s, const Segment& t) {
  if (SegmentIntersection(s, t)) return 0.0;
  return std::min({PointToSegmentDistance(s.a, t), PointToSegmentDistance(s.b, t), PointToSegmentDistance(t.a, s),
                   PointToSegmentDistance(t.b, s)});
}

FootprintCollisionChecker::FootprintCollisionChecker(const StaticSegmentIndex& walls, const ClearanceField& field,
                                                     Footprint footprint, double margin)
    : walls_(walls),
      field_(field),
      footprint_(std::move(footprint)),
      margin_(margin),
      inscribed_(InscribedRadius(footprint_)),
      circumscribed_(CircumscribedRadius(footprint_)) {}

bool FootprintCollisionChecker::Collides(const Pose2& pose) const {
  const Eigen::Vector2d centre = pose.translation();
  const double c = field_.At(centre), slack = field_.Slack();
  // A capped value still bounds the true clearance at the cell centre from below.
  if (c - slack > circumscribed_ + margin_) {
    ++counters_.free_by_field;
    return false;
  }
  if (c + slack < inscribed_ + margin_) {
    ++counters_.blocked_by_field;
    return true;
  }
  return CollidesExactly(pose);
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
