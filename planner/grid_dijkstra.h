#pragma once
// Distances from one cell to every cell of an occupancy grid over the grid mode's moves
// (8-connected, sqrt(2) diagonals, no corner cutting): the 2-D part of the SE(2) search's
// obstacle heuristic.

#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

#include "planner/grid_astar.h"

namespace minenav {

// Cells (infinity where unreachable or blocked), indexed by grid.Index(x, y).
std::vector<double> GridDistancesFrom(const OccupancyGrid& grid, GridCell source);

// The same distances, computed on demand: Distance() runs Dijkstra from the source only until
// the asked cell is settled, and the next call resumes where it stopped. A search near the
// source settles the cells near it; repeated searches to one goal keep the settled cells
// (Nav2 Smac caches its obstacle heuristic the same way). `grid` must outlive this.
class LazyGridDistances {
 public:
  LazyGridDistances(const OccupancyGrid& grid, GridCell source);

  // Cells from the source to (x, y); infinity where blocked, outside or unreachable.
  double Distance(int x, int y);
  GridCell source() const { return source_; }
  int64_t settled() const { return settled_; }

 private:
  using Entry = std::pair<double, size_t>;
  const OccupancyGrid& grid_;
  GridCell source_;
  std::vector<double> d_;
  std::vector<uint8_t> done_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;
  int64_t settled_ = 0;
};

}  // namespace minenav
