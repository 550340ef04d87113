#pragma once
// The map the task planner works on (TaskMap): the walls that block and, on a contour map,
// the frontiers that close the known free space (planner/contour_free_space.h).

#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "mapper/contour.h"
#include "planner/contour_free_space.h"
#include "planner/footprint.h"

namespace minenav {

// The map a task is planned on. A line map has walls only; a contour map also has the
// frontiers that close its open ends (the boundary of the space the ladar has seen).
struct TaskMap {
  std::vector<Segment> walls;
  std::vector<Segment> frontiers;
  // true for a contour map: every wall has the free space it was seen from on its left, so
  // the known free space can be asked (KnownFreeSpace) and faces are seen from the right side.
  bool oriented = false;

  // What the path planner plans against: walls and frontiers.
  std::vector<Segment> Boundary() const;
  ContourFreeSpace AsFreeSpace() const { return {walls, frontiers, 0, 0}; }
};

// The map without the frontiers that come within `margin` of the footprint at `pose`
// (FrontiersAwayFrom: the vehicle stands where the ladar has looked from). `dropped` (may be
// null) counts them.
TaskMap WithoutFrontiersAt(const TaskMap& map, const Footprint& footprint, const Pose2& pose, double margin,
                           int* dropped = nullptr);

// The walls and frontiers of a contour map (MakeContourFreeSpace).
TaskMap TaskMapFromContours(const std::vector<mapper::Contour>& contours, const FreeSpaceOptions& options = {});
// A line map (LINE_MAP, a surveyed map): walls only, no known-free-space test.
TaskMap TaskMapFromSegments(std::vector<Segment> segments);

}  // namespace minenav
