#include "common/segment_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/file_io.h"

namespace minenav {

// ---------------------------------------------------------------------------------------
// Cell geometry

GridFrame GridFrame::Covering(const std::vector<Segment>& segments, double cell_size, double margin) {
  if (segments.empty()) {
    GridFrame f;
    f.cell = cell_size;
    f.nx = f.ny = 1;
    return f;
  }
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
  double hi_x = -lo_x, hi_y = -lo_x;
  for (const Segment& s : segments) {
    lo_x = std::min({lo_x, s.a.x(), s.b.x()});
    lo_y = std::min({lo_y, s.a.y(), s.b.y()});
    hi_x = std::max({hi_x, s.a.x(), s.b.x()});
    hi_y = std::max({hi_y, s.a.y(), s.b.y()});
  }
  return Covering(Eigen::Vector2d(lo_x, lo_y), Eigen::Vector2d(hi_x, hi_y), cell_size, margin);
}

GridFrame GridFrame::Covering(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double cell_size,
                              double margin) {
  GridFrame f;
  f.cell = cell_size;
  f.x0 = lo.x() - margin - cell_size;
  f.y0 = lo.y() - margin - cell_size;
  const double nx = std::ceil((hi.x() + margin + cell_size - f.x0) / cell_size) + 1.0;
  const double ny = std::ceil((hi.y() + margin + cell_size - f.y0) / cell_size) + 1.0;
  // Found by the fuzz targets (issue 16): a map message with a coordinate of 1e39 m made the
  // counts overflow int (undefined behaviour) in the planners' and the iconic estimator's grids.
  if (!(nx * ny <= kMaxDenseCells))
    throw InputError("a grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " cells of " +
                     std::to_string(cell_size) + " m (at most " + std::to_string(kMaxDenseCells) +
                     "): the map spans too far");
  f.nx = static_cast<int>(nx);
  f.ny = static_cast<int>(ny);
  return f;
}

namespace {
// Squared distances: BoxSegmentMinDistance takes one square root, of the least (the planner's
// exact collision test calls it for every wall near every pose it cannot decide by the field).
double PointBoxSquaredDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return dx * dx + dy * dy;
}
// From p to the segment a + t d, t in [0, 1] (len2 = |d|^2; a point when 0).
double PointSegmentSquaredDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& d,
                                   double len2) {
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).squaredNorm();
}
}  // namespace

double BoxSegmentMinDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s) {
  const Eigen::Vector2d d = s.b - s.a;
  if (SegmentMeetsBox(s.a, d, lo, hi)) return 0.0;
  // Disjoint convex sets: the least distance is between a vertex of one and the other.
  const double len2 = d.squaredNorm();
  double best = std::min(PointBoxSquaredDistance(s.a, lo, hi), PointBoxSquaredDistance(s.b, lo, hi));
  for (const Eigen::Vector2d& corner : {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())})
    best = std::min(best, PointSegmentSquaredDistance(corner, s.a, d, len2));
  return std::sqrt(best);
}

double BoxSegmentMaxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s) {
  const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  double worst = 0.0;
  for (const Eigen::Vector2d& corner : c) worst = std::max(worst, PointToSegmentDistance(corner, s));
  return worst;
}

// ---------------------------------------------------------------------------------------
// StaticSegmentIndex

namespace {
bool Listable(const Segment& s) {
  constexpr double kMax = StaticSegmentIndex::kMaxCoordinate;
  return s.a.allFinite() && s.b.allFinite() && s.a.cwiseAbs().maxCoeff() <= kMax && s.b.cwiseAbs().maxCoeff() <= kMax;
}
}  // namespace

StaticSegmentIndex::StaticSegmentIndex(std::vector<Segment> segments, double cell_size)
    : segments_(std::move(segments)) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<double> lengths;
  lengths.reserve(segments_.size());
  double crossed = 0.0;  // m: the segments' lengths along both axes (|dx| + |dy| summed)
  for (size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    if (!Listable(s)) {
      unlisted_.push_back(static_cast<uint32_t>(i));
      continue;
    }
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    lengths.push_back(s.length());
    crossed += (s.b - s.a).cwiseAbs().sum();
  }
  cell_start_.assign(1, 0);
  frame_.nx = frame_.ny = 0;
  if (lengths.empty()) return;

  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
    cell_size = std::max(0.5, 2.0 * lengths[lengths.size() / 2]);
  }
  // The segments' cells within their budget: a segment touches at most 2 (|dx| + |dy|) / cell
  // + 4 cells (see kMaxLengthCells).
  const double length_cells = std::max(kMaxLengthCells, kLengthCellsPerSegment * static_cast<double>(lengths.size()));
  cell_size = std::max(cell_size, 2.0 * crossed / length_cells);
  // The grid covers the segments' box with half a cell around it, within the cell budget.
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(Eigen::Vector2d(1e-3, 1e-3));
  auto cells = [&](double c) { return (extent.x() / c + 2.0) * (extent.y() / c + 2.0); };
  if (cells(cell_size) > kMaxCells) {
    cell_size = std::max(cell_size, std::sqrt(extent.x()) * std::sqrt(extent.y()) / std::sqrt(kMaxCells));
    while (cells(cell_size) > kMaxCells) cell_size *= 1.05;
  }
  frame_.cell = cell_size;
  frame_.x0 = lo.x() - 0.5 * cell_size;
  frame_.y0 = lo.y() - 0.5 * cell_size;
  frame_.nx = static_cast<int>(std::ceil((extent.x() + cell_size) / cell_size)) + 1;
  frame_.ny = static_cast<int>(std::ceil((extent.y() + cell_size) / cell_size)) + 1;

  // Every (cell, segment) pair, then a counting sort by cell: within a cell the segments
  // stay in increasing index order.
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  pairs.reserve(2 * segments_.size());
  for (size_t i = 0; i < segments_.size(); ++i) {
    if (!Listable(segments_[i])) continue;
    ForEachCellTouched(frame_, frame_.Cells(), segments_[i], kNoCellLimit, [&](int ix, int iy) {
      pairs.emplace_back(static_cast<uint32_t>(frame_.Index(ix, iy)), static_cast<uint32_t>(i));
    });
  }
  const size_t num_cells = static_cast<size_t>(frame_.size());
  cell_start_.assign(num_cells + 1, 0);
  for (const auto& [c, i] : pairs) ++cell_start_[c + 1];
  for (size_t c = 0; c < num_cells; ++c) cell_start_[c + 1] += cell_start_[c];
  items_.resize(pairs.size());
  std::vector<uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (const auto& [c, i] : pairs) items_[next[c]++] = i;
}

std::optional<RayHit> StaticSegmentIndex::CastRay(const Eigen::Vector2d& origin, double bearing,
                                                  double max_range) const {
  return CastRayDir(origin, Eigen::Vector2d(std::cos(bearing), std::sin(bearing)), max_range);
}

std::optional<RayHit> StaticSegmentIndex::CastRayDir(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                                     double max_range) const {
  if (segments_.empty() || !(max_range >= 0.0) || !origin.allFinite() || !dir.allFinite() || dir.isZero())
    return std::nullopt;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  RayHit best{kInf, -1};
  // The same test and tie rule as brute force: nearest; equal ranges, the lowest index.
  auto test = [&](uint32_t k) {
    const int idx = static_cast<int>(k);
    const auto r = RaySegmentIntersection(origin, dir, segments_[k]);
    if (r && (*r < best.range || (*r == best.range && idx < best.segment))) best = {*r, idx};
  };
  for (const uint32_t k : unlisted_) test(k);  // usually none
  auto result = [&]() -> std::optional<RayHit> {
    if (best.segment < 0 || best.range > max_range) return std::nullopt;
    return best;
  };
  if (frame_.nx == 0) return result();

  // Clip the ray against the grid's box.
  const double cell = frame_.cell;
  const Eigen::Vector2d grid_lo(frame_.x0, frame_.y0);
  const int nx = frame_.nx, ny = frame_.ny;
  const Eigen::Vector2d grid_hi = grid_lo + cell * Eigen::Vector2d(nx, ny);
  double t_in = 0.0, t_out = kInf;
  for (int k = 0; k < 2; ++k) {
    if (dir[k] == 0.0) {
      if (origin[k] < grid_lo[k] || origin[k] > grid_hi[k]) return result();
    } else {
      double ta = (grid_lo[k] - origin[k]) / dir[k], tb = (grid_hi[k] - origin[k]) / dir[k];
      if (ta > tb) std::swap(ta, tb);
      t_in = std::max(t_in, ta);
      t_out = std::min(t_out, tb);
    }
  }
  if (t_in > t_out || t_in > max_range) return result();

  // Amanatides-Woo: visit the cells the ray crosses, in order.
  const Eigen::Vector2d start = origin + t_in * dir;
  int ix = std::clamp(frame_.CellX(start.x()), 0, nx - 1);
  int iy = std::clamp(frame_.CellY(start.y()), 0, ny - 1);
  const int step_x = dir.x() > 0.0 ? 1 : -1, step_y = dir.y() > 0.0 ? 1 : -1;
  double t_max_x = kInf, t_max_y = kInf, t_delta_x = kInf, t_delta_y = kInf;
  if (dir.x() != 0.0) {
    t_max_x = (grid_lo.x() + (ix + (step_x > 0 ? 1 : 0)) * cell - origin.x()) / dir.x();
    t_delta_x = cell / std::abs(dir.x());
  }
  if (dir.y() != 0.0) {
    t_max_y = (grid_lo.y() + (iy + (step_y > 0 ? 1 : 0)) * cell - origin.y()) / dir.y();
    t_delta_y = cell / std::abs(dir.y());
  }
  double t_cell_in = t_in;
  while (true) {
    const size_t c = static_cast<size_t>(iy) * static_cast<size_t>(nx) + static_cast<size_t>(ix);
    for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) test(items_[k]);
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
    if (ix < 0 || ix >= nx || iy < 0 || iy >= ny) break;
    if (t_cell_in > max_range + 1e-9 * (1.0 + max_range)) break;
  }
  return result();
}

std::vector<int> StaticSegmentIndex::Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                           double radius) const {
  std::vector<int> out;
  const CellRange r = CellsNear(lo, hi, radius);
  for (int iy = r.y_lo; iy <= r.y_hi; ++iy)
    for (int ix = r.x_lo; ix <= r.x_hi; ++ix)
      for (const uint32_t i : CellSegments(ix, iy)) out.push_back(static_cast<int>(i));
  for (const uint32_t i : unlisted_) out.push_back(static_cast<int>(i));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// ---------------------------------------------------------------------------------------
// IncrementalSegmentIndex

IncrementalSegmentIndex::IncrementalSegmentIndex(double cell_size) {
  frame_.cell = cell_size > 0.0 && std::isfinite(cell_size) ? cell_size : 2.0;
}

void IncrementalSegmentIndex::Insert(int group, const std::vector<Segment>& segments) {
  Remove(group);
  std::vector<int64_t>& keys = cells_of_group_[group];
  // Indexable: finite and well inside the cell coordinate range (so no cell is clamped).
  const double limit = (kMaxCellCoord - 2.0) * frame_.cell;
  auto indexable = [&](const Eigen::Vector2d& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::abs(p.x()) < limit && std::abs(p.y()) < limit;
  };
  const CellRange window{-kMaxCellCoord, -kMaxCellCoord, kMaxCellCoord, kMaxCellCoord};
  std::vector<int64_t> along;
  bool unindexed = false;
  for (size_t k = 0; k < segments.size(); ++k) {
    const Segment& s = segments[k];
    const SegmentId id{group, static_cast<int>(k)};
    if (!indexable(s.a) || !indexable(s.b)) {
      unindexed_.push_back(id);
      unindexed = true;
      continue;
    }
    const int x0 = Cell(std::min(s.a.x(), s.b.x())), x1 = Cell(std::max(s.a.x(), s.b.x()));
    const int y0 = Cell(std::min(s.a.y(), s.b.y())), y1 = Cell(std::max(s.a.y(), s.b.y()));
    const int64_t box_cells = (static_cast<int64_t>(x1) - x0 + 1) * (static_cast<int64_t>(y1) - y0 + 1);
    if (box_cells <= kMaxBoxCells) {
      for (int ix = x0; ix <= x1; ++ix)
        for (int iy = y0; iy <= y1; ++iy) {
          const int64_t key = Key(ix, iy);
          cells_[key].push_back(id);
          keys.push_back(key);
        }
      continue;
    }
    along.clear();
    if (ForEachCellTouched(frame_, window, s, kMaxCellsPerSegment,
                           [&](int ix, int iy) { along.push_back(Key(ix, iy)); })) {
      for (const int64_t key : along) {
        cells_[key].push_back(id);
        keys.push_back(key);
      }
    } else {
      unindexed_.push_back(id);
      unindexed = true;
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (unindexed) std::sort(unindexed_.begin(), unindexed_.end());
}

void IncrementalSegmentIndex::Remove(int group) {
  unindexed_.erase(std::remove_if(unindexed_.begin(), unindexed_.end(),
                                  [&](const SegmentId& r) { return r.group == group; }),
                   unindexed_.end());
  const auto it = cells_of_group_.find(group);
  if (it == cells_of_group_.end()) return;
  for (const int64_t key : it->second) {
    auto cell = cells_.find(key);
    if (cell == cells_.end()) continue;
    auto& v = cell->second;
    v.erase(std::remove_if(v.begin(), v.end(), [&](const SegmentId& r) { return r.group == group; }), v.end());
    if (v.empty()) cells_.erase(cell);
  }
  cells_of_group_.erase(it);
}

void IncrementalSegmentIndex::Clear() {
  cells_.clear();
  cells_of_group_.clear();
  unindexed_.clear();
}

std::vector<SegmentId> IncrementalSegmentIndex::Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                                      double radius) const {
  std::vector<SegmentId> out;
  const int x0 = Cell(lo.x() - radius), x1 = Cell(hi.x() + radius);
  const int y0 = Cell(lo.y() - radius), y1 = Cell(hi.y() + radius);
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

size_t IncrementalSegmentIndex::NumEntries() const {
  size_t n = unindexed_.size();
  for (const auto& [key, refs] : cells_) n += refs.size();
  return n;
}

}  // namespace minenav
