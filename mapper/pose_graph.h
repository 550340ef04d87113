#pragma once
// A sparse SE(2) pose graph: the joint step across a loop that concurrent refinement (thesis
// 4.7) lacks. Alternating poses and contours passes a loop's closing correction around the
// loop about one scan per round (the thesis ran 9 scans overnight); a pose graph spreads it
// over every pose at once. Nodes are scan poses (world_T_vehicle); an edge is a measured
// relative pose from_T_to (from registering one scan against another) with a 3x3 information
// matrix. Levenberg-Marquardt over all free poses; the normal equations are sparse (a 3x3
// block per node and per edge) and solved with Eigen's SimplicialLDLT, so one iteration costs
// O(edges) rather than the O(N^3) of a dense inversion (cf. thesis 3.5).
//
// Edge error (the usual SE(2) form, derived here and checked numerically in the test):
//   e_t = R_z^T (R_i^T (t_j - t_i) - t_z)       e_θ = wrap(θ_j - θ_i - θ_z)
// with z the measurement, i = from, j = to. With J the +90° rotation, Δ = t_j - t_i:
//   ∂e_t/∂t_i = -R_z^T R_i^T        ∂e_t/∂θ_i = -R_z^T J R_i^T Δ       ∂e_θ/∂θ_i = -1
//   ∂e_t/∂t_j =  R_z^T R_i^T        ∂e_t/∂θ_j = 0                      ∂e_θ/∂θ_j = +1
// Cost: Σ ρ(eᵀ Ω e) / 2 with ρ the identity, or Huber on the Mahalanobis length when
// huber_scale > 0 (iteratively reweighted).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/pose2.h"

namespace minenav::mapper {

struct PoseGraphEdge {
  int from = 0;
  int to = 0;
  Pose2 measurement;  // from_T_to
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  // of (e_x, e_y, e_θ): 1/m², 1/rad²
};

struct EdgeResidual {
  Eigen::Vector3d error = Eigen::Vector3d::Zero();  // (m, m, rad) in the measurement's frame
  Eigen::Matrix3d d_from = Eigen::Matrix3d::Zero();  // ∂e/∂(x_i, y_i, θ_i)
  Eigen::Matrix3d d_to = Eigen::Matrix3d::Zero();    // ∂e/∂(x_j, y_j, θ_j)
};
EdgeResidual ComputeEdgeResidual(const Pose2& from, const Pose2& to, const Pose2& measurement);

struct PoseGraphOptions {
  // Iteration limit.
  int max_iterations = 50;
  // Converged when no pose moves more than these in an iteration (m, rad).
  double min_translation_step = 1e-6;
  double min_rotation_step = 1e-7;
  // Levenberg-Marquardt damping, relative to the diagonal of the normal equations.
  double initial_damping = 1e-4;
  // Mahalanobis length (sqrt(eᵀΩe)) above which an edge's weight falls off as Huber's;
  // 0 = plain least squares.
  double huber_scale = 0.0;
};

std::string ValidateOptions(const PoseGraphOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, PoseGraphOptions& o);

struct PoseGraphResult {
  std::vector<Pose2> poses;
  bool converged = false;
  std::string reason;
  int iterations = 0;
  double initial_cost = 0.0;  // Σ eᵀΩe / 2 (robustified when huber_scale > 0)
  double final_cost = 0.0;
};

// Cost Σ ρ(eᵀΩe)/2 of the edges at `poses`.
double PoseGraphCost(const std::vector<Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                     double huber_scale = 0.0);

// Optimises the poses not marked fixed (at least one must be fixed: it anchors the frame).
// Edges naming a node out of range give a result with converged = false and a reason.
PoseGraphResult OptimizePoseGraph(std::vector<Pose2> initial, const std::vector<bool>& fixed,
                                  const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& options = {});

}  // namespace minenav::mapper
