#include "planner/clearance_field.h"

#include <algorithm>

namespace minenav {

ClearanceField::ClearanceField(const std::vector<Segment>& walls, const GridFrame& frame, double max_distance)
    : frame_(frame), max_distance_(max_distance), values_(static_cast<size_t>(frame.size()), max_distance) {
  // Each wall lowers the cells within max_distance of its bounding box: O(cells near walls).
  for (const Segment& w : walls) {
    if (!w.a.allFinite() || !w.b.allFinite()) continue;
    const Eigen::Vector2d lo = w.a.cwiseMin(w.b).array() - max_distance;
    const Eigen::Vector2d hi = w.a.cwiseMax(w.b).array() + max_distance;
    const int x0 = std::max(0, frame_.CellX(lo.x())), x1 = std::min(frame_.nx - 1, frame_.CellX(hi.x()));
    const int y0 = std::max(0, frame_.CellY(lo.y())), y1 = std::min(frame_.ny - 1, frame_.CellY(hi.y()));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        const Eigen::Vector2d centre = frame_.CellMin(ix, iy).array() + 0.5 * frame_.cell;
        double& v = values_[static_cast<size_t>(frame_.Index(ix, iy))];
        v = std::min(v, PointToSegmentDistance(centre, w));
      }
  }
}

}  // namespace minenav
