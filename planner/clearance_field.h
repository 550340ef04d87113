#pragma once
// The clearance field: on a grid of cells, the distance (m) from each cell's centre to the
// nearest wall, capped. Distance is 1-Lipschitz, so anywhere in a cell the true clearance is
// within Slack() (half the cell diagonal) of the cell's value. The collision checker uses it
// to decide most poses without an exact test, and the obstacle heuristic to know where the
// vehicle's centre can be at all.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/geometry.h"
#include "common/segment_index.h"

namespace minenav {

class ClearanceField {
 public:
  // Distances to the nearest of `walls` at the cell centres of `frame`, capped at
  // max_distance (m): a cell farther than that from every wall holds max_distance.
  ClearanceField(const std::vector<Segment>& walls, const GridFrame& frame, double max_distance);

  // m, the value of cell (ix, iy); 0 outside the frame.
  double AtCell(int ix, int iy) const {
    return frame_.Contains(ix, iy) ? values_[static_cast<size_t>(frame_.Index(ix, iy))] : 0.0;
  }
  // m, the value of the cell holding p; 0 outside the frame.
  double At(const Eigen::Vector2d& p) const { return AtCell(frame_.CellX(p.x()), frame_.CellY(p.y())); }
  // m: the true clearance anywhere in a cell is within this of its value (up to the cap).
  double Slack() const { return 0.5 * std::sqrt(2.0) * frame_.cell; }
  // m, bounds on the true clearance at p from the value at the centre c of p's cell and the
  // distance is 1-Lipschitz: true(p) >= value - |p - c| (a capped value is below the truth
  // too), and, where the value is under the cap, true(p) <= value + |p - c|. Outside the
  // frame: -infinity and +infinity (nothing known).
  // (The cell is found by a multiplication, not GridFrame's division: the bounds hold from
  // any cell's centre, so a point on a cell edge may round either way.)
  double LowerBound(const Eigen::Vector2d& p) const {
    const int ix = CellX(p.x()), iy = CellY(p.y());
    if (!frame_.Contains(ix, iy)) return -std::numeric_limits<double>::infinity();
    return values_[static_cast<size_t>(frame_.Index(ix, iy))] - OffsetFromCentre(p, ix, iy);
  }
  double UpperBound(const Eigen::Vector2d& p) const {
    const int ix = CellX(p.x()), iy = CellY(p.y());
    if (!frame_.Contains(ix, iy)) return std::numeric_limits<double>::infinity();
    const double v = values_[static_cast<size_t>(frame_.Index(ix, iy))];
    return v < max_distance_ ? v + OffsetFromCentre(p, ix, iy) : std::numeric_limits<double>::infinity();
  }
  double max_distance() const { return max_distance_; }
  // Distances to a wall computed while building: each wall costs the cells of its band, about
  // (length / cell + 1) (2 max_distance / cell + 5) (tests, tuning).
  int64_t distance_tests() const { return distance_tests_; }
  const GridFrame& frame() const { return frame_; }

 private:
  int CellX(double x) const { return ClampedFloor((x - frame_.x0) * inverse_cell_, -1, frame_.nx); }
  int CellY(double y) const { return ClampedFloor((y - frame_.y0) * inverse_cell_, -1, frame_.ny); }
  double OffsetFromCentre(const Eigen::Vector2d& p, int ix, int iy) const {
    const double dx = p.x() - (frame_.x0 + (ix + 0.5) * frame_.cell), dy = p.y() - (frame_.y0 + (iy + 0.5) * frame_.cell);
    return std::sqrt(dx * dx + dy * dy);
  }

  GridFrame frame_;
  double inverse_cell_;  // 1 / frame_.cell
  double max_distance_;
  std::vector<double> values_;
  int64_t distance_tests_ = 0;
};

}  // namespace minenav
