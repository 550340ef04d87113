#include "evaluation/map_evaluation.h"

#include <algorithm>
#include <cmath>

#include "common/segment_index.h"

namespace minenav::mapper {

MapDeviation ContourDeviation(const ContourMap& map, const std::vector<Segment>& truth, double step) {
  // Index the true walls in a grid of their own.
  const StaticSegmentIndex grid(truth, 2.0);
  auto nearest = [&](const Eigen::Vector2d& p) {
    double best = 1e300;
    for (double r = 1.0; r <= 64.0 && best > r; r *= 2.0)
      grid.ForEachNear(p, r, [&](int k) {
        best = std::min(best, PointToSegmentDistance(p, truth[static_cast<size_t>(k)]));
      });
    if (best > 64.0)
      for (const Segment& s : truth) best = std::min(best, PointToSegmentDistance(p, s));
    return best;
  };
  MapDeviation out;
  double sum = 0.0;
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k) {
      const Segment s = c.GetSegment(k);
      const int n = std::max(1, static_cast<int>(std::ceil(s.length() / step)));
      auto sample = [&](const Eigen::Vector2d& p) {
        const double d = nearest(p);
        sum += d;
        if (d > out.max) {
          out.max = d;
          out.worst_point = p;
          out.worst_contour = id;
        }
        ++out.samples;
      };
      for (int i = 0; i < n; ++i) sample(s.a + (static_cast<double>(i) / n) * (s.b - s.a));
      if (!c.closed && k == c.NumSegments() - 1) sample(s.b);
    }
  out.mean = out.samples > 0 ? sum / out.samples : 0.0;
  return out;
}

double Coverage(const std::vector<Eigen::Vector2d>& points, const ContourMap& map, double distance) {
  if (points.empty()) return 0.0;
  int covered = 0;
  for (const Eigen::Vector2d& p : points) {
    bool hit = false;
    map.ForEachSegmentNear(p, distance, [&](const SegmentRef& ref) {
      if (!hit && PointToSegmentDistance(p, map.Get(ref.contour).GetSegment(ref.segment)) <= distance) hit = true;
    });
    covered += hit ? 1 : 0;
  }
  return static_cast<double>(covered) / static_cast<double>(points.size());
}

}  // namespace minenav::mapper
