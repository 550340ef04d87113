#include "mapper/pose_graph.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace minenav::mapper {

std::string ValidateOptions(const PoseGraphOptions& o) {
  std::ostringstream why;
  if (o.max_iterations < 1)
    why << "max_iterations must be >= 1, got " << o.max_iterations;
  else if (!(o.min_translation_step >= 0.0) || !(o.min_rotation_step >= 0.0))
    why << "min_translation_step and min_rotation_step must be >= 0";
  else if (!(o.initial_damping >= 0.0))
    why << "initial_damping must be >= 0, got " << o.initial_damping;
  else if (!(o.huber_scale >= 0.0))
    why << "huber_scale must be >= 0, got " << o.huber_scale;
  return why.str();
}

void DeclareOptions(OptionScope s, PoseGraphOptions& o) {
  s.AddInt("max_iterations", &o.max_iterations,
           "Levenberg-Marquardt iteration limit; loop closure allows 100, since Huber reweighting slows "
           "convergence [iterations]",
           1, 100000);
  s.AddDouble("min_translation_step", &o.min_translation_step, "m",
              "converged when no pose moves more than this (and min_rotation_step) in an iteration; 1e-6 m",
              0.0, 1.0);
  s.AddDouble("min_rotation_step", &o.min_rotation_step, "rad", "heading part of the convergence test; 1e-7 rad",
              0.0, 1.0);
  s.AddDouble("initial_damping", &o.initial_damping, "1",
              "Levenberg-Marquardt damping relative to the diagonal of the normal equations; 1e-4 starts "
              "close to Gauss-Newton",
              0.0, 1e6);
  s.AddDouble("huber_scale", &o.huber_scale, "1",
              "Mahalanobis length above which an edge's weight falls off as Huber's (0 = plain least squares); "
              "loop closure uses 3, so a false registration bends the solution little before the gate drops it",
              0.0, 1000.0);
}

EdgeResidual ComputeEdgeResidual(const Pose2& from, const Pose2& to, const Pose2& z) {
  EdgeResidual r;
  const Eigen::Matrix2d ri_t = from.rotation().transpose();
  const Eigen::Matrix2d rz_t = z.rotation().transpose();
  const Eigen::Vector2d delta = to.translation() - from.translation();
  Eigen::Matrix2d j90;
  j90 << 0.0, -1.0, 1.0, 0.0;
  r.error.head<2>() = rz_t * (ri_t * delta - z.translation());
  r.error.z() = NormalizeAngle(to.theta - from.theta - z.theta);
  r.d_from.topLeftCorner<2, 2>() = -rz_t * ri_t;
  r.d_from.topRightCorner<2, 1>() = -rz_t * j90 * ri_t * delta;
  r.d_from(2, 2) = -1.0;
  r.d_to.topLeftCorner<2, 2>() = rz_t * ri_t;
  r.d_to(2, 2) = 1.0;
  return r;
}

namespace {

// ρ(χ²) and its derivative w.r.t. χ² (the IRLS weight).
double Robust(double chi2, double scale, double* weight) {
  if (scale <= 0.0 || chi2 <= scale * scale) {
    if (weight) *weight = 1.0;
    return chi2;
  }
  const double chi = std::sqrt(chi2);
  if (weight) *weight = scale / chi;
  return 2.0 * scale * chi - scale * scale;
}

}  // namespace

double PoseGraphCost(const std::vector<Pose2>& poses, const std::vector<PoseGraphEdge>& edges, double huber_scale) {
  double cost = 0.0;
  for (const PoseGraphEdge& e : edges) {
    const Eigen::Vector3d err =
        ComputeEdgeResidual(poses[static_cast<size_t>(e.from)], poses[static_cast<size_t>(e.to)], e.measurement).error;
    cost += 0.5 * Robust(err.dot(e.information * err), huber_scale, nullptr);
  }
  return cost;
}

PoseGraphResult OptimizePoseGraph(std::vector<Pose2> initial, const std::vector<bool>& fixed,
                                  const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& o) {
  PoseGraphResult out;
  out.poses = std::move(initial);
  const int n = static_cast<int>(out.poses.size());
  if (static_cast<int>(fixed.size()) != n) {
    out.reason = "fixed flags and poses differ in number";
    return out;
  }
  for (const PoseGraphEdge& e : edges)
    if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n || e.from == e.to) {
      out.reason = "edge " + std::to_string(e.from) + " -> " + std::to_string(e.to) + " names no pair of nodes";
      return out;
    }
  std::vector<int> var(static_cast<size_t>(n), -1);
  int num_free = 0;
  for (int k = 0; k < n; ++k)
    if (!fixed[static_cast<size_t>(k)]) var[static_cast<size_t>(k)] = num_free++;
  if (num_free == n) {
    out.reason = "no fixed pose: the frame is not anchored";
    return out;
  }
  out.initial_cost = out.final_cost = PoseGraphCost(out.poses, edges, o.huber_scale);
  if (num_free == 0 || edges.empty()) {
    out.converged = true;
    out.reason = num_free == 0 ? "every pose fixed" : "no edges";
    return out;
  }

  const int dim = 3 * num_free;
  double lambda = o.initial_damping;
  double cost = out.initial_cost;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool pattern_analysed = false;
  for (int iter = 1; iter <= o.max_iterations; ++iter) {
    out.iterations = iter;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(edges.size() * 36 + static_cast<size_t>(dim));
    Eigen::VectorXd b = Eigen::VectorXd::Zero(dim);
    auto add_block = [&](int r, int c, const Eigen::Matrix3d& m) {
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 3; ++k) triplets.emplace_back(3 * r + a, 3 * c + k, m(a, k));
    };
    for (const PoseGraphEdge& e : edges) {
      const int vi = var[static_cast<size_t>(e.from)], vj = var[static_cast<size_t>(e.to)];
      if (vi < 0 && vj < 0) continue;
      const EdgeResidual r =
          ComputeEdgeResidual(out.poses[static_cast<size_t>(e.from)], out.poses[static_cast<size_t>(e.to)], e.measurement);
      double w = 1.0;
      Robust(r.error.dot(e.information * r.error), o.huber_scale, &w);
      const Eigen::Matrix3d omega = w * e.information;
      if (vi >= 0) {
        add_block(vi, vi, r.d_from.transpose() * omega * r.d_from);
        b.segment<3>(3 * vi) += r.d_from.transpose() * omega * r.error;
      }
      if (vj >= 0) {
        add_block(vj, vj, r.d_to.transpose() * omega * r.d_to);
        b.segment<3>(3 * vj) += r.d_to.transpose() * omega * r.error;
      }
      if (vi >= 0 && vj >= 0) {
        add_block(vi, vj, r.d_from.transpose() * omega * r.d_to);
        add_block(vj, vi, r.d_to.transpose() * omega * r.d_from);
      }
    }
    // Every free node gets a diagonal entry so the pattern is fixed; damping is added below.
    for (int k = 0; k < dim; ++k) triplets.emplace_back(k, k, 0.0);
    Eigen::SparseMatrix<double> h(dim, dim);
    h.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::VectorXd diag = h.diagonal();

    bool accepted = false;
    double max_t = 0.0, max_r = 0.0;
    for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      Eigen::SparseMatrix<double> damped = h;
      for (int k = 0; k < dim; ++k) damped.coeffRef(k, k) += lambda * diag(k) + 1e-12;
      if (!pattern_analysed) {
        solver.analyzePattern(damped);
        pattern_analysed = true;
      }
      solver.factorize(damped);
      if (solver.info() != Eigen::Success) {
        lambda = std::max(lambda * 10.0, 1e-6);
        continue;
      }
      const Eigen::VectorXd step = solver.solve(-b);
      std::vector<Pose2> trial = out.poses;
      max_t = max_r = 0.0;
      for (int k = 0; k < n; ++k) {
        const int v = var[static_cast<size_t>(k)];
        if (v < 0) continue;
        const Eigen::Vector3d d = step.segment<3>(3 * v);
        Pose2& p = trial[static_cast<size_t>(k)];
        p = Pose2(p.x + d.x(), p.y + d.y(), NormalizeAngle(p.theta + d.z()));
        max_t = std::max(max_t, d.head<2>().norm());
        max_r = std::max(max_r, std::abs(d.z()));
      }
      const double trial_cost = PoseGraphCost(trial, edges, o.huber_scale);
      if (std::isfinite(trial_cost) && trial_cost <= cost) {
        out.poses = std::move(trial);
        cost = trial_cost;
        lambda = lambda / 3.0;
        accepted = true;
      } else {
        lambda = std::max(lambda * 10.0, 1e-6);
      }
    }
    out.final_cost = cost;
    if (!accepted) {
      out.converged = true;
      out.reason = "no step lowers the cost";
      return out;
    }
    if (max_t < o.min_translation_step && max_r < o.min_rotation_step) {
      out.converged = true;
      out.reason = "step small";
      return out;
    }
  }
  out.reason = "iteration limit";
  return out;
}

}  // namespace minenav::mapper
