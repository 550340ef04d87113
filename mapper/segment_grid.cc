#include "mapper/segment_grid.h"

#include <algorithm>
#include <cmath>

namespace minenav::mapper {

SegmentGrid::SegmentGrid(double cell_size) : cell_size_(cell_size > 0.0 ? cell_size : 2.0) {}

int SegmentGrid::CellCoord(double v) const {
  const double c = std::floor(v / cell_size_);
  if (!(c > -kMaxCellCoord)) return -kMaxCellCoord;  // also NaN: no UB in the cast below
  if (c > kMaxCellCoord) return kMaxCellCoord;
  return static_cast<int>(c);
}

bool SegmentGrid::CellsAlong(const Segment& s, std::vector<int64_t>* keys) const {
  keys->clear();
  // Walk along the major axis u one column of cells at a time; in each column the segment
  // covers an interval of the minor axis v, and every cell of it is listed.
  const bool steep = std::abs(s.b.y() - s.a.y()) > std::abs(s.b.x() - s.a.x());
  const double ua = steep ? s.a.y() : s.a.x(), ub = steep ? s.b.y() : s.b.x();
  const double va = steep ? s.a.x() : s.a.y(), vb = steep ? s.b.x() : s.b.y();
  if (ua == ub) return false;  // a point: never called for one (its box is one cell)
  const double ulo = std::min(ua, ub), uhi = std::max(ua, ub);
  // Rounding must never leave out a cell the segment touches: widen by far more than it.
  const double margin = 1e-6 * cell_size_ + 1e-12 * std::max({std::abs(ua), std::abs(ub), std::abs(va), std::abs(vb)});
  const int c0 = CellCoord(ulo - margin), c1 = CellCoord(uhi + margin);
  for (int col = c0; col <= c1; ++col) {
    const double s0 = std::clamp(static_cast<double>(col) * cell_size_, ulo, uhi);
    const double s1 = std::clamp(static_cast<double>(col + 1) * cell_size_, ulo, uhi);
    const double w0 = va + (s0 - ua) / (ub - ua) * (vb - va), w1 = va + (s1 - ua) / (ub - ua) * (vb - va);
    const int r0 = CellCoord(std::min(w0, w1) - margin), r1 = CellCoord(std::max(w0, w1) + margin);
    for (int r = r0; r <= r1; ++r) keys->push_back(steep ? Key(r, col) : Key(col, r));
    if (static_cast<int64_t>(keys->size()) > kMaxLineCells) return false;
  }
  return true;
}

void SegmentGrid::Insert(const Contour& contour) {
  Remove(contour.id);
  std::vector<int64_t>& keys = cells_of_contour_[contour.id];
  // Indexable: finite and well inside the cell coordinate range (so no cell is clamped).
  const double limit = (kMaxCellCoord - 2.0) * cell_size_;
  auto indexable = [&](const Eigen::Vector2d& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::abs(p.x()) < limit && std::abs(p.y()) < limit;
  };
  std::vector<int64_t> along;
  bool unindexed = false;
  for (int k = 0; k < contour.NumSegments(); ++k) {
    const Segment s = contour.GetSegment(k);
    const SegmentRef ref{contour.id, k};
    if (!indexable(s.a) || !indexable(s.b)) {
      unindexed_.push_back(ref);
      unindexed = true;
      continue;
    }
    const int x0 = CellCoord(std::min(s.a.x(), s.b.x())), x1 = CellCoord(std::max(s.a.x(), s.b.x()));
    const int y0 = CellCoord(std::min(s.a.y(), s.b.y())), y1 = CellCoord(std::max(s.a.y(), s.b.y()));
    const int64_t box_cells = (static_cast<int64_t>(x1) - x0 + 1) * (static_cast<int64_t>(y1) - y0 + 1);
    if (box_cells <= kMaxBoxCells) {
      for (int ix = x0; ix <= x1; ++ix)
        for (int iy = y0; iy <= y1; ++iy) {
          const int64_t key = Key(ix, iy);
          cells_[key].push_back(ref);
          keys.push_back(key);
        }
    } else if (CellsAlong(s, &along)) {
      for (const int64_t key : along) {
        cells_[key].push_back(ref);
        keys.push_back(key);
      }
    } else {
      unindexed_.push_back(ref);
      unindexed = true;
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (unindexed) std::sort(unindexed_.begin(), unindexed_.end());
}

void SegmentGrid::Remove(int contour_id) {
  unindexed_.erase(std::remove_if(unindexed_.begin(), unindexed_.end(),
                                  [&](const SegmentRef& r) { return r.contour == contour_id; }),
                   unindexed_.end());
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
  unindexed_.clear();
}

std::vector<SegmentRef> SegmentGrid::Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                           double radius) const {
  std::vector<SegmentRef> out;
  const int x0 = CellCoord(lo.x() - radius), x1 = CellCoord(hi.x() + radius);
  const int y0 = CellCoord(lo.y() - radius), y1 = CellCoord(hi.y() + radius);
  const int64_t span = (static_cast<int64_t>(x1) - x0 + 1) * (static_cast<int64_t>(y1) - y0 + 1);
  if (span > static_cast<int64_t>(cells_.size())) {
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
  out.insert(out.end(), unindexed_.begin(), unindexed_.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

size_t SegmentGrid::NumEntries() const {
  size_t n = unindexed_.size();
  for (const auto& [key, refs] : cells_) n += refs.size();
  return n;
}

}  // namespace minenav::mapper
