#pragma once
// A grid of free and blocked cells for the point-robot search (grid mode): cell (x, y) is
// column x, row y, row-major; what a cell's size is in metres is the caller's business.

#include <cstdint>
#include <vector>

namespace minenav {

struct OccupancyGrid {
  int width = 0;   // cells
  int height = 0;  // cells
  std::vector<uint8_t> blocked;  // width * height, 1 = blocked

  OccupancyGrid() = default;
  OccupancyGrid(int w, int h) : width(w), height(h), blocked(static_cast<size_t>(w) * h, 0) {}

  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  size_t Index(int x, int y) const { return static_cast<size_t>(y) * width + x; }
  // Outside the grid counts as blocked.
  bool Free(int x, int y) const { return Contains(x, y) && blocked[Index(x, y)] == 0; }
  void SetBlocked(int x, int y, bool b) { blocked[Index(x, y)] = b ? 1 : 0; }
};

}  // namespace minenav
