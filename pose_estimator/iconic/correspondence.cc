#include "pose_estimator/iconic/correspondence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/config.h"

#include "pose_estimator/iconic/brute_force_correspondence.h"
#include "pose_estimator/iconic/grid_search_correspondence.h"
#include "pose_estimator/iconic/lookup_table_correspondence.h"

namespace minenav {

const char* ToString(CorrespondenceMethod method) {
  switch (method) {
    case CorrespondenceMethod::kBruteForce: return "brute";
    case CorrespondenceMethod::kGridSearch: return "grid";
    case CorrespondenceMethod::kLookupTable: return "lookup";
  }
  return "?";
}

bool ParseCorrespondenceMethod(const std::string& text, CorrespondenceMethod* out) {
  if (text == "brute") *out = CorrespondenceMethod::kBruteForce;
  else if (text == "grid") *out = CorrespondenceMethod::kGridSearch;
  else if (text == "lookup") *out = CorrespondenceMethod::kLookupTable;
  else return false;
  return true;
}

double ChooseCellSize(const std::vector<Segment>& segments) {
  if (segments.empty()) return 0.5;
  std::vector<double> lengths;
  lengths.reserve(segments.size());
  for (const Segment& s : segments) lengths.push_back(s.length());
  auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return std::clamp(0.5 * *mid, 0.03, 1.0);
}

double CellSizeWithinBudget(const std::vector<Segment>& segments, double cell, double margin) {
  if (segments.empty()) return cell;
  Eigen::Vector2d lo = segments.front().a, hi = lo;
  for (const Segment& s : segments) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const Eigen::Vector2d extent = (hi - lo).array() + 2.0 * margin;
  // Cells along each side (with the frame's one-cell border), and the cell that fits the budget.
  const double cells = (extent.x() / cell + 3.0) * (extent.y() / cell + 3.0);
  if (cells > kMaxGridCells)
    cell = std::max(cell, std::sqrt(extent.x() * extent.y() / kMaxGridCells) * 1.01 + 3.0 * cell);
  // The band shrinks with the cell, to 3 cells per segment once the cell passes the margin
  // and the walls' length: the loop ends.
  const double band_budget = std::max(kMaxBandCells, 9.0 * static_cast<double>(segments.size()));
  while (BandCells(segments, cell, margin) > band_budget) cell *= 1.05;
  return cell;
}

double BandCells(const std::vector<Segment>& segments, double cell, double margin) {
  const double across = 2.0 * std::ceil(std::max(0.0, margin) / cell) + 1.0;
  double along = 0.0;
  for (const Segment& s : segments) along += std::ceil(s.length() / cell) + 1.0;
  return along * across;
}

std::unique_ptr<CorrespondenceSearch> MakeCorrespondenceSearch(std::vector<Segment> segments,
                                                               const CorrespondenceOptions& options) {
  // A map a few hundred metres across fits the chosen cell; a far larger one (or one
  // hostile segment kilometres long) gets coarser cells instead of gigabytes of grid.
  const double cell = CellSizeWithinBudget(
      segments, options.cell_size > 0.0 ? options.cell_size : ChooseCellSize(segments), options.max_distance);
  switch (options.method) {
    case CorrespondenceMethod::kBruteForce:
      return std::make_unique<BruteForceCorrespondence>(std::move(segments));
    case CorrespondenceMethod::kGridSearch:
      return std::make_unique<GridSearchCorrespondence>(std::move(segments), cell);
    case CorrespondenceMethod::kLookupTable:
      return std::make_unique<LookupTableCorrespondence>(std::move(segments), cell, options.max_distance);
  }
  return nullptr;
}

void FindCorrespondences(const CorrespondenceSearch& search, const std::vector<Eigen::Vector2d>& points,
                         double max_distance, std::vector<SegmentMatch>* out) {
  out->resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) (*out)[i] = search.Nearest(points[i], max_distance);
}

std::vector<uint8_t> ComputeOpenEnds(const std::vector<Segment>& segments) {
  // Count how many segment ends sit on each exact point; an end shared by no other is open.
  std::vector<std::pair<std::pair<double, double>, int>> ends;  // (point, 2 * segment + side)
  ends.reserve(2 * segments.size());
  for (size_t i = 0; i < segments.size(); ++i) {
    ends.push_back({{segments[i].a.x(), segments[i].a.y()}, static_cast<int>(2 * i)});
    ends.push_back({{segments[i].b.x(), segments[i].b.y()}, static_cast<int>(2 * i + 1)});
  }
  std::sort(ends.begin(), ends.end());
  std::vector<uint8_t> flags(segments.size(), 0);
  for (size_t k = 0; k < ends.size();) {
    size_t j = k;
    while (j < ends.size() && ends[j].first == ends[k].first) ++j;
    if (j - k == 1) {
      const int code = ends[k].second;
      flags[static_cast<size_t>(code / 2)] |= static_cast<uint8_t>(code % 2 ? 2 : 1);
    }
    k = j;
  }
  return flags;
}

std::vector<PreparedSegment> PrepareSegments(const std::vector<Segment>& segments) {
  std::vector<PreparedSegment> out;
  out.reserve(segments.size());
  for (const Segment& s : segments) out.emplace_back(s);
  return out;
}

SegmentMatch BruteForceCorrespondence::Nearest(const Eigen::Vector2d& p, double max_distance) const {
  double best_d2 = std::numeric_limits<double>::infinity();
  int best = -1;
  // Strict < keeps the lowest index among equally near segments.
  for (size_t i = 0; i < prepared_.size(); ++i) {
    const double d2 = prepared_[i].SquaredDistance(p);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  if (best < 0 || best_d2 > max_distance * max_distance) return SegmentMatch{};
  return MakeMatch(p, prepared_[static_cast<size_t>(best)], best, best_d2);
}

void DeclareOptions(OptionScope scope, CorrespondenceOptions& o) {
  scope.AddEnum("method", &o.method,
                "how a point finds its nearest segment: brute (Cox, every segment), grid (Gonzalez, the cells "
                "within the threshold), lookup (the thesis's grown table, one cell per point: the fastest, 3.1.1)",
                {CorrespondenceMethod::kBruteForce, CorrespondenceMethod::kGridSearch,
                 CorrespondenceMethod::kLookupTable});
  scope.AddDouble("cell_size", &o.cell_size, "m",
                  "grid cell of the grid search and the lookup table over a surveyed or fit map; 0 = automatic: "
                  "half the median segment length in [0.03, 1] m, which keeps the cell lists short",
                  0.0, 10.0);
  scope.AddDouble("max_distance", &o.max_distance, "m",
                  "how far from the map the lookup table is grown (points farther never match); raised to "
                  "match.initial_threshold when smaller, so 3 m covers the default",
                  0.01, 1000.0);
}

}  // namespace minenav
