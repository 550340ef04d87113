#pragma once
// A uniform grid over contour segments: the spatial index of the contour map. It replaces
// the bounding circles of thesis 4.3.2, which reject whole contours only. Every segment is
// listed in each cell its bounding box touches; a contour is re-indexed as a whole whenever
// it is edited (contours hold tens to hundreds of segments, so this is cheap and keeps the
// index exactly in step with the map).

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapper/contour.h"

namespace minenav::mapper {

class SegmentGrid {
 public:
  explicit SegmentGrid(double cell_size = 2.0);

  double cell_size() const { return cell_size_; }

  // (Re-)indexes every segment of the contour.
  void Insert(const Contour& contour);
  void Remove(int contour_id);
  void Clear();

  // Every segment whose bounding box comes within `radius` of the box [lo, hi] (a superset
  // of the segments within `radius` of any point in it), sorted and without duplicates.
  std::vector<SegmentRef> Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double radius) const;
  std::vector<SegmentRef> QueryPoint(const Eigen::Vector2d& p, double radius) const {
    return Query(p, p, radius);
  }

  // Calls fn(ref) for candidates near p without allocating (may repeat a segment).
  template <typename Fn>
  void ForEachNear(const Eigen::Vector2d& p, double radius, Fn&& fn) const {
    const int x0 = CellCoord(p.x() - radius), x1 = CellCoord(p.x() + radius);
    const int y0 = CellCoord(p.y() - radius), y1 = CellCoord(p.y() + radius);
    for (int ix = x0; ix <= x1; ++ix)
      for (int iy = y0; iy <= y1; ++iy) {
        const auto it = cells_.find(Key(ix, iy));
        if (it == cells_.end()) continue;
        for (const SegmentRef& r : it->second) fn(r);
      }
  }

  size_t NumEntries() const;

 private:
  int CellCoord(double v) const;
  static int64_t Key(int ix, int iy) {
    return (static_cast<int64_t>(ix) << 32) ^ static_cast<int64_t>(static_cast<uint32_t>(iy));
  }

  double cell_size_;
  std::unordered_map<int64_t, std::vector<SegmentRef>> cells_;
  std::unordered_map<int, std::vector<int64_t>> cells_of_contour_;
};

}  // namespace minenav::mapper
