#include "planner/planner_batch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/pose_text.h"
#include "mapper/contour_map_io.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"
#include "planner/path_svg.h"
#include "render/svg_render.h"

namespace minenav {

Footprint FootprintFromFlag(const std::string& text) {
  if (!std::filesystem::exists(text)) {
    const std::vector<double> wl = ParseNumberList(text, "--footprint", 2);
    if (!(wl[0] > 0.0) || !(wl[1] > 0.0)) throw UsageError("--footprint W,L needs W > 0 and L > 0");
    return Footprint::Rectangle(wl[0], wl[1]);
  }
  return ParseFootprintJson(ReadFile(text), text);
}

namespace {

Pose2 PoseFromFlag(const std::string& text, const std::string& what) {
  if (text.empty()) throw UsageError(what + " x,y,theta is required with --map");
  return ParsePoseText(text, what);
}

}  // namespace

std::string PathCsv(const PlannedPath& path) {
  std::ostringstream csv;
  csv.precision(12);
  csv << "x,y,theta,motion\n" << path.start.x << "," << path.start.y << "," << path.start.theta << ",start\n";
  for (const MotionPiece& p : path.pieces)
    csv << p.end.x << "," << p.end.y << "," << p.end.theta << "," << ToString(p.motion) << "\n";
  return csv.str();
}

std::string PathSvg(const Se2Planner& planner, const PlannedPath& path, const std::string& title,
                    const ContourFreeSpace* space, const FreeSpaceOptions& free_space) {
  return RenderSvg(PathScene(planner.map(), planner.footprint(), path, title, space, free_space));
}

int RunMapMode(const PlannerBatchFlags& flags, const Se2PlannerOptions& options, const SearchLimits& limits,
               const FreeSpaceOptions& free_space) {
  const bool contours = !flags.contour_map.empty();
  const std::string mode = contours ? "--contour-map" : "--map";
  if (contours && !flags.map.empty()) throw UsageError("give --map or --contour-map, not both");
  if (flags.allow_unknown && !contours) throw UsageError("--allow-unknown needs --contour-map");
  if (flags.path_out.empty()) throw UsageError(mode + " needs --path-out FILE");
  const std::string& map_file = contours ? flags.contour_map : flags.map;
  CheckOutputIsNotInput("--path-out", flags.path_out, {map_file, flags.footprint});
  CheckOutputIsNotInput("--svg-out", flags.svg_out, {map_file, flags.footprint, flags.path_out});
  if (const std::string e = ValidateOptions(free_space); !e.empty()) throw UsageError(e);
  const Pose2 start = PoseFromFlag(flags.start, "--start"), goal = PoseFromFlag(flags.goal, "--goal");
  std::optional<ContourFreeSpace> space;
  std::vector<Segment> walls;
  if (contours) {
    std::vector<mapper::Contour> list;
    const mapper::ContourMap map = mapper::LoadContourMapJson(flags.contour_map);
    for (const auto& [id, c] : map.contours()) list.push_back(c);
    space = MakeContourFreeSpace(list, free_space);
    walls = space->Boundary(flags.allow_unknown);
    MINENAV_LOG(kInfo) << flags.contour_map << ": " << list.size() << " contours, " << space->walls.size()
                       << " wall segments, " << space->frontiers.size() << " frontiers, " << space->unclosed_ends
                       << " ends left open";
    if (!flags.allow_unknown) {
      const KnownFreeSpace known(*space, free_space);
      for (const auto& [pose, what] : {std::pair{start, "start"}, std::pair{goal, "goal"}})
        if (!known.Contains(pose.translation())) {
          MINENAV_LOG(kError) << "no path (invalid_request): " << what << " " << pose
                              << " is not in the known free space (behind a frontier or unseen; --allow-unknown explores)";
          return kExitNoPath;
        }
    }
  } else {
    walls = LoadSegmentsJson(flags.map);
  }
  const Se2Planner planner(std::move(walls), FootprintFromFlag(flags.footprint), options);
  const auto t0 = std::chrono::steady_clock::now();
  const Se2PlanResult r = planner.Plan(start, goal, limits);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.status != SearchStatus::kFound) {
    MINENAV_LOG(kError) << "no path (" << ToString(r.status) << "): " << r.reason;
    return r.status == SearchStatus::kNoPath || r.status == SearchStatus::kInvalidRequest ? kExitNoPath
                                                                                          : kExitSearchLimit;
  }
  WriteFileAtomically(flags.path_out, PathCsv(r.path));
  std::ostringstream summary;
  summary.precision(4);
  summary << "path " << r.path.Length() << " m, " << r.path.pieces.size() << " pieces, " << r.path.Reversals()
          << " reversals, " << r.expansions << " expansions, " << seconds << " s";
  if (!flags.svg_out.empty())
    WriteFileAtomically(flags.svg_out,
                        PathSvg(planner, r.path, summary.str(), space ? &*space : nullptr, free_space));
  MINENAV_LOG(kInfo) << summary.str();
  return 0;
}

int RunGridMode(const PlannerBatchFlags& flags, const SearchLimits& limits) {
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

}  // namespace minenav
