#include "pose_estimator/iconic/scan_set_map.h"

#include <algorithm>
#include <limits>

#include "pose_estimator/iconic/scan_polylines.h"

namespace minenav {

std::pair<Eigen::Vector2d, double> BoundingCircle(const std::vector<Segment>& segments) {
  if (segments.empty()) return {Eigen::Vector2d::Zero(), 0.0};
  Eigen::Vector2d lo = segments[0].a, hi = segments[0].a;
  for (const Segment& s : segments) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  return {centre, 0.5 * (hi - lo).norm()};
}

int ScanSetMap::AddScan(std::vector<Segment> segments_in_scan_frame, const Pose2& pose) {
  Member m;
  m.pose = pose;
  m.inverse = pose.inverse();
  m.offset = static_cast<int>(world_segments_.size());
  const std::vector<Segment> world = TransformSegments(pose, segments_in_scan_frame);
  std::tie(m.centre, m.radius) = BoundingCircle(world);
  world_segments_.insert(world_segments_.end(), world.begin(), world.end());
  const double cell = cell_size_ > 0.0 ? cell_size_ : ChooseCellSize(segments_in_scan_frame);
  m.table = std::make_unique<LookupTableCorrespondence>(std::move(segments_in_scan_frame), cell, reach_);
  members_.push_back(std::move(m));
  return static_cast<int>(members_.size()) - 1;
}

std::pair<int, int> ScanSetMap::Locate(int global_segment) const {
  for (size_t k = members_.size(); k-- > 0;) {
    if (global_segment >= members_[k].offset) return {static_cast<int>(k), global_segment - members_[k].offset};
  }
  return {-1, -1};
}

SegmentMatch ScanSetMap::Nearest(const Eigen::Vector2d& p, double max_distance) const {
  SegmentMatch best;
  best.distance = std::numeric_limits<double>::infinity();
  for (const Member& m : members_) {
    if ((p - m.centre).norm() > m.radius + max_distance) continue;
    const SegmentMatch local = m.table->Nearest(m.inverse * p, std::min(max_distance, best.distance));
    if (!local.matched()) continue;
    if (local.distance < best.distance) {
      best = local;
      best.segment = m.offset + local.segment;
      best.closest = m.pose * local.closest;
    }
  }
  if (!best.matched()) return SegmentMatch{};
  return best;
}

}  // namespace minenav
