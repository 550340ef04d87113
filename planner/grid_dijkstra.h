#pragma once
// Distances from one cell to every cell of an occupancy grid over the grid mode's moves
// (8-connected, sqrt(2) diagonals, no corner cutting): the 2-D part of the SE(2) search's
// obstacle heuristic.

#include <vector>

#include "planner/grid_astar.h"

namespace minenav {

// Cells (infinity where unreachable or blocked), indexed by grid.Index(x, y).
std::vector<double> GridDistancesFrom(const OccupancyGrid& grid, GridCell source);

}  // namespace minenav
