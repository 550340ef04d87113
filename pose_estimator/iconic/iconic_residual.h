#pragma once
// The correspondence error of one scan point and its Jacobian (thesis A.2, A.3), derived
// here rather than copied: the OCR'd equations 15-22 are not trustworthy, and the unit
// test checks every derivative below against a central difference.
//
// A scan point p (vehicle frame of scan m) sits at P = R(th_m) p + t_m in the map. Its
// partner is a segment whose geometry lives in the frame of pose n (the identity for a
// surveyed map): start S = R(th_n) s + t_n, end E = R(th_n) e + t_n.
//   interior ("point-to-line", EQ 12/14):  f = u . (P - S),  u = unit left normal of E - S
//   endpoint ("point-to-point", EQ 10/11): f = |P - Q|,      u = (P - Q) / f, Q = S or E
// Both are f = u . (P - Q) with Q on the segment, so one set of derivatives serves:
//   df/dt_m = u                     df/dth_m =  u . J (P - t_m)
//   df/dt_n = -u                    df/dth_n = -u . J (P - t_n)
// where J rotates by +90 deg. For the endpoint case d|v| = u . dv; for the interior case
// the normal turns with pose n, and its term u . J(P - Q) cancels the difference between
// P and Q in the last formula (it is zero for the endpoint case because P - Q is along u).
// The interior f is signed: the least-squares cost f^2 is the squared distance either way.

#include <Eigen/Core>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

struct IconicResidual {
  double f = 0.0;                                          // m, signed for interior pairs
  Eigen::RowVector3d d_pose_m = Eigen::RowVector3d::Zero();  // df / d(x_m, y_m, th_m)
  Eigen::RowVector3d d_pose_n = Eigen::RowVector3d::Zero();  // df / d(x_n, y_n, th_n)
};

// p_m: point in the frame of pose_m. segment_n: segment in the frame of pose_n.
// `region` says which error applies (as found by correspondence at the current poses).
IconicResidual ComputeIconicResidual(const Pose2& pose_m, const Eigen::Vector2d& p_m, const Pose2& pose_n,
                                     const Segment& segment_n, SegmentRegion region);

}  // namespace minenav

namespace minenav {

// The same error against a fixed map (pose_n = identity), from a correspondence already
// found for the map point P = R(th_m) p + t_m: no trigonometry, for the inner loop.
// `closest` and `region` come from SegmentMatch.
IconicResidual ComputeMapResidual(const Eigen::Vector2d& P, const Eigen::Vector2d& t_m, const Segment& segment,
                                  const Eigen::Vector2d& closest, SegmentRegion region);

}  // namespace minenav
