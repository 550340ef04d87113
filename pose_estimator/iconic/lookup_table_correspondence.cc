#include "pose_estimator/iconic/lookup_table_correspondence.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace minenav {

namespace {
// Slack on the pruning test so that rounding never drops a segment that ties.
constexpr double kPruneSlack = 1e-9;

// Fast versions of BoxSegmentMin/MaxDistance (common/segment_index.h) for the build's inner
// loop; the unit test checks them against each other through the brute-force equality.
double BoxMaxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const PreparedSegment& s) {
  const double d2 = std::max(std::max(s.SquaredDistance(lo), s.SquaredDistance(hi)),
                             std::max(s.SquaredDistance({lo.x(), hi.y()}), s.SquaredDistance({hi.x(), lo.y()})));
  return std::sqrt(d2);
}

double PointBoxSquaredDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double dx = std::max(std::max(lo.x() - p.x(), 0.0), p.x() - hi.x());
  const double dy = std::max(std::max(lo.y() - p.y(), 0.0), p.y() - hi.y());
  return dx * dx + dy * dy;
}

double BoxMinDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const PreparedSegment& s) {
  if (SegmentMeetsBox(s.a, s.d, lo, hi)) return 0.0;
  // Disjoint convex sets: the least distance is between a vertex of one and the other.
  double d2 = std::min(PointBoxSquaredDistance(s.a, lo, hi), PointBoxSquaredDistance(s.a + s.d, lo, hi));
  d2 = std::min(d2, std::min(std::min(s.SquaredDistance(lo), s.SquaredDistance(hi)),
                             std::min(s.SquaredDistance({lo.x(), hi.y()}), s.SquaredDistance({hi.x(), lo.y()}))));
  return std::sqrt(d2);
}
}  // namespace

LookupTableCorrespondence::LookupTableCorrespondence(std::vector<Segment> segments, double cell_size,
                                                     double reach)
    : segments_(std::move(segments)),
      prepared_(PrepareSegments(segments_)),
      reach_(reach),
      frame_(GridFrame::Covering(segments_, cell_size, reach)),
      inv_cell_(1.0 / frame_.cell) {
  // A candidate in a cell, with its least distance to the cell cached for pruning.
  struct Entry {
    int32_t id;
    double dmin;
  };
  const size_t num_cells = static_cast<size_t>(frame_.size());
  std::vector<std::vector<Entry>> lists(num_cells);
  std::vector<double> bound(num_cells, std::numeric_limits<double>::infinity());  // U per cell
  std::vector<char> queued(num_cells, 0);
  std::vector<int64_t> stamp(segments_.size(), -1);  // membership test: last cell that listed it
  std::deque<int64_t> queue;
  const Eigen::Vector2d diag(frame_.cell, frame_.cell);
  const double half_diagonal = 0.5 * diag.norm();

  // Draw the map: every cell a segment passes through lists it.
  for (size_t i = 0; i < segments_.size(); ++i) {
    ForEachCellTouched(frame_, frame_.Cells(), segments_[i], kNoCellLimit, [&](int ix, int iy) {
      const int64_t k = frame_.Index(ix, iy);
      const Eigen::Vector2d lo = frame_.CellMin(ix, iy);
      lists[static_cast<size_t>(k)].push_back({static_cast<int32_t>(i), 0.0});
      bound[static_cast<size_t>(k)] = std::min(bound[static_cast<size_t>(k)], BoxMaxDistance(lo, lo + diag, prepared_[i]));
      if (!queued[static_cast<size_t>(k)]) {
        queued[static_cast<size_t>(k)] = 1;
        queue.push_back(k);
      }
    });
  }

  // Grassfire: a cell's lists flow to its 8 neighbours; a neighbour keeps what may be
  // nearest somewhere inside it and is within reach. Repeat until nothing changes.
  std::vector<Entry> added;
  while (!queue.empty()) {
    const int64_t k = queue.front();
    queue.pop_front();
    queued[static_cast<size_t>(k)] = 0;
    const int ix = static_cast<int>(k % frame_.nx);
    const int iy = static_cast<int>(k / frame_.nx);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !frame_.Contains(ix + dx, iy + dy)) continue;
        const int64_t n = frame_.Index(ix + dx, iy + dy);
        const size_t un = static_cast<size_t>(n);
        const Eigen::Vector2d lo = frame_.CellMin(ix + dx, iy + dy);
        const Eigen::Vector2d hi = lo + diag;
        const Eigen::Vector2d centre = lo + 0.5 * diag;
        std::vector<Entry>& target = lists[un];
        for (const Entry& e : target) stamp[static_cast<size_t>(e.id)] = n;
        // Segments of k the neighbour lacks and may need; tighten its bound with them.
        added.clear();
        for (const Entry& e : lists[static_cast<size_t>(k)]) {
          if (stamp[static_cast<size_t>(e.id)] == n) continue;
          const PreparedSegment& ps = prepared_[static_cast<size_t>(e.id)];
          const double dc = std::sqrt(ps.SquaredDistance(centre));
          // Cheap bounds first: dc - h <= dmin and dmax <= dc + h.
          if (dc - half_diagonal > reach_ || dc - half_diagonal > bound[un] + kPruneSlack) continue;
          const double dmin = BoxMinDistance(lo, hi, ps);
          if (dmin > reach_ || dmin > bound[un] + kPruneSlack) continue;
          added.push_back({e.id, dmin});
          stamp[static_cast<size_t>(e.id)] = n;
          bound[un] = std::min(bound[un], BoxMaxDistance(lo, hi, ps));
        }
        if (added.empty()) continue;
        target.insert(target.end(), added.begin(), added.end());
        // Drop what the tighter bound proves is never nearest in this cell.
        const double u = bound[un] + kPruneSlack;
        std::erase_if(target, [u](const Entry& e) { return e.dmin > u; });
        if (!queued[un]) {
          queued[un] = 1;
          queue.push_back(n);
        }
      }
    }
  }

  offsets_.assign(num_cells + 1, 0);
  for (size_t k = 0; k < num_cells; ++k) {
    std::sort(lists[k].begin(), lists[k].end(), [](const Entry& a, const Entry& b) { return a.id < b.id; });
    offsets_[k + 1] = offsets_[k] + static_cast<int32_t>(lists[k].size());
  }
  ids_.reserve(static_cast<size_t>(offsets_.back()));
  for (const auto& l : lists)
    for (const Entry& e : l) ids_.push_back(e.id);
}

SegmentMatch LookupTableCorrespondence::Nearest(const Eigen::Vector2d& p, double max_distance) const {
  // One cell per point (3.1.1); the comparisons also reject NaN coordinates.
  const double fx = (p.x() - frame_.x0) * inv_cell_;
  const double fy = (p.y() - frame_.y0) * inv_cell_;
  if (!(fx >= 0.0 && fy >= 0.0 && fx < frame_.nx && fy < frame_.ny) || !(max_distance >= 0.0))
    return SegmentMatch{};
  const size_t k = static_cast<size_t>(static_cast<int64_t>(fy) * frame_.nx + static_cast<int64_t>(fx));
  double best_d2 = std::numeric_limits<double>::infinity();
  int best = -1;
  // Lists are sorted by id, so strict < keeps the lowest index among ties.
  for (int32_t j = offsets_[k]; j < offsets_[k + 1]; ++j) {
    const int32_t id = ids_[static_cast<size_t>(j)];
    const double d2 = prepared_[static_cast<size_t>(id)].SquaredDistance(p);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = id;
    }
  }
  if (best < 0 || best_d2 > max_distance * max_distance) return SegmentMatch{};
  return MakeMatch(p, prepared_[static_cast<size_t>(best)], best, best_d2);
}

double LookupTableCorrespondence::MeanListLength() const {
  const int64_t grown = GrownCells();
  return grown > 0 ? static_cast<double>(ids_.size()) / static_cast<double>(grown) : 0.0;
}

int LookupTableCorrespondence::MaxListLength() const {
  int worst = 0;
  for (size_t k = 0; k + 1 < offsets_.size(); ++k) worst = std::max(worst, offsets_[k + 1] - offsets_[k]);
  return worst;
}

int64_t LookupTableCorrespondence::GrownCells() const {
  int64_t n = 0;
  for (size_t k = 0; k + 1 < offsets_.size(); ++k) n += offsets_[k + 1] > offsets_[k] ? 1 : 0;
  return n;
}

}  // namespace minenav
