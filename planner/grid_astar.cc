#include "planner/grid_astar.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <sstream>

namespace minenav {

double OctileDistance(int dx, int dy) {
  const int ax = std::abs(dx), ay = std::abs(dy);
  const int lo = std::min(ax, ay), hi = std::max(ax, ay);
  return std::numbers::sqrt2 * lo + (hi - lo);
}

bool GridMoveAllowed(const OccupancyGrid& grid, int x, int y, int dx, int dy) {
  if (!grid.Free(x + dx, y + dy)) return false;
  if (dx != 0 && dy != 0) return grid.Free(x + dx, y) && grid.Free(x, y + dy);
  return true;
}

GridAStar::GridAStar(const OccupancyGrid& grid)
    : grid_(grid),
      g_(grid.blocked.size(), 0.0),
      parent_(grid.blocked.size(), -1),
      stamp_(grid.blocked.size(), 0),
      closed_(grid.blocked.size(), 0) {}

namespace {

std::string CellText(GridCell c) {
  std::ostringstream s;
  s << "(" << c.x << ", " << c.y << ")";
  return s.str();
}

struct OpenEntry {
  double f, g;
  int32_t cell;
  // std::priority_queue pops the largest: the smallest f first, then the largest g (deeper
  // nodes first, fewer expansions on ties).
  bool operator<(const OpenEntry& o) const { return f != o.f ? f > o.f : g < o.g; }
};

}  // namespace

GridSearchResult GridAStar::Plan(GridCell start, GridCell goal, const SearchLimits& limits) {
  GridSearchResult result;
  if (!grid_.Free(start.x, start.y) || !grid_.Free(goal.x, goal.y)) {
    const bool start_bad = !grid_.Free(start.x, start.y);
    const GridCell c = start_bad ? start : goal;
    result.status = SearchStatus::kInvalidRequest;
    result.reason = std::string(start_bad ? "start " : "goal ") + CellText(c) +
                    (grid_.Contains(c.x, c.y) ? " is a blocked cell" : " is outside the grid");
    return result;
  }
  if (++search_ == 0) {  // the stamps wrapped: clear them once in 2^32 searches
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    std::fill(closed_.begin(), closed_.end(), 0u);
    search_ = 1;
  }
  const auto index = [&](int x, int y) { return static_cast<int32_t>(grid_.Index(x, y)); };
  const auto heuristic = [&](int x, int y) { return OctileDistance(goal.x - x, goal.y - y); };
  std::priority_queue<OpenEntry> open;
  const int32_t s = index(start.x, start.y), t = index(goal.x, goal.y);
  g_[s] = 0.0;
  parent_[s] = -1;
  stamp_[s] = search_;
  open.push({heuristic(start.x, start.y), 0.0, s});
  result.states = 1;
  while (!open.empty()) {
    const OpenEntry e = open.top();
    open.pop();
    if (closed_[e.cell] == search_ || e.g > g_[e.cell]) continue;  // a stale entry
    if (e.cell == t) {
      result.status = SearchStatus::kFound;
      result.length = g_[t];
      for (int32_t c = t; c != -1; c = parent_[c]) result.path.push_back({c % grid_.width, c / grid_.width});
      std::reverse(result.path.begin(), result.path.end());
      return result;
    }
    const SearchStatus limit = CheckLimits(limits, result.expansions, result.states);
    if (limit != SearchStatus::kFound) {
      result.status = limit;
      result.reason = LimitReason(limit, result.expansions, result.states);
      return result;
    }
    closed_[e.cell] = search_;
    ++result.expansions;
    const int x = e.cell % grid_.width, y = e.cell / grid_.width;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !GridMoveAllowed(grid_, x, y, dx, dy)) continue;
        const int32_t n = index(x + dx, y + dy);
        if (closed_[n] == search_) continue;
        const double g = e.g + (dx != 0 && dy != 0 ? std::numbers::sqrt2 : 1.0);
        if (stamp_[n] == search_ && g_[n] <= g) continue;
        if (stamp_[n] != search_) ++result.states;
        stamp_[n] = search_;
        g_[n] = g;
        parent_[n] = e.cell;
        open.push({g + heuristic(x + dx, y + dy), g, n});
      }
  }
  result.status = SearchStatus::kNoPath;
  result.reason = "goal " + CellText(goal) + " is not reachable from start " + CellText(start) + " (" +
                  std::to_string(result.expansions) + " cells searched)";
  return result;
}

}  // namespace minenav
