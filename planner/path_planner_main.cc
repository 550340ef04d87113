// path_planner: paths for the miner's polygon (planner/README.md).
//   live (neither --map, --contour-map nor --grid): answers PATH_REQUEST with PATH on the
//        CONTOUR_MAP the mapper publishes, replans when the map blocks the active path
//        (planner/path_planner_node.h), HEARTBEAT;
//   path_planner --map MAP.json --start x,y,theta --goal x,y,theta [--footprint FILE|W,L]
//                [--turn-radius R] [--clearance C] --path-out PATH.csv --svg-out PATH.svg
//   path_planner --contour-map MAP.json ... (the same on a contour map: walls and frontiers)
//   path_planner --grid MAP.map --scenarios MAP.map.scen --results-out R.csv
// Option parsing and wiring only: the commands are planner/planner_batch.h, the node
// planner/path_planner_node.h, the searches planner/grid_astar.h and planner/se2_planner.h.

#include <string>
#include <vector>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "planner/path_planner_node.h"
#include "planner/planner_batch.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  PlannerBatchFlags flags;
  PathPlannerNodeOptions options;
  return RunNodeProcess(
      "path_planner",
      "Plans safe, kinematically feasible paths for the miner's polygon: live on CONTOUR_MAP (answers PATH_REQUEST "
      "with PATH), in batch on a segment map (--map) or a contour map (--contour-map), or shortest grid paths for "
      "the Moving AI benchmark (--grid).",
      args,
      [&](ConfigSchema& s) {
        s.AddString("grid", &flags.grid, "grid mode: Moving AI .map file");
        s.AddString("scenarios", &flags.scenarios, "grid mode: Moving AI .map.scen file");
        s.AddString("results_out", &flags.results_out,
                    "grid mode: CSV index,length,expansions,seconds (length -1: no path)");
        s.AddString("map", &flags.map, "segment-map JSON {\"segments\": [[x1, y1, x2, y2], ...]}");
        s.AddString("contour_map", &flags.contour_map,
                    "contour-map JSON {\"contours\": [{\"closed\": false, \"points\": [[x, y], ...]}, ...]} "
                    "(contour_mapper --map-out): plan on its walls and frontiers");
        s.AddBool("allow_unknown", &flags.allow_unknown,
                  "with --contour-map: exploration, the open ends of contours are not closed by frontiers");
        s.AddString("start", &flags.start, "start pose x,y,theta (m, m, rad or 90deg)");
        s.AddString("goal", &flags.goal, "goal pose x,y,theta");
        s.AddString("footprint", &flags.footprint,
                    "W,L (m: a rectangle centred on the pose, x along L) or a JSON file {\"footprint\": [[x, y], ...]}");
        s.AddString("path_out", &flags.path_out, "path CSV x,y,theta,motion: the start, then the pose each motion reaches");
        s.AddString("svg_out", &flags.svg_out,
                    "SVG of the map, the path and the footprint along it (contour maps: frontiers and known free space)");
        DeclareOptions(s, options);
        s.AddHelpEpilog(
            "\nExit codes: 0 a path (grid mode: every scenario answered; live: stopped), 2 bad flag or input file,\n"
            "3 failure while running, 4 no path (or an invalid request: start or goal outside the map, in collision\n"
            "or outside the known free space; the line says why), 5 a search bound (search.max_expansions,\n"
            "search.max_states) stopped the search.\n");
      },
      [&](NodeRuntime& runtime) {
        if (const std::string e = ValidateOptions(options); !e.empty()) throw UsageError(e);
        if (!flags.grid.empty()) return RunGridMode(flags, options.search);
        if (!flags.map.empty() || !flags.contour_map.empty())
          return RunMapMode(flags, options.planner, options.search, options.free_space);
        // Live.
        Footprint footprint = FootprintFromFlag(flags.footprint);
        if (const std::string e = ValidateFootprint(footprint); !e.empty()) throw UsageError("--footprint: " + e);
        runtime.Start();
        PathPlannerNode node(runtime, options, Normalized(std::move(footprint)));
        return node.Run();
      });
}
