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

namespace {

// Is the polygon its own bounding box (4 vertices, each a corner of it)?
bool IsAxisAlignedBox(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  if (v.size() != 4 || !(lo.x() < hi.x()) || !(lo.y() < hi.y())) return false;
  int corners = 0;  // one bit per corner seen
  for (const Eigen::Vector2d& p : v) {
    const bool x_lo = p.x() == lo.x(), x_hi = p.x() == hi.x(), y_lo = p.y() == lo.y(), y_hi = p.y() == hi.y();
    if (!(x_lo || x_hi) || !(y_lo || y_hi)) return false;
    corners |= 1 << ((x_hi ? 1 : 0) + (y_hi ? 2 : 0));
  }
  return corners == 0xF;
}

}  // namespace

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
  box_lo_ = box_hi_ = v.front();
  for (const auto& p : v) {
    box_lo_ = box_lo_.cwiseMin(p);
    box_hi_ = box_hi_.cwiseMax(p);
  }
  box_footprint_ = IsAxisAlignedBox(v, box_lo_, box_hi_);
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
  if (field_.UpperBound(pose.translation()) < inscribed_ + margin_) {
    ++counters_.blocked_by_field;
    return {true, 0.0};
  }
  const double exact = ExactSpare(pose, c, s);
  return {exact < 0.0, std::max(0.0, exact)};
}

double FootprintCollisionChecker::ExactSpare(const Pose2& pose, double c, double s) const {
  // In the vehicle frame: each wall near the pose is turned into it (two rotations), and a
  // wall whose bounding box is more than margin + cap away from the polygon's bounding box
  // (in x or in y) is farther than that from every point of the polygon: skipped without
  // the polygon tests. Of the rest only the polygon edges whose box comes within margin +
  // cap of the wall's box are measured. A wall end inside the polygon, or a wall within the
  // margin of an edge (touching it when the margin is 0), is a collision.
  ++counters_.exact_tests;
  const double reach = margin_ + kExactSpareCap;
  const Eigen::Vector2d lo = box_lo_ - Eigen::Vector2d::Constant(reach), hi = box_hi_ + Eigen::Vector2d::Constant(reach);
  const auto& v = footprint_.vertices;
  double nearest = reach;  // the least distance measured, up to margin + cap
  bool hit = false;
  const auto& segments = walls_.segments();
  // The walls listed near the polygon's box turned into the world (its axis-aligned box there:
  // along an entry a third of the square round the circumscribed circle).
  const Eigen::Vector2d mid = 0.5 * (box_lo_ + box_hi_), half = 0.5 * (box_hi_ - box_lo_);
  const Eigen::Vector2d centre(pose.x + c * mid.x() - s * mid.y(), pose.y + s * mid.x() + c * mid.y());
  const Eigen::Vector2d extent(std::abs(c) * half.x() + std::abs(s) * half.y(),
                               std::abs(s) * half.x() + std::abs(c) * half.y());
  walls_.ForEachNearBox(centre - extent, centre + extent, reach, [&](int i) {
    if (hit) return;
    const Segment& w = segments[static_cast<size_t>(i)];
    const Eigen::Vector2d da = w.a - pose.translation(), db = w.b - pose.translation();
    const Eigen::Vector2d a(c * da.x() + s * da.y(), -s * da.x() + c * da.y());
    const Eigen::Vector2d b(c * db.x() + s * db.y(), -s * db.x() + c * db.y());
    if (box_footprint_) {
      // The polygon is its box (common/segment_index.h's box-to-segment distance: 0 when the
      // wall meets it). The gap between the wall's box and the polygon's along x or y is a
      // lower bound on their distance: a wall that far cannot come nearer than the nearest so
      // far (which starts at margin + cap), and is skipped without the distance.
      const double gap_x = std::max({box_lo_.x() - std::max(a.x(), b.x()), std::min(a.x(), b.x()) - box_hi_.x(), 0.0});
      const double gap_y = std::max({box_lo_.y() - std::max(a.y(), b.y()), std::min(a.y(), b.y()) - box_hi_.y(), 0.0});
      if (std::max(gap_x, gap_y) >= nearest) return;
      const double distance = BoxSegmentMinDistance(box_lo_, box_hi_, Segment(a, b));
      hit = distance < margin_ || distance <= 0.0;
      nearest = std::min(nearest, distance);
      return;
    }
    if (std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x() || std::max(a.y(), b.y()) < lo.y() ||
        std::min(a.y(), b.y()) > hi.y())
      return;
    if (PolygonContains(v, a) || PolygonContains(v, b)) {
      hit = true;
      return;
    }
    const Segment local(a, b);
    const Eigen::Vector2d wlo = a.cwiseMin(b) - Eigen::Vector2d::Constant(nearest),
                          whi = a.cwiseMax(b) + Eigen::Vector2d::Constant(nearest);
    for (size_t k = 0; k < v.size() && !hit; ++k) {
      const Eigen::Vector2d& p = v[k];
      const Eigen::Vector2d& q = v[(k + 1) % v.size()];
      // An edge whose box is beyond `nearest` of the wall's box cannot come nearer.
      if (std::max(p.x(), q.x()) < wlo.x() || std::min(p.x(), q.x()) > whi.x() || std::max(p.y(), q.y()) < wlo.y() ||
          std::min(p.y(), q.y()) > whi.y())
        continue;
      const double d = SegmentToSegmentDistance(Segment(p, q), local);
      hit = d < margin_ || d <= 0.0;
      nearest = std::min(nearest, d);
    }
  });
  return hit ? -1.0 : std::min(kExactSpareCap, nearest - margin_);
}

}  // namespace minenav
