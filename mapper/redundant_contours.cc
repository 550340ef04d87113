#include "mapper/redundant_contours.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace minenav::mapper {

namespace {

// Unit left normal at vertex v (mean of its segments' normals).
Eigen::Vector2d VertexNormal(const Contour& c, int v) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const int n = c.NumPoints();
  auto add = [&](int a, int b) {
    const Eigen::Vector2d d = c.points[static_cast<size_t>(b)] - c.points[static_cast<size_t>(a)];
    if (d.norm() > 0.0) sum += Eigen::Vector2d(-d.y(), d.x()).normalized();
  };
  if (v > 0 || c.closed) add((v + n - 1) % n, v);
  if (v < n - 1 || c.closed) add(v, (v + 1) % n);
  return sum.norm() > 0.0 ? Eigen::Vector2d(sum.normalized()) : sum;
}

}  // namespace

void DeclareOptions(OptionScope s, RedundantContourOptions& o) {
  s.AddDouble("distance", &o.distance, "m",
              "a vertex this close to another contour's segment facing the same way may be a copy; 0.4 m: "
              "more than the drift to close, less than the gap between distinct walls",
              0.0, 100.0);
  s.AddDouble("min_alignment", &o.min_alignment, "1",
              "cosine of the largest angle between the two contours' normals (same facing); 0.8 (37 "
              "degrees)",
              -1.0, 1.0);
  s.AddDouble("min_run_length", &o.min_run_length, "m",
              "only runs of redundant vertices this long along the contour are removed, so a post or crib beside a "
              "wall is not taken for a copy of it; 1 m",
              0.0, 1000.0);
}

int RemoveRedundantContours(ContourMap& map, const RedundantContourOptions& o) {
  int removed = 0;
  std::vector<int> ids = map.Ids();
  std::sort(ids.rbegin(), ids.rend());  // newest first
  for (const int id : ids) {
    const Contour* c = map.Find(id);
    if (!c) continue;
    const int n = c->NumPoints();
    std::vector<bool> redundant(static_cast<size_t>(n), false);
    for (int v = 0; v < n; ++v) {
      const Eigen::Vector2d& p = c->points[static_cast<size_t>(v)];
      const Eigen::Vector2d normal = VertexNormal(*c, v);
      bool hit = false;
      map.ForEachSegmentNear(p, o.distance, [&](const SegmentRef& ref) {
        if (hit || ref.contour >= id) return;  // only older contours
        const Segment s = map.Get(ref.contour).GetSegment(ref.segment);
        const Eigen::Vector2d d = s.b - s.a;
        if (d.norm() <= 0.0) return;
        const Eigen::Vector2d sn = Eigen::Vector2d(-d.y(), d.x()).normalized();
        if (sn.dot(normal) < o.min_alignment) return;
        const double t = (p - s.a).dot(d) / d.squaredNorm();  // within the perpendicular band?
        if (t < 0.0 || t > 1.0) return;
        if (std::abs(sn.dot(p - s.a)) <= o.distance) hit = true;
      });
      redundant[static_cast<size_t>(v)] = hit;
    }
    // Keep only runs of redundant vertices that are long enough.
    for (int v = 0; v < n;) {
      if (!redundant[static_cast<size_t>(v)]) {
        ++v;
        continue;
      }
      int e = v;
      while (e + 1 < n && redundant[static_cast<size_t>(e + 1)]) ++e;
      double length = 0.0;
      for (int k = v; k < e; ++k)
        length += (c->points[static_cast<size_t>(k + 1)] - c->points[static_cast<size_t>(k)]).norm();
      if (length < o.min_run_length)
        for (int k = v; k <= e; ++k) redundant[static_cast<size_t>(k)] = false;
      v = e + 1;
    }
    int count = 0;
    for (const bool r : redundant) count += r ? 1 : 0;
    if (count == 0) continue;
    removed += count;
    // Keep the maximal runs of non-redundant vertices as contours of their own.
    std::vector<Eigen::Vector2d> pts = c->points;
    const bool closed = c->closed;
    map.Remove(id);
    if (count == n) continue;
    int start = 0;
    if (closed) {  // start the walk at a redundant vertex so no run wraps around
      while (!redundant[static_cast<size_t>(start)]) ++start;
      std::rotate(pts.begin(), pts.begin() + start, pts.end());
      std::rotate(redundant.begin(), redundant.begin() + start, redundant.end());
    }
    std::vector<Eigen::Vector2d> run;
    for (int v = 0; v <= n; ++v) {
      if (v < n && !redundant[static_cast<size_t>(v)]) {
        run.push_back(pts[static_cast<size_t>(v)]);
        continue;
      }
      if (run.size() >= 2) map.Create(run);
      run.clear();
    }
  }
  return removed;
}

}  // namespace minenav::mapper
