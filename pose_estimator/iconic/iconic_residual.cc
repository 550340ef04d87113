#include "pose_estimator/iconic/iconic_residual.h"

#include <cmath>

namespace minenav {

namespace {
Eigen::Vector2d Perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }  // J v
}  // namespace

IconicResidual ComputeIconicResidual(const Pose2& pose_m, const Eigen::Vector2d& p_m, const Pose2& pose_n,
                                     const Segment& segment_n, SegmentRegion region) {
  const Eigen::Vector2d P = pose_m * p_m;
  const Eigen::Vector2d S = pose_n * segment_n.a;
  const Eigen::Vector2d E = pose_n * segment_n.b;
  IconicResidual r;
  Eigen::Vector2d u;
  const double length = (E - S).norm();
  if (region == SegmentRegion::kInterior && length > 0.0) {
    u = Perp(E - S) / length;  // (a, b) of EQ 12: a = -(ye - ys)/l, b = (xe - xs)/l
    r.f = u.dot(P - S);
  } else {
    const Eigen::Vector2d Q = (region == SegmentRegion::kEndPoint) ? E : S;
    const Eigen::Vector2d v = P - Q;
    r.f = v.norm();
    // At f = 0 the distance has no gradient; any unit direction gives a zero residual and
    // a harmless Jacobian row.
    u = r.f > 0.0 ? Eigen::Vector2d(v / r.f) : Eigen::Vector2d(1.0, 0.0);
  }
  const Eigen::Vector2d tm = pose_m.translation();
  const Eigen::Vector2d tn = pose_n.translation();
  r.d_pose_m << u.x(), u.y(), u.dot(Perp(P - tm));
  r.d_pose_n << -u.x(), -u.y(), -u.dot(Perp(P - tn));
  return r;
}

}  // namespace minenav

namespace minenav {

IconicResidual ComputeMapResidual(const Eigen::Vector2d& P, const Eigen::Vector2d& t_m, const Segment& segment,
                                  const Eigen::Vector2d& closest, SegmentRegion region) {
  IconicResidual r;
  const Eigen::Vector2d d = segment.b - segment.a;
  const double length = d.norm();
  Eigen::Vector2d u;
  if (region == SegmentRegion::kInterior && length > 0.0) {
    u = Eigen::Vector2d(-d.y(), d.x()) / length;
    r.f = u.dot(P - segment.a);
  } else {
    const Eigen::Vector2d v = P - closest;
    r.f = v.norm();
    u = r.f > 0.0 ? Eigen::Vector2d(v / r.f) : Eigen::Vector2d(1.0, 0.0);
  }
  const Eigen::Vector2d w = P - t_m;
  r.d_pose_m << u.x(), u.y(), -u.x() * w.y() + u.y() * w.x();
  r.d_pose_n << -u.x(), -u.y(), u.x() * P.y() - u.y() * P.x();
  return r;
}

}  // namespace minenav
