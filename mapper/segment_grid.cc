#include "mapper/segment_grid.h"

#include <algorithm>
#include <cmath>

namespace minenav::mapper {

SegmentGrid::SegmentGrid(double cell_size) : cell_size_(cell_size > 0.0 ? cell_size : 2.0) {}

int SegmentGrid::CellCoord(double v) const { return static_cast<int>(std::floor(v / cell_size_)); }

void SegmentGrid::Insert(const Contour& contour) {
  Remove(contour.id);
  std::vector<int64_t>& keys = cells_of_contour_[contour.id];
  for (int k = 0; k < contour.NumSegments(); ++k) {
    const Segment s = contour.GetSegment(k);
    const int x0 = CellCoord(std::min(s.a.x(), s.b.x())), x1 = CellCoord(std::max(s.a.x(), s.b.x()));
    const int y0 = CellCoord(std::min(s.a.y(), s.b.y())), y1 = CellCoord(std::max(s.a.y(), s.b.y()));
    for (int ix = x0; ix <= x1; ++ix)
      for (int iy = y0; iy <= y1; ++iy) {
        const int64_t key = Key(ix, iy);
        cells_[key].push_back({contour.id, k});
        keys.push_back(key);
      }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

void SegmentGrid::Remove(int contour_id) {
  const auto it = cells_of_contour_.find(contour_id);
  if (it == cells_of_contour_.end()) return;
  for (const int64_t key : it->second) {
    auto cell = cells_.find(key);
    if (cell == cells_.end()) continue;
    auto& v = cell->second;
    v.erase(std::remove_if(v.begin(), v.end(), [&](const SegmentRef& r) { return r.contour == contour_id; }),
            v.end());
    if (v.empty()) cells_.erase(cell);
  }
  cells_of_contour_.erase(it);
}

void SegmentGrid::Clear() {
  cells_.clear();
  cells_of_contour_.clear();
}

std::vector<SegmentRef> SegmentGrid::Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                           double radius) const {
  std::vector<SegmentRef> out;
  const int x0 = CellCoord(lo.x() - radius), x1 = CellCoord(hi.x() + radius);
  const int y0 = CellCoord(lo.y() - radius), y1 = CellCoord(hi.y() + radius);
  const long span = static_cast<long>(x1 - x0 + 1) * static_cast<long>(y1 - y0 + 1);
  if (span > static_cast<long>(cells_.size())) {
    // A query box larger than the occupied area: scan the occupied cells instead.
    for (const auto& [key, refs] : cells_) {
      const int ix = static_cast<int>(key >> 32), iy = static_cast<int>(static_cast<int32_t>(key & 0xffffffff));
      if (ix >= x0 && ix <= x1 && iy >= y0 && iy <= y1) out.insert(out.end(), refs.begin(), refs.end());
    }
  } else {
    for (int ix = x0; ix <= x1; ++ix)
      for (int iy = y0; iy <= y1; ++iy) {
        const auto it = cells_.find(Key(ix, iy));
        if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

size_t SegmentGrid::NumEntries() const {
  size_t n = 0;
  for (const auto& [key, refs] : cells_) n += refs.size();
  return n;
}

}  // namespace minenav::mapper
