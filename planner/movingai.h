#pragma once
// The Moving AI benchmark's file formats (https://movingai.com/benchmarks/formats.html):
//   .map       "type octile", "height H", "width W", "map", then H rows of W characters;
//              passable '.', 'G', 'S'; blocked '@', 'O', 'T', 'W'. Cell (x, y) is column x of
//              row y, row 0 the first row of the file.
//   .map.scen  "version 1", then one problem per line, tab-separated: bucket, map, width,
//              height, start x, start y, goal x, goal y, optimal length.
// Readers validate everything and throw InputError with one line naming source, line and
// what was wrong.

#include <string>
#include <vector>

#include "planner/grid_astar.h"
#include "planner/occupancy_grid.h"

namespace minenav {

OccupancyGrid ParseMovingAiMap(const std::string& text, const std::string& source_name);
OccupancyGrid LoadMovingAiMap(const std::string& path);

struct MovingAiScenario {
  int bucket = 0;
  std::string map;          // the map's name as the scenario file gives it
  int map_width = 0, map_height = 0;
  GridCell start, goal;
  double optimal_length = 0.0;  // cells, as published (about 6 significant digits)
};

std::vector<MovingAiScenario> ParseMovingAiScenarios(const std::string& text, const std::string& source_name);
std::vector<MovingAiScenario> LoadMovingAiScenarios(const std::string& path);

// Throws InputError unless every scenario fits the grid (its width and height are the
// grid's, start and goal lie inside it).
void CheckScenariosFitMap(const std::vector<MovingAiScenario>& scenarios, const OccupancyGrid& grid,
                          const std::string& source_name);

}  // namespace minenav
