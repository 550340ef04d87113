#include "pose_estimator/feature/feature_map.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/config.h"

namespace minenav {

FeatureMapBuild BuildFeatureMap(const std::vector<Segment>& segments,
                                const FeatureMapOptions& options) {
  FeatureMapBuild out;
  FeatureMap& m = out.map;
  for (const Segment& s : segments) {
    if (!s.a.allFinite() || !s.b.allFinite() || s.length() < options.vertex_merge_distance) {
      ++out.dropped;
      continue;
    }
    m.segments.push_back(s);
  }
  // Sort endpoints by x and merge neighbours within the tolerance: O(N log N) for maps
  // whose vertices are not piled up in one column.
  const int n = static_cast<int>(m.segments.size());
  std::vector<Eigen::Vector2d> ends(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    ends[2 * static_cast<size_t>(i)] = m.segments[static_cast<size_t>(i)].a;
    ends[2 * static_cast<size_t>(i) + 1] = m.segments[static_cast<size_t>(i)].b;
  }
  std::vector<int> order(ends.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return ends[static_cast<size_t>(a)].x() < ends[static_cast<size_t>(b)].x(); });
  std::vector<int> vertex_of(ends.size(), -1);
  const double tol = options.vertex_merge_distance;
  for (size_t k = 0; k < order.size(); ++k) {
    const int e = order[k];
    if (vertex_of[static_cast<size_t>(e)] >= 0) continue;
    const int v = static_cast<int>(m.vertices.size());
    m.vertices.push_back(ends[static_cast<size_t>(e)]);
    vertex_of[static_cast<size_t>(e)] = v;
    for (size_t j = k + 1; j < order.size(); ++j) {
      const int o = order[j];
      if (ends[static_cast<size_t>(o)].x() - ends[static_cast<size_t>(e)].x() > tol) break;
      if (vertex_of[static_cast<size_t>(o)] < 0 &&
          (ends[static_cast<size_t>(o)] - ends[static_cast<size_t>(e)]).norm() <= tol) {
        vertex_of[static_cast<size_t>(o)] = v;
      }
    }
  }
  m.segment_vertices.resize(static_cast<size_t>(n));
  m.vertex_segments.resize(m.vertices.size());
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 2; ++k) {
      const int v = vertex_of[2 * static_cast<size_t>(i) + static_cast<size_t>(k)];
      m.segment_vertices[static_cast<size_t>(i)][static_cast<size_t>(k)] = v;
      auto& list = m.vertex_segments[static_cast<size_t>(v)];
      if (std::find(list.begin(), list.end(), i) == list.end()) list.push_back(i);
    }
  }
  return out;
}

void DeclareOptions(OptionScope scope, FeatureMapOptions& o) {
  scope.AddDouble("vertex_merge_distance", &o.vertex_merge_distance, "m",
                  "map segment endpoints closer than this are one vertex, so two segments sharing an end make a "
                  "corner; shorter segments are dropped (1 cm: survey rounding)",
                  1e-6, 10.0);
}

}  // namespace minenav
