// Grid A* against a brute-force reference: Bellman-Ford relaxation of every cell until
// nothing changes, with the same moves (8-connected, sqrt(2) diagonals, no corner cutting),
// on random grids; and the rules themselves on small hand-made grids.

#include "planner/grid_astar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace minenav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Distances from `source` to every cell by relaxing all moves of all cells until a fixed point.
std::vector<double> BellmanFordDistances(const OccupancyGrid& grid, GridCell source) {
  std::vector<double> d(grid.blocked.size(), kInf);
  d[grid.Index(source.x, source.y)] = 0.0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x) {
        const double here = d[grid.Index(x, y)];
        if (here == kInf || !grid.Free(x, y)) continue;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const int nx = x + dx, ny = y + dy;
            if (!grid.Free(nx, ny)) continue;
            if (dx != 0 && dy != 0 && (!grid.Free(x + dx, y) || !grid.Free(x, y + dy))) continue;
            const double c = here + ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0);
            double& there = d[grid.Index(nx, ny)];
            if (c < there - 1e-12) {
              there = c;
              changed = true;
            }
          }
      }
  }
  return d;
}

OccupancyGrid FromRows(const std::vector<std::string>& rows) {
  OccupancyGrid g(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()));
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) g.SetBlocked(x, y, rows[static_cast<size_t>(y)][static_cast<size_t>(x)] == '@');
  return g;
}

// Every step of a returned path is an allowed move and the steps add up to the length.
double CheckedPathLength(const OccupancyGrid& grid, const std::vector<GridCell>& path) {
  double length = 0.0;
  for (size_t i = 1; i < path.size(); ++i) {
    const int dx = path[i].x - path[i - 1].x, dy = path[i].y - path[i - 1].y;
    EXPECT_TRUE(std::abs(dx) <= 1 && std::abs(dy) <= 1 && (dx != 0 || dy != 0));
    EXPECT_TRUE(GridMoveAllowed(grid, path[i - 1].x, path[i - 1].y, dx, dy));
    length += (dx != 0 && dy != 0) ? std::numbers::sqrt2 : 1.0;
  }
  return length;
}

TEST(OctileDistanceTest, IsTheEmptyGridPathLength) {
  EXPECT_DOUBLE_EQ(OctileDistance(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(OctileDistance(3, 0), 3.0);
  EXPECT_DOUBLE_EQ(OctileDistance(-2, 2), 2.0 * std::numbers::sqrt2);
  EXPECT_DOUBLE_EQ(OctileDistance(5, -2), 3.0 + 2.0 * std::numbers::sqrt2);
}

TEST(GridAStarTest, NoCornerCuttingMakesTheDiagonalPassThroughAnOpenSide) {
  // From the top-left to the bottom-right: the diagonal step is blocked by the wall beside
  // it, so the path takes two straight steps (length 2, not sqrt 2).
  const OccupancyGrid g = FromRows({"..", "@."});
  GridAStar astar(g);
  const GridSearchResult r = astar.Plan({0, 0}, {1, 1});
  ASSERT_EQ(r.status, SearchStatus::kFound);
  EXPECT_DOUBLE_EQ(r.length, 2.0);
  EXPECT_FALSE(GridMoveAllowed(g, 0, 0, 1, 1));
  // Two diagonal blocks leave no way at all.
  const OccupancyGrid closed = FromRows({".@", "@."});
  GridAStar a2(closed);
  const GridSearchResult r2 = a2.Plan({0, 0}, {1, 1});
  EXPECT_EQ(r2.status, SearchStatus::kNoPath);
  EXPECT_DOUBLE_EQ(r2.length, -1.0);
  EXPECT_NE(r2.reason.find("not reachable"), std::string::npos) << r2.reason;
}

TEST(GridAStarTest, BadRequestsSayWhy) {
  const OccupancyGrid g = FromRows({"...", ".@.", "..."});
  GridAStar astar(g);
  const GridSearchResult blocked = astar.Plan({1, 1}, {0, 0});
  EXPECT_EQ(blocked.status, SearchStatus::kInvalidRequest);
  EXPECT_NE(blocked.reason.find("start (1, 1) is a blocked cell"), std::string::npos) << blocked.reason;
  const GridSearchResult outside = astar.Plan({0, 0}, {3, -1});
  EXPECT_EQ(outside.status, SearchStatus::kInvalidRequest);
  EXPECT_NE(outside.reason.find("goal (3, -1) is outside the grid"), std::string::npos) << outside.reason;
  const GridSearchResult same = astar.Plan({2, 2}, {2, 2});
  ASSERT_EQ(same.status, SearchStatus::kFound);
  EXPECT_DOUBLE_EQ(same.length, 0.0);
}

TEST(GridAStarTest, EveryLimitStopsTheSearchAndIsNamed) {
  OccupancyGrid g(200, 200);
  GridAStar astar(g);
  SearchLimits few_expansions;
  few_expansions.max_expansions = 10;
  const GridSearchResult e = astar.Plan({0, 0}, {199, 150}, few_expansions);
  EXPECT_EQ(e.status, SearchStatus::kExpansionLimit);
  EXPECT_EQ(e.expansions, 10);
  EXPECT_NE(e.reason.find("expansion_limit"), std::string::npos) << e.reason;
  SearchLimits few_states;
  few_states.max_states = 50;
  EXPECT_EQ(astar.Plan({0, 0}, {199, 150}, few_states).status, SearchStatus::kMemoryLimit);
  SearchLimits deadline;
  int polls = 0;
  deadline.stop_requested = [&] { return ++polls >= 3; };
  const GridSearchResult d = astar.Plan({0, 0}, {199, 150}, deadline);
  EXPECT_EQ(d.status, SearchStatus::kStopped);
  EXPECT_EQ(polls, 3);
  // The same object still answers a full search afterwards.
  const GridSearchResult full = astar.Plan({0, 0}, {199, 150});
  ASSERT_EQ(full.status, SearchStatus::kFound);
  EXPECT_NEAR(full.length, OctileDistance(199, 150), 1e-9);
}

TEST(GridAStarTest, MatchesBellmanFordOnRandomGrids) {
  std::mt19937 rng(13);
  int found = 0, unreachable = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 5 + trial % 17, h = 4 + (trial * 7) % 15;
    const double density = 0.1 + 0.35 * (trial % 5) / 4.0;
    OccupancyGrid g(w, h);
    std::bernoulli_distribution blocked(density);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) g.SetBlocked(x, y, blocked(rng));
    std::uniform_int_distribution<int> ux(0, w - 1), uy(0, h - 1);
    GridCell s{ux(rng), uy(rng)};
    g.SetBlocked(s.x, s.y, false);
    const std::vector<double> reference = BellmanFordDistances(g, s);
    GridAStar astar(g);
    for (int q = 0; q < 10; ++q) {
      GridCell t{ux(rng), uy(rng)};
      if (!g.Free(t.x, t.y)) continue;
      const GridSearchResult r = astar.Plan(s, t);
      const double want = reference[g.Index(t.x, t.y)];
      if (want == kInf) {
        EXPECT_EQ(r.status, SearchStatus::kNoPath) << "trial " << trial;
        EXPECT_DOUBLE_EQ(r.length, -1.0);
        ++unreachable;
        continue;
      }
      ASSERT_EQ(r.status, SearchStatus::kFound) << "trial " << trial;
      EXPECT_NEAR(r.length, want, 1e-9) << "trial " << trial;
      ASSERT_FALSE(r.path.empty());
      EXPECT_EQ(r.path.front(), s);
      EXPECT_EQ(r.path.back(), t);
      EXPECT_NEAR(CheckedPathLength(g, r.path), r.length, 1e-9);
      ++found;
    }
  }
  // The trials cover both answers.
  EXPECT_GT(found, 200);
  EXPECT_GT(unreachable, 20);
}

}  // namespace
}  // namespace minenav
