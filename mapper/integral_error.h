#pragma once
// The integral error metric of thesis 4.3.3 (EQ 1) and its gradients (EQ 2, EQ 4), derived
// here afresh because the printed equations came through OCR with errors.
//
// One "piece": two consecutive scan points p_i, p_j (consecutive after sorting the points
// that correspond to one contour segment by their position along it) and the contour
// segment s -> e. With
//   h = |e - s|, u = (e - s) / h, n = (-u_y, u_x)   (unit direction and LEFT normal),
//   d_k = n . (p_k - s)                               (signed distance, + on the free side),
//   l = u . (p_j - p_i)                               (length of the piece along the segment),
// the squared distance, linear between the two points, integrated along the segment is
//   f = |l| * (d_i^2 + d_i d_j + d_j^2) / 3          (= EQ 1's |l| (d_i^2 + d_i Δ + Δ^2/3)).
//
// Gradients, with g = (d_i^2 + d_i d_j + d_j^2)/3, g_i = (2 d_i + d_j)/3, g_j = (d_i + 2 d_j)/3,
// σ = sgn(l), α_k = u . (p_k - s) (position of p_k along the segment):
//   ∂f/∂p_i = -σ g u + |l| g_i n            ∂f/∂p_j = σ g u + |l| g_j n
//   ∂d_k/∂e = -(α_k / h) n                   ∂d_k/∂s = -(1 - α_k / h) n
//   ∂l/∂e = ((d_j - d_i) / h) n              ∂l/∂s = -((d_j - d_i) / h) n
//   ∂f/∂e = σ g ∂l/∂e + |l| (g_i ∂d_i/∂e + g_j ∂d_j/∂e), and likewise for s   (EQ 4)
// For a scan at pose (x, y, θ) with p_k = R(θ) q_k + t:
//   ∂f/∂(x, y) = ∂f/∂p_i + ∂f/∂p_j = |l| (d_i + d_j) n
//   ∂f/∂θ = ∂f/∂p_i . J (p_i - t) + ∂f/∂p_j . J (p_j - t),  J = rotation by +90°  (EQ 2)
// Error around contour vertices (points on two different segments) is ignored, as in the
// thesis (7.2.1).

#include <Eigen/Core>

#include "common/pose2.h"

namespace minenav::mapper {

// EQ 1. Zero for a degenerate segment (h ~ 0).
double PieceError(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j, const Eigen::Vector2d& s,
                  const Eigen::Vector2d& e);

struct PieceGradient {
  double value = 0.0;
  Eigen::Vector2d d_pi = Eigen::Vector2d::Zero();
  Eigen::Vector2d d_pj = Eigen::Vector2d::Zero();
  Eigen::Vector2d d_s = Eigen::Vector2d::Zero();  // EQ 4
  Eigen::Vector2d d_e = Eigen::Vector2d::Zero();  // EQ 4
};
PieceGradient PieceErrorGradient(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j,
                                 const Eigen::Vector2d& s, const Eigen::Vector2d& e);

// EQ 2: value and gradient w.r.t. (x, y, θ) of world_T_vehicle for points q_i, q_j given
// in the vehicle frame.
struct PosePieceGradient {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};
PosePieceGradient PieceErrorPoseGradient(const Eigen::Vector2d& q_i, const Eigen::Vector2d& q_j,
                                         const Pose2& world_T_vehicle, const Eigen::Vector2d& s,
                                         const Eigen::Vector2d& e);

// Gauss-Newton curvature of f along the segment normal for each end vertex:
// ∂²f/∂s² ≈ 2 w_s n nᵀ, ∂²f/∂e² ≈ 2 w_e n nᵀ with w = ∫ (∂d/∂v)² dl over the piece.
// Used to precondition contour fitting (a step beyond the thesis's plain gradient).
struct PieceCurvature {
  double w_s = 0.0;
  double w_e = 0.0;
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
};
PieceCurvature PieceVertexCurvature(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j,
                                    const Eigen::Vector2d& s, const Eigen::Vector2d& e);

}  // namespace minenav::mapper
