#include "pose_estimator/iconic/iconic_residual.h"

#include <gtest/gtest.h>

#include <random>

namespace minenav {
namespace {

// Central differences of f with respect to each of the six pose parameters, keeping the
// correspondence (region) fixed as Gauss-Newton does within one iteration.
void CheckAgainstNumerical(const Pose2& pm, const Eigen::Vector2d& p, const Pose2& pn, const Segment& s,
                           SegmentRegion region) {
  const IconicResidual r = ComputeIconicResidual(pm, p, pn, s, region);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d dv = Eigen::Vector3d::Zero();
    dv(k) = h;
    const double fm_plus = ComputeIconicResidual(Pose2::FromVector(pm.vector() + dv), p, pn, s, region).f;
    const double fm_minus = ComputeIconicResidual(Pose2::FromVector(pm.vector() - dv), p, pn, s, region).f;
    EXPECT_NEAR(r.d_pose_m(k), (fm_plus - fm_minus) / (2 * h), 1e-6) << "d/d pose_m[" << k << "]";
    const double fn_plus = ComputeIconicResidual(pm, p, Pose2::FromVector(pn.vector() + dv), s, region).f;
    const double fn_minus = ComputeIconicResidual(pm, p, Pose2::FromVector(pn.vector() - dv), s, region).f;
    EXPECT_NEAR(r.d_pose_n(k), (fn_plus - fn_minus) / (2 * h), 1e-6) << "d/d pose_n[" << k << "]";
  }
}

TEST(IconicResidualTest, JacobiansMatchNumericalDerivatives) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-5.0, 5.0), a(-3.1, 3.1);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 pm(u(rng), u(rng), a(rng)), pn(u(rng), u(rng), a(rng));
    const Eigen::Vector2d p(u(rng), u(rng));
    const Segment s(u(rng), u(rng), u(rng), u(rng));
    for (SegmentRegion region : {SegmentRegion::kInterior, SegmentRegion::kStartPoint, SegmentRegion::kEndPoint})
      CheckAgainstNumerical(pm, p, pn, s, region);
  }
}

TEST(IconicResidualTest, ValuesAreTheThesisDistances) {
  const Pose2 identity;
  const Segment s(0, 0, 4, 0);
  // EQ 12/14: signed perpendicular distance, positive on the left of start -> end.
  EXPECT_NEAR(ComputeIconicResidual(identity, {1, 0.3}, identity, s, SegmentRegion::kInterior).f, 0.3, 1e-12);
  EXPECT_NEAR(ComputeIconicResidual(identity, {1, -0.3}, identity, s, SegmentRegion::kInterior).f, -0.3, 1e-12);
  // EQ 10/11: distance to the endpoint.
  EXPECT_NEAR(ComputeIconicResidual(identity, {7, 4}, identity, s, SegmentRegion::kEndPoint).f, 5.0, 1e-12);
  EXPECT_NEAR(ComputeIconicResidual(identity, {-3, -4}, identity, s, SegmentRegion::kStartPoint).f, 5.0, 1e-12);
  // The point rotates with pose_m: (1, 0) at theta = 90 deg lands on (0, 1) + t.
  EXPECT_NEAR(ComputeIconicResidual(Pose2(2, 0.5, kPi / 2), {1, 0}, identity, s, SegmentRegion::kInterior).f,
              1.5, 1e-12);
}

TEST(IconicResidualTest, MapResidualEqualsGeneralWithIdentityMapPose) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-5.0, 5.0), a(-3.1, 3.1);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 pm(u(rng), u(rng), a(rng));
    const Eigen::Vector2d p(u(rng), u(rng));
    const Segment s(u(rng), u(rng), u(rng), u(rng));
    const Eigen::Vector2d P = pm * p;
    const SegmentProjection proj = ProjectOntoSegment(P, s);
    const IconicResidual g = ComputeIconicResidual(pm, p, Pose2(), s, proj.region);
    const IconicResidual f = ComputeMapResidual(P, pm.translation(), s, proj.point, proj.region);
    EXPECT_NEAR(f.f, g.f, 1e-9);
    EXPECT_LT((f.d_pose_m - g.d_pose_m).norm(), 1e-9);
    EXPECT_LT((f.d_pose_n - g.d_pose_n).norm(), 1e-9);
    EXPECT_NEAR(std::abs(f.f), proj.distance, 1e-9);  // |f| is the correspondence distance
  }
}

}  // namespace
}  // namespace minenav
