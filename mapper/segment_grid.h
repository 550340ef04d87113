#pragma once
// A uniform grid over contour segments: the spatial index of the contour map. It replaces
// the bounding circles of thesis 4.3.2, which reject whole contours only. Every segment is
// listed in each cell its bounding box touches; a contour is re-indexed as a whole whenever
// it is edited (contours hold tens to hundreds of segments, so this is cheap and keeps the
// index exactly in step with the map).
//
// What one segment may cost is capped, whatever its geometry (issue 11, item 7: a 20 km
// diagonal segment in a forged map spans 10^8 cells of its bounding box and took 6 GB):
//   * a segment whose bounding box spans at most kMaxBoxCells cells is listed in each of
//     them (every segment the mapper makes: 0.5 m long, 1 to 4 cells);
//   * a longer one is listed only in the cells along it (a conservative walk column by
//     column), at most kMaxLineCells of them (a straight wall of several km in 2 m cells);
//   * anything longer, or with a coordinate beyond the grid's integer range, is kept in a
//     short list that every query returns as a candidate (callers test exact distance).
// Files are checked before they get here (contour_map_io.h kMaxSegmentLength), so the list
// stays empty in practice; it only guarantees that no geometry makes the index blow up.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapper/contour.h"

namespace minenav::mapper {

class SegmentGrid {
 public:
  // Cells of a segment's bounding box above which it is indexed along its line instead.
  static constexpr int64_t kMaxBoxCells = 256;
  // Cells along a segment above which it goes to the list every query returns.
  static constexpr int64_t kMaxLineCells = 4096;

  explicit SegmentGrid(double cell_size = 2.0);

  double cell_size() const { return cell_size_; }

  // (Re-)indexes every segment of the contour.
  void Insert(const Contour& contour);
  void Remove(int contour_id);
  void Clear();

  // Every segment listed in a cell within `radius` of the box [lo, hi], and the unindexed
  // ones (a superset of the segments within `radius` of any point in it), sorted and
  // without duplicates.
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
    for (const SegmentRef& r : unindexed_) fn(r);
  }

  // Entries over all cells plus the segments every query returns.
  size_t NumEntries() const;
  // Segments too long (or too far out) to be indexed by cell: every query returns them.
  size_t NumUnindexed() const { return unindexed_.size(); }

 private:
  // Cell coordinates stay within ±kMaxCellCoord, so Key() never overflows and a query
  // beyond the range clamps to its edge (where no indexed segment lies).
  static constexpr int kMaxCellCoord = 1 << 30;
  int CellCoord(double v) const;
  static int64_t Key(int ix, int iy) {
    return (static_cast<int64_t>(ix) << 32) ^ static_cast<int64_t>(static_cast<uint32_t>(iy));
  }
  // The cells along segment s (at most kMaxLineCells + a few); false when there are more.
  bool CellsAlong(const Segment& s, std::vector<int64_t>* keys) const;

  double cell_size_;
  std::unordered_map<int64_t, std::vector<SegmentRef>> cells_;
  std::unordered_map<int, std::vector<int64_t>> cells_of_contour_;
  std::vector<SegmentRef> unindexed_;  // sorted
};

}  // namespace minenav::mapper
