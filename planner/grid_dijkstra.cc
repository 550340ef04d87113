#include "planner/grid_dijkstra.h"

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
      d_(grid.blocked.size(), std::numeric_limits<double>::infinity()),
      done_(grid.blocked.size(), 0) {
  if (!grid.Free(source.x, source.y)) return;
  d_[grid.Index(source.x, source.y)] = 0.0;
  open_.push({0.0, grid.Index(source.x, source.y)});
}

double LazyGridDistances::Distance(int x, int y) {
  if (x < 0 || y < 0 || x >= grid_.width || y >= grid_.height || !grid_.Free(x, y))
    return std::numeric_limits<double>::infinity();
  const size_t target = grid_.Index(x, y);
  while (!done_[target] && !open_.empty()) {
    const auto [g, c] = open_.top();
    open_.pop();
    if (done_[c] || g > d_[c]) continue;
    done_[c] = 1;
    ++settled_;
    const int cx = static_cast<int>(c % static_cast<size_t>(grid_.width));
    const int cy = static_cast<int>(c / static_cast<size_t>(grid_.width));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !GridMoveAllowed(grid_, cx, cy, dx, dy)) continue;
        const size_t n = grid_.Index(cx + dx, cy + dy);
        const double ng = g + (dx != 0 && dy != 0 ? std::numbers::sqrt2 : 1.0);
        if (ng < d_[n]) {
          d_[n] = ng;
          open_.push({ng, n});
        }
      }
  }
  return done_[target] ? d_[target] : std::numeric_limits<double>::infinity();
}

}  // namespace minenav
