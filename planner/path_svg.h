#pragma once
// The picture of a planned path (path_planner --svg-out, the task planner's pictures): the
// map, the path (arcs as 0.5 m chords) and the footprint every 2 m along it; with a contour
// map's free space also its frontiers (dashed) and the known free space (filled, sampled every
// 0.5 m by KnownFreeSpace). A scene, so callers can add their own layers before rendering.

#include <string>
#include <vector>

#include "common/geometry.h"
#include "planner/contour_free_space.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "render/svg_render.h"

namespace minenav {

// `map` is what the path was planned on (its bounding box bounds the known-free-space
// sampling); `space` (may be null) the contour map's walls and frontiers.
SvgScene PathScene(const std::vector<Segment>& map, const Footprint& footprint, const PlannedPath& path,
                   const std::string& title, const ContourFreeSpace* space = nullptr,
                   const FreeSpaceOptions& free_space = {});

}  // namespace minenav
