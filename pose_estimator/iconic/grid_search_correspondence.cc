#include "pose_estimator/iconic/grid_search_correspondence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {

GridSearchCorrespondence::GridSearchCorrespondence(std::vector<Segment> segments, double cell_size)
    : index_(std::move(segments), cell_size),
      prepared_(PrepareSegments(index_.segments())),
      stamp_(index_.segments().size(), 0) {}

SegmentMatch GridSearchCorrespondence::Nearest(const Eigen::Vector2d& p, double max_distance) const {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !(max_distance >= 0.0)) return SegmentMatch{};
  if (++query_ == 0) {  // wrapped: clear stamps once every 4 billion queries
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    query_ = 1;
  }
  // Every cell within the threshold of p, every segment listed there, each measured once.
  double best_d2 = std::numeric_limits<double>::infinity();
  int best = -1;
  uint32_t* const stamp = stamp_.data();
  const PreparedSegment* const prepared = prepared_.data();
  const uint32_t query = query_;
  index_.ForEachNear(p, max_distance, [&](int id) {
    const size_t k = static_cast<size_t>(id);
    if (stamp[k] == query) return;
    stamp[k] = query;
    const double d2 = prepared[k].SquaredDistance(p);
    if (d2 < best_d2 || (d2 == best_d2 && id < best)) {
      best_d2 = d2;
      best = id;
    }
  });
  if (best < 0 || best_d2 > max_distance * max_distance) return SegmentMatch{};
  return MakeMatch(p, prepared_[static_cast<size_t>(best)], best, best_d2);
}

}  // namespace minenav
