#pragma once
// Grid mode: A* for a point robot on an occupancy grid, 8-connected, straight moves cost 1
// and diagonal moves sqrt(2), no corner cutting (a diagonal move needs both cells beside it
// free), with the octile distance as heuristic (admissible and consistent for these moves,
// so the first time the goal is taken off the open list its length is optimal). These are
// the rules of the Moving AI benchmark (Sturtevant, "Benchmarks for Grid-Based Pathfinding",
// IEEE TCIAIG 4(2), 2012), against whose published optima the search core is tested.

#include <cstdint>
#include <string>
#include <vector>

#include "planner/occupancy_grid.h"
#include "planner/search_limits.h"

namespace minenav {

struct GridCell {
  int x = 0, y = 0;
  bool operator==(const GridCell&) const = default;
};

// The octile distance: the length of the shortest 8-connected path between two cells on an
// empty grid, sqrt(2) min(|dx|, |dy|) + (max - min).
double OctileDistance(int dx, int dy);

// May the robot step from (x, y) by (dx, dy) (each -1, 0 or 1, not both 0)? The target cell
// must be free and, for a diagonal step, both orthogonal neighbours it passes between.
bool GridMoveAllowed(const OccupancyGrid& grid, int x, int y, int dx, int dy);

struct GridSearchResult {
  SearchStatus status = SearchStatus::kNoPath;
  std::string reason;          // one line: why there is no path, or which bound stopped it
  double length = -1.0;        // cells; -1 without a path
  int64_t expansions = 0;      // cells taken off the open list
  int64_t states = 0;          // cells given a cost (the memory the search used)
  std::vector<GridCell> path;  // start .. goal, when found
};

// A* over one grid, its buffers kept between searches (a benchmark runs thousands of
// queries on one map without clearing width * height cells each time).
class GridAStar {
 public:
  explicit GridAStar(const OccupancyGrid& grid);

  // Start or goal outside the grid or blocked: kInvalidRequest. start == goal: length 0.
  GridSearchResult Plan(GridCell start, GridCell goal, const SearchLimits& limits = {});

 private:
  const OccupancyGrid& grid_;
  std::vector<double> g_;          // cost from start, valid where stamp_ == search_
  std::vector<int32_t> parent_;    // cell index, -1 at the start
  std::vector<uint32_t> stamp_;    // search number that last touched the cell
  std::vector<uint32_t> closed_;   // search number that closed the cell
  uint32_t search_ = 0;
};

}  // namespace minenav
