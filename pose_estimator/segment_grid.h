#pragma once
// A regular grid over the plane and the box-to-segment distances the grid searches of
// 3.1.1 need: which cells a segment is drawn into, and the least and greatest distance
// from any point of a cell to a segment.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace minenav {

struct GridFrame {
  double x0 = 0.0, y0 = 0.0;  // m, lower-left corner of cell (0, 0)
  double cell = 1.0;          // m
  int nx = 0, ny = 0;

  // The frame that covers all segments with `margin` (m) around them; nx, ny >= 1.
  static GridFrame Covering(const std::vector<Segment>& segments, double cell_size, double margin);

  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx && iy < ny; }
  // Cell coordinates of p (may lie outside the grid).
  int CellX(double x) const;
  int CellY(double y) const;
  int64_t Index(int ix, int iy) const { return static_cast<int64_t>(iy) * nx + ix; }
  int64_t size() const { return static_cast<int64_t>(nx) * ny; }
  Eigen::Vector2d CellMin(int ix, int iy) const { return {x0 + ix * cell, y0 + iy * cell}; }
};

// Least distance from any point of the axis-aligned box [lo, hi] to segment s (0 if they meet).
double BoxSegmentMinDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s);
// Greatest distance from any point of the box to s: the distance to a convex set is convex,
// so it is attained at a corner.
double BoxSegmentMaxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s);

// Cells (ix, iy) of `frame` that segment s passes through (clipped to the grid).
std::vector<std::pair<int, int>> CellsTouchedBySegment(const GridFrame& frame, const Segment& s);

}  // namespace minenav
