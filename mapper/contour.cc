#include "mapper/contour.h"

#include <algorithm>
#include <cmath>

namespace minenav::mapper {

std::vector<Eigen::Vector2d> ResamplePolyline(const std::vector<Eigen::Vector2d>& points, bool closed,
                                              double nominal_length) {
  if (points.size() < 2 || nominal_length <= 0.0) return points;
  std::vector<Eigen::Vector2d> path = points;
  if (closed) path.push_back(points.front());
  const double total = PolylineLength(path, false);
  const int segments = std::max(closed ? 3 : 1, static_cast<int>(std::lround(total / nominal_length)));
  const double step = total / segments;
  std::vector<Eigen::Vector2d> out;
  out.push_back(path.front());
  double walked = 0.0;  // arc length at path[k]
  size_t k = 0;
  for (int s = 1; s < segments; ++s) {
    const double target = s * step;
    while (k + 1 < path.size() && walked + (path[k + 1] - path[k]).norm() < target) {
      walked += (path[k + 1] - path[k]).norm();
      ++k;
    }
    if (k + 1 >= path.size()) break;
    const double len = (path[k + 1] - path[k]).norm();
    const double u = len > 0.0 ? (target - walked) / len : 0.0;
    out.push_back(path[k] + u * (path[k + 1] - path[k]));
  }
  if (!closed) out.push_back(path.back());
  return out;
}

std::vector<Eigen::Vector2d> PickVertices(const std::vector<Eigen::Vector2d>& points, double min_length) {
  if (points.size() <= 2) return points;
  std::vector<Eigen::Vector2d> out{points.front()};
  for (size_t i = 1; i + 1 < points.size(); ++i)
    if ((points[i] - out.back()).norm() >= min_length) out.push_back(points[i]);
  if (out.size() > 1 && (points.back() - out.back()).norm() < 0.5 * min_length) out.pop_back();
  out.push_back(points.back());
  return out;
}

}  // namespace minenav::mapper
