#include "planner/grid_dijkstra.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <queue>

namespace minenav {

std::vector<double> GridDistancesFrom(const OccupancyGrid& grid, GridCell source) {
  LazyGridDistances lazy(grid, source);
  std::vector<double> d(grid.blocked.size());
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) d[grid.Index(x, y)] = lazy.Distance(x, y);
  return d;
}

LazyGridDistances::LazyGridDistances(const OccupancyGrid& grid, GridCell source)
    : grid_(grid),
      source_(source),
      tiles_x_(static_cast<size_t>((grid.width + kTile - 1) >> kTileBits)),
      tiles_(tiles_x_ * static_cast<size_t>((grid.height + kTile - 1) >> kTileBits)) {
  if (!grid.Free(source.x, source.y)) return;
  const CellRef r = Ref(source.x, source.y);
  TileAt(r.tile).d[r.k] = 0.0;
  open_.push({0.0, grid.Index(source.x, source.y)});
}

LazyGridDistances::Tile& LazyGridDistances::TileAt(size_t tile) {
  std::unique_ptr<Tile>& t = tiles_[tile];
  if (!t) {
    t.reset(new Tile);  // default-initialised: filled below, once
    t->d.fill(std::numeric_limits<double>::infinity());
    t->done.fill(0);
    ++allocated_;
  }
  return *t;
}

double LazyGridDistances::Distance(int x, int y) {
  if (x < 0 || y < 0 || x >= grid_.width || y >= grid_.height || !grid_.Free(x, y))
    return std::numeric_limits<double>::infinity();
  const CellRef target = Ref(x, y);
  Tile& target_tile = TileAt(target.tile);
  while (!target_tile.done[target.k] && !open_.empty()) {
    const auto [g, c] = open_.top();
    open_.pop();
    const int cx = static_cast<int>(c % static_cast<size_t>(grid_.width));
    const int cy = static_cast<int>(c / static_cast<size_t>(grid_.width));
    const CellRef cr = Ref(cx, cy);
    Tile& ct = *tiles_[cr.tile];  // allocated when the cell was queued
    if (ct.done[cr.k] || g > ct.d[cr.k]) continue;
    ct.done[cr.k] = 1;
    ++settled_;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !GridMoveAllowed(grid_, cx, cy, dx, dy)) continue;
        const CellRef nr = Ref(cx + dx, cy + dy);
        double& nd = TileAt(nr.tile).d[nr.k];
        const double ng = g + (dx != 0 && dy != 0 ? std::numbers::sqrt2 : 1.0);
        if (ng < nd) {
          nd = ng;
          open_.push({ng, grid_.Index(cx + dx, cy + dy)});
        }
      }
  }
  return target_tile.done[target.k] ? target_tile.d[target.k] : std::numeric_limits<double>::infinity();
}

LazyHeadingGridDistances::LazyHeadingGridDistances(const OccupancyGrid& grid, GridCell source, int source_heading,
                                                   double turn_cost, double reverse_factor,
                                                   const std::vector<uint8_t>* roomy, double narrow_turn_factor)
    : grid_(grid),
      source_(source),
      source_heading_(((source_heading % 8) + 8) % 8),
      turn_cost_(turn_cost),
      reverse_factor_(reverse_factor),
      roomy_(roomy),
      narrow_turn_factor_(narrow_turn_factor),
      d_(grid.blocked.size() * 8, std::numeric_limits<double>::infinity()),
      done_(grid.blocked.size() * 8, 0) {
  if (!grid.Free(source.x, source.y)) return;
  const size_t s = grid.Index(source.x, source.y) * 8 + static_cast<size_t>(source_heading_);
  d_[s] = 0.0;
  open_.push({0.0, s});
}

int LazyHeadingGridDistances::HeadingOf(double theta) {
  const int k = static_cast<int>(std::lround(theta / (std::numbers::pi / 4.0)));
  return ((k % 8) + 8) % 8;
}

double LazyHeadingGridDistances::TurnCostAt(int x, int y) const {
  return roomy_ == nullptr || (*roomy_)[grid_.Index(x, y)] ? turn_cost_ : turn_cost_ * narrow_turn_factor_;
}

double LazyHeadingGridDistances::Distance(int x, int y, int heading) {
  if (x < 0 || y < 0 || x >= grid_.width || y >= grid_.height || !grid_.Free(x, y))
    return std::numeric_limits<double>::infinity();
  const size_t target = grid_.Index(x, y) * 8 + static_cast<size_t>(((heading % 8) + 8) % 8);
  while (!done_[target] && !open_.empty()) {
    const auto [g, s] = open_.top();
    open_.pop();
    if (done_[s] || g > d_[s]) continue;
    done_[s] = 1;
    ++settled_;
    const size_t c = s / 8;
    const int k = static_cast<int>(s % 8);
    const auto relax = [&](size_t n, double ng) {
      if (ng < d_[n]) {
        d_[n] = ng;
        open_.push({ng, n});
      }
    };
    const int cx = static_cast<int>(c % static_cast<size_t>(grid_.width));
    const int cy = static_cast<int>(c / static_cast<size_t>(grid_.width));
    const double turn = TurnCostAt(cx, cy);
    relax(c * 8 + static_cast<size_t>((k + 1) % 8), g + turn);
    relax(c * 8 + static_cast<size_t>((k + 7) % 8), g + turn);
    // Predecessors: the cell behind drove forward into c, the cell ahead reversed into it.
    const double step = k % 2 == 1 ? std::numbers::sqrt2 : 1.0;
    for (const int sign : {-1, 1}) {
      const int dx = sign * kDx[k], dy = sign * kDy[k];
      if (!GridMoveAllowed(grid_, cx, cy, dx, dy)) continue;
      relax(grid_.Index(cx + dx, cy + dy) * 8 + static_cast<size_t>(k), g + step * (sign < 0 ? 1.0 : reverse_factor_));
    }
  }
  return done_[target] ? d_[target] : std::numeric_limits<double>::infinity();
}

}  // namespace minenav
