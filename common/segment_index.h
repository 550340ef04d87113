#pragma once
// The spatial index of line segments, one for the whole fleet: a uniform grid of square
// cells, each listing the segments that touch it (the "grid" the thesis measured for
// correspondence search, Table 9). The ladar simulator casts rays through it (sensor_driver/),
// the iconic estimator's grid search and lookup table draw their maps into it
// (pose_estimator/, 3.1.1), and the contour mapper keeps its contours in it (mapper/, in
// place of the bounding circles of 4.3.2).
//
// Shared by both storages:
//   GridFrame           the cell geometry: origin, cell size, the cell of a point (clamped
//                       before conversion, so no point, however far or NaN, overflows an int);
//   ForEachCellTouched  which cells a segment touches: the Liang-Barsky clip of the segment
//                       against each cell box grown by CellMargin (so rounding never loses a
//                       segment), with candidates walked along the segment only, so a segment
//                       costs O(length / cell), never the cells of its bounding box.
// The two storages:
//   StaticSegmentIndex       built once from a vector of segments, dense cells (CSR); exact
//                            ray casting, the same answer as CastRay of common/geometry.h
//                            bit for bit; radius queries by segment index;
//   IncrementalSegmentIndex  groups of segments inserted, replaced and removed by a group id,
//                            sparse cells (a hash map) over the whole plane; radius queries
//                            return SegmentId{group, index}. Short segments are listed in
//                            the cells of their bounding box (see the class), long ones
//                            through ForEachCellTouched.
// Radius queries return candidates: every segment within the radius and maybe more (callers
// test the exact distance). No geometry makes an index blow up: a segment that cannot be
// listed by cell (a non-finite or absurdly large coordinate, or, in the incremental index,
// more than kMaxCellsPerSegment cells) is kept in a short list that every query returns.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/geometry.h"

namespace minenav {

// ---------------------------------------------------------------------------------------
// Cell geometry

// floor(v) as an int clamped to [lo, hi]; NaN gives lo. Clamped before the conversion, so
// no value overflows an int. The conversion truncates and corrects below 0 rather than call
// std::floor: without SSE4.1 that is a libm call, and the collision test asks this for every
// cell it looks up (7 % of a planning search's time).
inline int ClampedFloor(double v, int lo, int hi) {
  if (!(v >= lo)) return lo;
  if (v >= static_cast<double>(hi) + 1.0) return hi;
  const int t = static_cast<int>(v);
  return t > v ? t - 1 : t;
}

// An inclusive rectangle of cells [x_lo, x_hi] x [y_lo, y_hi] (empty when lo > hi).
struct CellRange {
  int x_lo = 0, y_lo = 0, x_hi = -1, y_hi = -1;
  bool empty() const { return x_lo > x_hi || y_lo > y_hi; }
};

// Cell (ix, iy) is the square [x0 + ix cell, x0 + (ix + 1) cell] x [y0 + iy cell, ...]. A
// dense grid has the cells 0 <= ix < nx, 0 <= iy < ny; a sparse one uses any cell
// coordinates within a range it chooses (nx = ny = 0).
struct GridFrame {
  double x0 = 0.0, y0 = 0.0;  // m, lower-left corner of cell (0, 0)
  double cell = 1.0;          // m
  int nx = 0, ny = 0;

  // The most cells a dense frame may have (2^28: 16384 x 16384): more is a map of absurd extent
  // for its cell size (hostile coordinates such as 1e39 m: the counts would not even fit an int).
  static constexpr double kMaxDenseCells = 268435456.0;

  // The dense frame that covers all segments with `margin` (m) and one more cell around
  // them; nx, ny >= 1. Throws InputError when it would have more than kMaxDenseCells cells.
  static GridFrame Covering(const std::vector<Segment>& segments, double cell_size, double margin);
  static GridFrame Covering(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double cell_size, double margin);

  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx && iy < ny; }
  // Cell coordinates of a point, clamped to [lo, hi].
  int CellX(double x, int lo, int hi) const { return ClampedFloor((x - x0) / cell, lo, hi); }
  int CellY(double y, int lo, int hi) const { return ClampedFloor((y - y0) / cell, lo, hi); }
  // Dense grids: clamped to [-1, nx] and [-1, ny] (one past each edge: outside the grid).
  int CellX(double x) const { return CellX(x, -1, nx); }
  int CellY(double y) const { return CellY(y, -1, ny); }
  int64_t Index(int ix, int iy) const { return static_cast<int64_t>(iy) * nx + ix; }
  int64_t size() const { return static_cast<int64_t>(nx) * ny; }
  CellRange Cells() const { return {0, 0, nx - 1, ny - 1}; }
  Eigen::Vector2d CellMin(int ix, int iy) const { return {x0 + ix * cell, y0 + iy * cell}; }
};

// m: every cell box is grown by this much when segments are listed, so a segment passing
// within rounding distance of a cell (or through a corner a ray steps around) is listed.
inline constexpr double kCellMargin = 1e-6;

// The margin the cell test uses for s in frame f: kCellMargin, plus 1e-12 of the largest
// coordinate involved so that rounding stays inside it far from the origin.
inline double CellMargin(const GridFrame& f, const Segment& s) {
  const double big = std::max({std::abs(f.x0), std::abs(f.y0), std::abs(s.a.x()), std::abs(s.a.y()),
                               std::abs(s.b.x()), std::abs(s.b.y())});
  return kCellMargin + 1e-12 * big;
}

// Does the segment a + t d, t in [0, 1], meet the box [lo, hi]? (Liang-Barsky clip.)
inline bool SegmentMeetsBox(const Eigen::Vector2d& a, const Eigen::Vector2d& d, const Eigen::Vector2d& lo,
                            const Eigen::Vector2d& hi) {
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - lo.x(), hi.x() - a.x(), a.y() - lo.y(), hi.y() - a.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
    } else {
      const double r = q[k] / p[k];
      if (p[k] < 0.0)
        t0 = std::max(t0, r);
      else
        t1 = std::min(t1, r);
      if (t0 > t1) return false;
    }
  }
  return true;
}

// The cell test: does s meet cell (ix, iy) of f grown by `margin` on every side?
inline bool SegmentTouchesCell(const GridFrame& f, int ix, int iy, const Segment& s, double margin) {
  const Eigen::Vector2d lo(f.x0 + ix * f.cell - margin, f.y0 + iy * f.cell - margin);
  const Eigen::Vector2d hi(f.x0 + (ix + 1.0) * f.cell + margin, f.y0 + (iy + 1.0) * f.cell + margin);
  return SegmentMeetsBox(s.a, s.b - s.a, lo, hi);
}
inline bool SegmentTouchesCell(const GridFrame& f, int ix, int iy, const Segment& s) {
  return SegmentTouchesCell(f, ix, iy, s, CellMargin(f, s));
}

inline constexpr int64_t kNoCellLimit = std::numeric_limits<int64_t>::max();

// Calls fn(ix, iy) once for every cell of `window` that s touches (SegmentTouchesCell):
// exactly the cells a test of every cell box would give, found by walking along the major
// axis of s one column of cells at a time and testing the few cells of each column that the
// segment's span there (widened by twice the margin) covers. At most max_cells calls: returns
// false when s touches more, or when it has a non-finite coordinate (then nothing is called).
template <typename Fn>
bool ForEachCellTouched(const GridFrame& f, const CellRange& window, const Segment& s, int64_t max_cells,
                        Fn&& fn) {
  if (!s.a.allFinite() || !s.b.allFinite()) return false;
  if (window.empty()) return true;
  const double margin = CellMargin(f, s);
  const double slack = 2.0 * margin;  // candidates reach further than the test: rounding loses none
  const Eigen::Vector2d d = s.b - s.a;
  const int u = std::abs(d.y()) > std::abs(d.x()) ? 1 : 0, v = 1 - u;  // major, minor axis
  const double u0 = u == 0 ? f.x0 : f.y0, v0 = u == 0 ? f.y0 : f.x0;
  const int u_lo = u == 0 ? window.x_lo : window.y_lo, u_hi = u == 0 ? window.x_hi : window.y_hi;
  const int v_lo = u == 0 ? window.y_lo : window.x_lo, v_hi = u == 0 ? window.y_hi : window.x_hi;
  const double ulo = std::min(s.a[u], s.b[u]), uhi = std::max(s.a[u], s.b[u]);
  const int c0 = ClampedFloor((ulo - slack - u0) / f.cell, u_lo, u_hi);
  const int c1 = ClampedFloor((uhi + slack - u0) / f.cell, u_lo, u_hi);
  int64_t count = 0;
  for (int64_t col = c0; col <= c1; ++col) {
    // The part of s over this column (grown by the slack), and its span on the minor axis.
    const double s0 = std::clamp(u0 + static_cast<double>(col) * f.cell - slack, ulo, uhi);
    const double s1 = std::clamp(u0 + static_cast<double>(col + 1) * f.cell + slack, ulo, uhi);
    double w0 = s.a[v], w1 = s.b[v];
    if (d[u] != 0.0) {
      w0 = s.a[v] + (s0 - s.a[u]) / d[u] * d[v];
      w1 = s.a[v] + (s1 - s.a[u]) / d[u] * d[v];
    }
    const int r0 = ClampedFloor((std::min(w0, w1) - slack - v0) / f.cell, v_lo, v_hi);
    const int r1 = ClampedFloor((std::max(w0, w1) + slack - v0) / f.cell, v_lo, v_hi);
    for (int64_t row = r0; row <= r1; ++row) {
      const int ix = static_cast<int>(u == 0 ? col : row), iy = static_cast<int>(u == 0 ? row : col);
      if (!SegmentTouchesCell(f, ix, iy, s, margin)) continue;
      if (count == max_cells) return false;
      ++count;
      fn(ix, iy);
    }
  }
  return true;
}

// Least distance from any point of the axis-aligned box [lo, hi] to segment s (0 if they meet).
double BoxSegmentMinDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s);
// Greatest distance from any point of the box to s: the distance to a convex set is convex,
// so it is attained at a corner.
double BoxSegmentMaxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s);

// ---------------------------------------------------------------------------------------
// Static storage: built once, dense cells

class StaticSegmentIndex {
 public:
  // Most cells the grid may have: a larger extent gets coarser cells.
  static constexpr double kMaxCells = 4e6;
  // m: a segment with a coordinate beyond this is not listed by cell (every query tests it).
  static constexpr double kMaxCoordinate = 1e12;
  // What the segments' lengths may cost, whatever the map (issue 16: the fuzz targets met a
  // map of one wall 8e10 m long beside short ones: in a grid of 3 x 1.9e6 cells the wall
  // alone touched 1.9e6 cells, 40 s in the fuzz build). A segment touches at most
  // 2 (|dx| + |dy|) / cell + 4 cells (the cells of each column it crosses, grown by the
  // margin); the cell is chosen so that the first term, summed over the listed segments, is at
  // most the larger of kMaxLengthCells and kLengthCellsPerSegment per segment. So entries()
  // <= max(kMaxLengthCells, kLengthCellsPerSegment n) + 4 n for n listed segments: linear in
  // the input. A real map (segments of about the median length, cells of twice it: ~1.3 per
  // segment) never reaches it, so its cells are what they were.
  static constexpr double kMaxLengthCells = 131072.0;
  static constexpr double kLengthCellsPerSegment = 8.0;

  // cell_size in m; 0 picks one from the segments (twice the median segment length, at
  // least 0.5 m). Either way the grid has at most ~kMaxCells cells. It covers the box of
  // the listed segments with half a cell around it.
  explicit StaticSegmentIndex(std::vector<Segment> segments, double cell_size = 0.0);

  // Nearest hit of the ray from origin at bearing (rad, world frame) within max_range;
  // identical to CastRay(origin, bearing, segments(), max_range): same range bit for bit,
  // same index (nearest; equal ranges: the lowest index).
  std::optional<RayHit> CastRay(const Eigen::Vector2d& origin, double bearing, double max_range) const;
  // Same with an explicit direction (dir = (cos b, sin b) gives CastRay's answer).
  std::optional<RayHit> CastRayDir(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                   double max_range) const;

  // Calls fn(index) for every segment listed in a cell that the box [p - radius, p + radius]
  // overlaps, and the unlisted ones: a superset of the segments within `radius` of p. May
  // repeat an index; allocates nothing.
  template <typename Fn>
  void ForEachNear(const Eigen::Vector2d& p, double radius, Fn&& fn) const {
    ForEachNearBox(p, p, radius, std::forward<Fn>(fn));
  }
  // The same for the box [lo - radius, hi + radius]: a superset of the segments within
  // `radius` of any point of [lo, hi] (a footprint's box in the world frame asks for fewer
  // cells than the circle round it).
  template <typename Fn>
  void ForEachNearBox(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double radius, Fn&& fn) const {
    const CellRange r = CellsNear(lo, hi, radius);
    for (int iy = r.y_lo; iy <= r.y_hi; ++iy)
      for (int ix = r.x_lo; ix <= r.x_hi; ++ix)
        for (const uint32_t i : CellSegments(ix, iy)) fn(static_cast<int>(i));
    for (const uint32_t i : unlisted_) fn(static_cast<int>(i));
  }
  // The candidates near any point of the box [lo, hi], sorted, without duplicates.
  std::vector<int> Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double radius) const;
  std::vector<int> QueryPoint(const Eigen::Vector2d& p, double radius) const { return Query(p, p, radius); }

  // The segments listed in cell (ix, iy), in increasing index order (frame().Contains(ix, iy)).
  std::span<const uint32_t> CellSegments(int ix, int iy) const {
    const size_t c = static_cast<size_t>(frame_.Index(ix, iy));
    return {items_.data() + cell_start_[c], items_.data() + cell_start_[c + 1]};
  }
  // Segments in no cell (non-finite or beyond kMaxCoordinate): every query returns them.
  const std::vector<uint32_t>& unlisted() const { return unlisted_; }

  const std::vector<Segment>& segments() const { return segments_; }
  const GridFrame& frame() const { return frame_; }
  double cell_size() const { return frame_.cell; }
  int cols() const { return frame_.nx; }
  int rows() const { return frame_.ny; }
  // Total number of (cell, segment) entries, for tuning.
  size_t entries() const { return items_.size(); }

 private:
  // The cells of the grid that the box [lo - radius, hi + radius] overlaps.
  CellRange CellsNear(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double radius) const {
    return {std::max(0, frame_.CellX(lo.x() - radius)), std::max(0, frame_.CellY(lo.y() - radius)),
            std::min(frame_.nx - 1, frame_.CellX(hi.x() + radius)),
            std::min(frame_.ny - 1, frame_.CellY(hi.y() + radius))};
  }
  std::vector<Segment> segments_;
  GridFrame frame_;                   // nx = ny = 0 when no segment is listed
  std::vector<uint32_t> cell_start_;  // CSR: items_[cell_start_[c] .. cell_start_[c + 1])
  std::vector<uint32_t> items_;
  std::vector<uint32_t> unlisted_;    // increasing
};

// ---------------------------------------------------------------------------------------
// Incremental storage: groups inserted and removed, sparse cells

// Segment `index` of group `group` (the mapper: segment of a contour).
struct SegmentId {
  int group = -1;
  int index = -1;
  bool operator==(const SegmentId&) const = default;
  auto operator<=>(const SegmentId&) const = default;
};

// What one segment may cost is capped, whatever its geometry (issue 11, item 7: a 20 km
// diagonal segment in a forged map spans 10^8 cells of its bounding box and took 6 GB):
//   * a segment whose bounding box spans at most kMaxBoxCells cells is listed in each of
//     them (every segment the mapper makes: 0.5 m long, 1 to 4 cells of 2 m). This keeps the
//     contour mapper's maps bit for bit what they were: it breaks exact ties (a contour
//     vertex lies on two segments) by the order in which its queries meet candidates, and
//     listing these only in the cells they touch changes that order;
//   * a longer one is listed in the cells it touches (ForEachCellTouched), at most
//     kMaxCellsPerSegment of them (a straight wall of several km in 2 m cells);
//   * anything longer, or with a coordinate beyond the cell coordinate range, is kept in a
//     short list that every query returns as a candidate.
class IncrementalSegmentIndex {
 public:
  // Cells of a segment's bounding box up to which it is listed in all of them.
  static constexpr int64_t kMaxBoxCells = 256;
  // Cells a longer segment may be listed in; one touching more goes to the list.
  static constexpr int64_t kMaxCellsPerSegment = 4096;

  explicit IncrementalSegmentIndex(double cell_size = 2.0);

  double cell_size() const { return frame_.cell; }

  // (Re-)indexes a group: whatever was indexed under `group` is replaced by `segments`
  // (segment k gets SegmentId{group, k}).
  void Insert(int group, const std::vector<Segment>& segments);
  void Remove(int group);
  void Clear();

  // Every segment listed in a cell within `radius` of the box [lo, hi], and the unindexed
  // ones (a superset of the segments within `radius` of any point in it), sorted and
  // without duplicates.
  std::vector<SegmentId> Query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double radius) const;
  std::vector<SegmentId> QueryPoint(const Eigen::Vector2d& p, double radius) const {
    return Query(p, p, radius);
  }

  // Calls fn(id) for candidates near p without allocating (may repeat a segment).
  template <typename Fn>
  void ForEachNear(const Eigen::Vector2d& p, double radius, Fn&& fn) const {
    const int x0 = Cell(p.x() - radius), x1 = Cell(p.x() + radius);
    const int y0 = Cell(p.y() - radius), y1 = Cell(p.y() + radius);
    for (int ix = x0; ix <= x1; ++ix)
      for (int iy = y0; iy <= y1; ++iy) {
        const auto it = cells_.find(Key(ix, iy));
        if (it == cells_.end()) continue;
        for (const SegmentId& r : it->second) fn(r);
      }
    for (const SegmentId& r : unindexed_) fn(r);
  }

  // Entries over all cells plus the segments every query returns.
  size_t NumEntries() const;
  // Segments too long (or too far out) to be indexed by cell: every query returns them.
  size_t NumUnindexed() const { return unindexed_.size(); }

 private:
  // Cell coordinates stay within ±kMaxCellCoord, so Key() never overflows and a query
  // beyond the range clamps to its edge (where no indexed segment lies).
  static constexpr int kMaxCellCoord = 1 << 30;
  int Cell(double v) const { return ClampedFloor(v / frame_.cell, -kMaxCellCoord, kMaxCellCoord); }
  static int64_t Key(int ix, int iy) {
    return (static_cast<int64_t>(ix) << 32) ^ static_cast<int64_t>(static_cast<uint32_t>(iy));
  }

  GridFrame frame_;  // origin (0, 0); cells within ±kMaxCellCoord
  std::unordered_map<int64_t, std::vector<SegmentId>> cells_;
  std::unordered_map<int, std::vector<int64_t>> cells_of_group_;
  std::vector<SegmentId> unindexed_;  // sorted
};

}  // namespace minenav
