#include "planner/planner_batch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/pose_text.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"
#include "render/svg_render.h"

namespace minenav {
namespace {

// "W,L" (a rectangle W wide and L long, centred on the pose, x along L) or a JSON file.
Footprint FootprintFromFlag(const std::string& text) {
  if (!std::filesystem::exists(text)) {
    const std::vector<double> wl = ParseNumberList(text, "--footprint", 2);
    if (!(wl[0] > 0.0) || !(wl[1] > 0.0)) throw UsageError("--footprint W,L needs W > 0 and L > 0");
    return Footprint::Rectangle(wl[0], wl[1]);
  }
  return ParseFootprintJson(ReadFile(text), text);
}

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

// The map, the path through every piece (arcs drawn as chords every 0.5 m) and the footprint
// every 2 m along it.
std::string PathSvg(const Se2Planner& planner, const PlannedPath& path, const std::string& title) {
  SvgScene scene;
  scene.title = title;
  scene.lines.push_back({"map", "#333333", 1.5, planner.map(), {}});
  SvgTrajectory traj{"path", "#1f77b4", 2.0, false, false, {path.start}};
  SvgLineLayer footprints{"footprint", "#ff7f0e", 0.8, {}, {}};
  Pose2 from = path.start;
  double since_footprint = 1e9;
  for (const MotionPiece& p : path.pieces) {
    const double extent = p.motion == Motion::kTurnInPlace ? std::abs(p.amount) * 5.0 : p.amount;
    const int n = std::max(1, static_cast<int>(std::ceil(extent / 0.5)));
    for (int k = 1; k <= n; ++k) {
      const Pose2 q = PoseAfter(from, p.motion, p.amount * k / n, p.radius);
      traj.poses.push_back(q);
      since_footprint += extent / n;
      if (since_footprint >= 2.0 || (k == n && &p == &path.pieces.back())) {
        SvgPolyline outline{{}, true};
        for (const auto& v : planner.footprint().vertices) outline.points.push_back(q * v);
        footprints.polylines.push_back(outline);
        since_footprint = 0.0;
      }
    }
    from = p.end;
  }
  SvgPolyline start_outline{{}, true};
  for (const auto& v : planner.footprint().vertices) start_outline.points.push_back(path.start * v);
  footprints.polylines.push_back(start_outline);
  scene.lines.push_back(footprints);
  scene.trajectories.push_back(traj);
  return RenderSvg(scene);
}

int RunMapMode(const PlannerBatchFlags& flags, const Se2PlannerOptions& options, const SearchLimits& limits) {
  if (flags.path_out.empty()) throw UsageError("--map needs --path-out FILE");
  CheckOutputIsNotInput("--path-out", flags.path_out, {flags.map, flags.footprint});
  CheckOutputIsNotInput("--svg-out", flags.svg_out, {flags.map, flags.footprint, flags.path_out});
  const Pose2 start = PoseFromFlag(flags.start, "--start"), goal = PoseFromFlag(flags.goal, "--goal");
  const Se2Planner planner(LoadSegmentsJson(flags.map), FootprintFromFlag(flags.footprint), options);
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
  if (!flags.svg_out.empty()) WriteFileAtomically(flags.svg_out, PathSvg(planner, r.path, summary.str()));
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
