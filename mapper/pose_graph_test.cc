#include "mapper/pose_graph.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace minenav::mapper {
namespace {

Pose2 Perturb(const Pose2& p, const Eigen::Vector3d& d) { return Pose2(p.x + d.x(), p.y + d.y(), p.theta + d.z()); }

TEST(PoseGraphTest, JacobiansMatchCentralDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0), a(-3.1, 3.1);
  const double h = 1e-6;
  for (int trial = 0; trial < 200; ++trial) {
    const Pose2 from(u(rng), u(rng), a(rng)), to(u(rng), u(rng), a(rng));
    // Near the measurement (the angle error away from its ±π wrap).
    const Pose2 z = Perturb(Between(from, to), Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.05 * u(rng)));
    const EdgeResidual r = ComputeEdgeResidual(from, to, z);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d dk = h * Eigen::Vector3d::Unit(k);
      const Eigen::Vector3d num_from =
          (ComputeEdgeResidual(Perturb(from, dk), to, z).error - ComputeEdgeResidual(Perturb(from, -dk), to, z).error) /
          (2 * h);
      const Eigen::Vector3d num_to =
          (ComputeEdgeResidual(from, Perturb(to, dk), z).error - ComputeEdgeResidual(from, Perturb(to, -dk), z).error) /
          (2 * h);
      EXPECT_LT((num_from - r.d_from.col(k)).norm(), 1e-6) << "trial " << trial << " d_from col " << k;
      EXPECT_LT((num_to - r.d_to.col(k)).norm(), 1e-6) << "trial " << trial << " d_to col " << k;
    }
  }
}

TEST(PoseGraphTest, ErrorIsZeroForAConsistentMeasurement) {
  const Pose2 from(1.0, 2.0, 0.7), to(-3.0, 0.5, -2.9);
  EXPECT_LT(ComputeEdgeResidual(from, to, Between(from, to)).error.norm(), 1e-12);
}

TEST(PoseGraphTest, OneEdgePlacesTheFreeNodeExactly) {
  const Pose2 z(2.0, -1.0, 0.4);
  const PoseGraphResult r =
      OptimizePoseGraph({Pose2(1, 1, 0.3), Pose2(0, 0, 0)}, {true, false}, {{0, 1, z, Eigen::Matrix3d::Identity()}});
  ASSERT_TRUE(r.converged) << r.reason;
  const Pose2 want = Pose2(1, 1, 0.3) * z;
  EXPECT_LT(TranslationDistance(r.poses[1], want), 1e-9);
  EXPECT_LT(HeadingDistance(r.poses[1], want), 1e-9);
  EXPECT_LT(r.final_cost, 1e-18);
}

// With every measured rotation 0 and the headings held there by a huge rotational weight
// (otherwise turning a node would trade rotation error for translation error), the problem
// is linear in the positions: the optimum is the weighted least-squares solution, computed
// here densely.
TEST(PoseGraphTest, TranslationOnlyLoopMatchesDenseLeastSquares) {
  // Four nodes on a square loop, node 0 fixed at the origin; inconsistent measurements.
  struct M {
    int i, j;
    double dx, dy, wx, wy;
  };
  const std::vector<M> ms = {{0, 1, 10.2, 0.1, 4, 1},  {1, 2, -0.3, 9.8, 1, 2}, {2, 3, -10.1, 0.4, 3, 3},
                             {3, 0, 0.2, -10.3, 2, 5}, {0, 2, 9.7, 10.2, 1, 1}};
  std::vector<PoseGraphEdge> edges;
  for (const M& m : ms) {
    PoseGraphEdge e;
    e.from = m.i;
    e.to = m.j;
    e.measurement = Pose2(m.dx, m.dy, 0.0);
    e.information = Eigen::Vector3d(m.wx, m.wy, 1e10).asDiagonal();  // headings held at 0
    edges.push_back(e);
  }
  const PoseGraphResult r =
      OptimizePoseGraph({Pose2(), Pose2(9, 1, 0), Pose2(11, 9, 0), Pose2(-1, 11, 0)}, {true, false, false, false}, edges);
  ASSERT_TRUE(r.converged) << r.reason;
  // Dense reference: unknowns (x1, y1, x2, y2, x3, y3); x and y decouple.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 6);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(6);
  for (const M& m : ms)
    for (int c = 0; c < 2; ++c) {
      const double w = c == 0 ? m.wx : m.wy, d = c == 0 ? m.dx : m.dy;
      // residual = p_j - p_i - d
      const int vi = m.i > 0 ? 2 * (m.i - 1) + c : -1, vj = m.j > 0 ? 2 * (m.j - 1) + c : -1;
      if (vi >= 0) a(vi, vi) += w;
      if (vj >= 0) a(vj, vj) += w;
      if (vi >= 0 && vj >= 0) {
        a(vi, vj) -= w;
        a(vj, vi) -= w;
      }
      if (vj >= 0) rhs(vj) += w * d;
      if (vi >= 0) rhs(vi) -= w * d;
    }
  const Eigen::VectorXd x = a.ldlt().solve(rhs);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_NEAR(r.poses[static_cast<size_t>(k)].x, x(2 * (k - 1)), 1e-7) << k;
    EXPECT_NEAR(r.poses[static_cast<size_t>(k)].y, x(2 * (k - 1) + 1), 1e-7) << k;
    EXPECT_NEAR(r.poses[static_cast<size_t>(k)].theta, 0.0, 1e-9) << k;
  }
}

// A rotated, inconsistent graph: the result is a minimum of the cost (numerical gradient
// ~0; no random perturbation lowers it).
TEST(PoseGraphTest, RotatedLoopReachesAMinimumOfTheCost) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  const int n = 12;
  std::vector<Pose2> truth;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * kPi * k / n;
    truth.emplace_back(8.0 * std::cos(a), 8.0 * std::sin(a), NormalizeAngle(a + kPi / 2));
  }
  std::vector<PoseGraphEdge> edges;
  for (int k = 0; k < n; ++k)
    for (int step : {1, 2}) {
      PoseGraphEdge e;
      e.from = k;
      e.to = (k + step) % n;
      e.measurement = Perturb(Between(truth[static_cast<size_t>(e.from)], truth[static_cast<size_t>(e.to)]),
                              Eigen::Vector3d(noise(rng), noise(rng), 0.2 * noise(rng)));
      e.information = Eigen::Vector3d(100.0, 50.0, 2000.0).asDiagonal();
      edges.push_back(e);
    }
  // Start from dead-reckoned poses: chained edges 0->1->2..., with a drift.
  std::vector<Pose2> start = {truth[0]};
  for (int k = 1; k < n; ++k) start.push_back(start.back() * edges[static_cast<size_t>(2 * (k - 1))].measurement * Pose2(0.1, 0, 0.05));
  std::vector<bool> fixed(static_cast<size_t>(n), false);
  fixed[0] = true;
  const PoseGraphResult r = OptimizePoseGraph(start, fixed, edges);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(r.final_cost, r.initial_cost);
  const double c0 = PoseGraphCost(r.poses, edges);
  const double h = 1e-6;
  for (int k = 1; k < n; ++k)
    for (int d = 0; d < 3; ++d) {
      std::vector<Pose2> plus = r.poses, minus = r.poses;
      plus[static_cast<size_t>(k)] = Perturb(plus[static_cast<size_t>(k)], h * Eigen::Vector3d::Unit(d));
      minus[static_cast<size_t>(k)] = Perturb(minus[static_cast<size_t>(k)], -h * Eigen::Vector3d::Unit(d));
      const double g = (PoseGraphCost(plus, edges) - PoseGraphCost(minus, edges)) / (2 * h);
      EXPECT_LT(std::abs(g), 1e-4) << "node " << k << " dof " << d;
    }
  std::normal_distribution<double> small(0.0, 1e-3);
  for (int t = 0; t < 50; ++t) {
    std::vector<Pose2> p = r.poses;
    for (int k = 1; k < n; ++k) p[static_cast<size_t>(k)] = Perturb(p[static_cast<size_t>(k)], {small(rng), small(rng), small(rng)});
    EXPECT_GE(PoseGraphCost(p, edges), c0);
  }
  // And it is close to the truth (noise 5 cm per edge, 24 edges).
  for (int k = 0; k < n; ++k) EXPECT_LT(TranslationDistance(r.poses[static_cast<size_t>(k)], truth[static_cast<size_t>(k)]), 0.15);
}

TEST(PoseGraphTest, ConsistentGraphIsRecoveredExactlyAndHuberIgnoresAnOutlier) {
  const std::vector<Pose2> truth = {Pose2(0, 0, 0), Pose2(5, 0, 0.5), Pose2(7, 4, 1.6), Pose2(3, 6, 3.0), Pose2(-1, 3, -2.0)};
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) edges.push_back({i, j, Between(truth[static_cast<size_t>(i)], truth[static_cast<size_t>(j)]), Eigen::Matrix3d::Identity() * 100.0});
  std::vector<Pose2> start;
  for (const Pose2& p : truth) start.push_back(Perturb(p, {0.4, -0.3, 0.2}));
  start[0] = truth[0];
  const std::vector<bool> fixed = {true, false, false, false, false};
  const PoseGraphResult r = OptimizePoseGraph(start, fixed, edges);
  ASSERT_TRUE(r.converged) << r.reason;
  for (size_t k = 0; k < truth.size(); ++k) {
    EXPECT_LT(TranslationDistance(r.poses[k], truth[k]), 1e-8);
    EXPECT_LT(HeadingDistance(r.poses[k], truth[k]), 1e-8);
  }
  // One wrong edge 2 m off: least squares bends, Huber nearly ignores it.
  std::vector<PoseGraphEdge> bad = edges;
  bad.push_back({1, 3, Perturb(Between(truth[1], truth[3]), {2.0, 0.0, 0.0}), Eigen::Matrix3d::Identity() * 100.0});
  PoseGraphOptions robust;
  robust.huber_scale = 1.0;
  const PoseGraphResult plain = OptimizePoseGraph(start, fixed, bad);
  const PoseGraphResult huber = OptimizePoseGraph(start, fixed, bad, robust);
  double worst_plain = 0.0, worst_huber = 0.0;
  for (size_t k = 0; k < truth.size(); ++k) {
    worst_plain = std::max(worst_plain, TranslationDistance(plain.poses[k], truth[k]));
    worst_huber = std::max(worst_huber, TranslationDistance(huber.poses[k], truth[k]));
  }
  EXPECT_GT(worst_plain, 0.15);
  EXPECT_LT(worst_huber, 0.3 * worst_plain) << worst_plain << " " << worst_huber;
}

TEST(PoseGraphTest, BadInputIsAReasonNotACrash) {
  const PoseGraphResult unanchored = OptimizePoseGraph({Pose2(), Pose2()}, {false, false}, {{0, 1, Pose2(), Eigen::Matrix3d::Identity()}});
  EXPECT_FALSE(unanchored.converged);
  EXPECT_NE(unanchored.reason.find("anchored"), std::string::npos);
  const PoseGraphResult bad_edge = OptimizePoseGraph({Pose2(), Pose2()}, {true, false}, {{0, 5, Pose2(), Eigen::Matrix3d::Identity()}});
  EXPECT_FALSE(bad_edge.converged);
  EXPECT_NE(bad_edge.reason, "");
  PoseGraphOptions o;
  o.max_iterations = 0;
  EXPECT_NE(ValidateOptions(o), "");
  EXPECT_EQ(ValidateOptions(PoseGraphOptions{}), "");
}

}  // namespace
}  // namespace minenav::mapper
