#include "mapper/correspondence.h"

#include <algorithm>
#include <cmath>

namespace minenav::mapper {

std::vector<Eigen::Vector2d> ToWorld(const PartialScan& partial, const Pose2& world_T_vehicle) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(partial.points.size());
  for (const Eigen::Vector2d& q : partial.points) out.push_back(world_T_vehicle * q);
  return out;
}

std::vector<PointMatch> MatchPoints(const std::vector<Eigen::Vector2d>& world_points,
                                    const Eigen::Vector2d& sensor_world, const ContourMap& map,
                                    double threshold) {
  std::vector<PointMatch> out(world_points.size());
  const Contour* cached = nullptr;
  for (size_t k = 0; k < world_points.size(); ++k) {
    const Eigen::Vector2d& p = world_points[k];
    PointMatch& best = out[k];
    double best_abs = threshold;
    map.ForEachSegmentNear(p, threshold, [&](const SegmentRef& ref) {
      if (!cached || cached->id != ref.contour) cached = map.Find(ref.contour);
      const Eigen::Vector2d& s = cached->points[static_cast<size_t>(cached->SegmentStart(ref.segment))];
      const Eigen::Vector2d& e = cached->points[static_cast<size_t>(cached->SegmentEnd(ref.segment))];
      const Eigen::Vector2d w = e - s;
      const double h = w.norm();
      if (h <= 0.0) return;
      const Eigen::Vector2d u = w / h, n(-u.y(), u.x());
      const double along = u.dot(p - s);
      if (along < 0.0 || along > h) return;                 // condition 1
      const double d = n.dot(p - s);
      if (std::abs(d) >= best_abs) return;                  // condition 3, and nearest wins
      if (n.dot(sensor_world - s) <= 0.0) return;           // condition 2
      best_abs = std::abs(d);
      best.segment = ref;
      best.along = along;
      best.distance = d;
    });
  }
  return out;
}

void AppendPieces(int partial, const std::vector<PointMatch>& matches, std::vector<ErrorPiece>* pieces) {
  std::vector<int> order;
  order.reserve(matches.size());
  for (size_t k = 0; k < matches.size(); ++k)
    if (matches[k].matched()) order.push_back(static_cast<int>(k));
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const PointMatch& ma = matches[static_cast<size_t>(a)];
    const PointMatch& mb = matches[static_cast<size_t>(b)];
    if (ma.segment != mb.segment) return ma.segment < mb.segment;
    return ma.along < mb.along;
  });
  for (size_t k = 1; k < order.size(); ++k) {
    const PointMatch& a = matches[static_cast<size_t>(order[k - 1])];
    const PointMatch& b = matches[static_cast<size_t>(order[k])];
    if (a.segment != b.segment) continue;
    pieces->push_back({partial, order[k - 1], order[k], a.segment});
  }
}

ScanCorrespondence CorrespondScan(const PreprocessedScan& scan, const Pose2& world_T_vehicle,
                                  const ContourMap& map, double threshold) {
  ScanCorrespondence out;
  const Eigen::Vector2d sensor = world_T_vehicle * scan.sensor_position;
  out.matches.reserve(scan.partial_scans.size());
  for (size_t k = 0; k < scan.partial_scans.size(); ++k) {
    const auto world = ToWorld(scan.partial_scans[k], world_T_vehicle);
    out.matches.push_back(MatchPoints(world, sensor, map, threshold));
    out.num_points += static_cast<int>(world.size());
    for (const PointMatch& m : out.matches.back()) out.num_matched += m.matched() ? 1 : 0;
    AppendPieces(static_cast<int>(k), out.matches.back(), &out.pieces);
  }
  return out;
}

}  // namespace minenav::mapper
