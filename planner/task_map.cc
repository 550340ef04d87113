#include "planner/task_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace minenav {

std::vector<Segment> TaskMap::Boundary() const {
  std::vector<Segment> out = walls;
  out.insert(out.end(), frontiers.begin(), frontiers.end());
  return out;
}

namespace {

// m between a segment and a polygon (0 when they cross or the segment is inside).
double SegmentPolygonDistance(const Segment& s, const std::vector<Eigen::Vector2d>& polygon) {
  if (PolygonContains(polygon, s.a) || PolygonContains(polygon, s.b)) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Segment edge(polygon[k], polygon[(k + 1) % polygon.size()]);
    if (SegmentIntersection(s, edge)) return 0.0;
    d = std::min(
        {d, PointToSegmentDistance(s.a, edge), PointToSegmentDistance(s.b, edge), PointToSegmentDistance(edge.a, s)});
  }
  return d;
}

}  // namespace

TaskMap WithoutFrontiersAt(const TaskMap& map, const Footprint& footprint, const Pose2& pose, double margin,
                           int* dropped) {
  std::vector<Eigen::Vector2d> polygon;
  for (const Eigen::Vector2d& v : footprint.vertices) polygon.push_back(pose * v);
  TaskMap out = map;
  out.frontiers.clear();
  int n = 0;
  for (const Segment& f : map.frontiers) {
    if (SegmentPolygonDistance(f, polygon) < margin)
      ++n;
    else
      out.frontiers.push_back(f);
  }
  if (dropped != nullptr) *dropped = n;
  return out;
}

TaskMap TaskMapFromContours(const std::vector<mapper::Contour>& contours, const FreeSpaceOptions& options) {
  ContourFreeSpace space = MakeContourFreeSpace(contours, options);
  TaskMap map;
  map.walls = std::move(space.walls);
  map.frontiers = std::move(space.frontiers);
  map.oriented = true;
  return map;
}

TaskMap TaskMapFromSegments(std::vector<Segment> segments) {
  TaskMap map;
  map.walls = std::move(segments);
  return map;
}

}  // namespace minenav
