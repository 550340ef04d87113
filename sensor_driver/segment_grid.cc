#include "sensor_driver/segment_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {

namespace {
// m: cells are grown by this much when listing segments, so a segment passing within
// rounding distance of a cell (or through a corner the DDA steps around) is listed there.
constexpr double kMargin = 1e-6;
}  // namespace

SegmentGrid::SegmentGrid(std::vector<Segment> segments, double cell_size) : segments_(std::move(segments)) {
  if (segments_.empty()) return;
  Eigen::Vector2d lo = segments_.front().a, hi = lo;
  std::vector<double> lengths;
  lengths.reserve(segments_.size());
  for (const Segment& s : segments_) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    lengths.push_back(s.length());
  }
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(Eigen::Vector2d(1e-3, 1e-3));
  if (!(cell_size > 0.0)) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    cell_size = std::max(0.5, 2.0 * lengths[lengths.size() / 2]);
  }
  const double max_cells = 4e6;
  if ((extent.x() / cell_size + 1) * (extent.y() / cell_size + 1) > max_cells)
    cell_size = std::sqrt(extent.x() * extent.y() / max_cells) * 1.01 + 1e-9;
  cell_ = cell_size;
  origin_ = lo - Eigen::Vector2d(0.5 * cell_, 0.5 * cell_);
  nx_ = static_cast<int>(std::ceil((extent.x() + cell_) / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil((extent.y() + cell_) / cell_)) + 1;
  Build();
}

bool SegmentGrid::CellTouches(int cx, int cy, const Segment& s) const {
  // Liang-Barsky clip of the segment against the grown cell box.
  const double x0 = origin_.x() + cx * cell_ - kMargin, x1 = x0 + cell_ + 2 * kMargin;
  const double y0 = origin_.y() + cy * cell_ - kMargin, y1 = y0 + cell_ + 2 * kMargin;
  const Eigen::Vector2d d = s.b - s.a;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {s.a.x() - x0, x1 - s.a.x(), s.a.y() - y0, y1 - s.a.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
    } else {
      const double t = q[k] / p[k];
      if (p[k] < 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
  }
  return true;
}

void SegmentGrid::Build() {
  const size_t cells = static_cast<size_t>(nx_) * ny_;
  std::vector<std::vector<uint32_t>> lists(cells);
  for (size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    const Eigen::Vector2d lo = s.a.cwiseMin(s.b), hi = s.a.cwiseMax(s.b);
    const int cx0 = std::clamp(static_cast<int>(std::floor((lo.x() - kMargin - origin_.x()) / cell_)), 0, nx_ - 1);
    const int cx1 = std::clamp(static_cast<int>(std::floor((hi.x() + kMargin - origin_.x()) / cell_)), 0, nx_ - 1);
    const int cy0 = std::clamp(static_cast<int>(std::floor((lo.y() - kMargin - origin_.y()) / cell_)), 0, ny_ - 1);
    const int cy1 = std::clamp(static_cast<int>(std::floor((hi.y() + kMargin - origin_.y()) / cell_)), 0, ny_ - 1);
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx)
        if (CellTouches(cx, cy, s)) lists[static_cast<size_t>(cy) * nx_ + cx].push_back(static_cast<uint32_t>(i));
  }
  cell_start_.assign(cells + 1, 0);
  for (size_t c = 0; c < cells; ++c) cell_start_[c + 1] = cell_start_[c] + static_cast<uint32_t>(lists[c].size());
  items_.reserve(cell_start_.back());
  for (const auto& l : lists) items_.insert(items_.end(), l.begin(), l.end());
}

std::optional<RayHit> SegmentGrid::CastRay(const Eigen::Vector2d& origin, double bearing, double max_range) const {
  return CastRayDir(origin, Eigen::Vector2d(std::cos(bearing), std::sin(bearing)), max_range);
}

std::optional<RayHit> SegmentGrid::CastRayDir(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                              double max_range) const {
  if (segments_.empty() || !(max_range >= 0.0) || !origin.allFinite() || !dir.allFinite() || dir.isZero())
    return std::nullopt;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Clip the ray against the grid's box.
  const Eigen::Vector2d box_lo = origin_, box_hi = origin_ + cell_ * Eigen::Vector2d(nx_, ny_);
  double t_in = 0.0, t_out = kInf;
  for (int k = 0; k < 2; ++k) {
    if (dir[k] == 0.0) {
      if (origin[k] < box_lo[k] || origin[k] > box_hi[k]) return std::nullopt;
    } else {
      double ta = (box_lo[k] - origin[k]) / dir[k], tb = (box_hi[k] - origin[k]) / dir[k];
      if (ta > tb) std::swap(ta, tb);
      t_in = std::max(t_in, ta);
      t_out = std::min(t_out, tb);
    }
  }
  if (t_in > t_out || t_in > max_range) return std::nullopt;

  const Eigen::Vector2d start = origin + t_in * dir;
  int ix = std::clamp(static_cast<int>(std::floor((start.x() - origin_.x()) / cell_)), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((start.y() - origin_.y()) / cell_)), 0, ny_ - 1);
  const int step_x = dir.x() > 0.0 ? 1 : -1, step_y = dir.y() > 0.0 ? 1 : -1;
  double t_max_x = kInf, t_max_y = kInf, t_delta_x = kInf, t_delta_y = kInf;
  if (dir.x() != 0.0) {
    t_max_x = (origin_.x() + (ix + (step_x > 0 ? 1 : 0)) * cell_ - origin.x()) / dir.x();
    t_delta_x = cell_ / std::abs(dir.x());
  }
  if (dir.y() != 0.0) {
    t_max_y = (origin_.y() + (iy + (step_y > 0 ? 1 : 0)) * cell_ - origin.y()) / dir.y();
    t_delta_y = cell_ / std::abs(dir.y());
  }

  RayHit best{kInf, -1};
  double t_cell_in = t_in;
  while (true) {
    const size_t c = static_cast<size_t>(iy) * nx_ + ix;
    for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const int idx = static_cast<int>(items_[k]);
      const auto r = RaySegmentIntersection(origin, dir, segments_[idx]);
      if (r && (*r < best.range || (*r == best.range && idx < best.segment))) best = {*r, idx};
    }
    const double t_cell_out = std::min(t_max_x, t_max_y);
    // Every hit nearer than this cell's exit lies in a cell already searched.
    if (best.segment >= 0 && best.range < t_cell_out - 1e-9 * (1.0 + t_cell_out)) break;
    if (t_max_x < t_max_y) {
      ix += step_x;
      t_cell_in = t_max_x;
      t_max_x += t_delta_x;
    } else {
      iy += step_y;
      t_cell_in = t_max_y;
      t_max_y += t_delta_y;
    }
    if (ix < 0 || ix >= nx_ || iy < 0 || iy >= ny_) break;
    if (t_cell_in > max_range + 1e-9 * (1.0 + max_range)) break;
  }
  if (best.segment < 0 || best.range > max_range) return std::nullopt;
  return best;
}

}  // namespace minenav
