#include "mapper/integral_error.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>

namespace minenav::mapper {
namespace {

using Vec = Eigen::Vector2d;

// Central difference of a scalar function of a 2-vector.
Vec NumericGradient(const std::function<double(const Vec&)>& f, const Vec& x, double h = 1e-6) {
  Vec g;
  for (int k = 0; k < 2; ++k) {
    Vec a = x, b = x;
    a[k] += h;
    b[k] -= h;
    g[k] = (f(a) - f(b)) / (2 * h);
  }
  return g;
}

struct Case {
  Vec pi, pj, s, e;
};

std::vector<Case> RandomCases(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Case> out;
  while (static_cast<int>(out.size()) < n) {
    Case c{{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
    // Stay away from the kink at l = 0 and from tiny segments.
    const Vec dir = (c.e - c.s).normalized();
    if ((c.e - c.s).norm() < 0.3 || std::abs(dir.dot(c.pj - c.pi)) < 0.05) continue;
    out.push_back(c);
  }
  return out;
}

TEST(IntegralErrorTest, MatchesNumericalIntegration) {
  for (const Case& c : RandomCases(1, 50)) {
    // Integrate the squared distance of the straight piece p_i -> p_j along the segment.
    const Vec u = (c.e - c.s).normalized(), n(-u.y(), u.x());
    const double di = n.dot(c.pi - c.s), dj = n.dot(c.pj - c.s), l = u.dot(c.pj - c.pi);
    const int steps = 20000;
    double sum = 0;
    for (int k = 0; k < steps; ++k) {
      const double t = (k + 0.5) / steps;
      const double d = di + t * (dj - di);
      sum += d * d;
    }
    EXPECT_NEAR(PieceError(c.pi, c.pj, c.s, c.e), std::abs(l) * sum / steps, 1e-6);
  }
}

TEST(IntegralErrorTest, ZeroOnTheLineAndSymmetricInPointOrder) {
  const Vec s(0, 0), e(2, 0);
  EXPECT_DOUBLE_EQ(PieceError({0.5, 0}, {1.5, 0}, s, e), 0.0);
  // Constant offset 0.1 over length 1: 0.01 m^3.
  EXPECT_NEAR(PieceError({0.5, 0.1}, {1.5, 0.1}, s, e), 0.01, 1e-15);
  EXPECT_NEAR(PieceError({1.5, 0.1}, {0.5, -0.2}, s, e), PieceError({0.5, -0.2}, {1.5, 0.1}, s, e), 1e-15);
  EXPECT_DOUBLE_EQ(PieceError({0.5, 0.1}, {1.5, 0.1}, s, s), 0.0);
}

TEST(IntegralErrorTest, PointGradientsMatchNumericalDerivatives) {
  for (const Case& c : RandomCases(2, 200)) {
    const PieceGradient g = PieceErrorGradient(c.pi, c.pj, c.s, c.e);
    EXPECT_NEAR(g.value, PieceError(c.pi, c.pj, c.s, c.e), 1e-12);
    const Vec n_pi = NumericGradient([&](const Vec& x) { return PieceError(x, c.pj, c.s, c.e); }, c.pi);
    const Vec n_pj = NumericGradient([&](const Vec& x) { return PieceError(c.pi, x, c.s, c.e); }, c.pj);
    EXPECT_LT((g.d_pi - n_pi).norm(), 1e-6 * (1 + n_pi.norm()));
    EXPECT_LT((g.d_pj - n_pj).norm(), 1e-6 * (1 + n_pj.norm()));
  }
}

TEST(IntegralErrorTest, ContourVertexGradientsMatchNumericalDerivatives) {  // EQ 4
  for (const Case& c : RandomCases(3, 200)) {
    const PieceGradient g = PieceErrorGradient(c.pi, c.pj, c.s, c.e);
    const Vec n_s = NumericGradient([&](const Vec& x) { return PieceError(c.pi, c.pj, x, c.e); }, c.s);
    const Vec n_e = NumericGradient([&](const Vec& x) { return PieceError(c.pi, c.pj, c.s, x); }, c.e);
    EXPECT_LT((g.d_s - n_s).norm(), 1e-6 * (1 + n_s.norm())) << g.d_s.transpose() << " vs " << n_s.transpose();
    EXPECT_LT((g.d_e - n_e).norm(), 1e-6 * (1 + n_e.norm())) << g.d_e.transpose() << " vs " << n_e.transpose();
  }
}

TEST(IntegralErrorTest, PoseGradientMatchesNumericalDerivatives) {  // EQ 2
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-3, 3);
  int tested = 0;
  for (const Case& c : RandomCases(5, 200)) {
    const Pose2 pose(u(rng), u(rng), u(rng));
    // Points in the vehicle frame that land on c.pi, c.pj at this pose.
    const Vec qi = pose.inverse() * c.pi, qj = pose.inverse() * c.pj;
    const PosePieceGradient g = PieceErrorPoseGradient(qi, qj, pose, c.s, c.e);
    EXPECT_NEAR(g.value, PieceError(c.pi, c.pj, c.s, c.e), 1e-9);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d a = pose.vector(), b = pose.vector();
      a[k] += h;
      b[k] -= h;
      const Pose2 pa(a.x(), a.y(), a.z()), pb(b.x(), b.y(), b.z());
      const double num = (PieceError(pa * qi, pa * qj, c.s, c.e) - PieceError(pb * qi, pb * qj, c.s, c.e)) / (2 * h);
      EXPECT_NEAR(g.gradient[k], num, 1e-5 * (1 + std::abs(num))) << "component " << k;
    }
    ++tested;
  }
  EXPECT_EQ(tested, 200);
}

TEST(IntegralErrorTest, CurvatureIsTheGaussNewtonSecondDerivative) {
  // f is quadratic in a vertex's normal offset when the direction barely changes: compare
  // 2 w with the numerical second derivative along n for a long segment.
  const Vec s(0, 0), e(100, 0), pi(30, 0.05), pj(60, -0.02);
  const PieceCurvature c = PieceVertexCurvature(pi, pj, s, e);
  const double h = 1e-3;
  auto along_n_e = [&](double t) { return PieceError(pi, pj, s, e + t * c.normal); };
  auto along_n_s = [&](double t) { return PieceError(pi, pj, s + t * c.normal, e); };
  const double d2e = (along_n_e(h) - 2 * along_n_e(0) + along_n_e(-h)) / (h * h);
  const double d2s = (along_n_s(h) - 2 * along_n_s(0) + along_n_s(-h)) / (h * h);
  EXPECT_NEAR(d2e, 2 * c.w_e, 1e-3 * 2 * c.w_e);
  EXPECT_NEAR(d2s, 2 * c.w_s, 1e-3 * 2 * c.w_s);
}

}  // namespace
}  // namespace minenav::mapper
