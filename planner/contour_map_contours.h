#pragma once
// A CONTOUR_MAP message's contours as the mapper's type (mapper::Contour), what the
// planners' nodes hand to MakeContourFreeSpace (path_planner_node, task_planner_node).

#include <vector>

#include "common/node/contour_map_conversions.h"
#include "mapper/contour.h"

namespace minenav {

// The contours of `map` (taken: its points are moved), ids and closure kept.
std::vector<mapper::Contour> ContoursOf(ContourMapMessage map);

}  // namespace minenav
