#pragma once
// Distances from one cell to every cell of an occupancy grid over the grid mode's moves
// (8-connected, sqrt(2) diagonals, no corner cutting): the 2-D part of the SE(2) search's
// obstacle heuristic.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
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
  // Cells of the tiles allocated so far (tests: a search near the source touches its tiles only).
  size_t cells_allocated() const { return allocated_ * kTileCells; }

 private:
  // Distances and settled flags live in tiles of kTile x kTile cells, allocated when the
  // search first reaches them: a request settles the cells near its goal, so a new goal costs
  // what is searched, not the map's size (a whole-field array filled per goal, and its page
  // faults, made a 6 m slab cut's first request 19.4 ms against 14.4 ms for its repeat;
  // planner/README.md "Fifth speed round").
  static constexpr int kTileBits = 5;
  static constexpr int kTile = 1 << kTileBits;
  static constexpr size_t kTileCells = static_cast<size_t>(kTile) * kTile;
  struct Tile {
    std::array<double, kTileCells> d;
    std::array<uint8_t, kTileCells> done;
  };
  struct CellRef {
    size_t tile;
    size_t k;  // within the tile
  };
  CellRef Ref(int x, int y) const {
    return {static_cast<size_t>(y >> kTileBits) * tiles_x_ + static_cast<size_t>(x >> kTileBits),
            static_cast<size_t>(y & (kTile - 1)) * kTile + static_cast<size_t>(x & (kTile - 1))};
  }
  Tile& TileAt(size_t tile);  // allocated (distances infinite, nothing settled) on first use

  using Entry = std::pair<double, size_t>;  // (distance, grid.Index of the cell)
  const OccupancyGrid& grid_;
  GridCell source_;
  size_t tiles_x_ = 0;
  std::vector<std::unique_ptr<Tile>> tiles_;
  size_t allocated_ = 0;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;
  int64_t settled_ = 0;
};

// Costs to go to a source state over (cell, heading) states, heading k = 0..7 the direction
// k * 45 degrees: a state moves to the next cell ahead (1 or sqrt(2) cells, no corner
// cutting) or, at `reverse_factor` times that, to the cell behind, and turns by 45 degrees in
// place at `turn_cost` cells where `roomy` (a cell per grid cell, may be null = everywhere)
// is set, at `narrow_turn_factor` times that elsewhere. Distance(x, y, k) is the cost from
// (x, y, k) to the source state, settled on demand like LazyGridDistances. With turn_cost > 0
// paths with fewer turns, turning where there is room, are cheaper: the SE(2) search's guide
// (not a lower bound on the vehicle's cost, whose arcs turn at no extra cost).
// `grid` and `roomy` must outlive this.
class LazyHeadingGridDistances {
 public:
  LazyHeadingGridDistances(const OccupancyGrid& grid, GridCell source, int source_heading, double turn_cost,
                           double reverse_factor, const std::vector<uint8_t>* roomy, double narrow_turn_factor);

  // Cost from (x, y, heading) to the source state; infinity where blocked, outside or
  // unreachable.
  double Distance(int x, int y, int heading);
  GridCell source() const { return source_; }
  int source_heading() const { return source_heading_; }
  double turn_cost() const { return turn_cost_; }
  double reverse_factor() const { return reverse_factor_; }
  double TurnCostAt(int x, int y) const;
  int64_t settled() const { return settled_; }
  // The heading (0..7) nearest to theta (radians).
  static int HeadingOf(double theta);
  static constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  static constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

 private:
  using Entry = std::pair<double, size_t>;
  const OccupancyGrid& grid_;
  GridCell source_;
  int source_heading_;
  double turn_cost_, reverse_factor_;
  const std::vector<uint8_t>* roomy_;
  double narrow_turn_factor_;
  std::vector<double> d_;  // [cell * 8 + heading]
  std::vector<uint8_t> done_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;
  int64_t settled_ = 0;
};

}  // namespace minenav
