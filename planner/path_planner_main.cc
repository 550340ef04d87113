// path_planner: paths for the miner's polygon on a segment map, and the grid mode that checks
// the search core against the Moving AI benchmark (planner/README.md). Batch contracts:
//   path_planner --grid MAP.map --scenarios MAP.map.scen --results-out R.csv
//   path_planner --map MAP.json --start x,y,theta --goal x,y,theta [--footprint FILE|W,L]
//                [--turn-radius R] [--clearance C] --path-out PATH.csv --svg-out PATH.svg
// Option parsing and wiring only: the commands are planner/planner_batch.h, the searches
// planner/grid_astar.h and planner/se2_planner.h.

#include <exception>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "planner/planner_batch.h"
#include "planner/search_limits.h"
#include "planner/se2_planner.h"

namespace minenav {
namespace {

int Main(int argc, char** argv) {
  ConfigSchema schema("path_planner",
                      "Plans safe, kinematically feasible paths for the miner's polygon on a segment map, or "
                      "shortest grid paths for the Moving AI benchmark (--grid).");
  PlannerBatchFlags flags;
  SearchLimits limits;
  schema.AddString("grid", &flags.grid, "grid mode: Moving AI .map file");
  schema.AddString("scenarios", &flags.scenarios, "grid mode: Moving AI .map.scen file");
  schema.AddString("results_out", &flags.results_out, "grid mode: CSV index,length,expansions,seconds (length -1: no path)");
  schema.AddString("map", &flags.map, "segment-map JSON {\"segments\": [[x1, y1, x2, y2], ...]}");
  schema.AddString("start", &flags.start, "start pose x,y,theta (m, m, rad or 90deg)");
  schema.AddString("goal", &flags.goal, "goal pose x,y,theta");
  schema.AddString("footprint", &flags.footprint, "W,L (m: a rectangle centred on the pose, x along L) or a JSON file {\"footprint\": [[x, y], ...]}");
  schema.AddString("path_out", &flags.path_out, "path CSV x,y,theta,motion: the start, then the pose each motion reaches");
  schema.AddString("svg_out", &flags.svg_out, "SVG of the map, the path and the footprint along it");
  Se2PlannerOptions options;
  DeclareOptions(OptionScope(schema), options);
  DeclareOptions(OptionScope(schema).Nested("search"), limits);
  schema.AddHelpEpilog(
      "\nExit codes: 0 a path (grid mode: every scenario answered), 2 bad flag or input file, 3 failure while\n"
      "running, 4 no path (or an invalid request: start or goal outside the map or in collision; the line\n"
      "says why), 5 a search bound (search.max_expansions, search.max_states) stopped the search.\n");
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (!flags.grid.empty()) return RunGridMode(flags, limits);
  if (!flags.map.empty()) return RunMapMode(flags, options, limits);
  throw UsageError("give --grid MAP.map (grid mode) or --map MAP.json (see --help)");
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  minenav::SetLogProgramName("path_planner");
  try {
    return minenav::Main(argc, argv);
  } catch (const minenav::UsageError& e) {
    MINENAV_LOG(kError) << e.what();
    return minenav::kExitUsage;
  } catch (const minenav::InputError& e) {
    MINENAV_LOG(kError) << e.what();
    return minenav::kExitUsage;
  } catch (const std::exception& e) {
    MINENAV_LOG(kError) << e.what();
    return minenav::kExitRuntime;
  }
}
