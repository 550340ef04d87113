#pragma once
// The corridor route of a hierarchical plan: the 2-D obstacle-aware route from start to goal
// over (cell, 45-degree heading) states (LazyHeadingGridDistances, turns charged where the
// centre has room: the crossings), read off as the runs of one heading, and the places where
// it turns. Se2Planner plans such a route as straight legs (analytic shots) between local
// SE(2) searches round each turn, from a pose `lead` cells before the turn (heading along the
// entry it leaves) to one `lead` cells after it (heading along the next entry); turns closer
// than 2 * lead to each other are one local search. In the manner of the hierarchical
// planners of Kuwata et al., "Real-time motion planning with applications to autonomous urban
// driving" (IEEE T-CST 2009): a coarse route, then the fine maneuvers along it.

#include <cstddef>
#include <vector>

#include "common/segment_index.h"
#include "planner/grid_astar.h"
#include "planner/grid_dijkstra.h"

namespace minenav {

// The grid the route is planned on: coarser than the clearance field's (a route across a
// section at the field's 0.2 m settles ~2 million (cell, heading) states; at 1 m 25 times
// fewer). A coarse cell is free (roomy) when the fine cell at its centre is.
struct RouteGrid {
  GridFrame frame;
  OccupancyGrid cells;
  std::vector<uint8_t> roomy;
};
RouteGrid CoarseRouteGrid(const GridFrame& fine, const OccupancyGrid& fine_cells, const std::vector<uint8_t>& fine_roomy,
                          double resolution);

// One cell of the route and the heading (0..7, k * 45 degrees) the route moves along there.
struct RouteStep {
  GridCell cell;
  int heading = 0;
};

// The route from (start, start_heading) to the source state of `to_goal` by steepest descent
// of its costs over the moves `cells` allows, one step per cell moved (a turn in place changes
// the heading of the next step). Empty when the start state is unreachable or the descent
// breaks (rounding).
std::vector<RouteStep> DescendRoute(LazyHeadingGridDistances& to_goal, const OccupancyGrid& cells, GridCell start,
                                    int start_heading);

// A stretch of the route where it turns: the step `lead` before its first turn, the step
// `lead` after its last, and the step at which it first turns (indices into the route; the
// route turns in place in the cell of step `first - 1`).
struct RouteTurn {
  size_t before = 0, after = 0, first = 0;
};

// The turns of `route` (where the heading changes), turns closer than 2 * lead steps merged.
// `before` is clamped to 0 and `after` to the last step (there the start or goal serves).
std::vector<RouteTurn> RouteTurns(const std::vector<RouteStep>& route, size_t lead);

}  // namespace minenav
