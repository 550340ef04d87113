#include "pose_estimator/correspondence.h"

#include <algorithm>
#include <limits>

#include "pose_estimator/brute_force_correspondence.h"
#include "pose_estimator/grid_search_correspondence.h"
#include "pose_estimator/lookup_table_correspondence.h"

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
  return std::clamp(*mid, 0.1, 1.0);
}

std::unique_ptr<CorrespondenceSearch> MakeCorrespondenceSearch(std::vector<Segment> segments,
                                                               const CorrespondenceOptions& options) {
  const double cell = options.cell_size > 0.0 ? options.cell_size : ChooseCellSize(segments);
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

std::vector<PreparedSegment> PrepareSegments(const std::vector<Segment>& segments) {
  std::vector<PreparedSegment> out;
  out.reserve(segments.size());
  for (const Segment& s : segments) out.emplace_back(s);
  return out;
}

SegmentMatch MakeMatch(const Eigen::Vector2d& p, const std::vector<Segment>& segments, int index) {
  const SegmentProjection proj = ProjectOntoSegment(p, segments[static_cast<size_t>(index)]);
  return {index, proj.distance, proj.region, proj.point};
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
  return MakeMatch(p, segments_, best);
}

}  // namespace minenav
