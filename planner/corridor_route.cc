#include "planner/corridor_route.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace minenav {

RouteGrid CoarseRouteGrid(const GridFrame& fine, const OccupancyGrid& fine_cells, const std::vector<uint8_t>& fine_roomy,
                          double resolution) {
  RouteGrid g;
  g.frame = fine;
  g.frame.cell = resolution;
  g.frame.nx = std::max(1, static_cast<int>(std::ceil(fine.nx * fine.cell / resolution)));
  g.frame.ny = std::max(1, static_cast<int>(std::ceil(fine.ny * fine.cell / resolution)));
  g.cells = OccupancyGrid(g.frame.nx, g.frame.ny);
  g.roomy.assign(g.cells.blocked.size(), 0);
  for (int iy = 0; iy < g.frame.ny; ++iy)
    for (int ix = 0; ix < g.frame.nx; ++ix) {
      const int fx = fine.CellX(fine.x0 + (ix + 0.5) * resolution), fy = fine.CellY(fine.y0 + (iy + 0.5) * resolution);
      const bool free = fine_cells.Free(fx, fy);
      g.cells.SetBlocked(ix, iy, !free);
      g.roomy[g.cells.Index(ix, iy)] = free && fine_roomy[fine_cells.Index(fx, fy)] ? 1 : 0;
    }
  return g;
}

std::vector<RouteStep> DescendRoute(LazyHeadingGridDistances& d, const OccupancyGrid& cells, GridCell start,
                                    int start_heading) {
  using H = LazyHeadingGridDistances;
  std::vector<RouteStep> route;
  int x = start.x, y = start.y, k = start_heading;
  double here = d.Distance(x, y, k);
  if (here == std::numeric_limits<double>::infinity()) return {};
  const int64_t guard = 8LL * cells.width * cells.height;
  for (int64_t i = 0; here > 1e-9 && i < guard; ++i) {
    bool moved = false;
    const double step = k % 2 == 1 ? std::numbers::sqrt2 : 1.0;
    for (const int sign : {1, -1}) {
      const int dx = sign * H::kDx[k], dy = sign * H::kDy[k];
      if (!GridMoveAllowed(cells, x, y, dx, dy)) continue;
      const double there = d.Distance(x + dx, y + dy, k);
      if (std::abs(there + step * (sign > 0 ? 1.0 : d.reverse_factor()) - here) < 1e-6) {
        x += dx, y += dy, here = there, moved = true;
        route.push_back({{x, y}, k});
        break;
      }
    }
    if (moved) continue;
    for (const int b : {(k + 1) % 8, (k + 7) % 8}) {
      const double there = d.Distance(x, y, b);
      if (std::abs(there + d.TurnCostAt(x, y) - here) < 1e-6) {
        k = b, here = there, moved = true;
        break;
      }
    }
    if (!moved) return {};
  }
  if (here > 1e-9) return {};
  return route;
}

std::vector<RouteTurn> RouteTurns(const std::vector<RouteStep>& route, size_t lead) {
  std::vector<RouteTurn> turns;
  if (route.empty()) return turns;
  const size_t last = route.size() - 1;
  for (size_t i = 1; i < route.size(); ++i) {
    if (route[i].heading == route[i - 1].heading) continue;
    const size_t before = i > lead ? i - 1 - lead : 0, after = std::min(last, i + lead);
    // A turn whose lead-in overlaps the previous turn's lead-out is part of it.
    if (!turns.empty() && before <= turns.back().after)
      turns.back().after = after;
    else
      turns.push_back({before, after, i});
  }
  return turns;
}

}  // namespace minenav
