#include "planner/task_map.h"

#include <utility>

namespace minenav {

std::vector<Segment> TaskMap::Boundary() const {
  std::vector<Segment> out = walls;
  out.insert(out.end(), frontiers.begin(), frontiers.end());
  return out;
}

TaskMap WithoutFrontiersAt(const TaskMap& map, const Footprint& footprint, const Pose2& pose, double margin,
                           int* dropped) {
  TaskMap out = map;
  out.frontiers = FrontiersAwayFrom(map.frontiers, footprint.At(pose), margin, dropped);
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
