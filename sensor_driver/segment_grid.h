#pragma once
// A uniform-grid index over line segments for fast ray casting (the "grid" idea the
// thesis measured for correspondence search in Table 9, applied to scan simulation).
//
// Each cell lists the segments that touch it (conservatively: cells are grown by a small
// margin, so floating-point error never loses a segment). A ray walks the cells it crosses
// in order (Amanatides-Woo DDA) and stops once the nearest hit so far lies before the
// current cell's exit. Hits are computed with the same RaySegmentIntersection as the brute
// force CastRay of common/geometry.h, with the same tie rule (nearest; equal ranges: lowest
// index), so the answer is identical to brute force: same range bit for bit, same index.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/geometry.h"

namespace minenav {

class SegmentGrid {
 public:
  // cell_size in m; 0 picks one from the segments (about twice the median segment length,
  // at least 0.5 m, and at most ~4 million cells).
  explicit SegmentGrid(std::vector<Segment> segments, double cell_size = 0.0);

  // Nearest hit of the ray from origin at bearing (rad, world frame) within max_range;
  // identical to CastRay(origin, bearing, segments(), max_range).
  std::optional<RayHit> CastRay(const Eigen::Vector2d& origin, double bearing, double max_range) const;
  // Same with an explicit unit direction (dir = (cos b, sin b) gives CastRay's answer).
  std::optional<RayHit> CastRayDir(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                   double max_range) const;

  const std::vector<Segment>& segments() const { return segments_; }
  double cell_size() const { return cell_; }
  int cols() const { return nx_; }
  int rows() const { return ny_; }
  // Total number of (cell, segment) entries, for tuning.
  size_t entries() const { return items_.size(); }

 private:
  void Build();
  bool CellTouches(int cx, int cy, const Segment& s) const;

  std::vector<Segment> segments_;
  double cell_ = 1.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // lower-left corner of cell (0, 0)
  int nx_ = 0;
  int ny_ = 0;
  std::vector<uint32_t> cell_start_;  // CSR: items_[cell_start_[c] .. cell_start_[c + 1])
  std::vector<uint32_t> items_;
};

}  // namespace minenav
