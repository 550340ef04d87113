#include "pose_estimator/grid_search_correspondence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {

GridSearchCorrespondence::GridSearchCorrespondence(std::vector<Segment> segments, double cell_size)
    : segments_(std::move(segments)),
      prepared_(PrepareSegments(segments_)),
      frame_(GridFrame::Covering(segments_, cell_size, 0.0)),
      stamp_(segments_.size(), 0) {
  std::vector<std::vector<int32_t>> cells(static_cast<size_t>(frame_.size()));
  for (size_t i = 0; i < segments_.size(); ++i) {
    for (const auto& [ix, iy] : CellsTouchedBySegment(frame_, segments_[i]))
      cells[static_cast<size_t>(frame_.Index(ix, iy))].push_back(static_cast<int32_t>(i));
  }
  offsets_.assign(cells.size() + 1, 0);
  for (size_t k = 0; k < cells.size(); ++k)
    offsets_[k + 1] = offsets_[k] + static_cast<int32_t>(cells[k].size());
  ids_.reserve(static_cast<size_t>(offsets_.back()));
  for (const auto& c : cells) ids_.insert(ids_.end(), c.begin(), c.end());
}

SegmentMatch GridSearchCorrespondence::Nearest(const Eigen::Vector2d& p, double max_distance) const {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !(max_distance >= 0.0)) return SegmentMatch{};
  if (++query_ == 0) {  // wrapped: clear stamps once every 4 billion queries
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    query_ = 1;
  }
  const int x_lo = std::max(0, frame_.CellX(p.x() - max_distance));
  const int x_hi = std::min(frame_.nx - 1, frame_.CellX(p.x() + max_distance));
  const int y_lo = std::max(0, frame_.CellY(p.y() - max_distance));
  const int y_hi = std::min(frame_.ny - 1, frame_.CellY(p.y() + max_distance));
  double best_d2 = std::numeric_limits<double>::infinity();
  int best = -1;
  for (int iy = y_lo; iy <= y_hi; ++iy) {
    for (int ix = x_lo; ix <= x_hi; ++ix) {
      const size_t k = static_cast<size_t>(frame_.Index(ix, iy));
      for (int32_t j = offsets_[k]; j < offsets_[k + 1]; ++j) {
        const int32_t id = ids_[static_cast<size_t>(j)];
        if (stamp_[static_cast<size_t>(id)] == query_) continue;
        stamp_[static_cast<size_t>(id)] = query_;
        const double d2 = prepared_[static_cast<size_t>(id)].SquaredDistance(p);
        if (d2 < best_d2 || (d2 == best_d2 && id < best)) {
          best_d2 = d2;
          best = id;
        }
      }
    }
  }
  if (best < 0 || best_d2 > max_distance * max_distance) return SegmentMatch{};
  return MakeMatch(p, prepared_[static_cast<size_t>(best)], best, best_d2);
}

}  // namespace minenav
