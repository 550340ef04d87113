#include "mapper/integral_error.h"

#include <cmath>

namespace minenav::mapper {

namespace {
constexpr double kMinSegmentLength = 1e-9;  // m

struct Frame {
  double h;
  Eigen::Vector2d u, n;
};
bool MakeFrame(const Eigen::Vector2d& s, const Eigen::Vector2d& e, Frame* f) {
  const Eigen::Vector2d w = e - s;
  f->h = w.norm();
  if (f->h < kMinSegmentLength) return false;
  f->u = w / f->h;
  f->n = Eigen::Vector2d(-f->u.y(), f->u.x());
  return true;
}
double Sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }
}  // namespace

double PieceError(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j, const Eigen::Vector2d& s,
                  const Eigen::Vector2d& e) {
  Frame f;
  if (!MakeFrame(s, e, &f)) return 0.0;
  const double di = f.n.dot(p_i - s), dj = f.n.dot(p_j - s);
  const double l = f.u.dot(p_j - p_i);
  return std::abs(l) * (di * di + di * dj + dj * dj) / 3.0;
}

PieceGradient PieceErrorGradient(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j,
                                 const Eigen::Vector2d& s, const Eigen::Vector2d& e) {
  PieceGradient out;
  Frame f;
  if (!MakeFrame(s, e, &f)) return out;
  const double di = f.n.dot(p_i - s), dj = f.n.dot(p_j - s);
  const double ai = f.u.dot(p_i - s), aj = f.u.dot(p_j - s);
  const double l = aj - ai, abs_l = std::abs(l), sigma = Sign(l);
  const double g = (di * di + di * dj + dj * dj) / 3.0;
  const double gi = (2.0 * di + dj) / 3.0, gj = (di + 2.0 * dj) / 3.0;
  out.value = abs_l * g;
  out.d_pi = -sigma * g * f.u + abs_l * gi * f.n;
  out.d_pj = sigma * g * f.u + abs_l * gj * f.n;
  const Eigen::Vector2d dl_de = ((dj - di) / f.h) * f.n;
  out.d_e = sigma * g * dl_de - abs_l * (gi * ai + gj * aj) / f.h * f.n;
  out.d_s = -sigma * g * dl_de - abs_l * (gi * (1.0 - ai / f.h) + gj * (1.0 - aj / f.h)) * f.n;
  return out;
}

PosePieceGradient PieceErrorPoseGradient(const Eigen::Vector2d& q_i, const Eigen::Vector2d& q_j,
                                         const Pose2& world_T_vehicle, const Eigen::Vector2d& s,
                                         const Eigen::Vector2d& e) {
  const Eigen::Vector2d p_i = world_T_vehicle * q_i, p_j = world_T_vehicle * q_j;
  const PieceGradient g = PieceErrorGradient(p_i, p_j, s, e);
  const Eigen::Vector2d t = world_T_vehicle.translation();
  auto perp = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); };
  PosePieceGradient out;
  out.value = g.value;
  out.gradient.head<2>() = g.d_pi + g.d_pj;
  out.gradient.z() = g.d_pi.dot(perp(p_i - t)) + g.d_pj.dot(perp(p_j - t));
  return out;
}

PieceCurvature PieceVertexCurvature(const Eigen::Vector2d& p_i, const Eigen::Vector2d& p_j,
                                    const Eigen::Vector2d& s, const Eigen::Vector2d& e) {
  PieceCurvature out;
  Frame f;
  if (!MakeFrame(s, e, &f)) return out;
  const double ai = f.u.dot(p_i - s) / f.h, aj = f.u.dot(p_j - s) / f.h;
  const double abs_l = std::abs(aj - ai) * f.h;
  // ∫ a² over a linear a(·) from a_i to a_j, times |l|; and the same for (1 - a).
  out.w_e = abs_l * (ai * ai + ai * aj + aj * aj) / 3.0;
  const double bi = 1.0 - ai, bj = 1.0 - aj;
  out.w_s = abs_l * (bi * bi + bi * bj + bj * bj) / 3.0;
  out.normal = f.n;
  return out;
}

}  // namespace minenav::mapper
