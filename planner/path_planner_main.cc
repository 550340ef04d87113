// path_planner: paths for the miner's polygon on a segment map, and the grid mode that checks
// the search core against the Moving AI benchmark (planner/README.md). Batch contracts:
//   path_planner --grid MAP.map --scenarios MAP.map.scen --results-out R.csv
//   path_planner --map MAP.json --start x,y,theta --goal x,y,theta [--footprint FILE|W,L]
//                [--turn-radius R] [--clearance C] --path-out PATH.csv --svg-out PATH.svg
// Option parsing and wiring only: the searches are planner/grid_astar.h and
// planner/se2_planner.h.

#include <chrono>
#include <cstdio>
#include <sstream>
#include <string>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"

namespace minenav {
namespace {

// Exit codes besides common/config.h's kExitUsage (2) and kExitRuntime (3).
constexpr int kExitNoPath = 4;        // no path exists, or the request is invalid (the line says why)
constexpr int kExitSearchLimit = 5;   // a search bound stopped the search before an answer

struct Flags {
  std::string grid, scenarios, results_out;
};

int RunGridMode(const Flags& flags, const SearchLimits& limits) {
  if (flags.scenarios.empty() || flags.results_out.empty())
    throw UsageError("--grid needs --scenarios FILE and --results-out FILE");
  CheckOutputIsNotInput("--results-out", flags.results_out, {flags.grid, flags.scenarios});
  const OccupancyGrid grid = LoadMovingAiMap(flags.grid);
  const std::vector<MovingAiScenario> scenarios = LoadMovingAiScenarios(flags.scenarios);
  CheckScenariosFitMap(scenarios, grid, flags.scenarios);
  GridAStar astar(grid);
  std::ostringstream csv;
  csv.precision(10);
  csv << "index,length,expansions,seconds\n";
  for (size_t i = 0; i < scenarios.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const GridSearchResult r = astar.Plan(scenarios[i].start, scenarios[i].goal, limits);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    csv << i << "," << (r.status == SearchStatus::kFound ? r.length : -1.0) << "," << r.expansions << ","
        << seconds << "\n";
  }
  WriteFileAtomically(flags.results_out, csv.str());
  return 0;
}

int Main(int argc, char** argv) {
  ConfigSchema schema("path_planner",
                      "Plans safe, kinematically feasible paths for the miner's polygon on a segment map, or "
                      "shortest grid paths for the Moving AI benchmark (--grid).");
  Flags flags;
  SearchLimits limits;
  schema.AddString("grid", &flags.grid, "grid mode: Moving AI .map file");
  schema.AddString("scenarios", &flags.scenarios, "grid mode: Moving AI .map.scen file");
  schema.AddString("results_out", &flags.results_out, "grid mode: CSV index,length,expansions,seconds (length -1: no path)");
  DeclareOptions(OptionScope(schema).Nested("search"), limits);
  schema.AddHelpEpilog(
      "\nExit codes: 0 a path (grid mode: every scenario answered), 2 bad flag or input file, 3 failure while\n"
      "running, 4 no path (or an invalid request: start or goal outside the map or in collision; the line\n"
      "says why), 5 a search bound (search.max_expansions, search.max_states) stopped the search.\n");
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (!flags.grid.empty()) return RunGridMode(flags, limits);
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
