#include "pose_estimator/iconic/segment_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "common/config.h"

namespace minenav {

namespace {
bool Finite(const Segment& s) {
  return std::isfinite(s.a.x()) && std::isfinite(s.a.y()) && std::isfinite(s.b.x()) &&
         std::isfinite(s.b.y());
}

// Endpoints in a canonical order so that a->b and b->a compare equal.
std::tuple<double, double, double, double> Key(const Segment& s) {
  const bool swap = std::tie(s.b.x(), s.b.y()) < std::tie(s.a.x(), s.a.y());
  const Eigen::Vector2d& p = swap ? s.b : s.a;
  const Eigen::Vector2d& q = swap ? s.a : s.b;
  return {p.x(), p.y(), q.x(), q.y()};
}
}  // namespace

SegmentMap PrepareSegmentMap(const std::vector<Segment>& raw, const SegmentMapOptions& options) {
  SegmentMap map;
  std::vector<std::pair<std::tuple<double, double, double, double>, size_t>> keyed;
  keyed.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    const Segment& s = raw[i];
    if (!Finite(s)) {
      ++map.dropped_nonfinite;
    } else if (!(s.length() >= options.min_segment_length)) {
      ++map.dropped_zero_length;
    } else {
      keyed.push_back({Key(s), i});
    }
  }
  // Sort by key so that duplicates are neighbours; keep the first occurrence in input order.
  std::sort(keyed.begin(), keyed.end());
  std::vector<size_t> keep;
  keep.reserve(keyed.size());
  const double tol = options.duplicate_tolerance;
  for (size_t k = 0; k < keyed.size(); ++k) {
    bool duplicate = false;
    // Exact-key neighbours plus a tolerance check against the recent kept ones.
    for (size_t j = k; j-- > 0;) {
      const auto& [a, b, c, d] = keyed[j].first;
      const auto& [e, f, g, h] = keyed[k].first;
      if (e - a > tol) break;
      if (std::abs(b - f) <= tol && std::abs(c - g) <= tol && std::abs(d - h) <= tol) {
        duplicate = true;
        break;
      }
    }
    if (duplicate)
      ++map.dropped_duplicates;
    else
      keep.push_back(keyed[k].second);
  }
  std::sort(keep.begin(), keep.end());
  map.segments.reserve(keep.size());
  for (size_t i : keep) map.segments.push_back(raw[i]);
  if (map.segments.empty()) {
    std::ostringstream why;
    why << "map has no usable segments (" << raw.size() << " given: " << map.dropped_nonfinite
        << " non-finite, " << map.dropped_zero_length << " zero-length, " << map.dropped_duplicates
        << " duplicate)";
    map.problem = why.str();
  }
  return map;
}

void DeclareOptions(OptionScope scope, SegmentMapOptions& o) {
  scope.AddDouble("min_segment_length", &o.min_segment_length, "m",
                  "map segments shorter than this are dropped before matching (1 um: only degenerate ones, whose "
                  "zero length would divide by zero)",
                  0.0, 10.0);
  scope.AddDouble("duplicate_tolerance", &o.duplicate_tolerance, "m",
                  "segments whose endpoints coincide within this (either direction) are one: a doubled wall would "
                  "be two equally near candidates (1 nm: exact copies only)",
                  0.0, 1.0);
}

}  // namespace minenav
