#pragma once
// The path_planner's two batch commands (planner/README.md): a path for the miner's polygon
// on a segment map, written as CSV and SVG, and the grid mode over a Moving AI scenario file.
// They read and write files and time each search; the searches themselves are
// planner/se2_planner.h and planner/grid_astar.h.

#include <string>

#include "planner/contour_free_space.h"
#include "planner/footprint.h"
#include "planner/search_limits.h"
#include "planner/se2_planner.h"

namespace minenav {

// Exit codes besides common/config.h's kExitUsage (2) and kExitRuntime (3).
inline constexpr int kExitNoPath = 4;       // no path exists, or the request is invalid (the line says why)
inline constexpr int kExitSearchLimit = 5;  // a search bound stopped the search before an answer

struct PlannerBatchFlags {
  std::string grid, scenarios, results_out;
  std::string map, start, goal, footprint = "3.3,10", path_out, svg_out;
  std::string contour_map;     // instead of --map: a contour-map JSON (contour_mapper --map-out)
  bool allow_unknown = false;  // with --contour-map: do not close the open ends by frontiers
};

// "W,L" (a rectangle W wide and L long, centred on the pose, x along L) or a JSON file
// {"footprint": [[x, y], ...]}; throws UsageError / InputError.
Footprint FootprintFromFlag(const std::string& text);

// --map (or --contour-map) mode: plans from --start to --goal, writes --path-out (and
// --svg-out). On a contour map the walls are its contours and, unless --allow-unknown, the
// frontiers that close their open ends (contour_free_space.h); a start or goal outside the
// known free space is then refused. Returns 0, kExitNoPath or kExitSearchLimit; throws
// UsageError / InputError on bad flags or files.
int RunMapMode(const PlannerBatchFlags& flags, const Se2PlannerOptions& options, const SearchLimits& limits,
               const FreeSpaceOptions& free_space = {});
// --grid mode: one CSV row per scenario (index,length,expansions,seconds; length -1 = none).
int RunGridMode(const PlannerBatchFlags& flags, const SearchLimits& limits);

// The path as CSV x,y,theta,motion: the start, then the pose each piece reaches.
std::string PathCsv(const PlannedPath& path);
// The map, the path (arcs as 0.5 m chords) and the footprint every 2 m along it; with a
// contour map's free space also its frontiers (dashed) and the known free space (filled,
// sampled every 0.5 m by KnownFreeSpace).
std::string PathSvg(const Se2Planner& planner, const PlannedPath& path, const std::string& title,
                    const ContourFreeSpace* space = nullptr, const FreeSpaceOptions& free_space = {});

}  // namespace minenav
