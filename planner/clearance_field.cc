#include "planner/clearance_field.h"

#include <algorithm>

namespace minenav {

ClearanceField::ClearanceField(const std::vector<Segment>& walls, const GridFrame& frame, double max_distance)
    : frame_(frame), inverse_cell_(1.0 / frame.cell), max_distance_(max_distance), values_(static_cast<size_t>(frame.size()), max_distance) {
  // Each wall lowers the cells within max_distance of it: per row of cells, only the run of
  // cells near the part of the wall within reach of that row. A long diagonal wall costs its
  // band (length x reach), not its bounding box (issue 16: a map of long walls far apart took
  // minutes). Cells left out are farther than max_distance + one cell from the wall, so they
  // would have kept max_distance: the field is what testing every cell of the box gives.
  const double reach = max_distance + frame_.cell;
  for (const Segment& w : walls) {
    if (!w.a.allFinite() || !w.b.allFinite()) continue;
    const Eigen::Vector2d d = w.b - w.a;
    const int y0 = std::max(0, frame_.CellY(std::min(w.a.y(), w.b.y()) - reach));
    const int y1 = std::min(frame_.ny - 1, frame_.CellY(std::max(w.a.y(), w.b.y()) + reach));
    for (int iy = y0; iy <= y1; ++iy) {
      // The part of the wall within `reach` of this row's centre line, as parameters t in [0, 1].
      const double yc = frame_.y0 + (iy + 0.5) * frame_.cell;
      double t0 = 0.0, t1 = 1.0;
      if (d.y() != 0.0) {
        const double ta = (yc - reach - w.a.y()) / d.y(), tb = (yc + reach - w.a.y()) / d.y();
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
        if (t0 > t1) continue;
      } else if (std::abs(w.a.y() - yc) > reach) {
        continue;
      }
      const double xa = w.a.x() + t0 * d.x(), xb = w.a.x() + t1 * d.x();
      const int x0 = std::max(0, frame_.CellX(std::min(xa, xb) - reach));
      const int x1 = std::min(frame_.nx - 1, frame_.CellX(std::max(xa, xb) + reach));
      for (int ix = x0; ix <= x1; ++ix) {
        const Eigen::Vector2d centre = frame_.CellMin(ix, iy).array() + 0.5 * frame_.cell;
        double& v = values_[static_cast<size_t>(frame_.Index(ix, iy))];
        v = std::min(v, PointToSegmentDistance(centre, w));
        ++distance_tests_;
      }
    }
  }
}

}  // namespace minenav
