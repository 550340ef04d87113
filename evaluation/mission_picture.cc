#include "evaluation/mission_picture.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

namespace minenav {

std::vector<Pose2> SamplePath(const PlannedPath& path, double step) {
  std::vector<Pose2> out = {path.start};
  Pose2 from = path.start;
  for (const MotionPiece& p : path.pieces) {
    const double per = p.motion == Motion::kTurnInPlace ? 0.1 : std::max(step, 1e-3);
    const int n = std::clamp(static_cast<int>(std::ceil(std::abs(p.amount) / per)), 1, 10000);
    for (int i = 1; i < n; ++i) out.push_back(PoseAfter(from, p.motion, p.amount * i / n, p.radius));
    out.push_back(p.end);
    from = p.end;
  }
  return out;
}

namespace {

std::vector<Pose2> Thinned(const std::vector<StampedPose>& track, double step) {
  std::vector<Pose2> out;
  for (const StampedPose& p : track)
    if (out.empty() || TranslationDistance(out.back(), p.pose) >= step) out.push_back(p.pose);
  if (!track.empty() && TranslationDistance(out.back(), track.back().pose) > 0.0) out.push_back(track.back().pose);
  return out;
}

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

SvgScene MissionScene(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& evaluation,
                      const MissionPictureOptions& o) {
  SvgScene scene;
  scene.title = o.title;
  if (in.mission) scene.title += ": " + in.mission->mission_id + " (" + in.mission->state + ")";
  else if (!f.time.final_state.empty()) scene.title += " (" + f.time.final_state + ")";
  scene.notes = HeadlineLines(in, f);

  if (o.free_space) {
    scene.areas.push_back({"explored: the map shows it free", "#2ca02c", 0.18, CellRuns(f.grid, true, true)});
    scene.areas.push_back({"free, never shown free", "#ff7f0e", 0.15, CellRuns(f.grid, true, false)});
    scene.areas.push_back({"shown free, not free", "#d62728", 0.6, CellRuns(f.grid, false, true)});
  }

  SvgLineLayer initial{"true walls at the start", "#c8c8c8", 4.0, in.initial_world, {}};
  SvgLineLayer final_walls{"true walls at the end", "#333333", 1.2, in.final_world, {}};
  SvgLineLayer map{"final contour map", "#1f77b4", 1.5, {}, {}};
  for (const auto& [id, c] : in.map.contours()) map.polylines.push_back({c.points, c.closed});
  scene.lines = {initial, final_walls, map};
  SvgLineLayer faces{"cut faces (as planned)", "#ff7f0e", 3.0, {}, {}};
  for (const CutFigures& c : f.cuts) {
    if (!c.face) continue;
    faces.segments.push_back(*c.face);
    // The face where the request would put it, dashed (a trajectory: line layers are solid).
    const Eigen::Vector2d d = c.requested_m * Eigen::Vector2d(std::cos(c.target.theta), std::sin(c.target.theta));
    const Eigen::Vector2d a = c.face->a + d, b = c.face->b + d;
    scene.trajectories.push_back({scene.trajectories.empty() ? "requested depth of each cut" : "", "#ff7f0e", 1.5,
                                  true, false, {Pose2(a.x(), a.y(), 0.0), Pose2(b.x(), b.y(), 0.0)}});
  }
  if (!faces.segments.empty()) scene.lines.push_back(faces);

  // The paths the tracker was given; without DRIVE_PATH (a survey without the coordinator),
  // the planner's answers.
  const bool drive = !in.log.drive_paths.empty();
  const std::vector<LoggedPath>& paths = drive ? in.log.drive_paths : in.log.planner_paths;
  std::set<std::pair<int64_t, std::string>> drawn;
  bool first = true;
  for (const LoggedPath& p : paths) {
    if (!p.feasible || p.path.pieces.empty() || !drawn.insert({p.request_id, p.status}).second) continue;
    SvgTrajectory t;
    t.label = first ? (drive ? "planned paths (DRIVE_PATH)" : "planned paths (PATH)") : "";
    t.color = "#9edae5";  // a light band under the driven track
    t.width_px = 4.0;
    t.markers = false;
    t.poses = SamplePath(p.path, o.path_step);
    scene.trajectories.push_back(std::move(t));
    first = false;
  }
  if (o.odometry && !in.log.odometry.empty())
    scene.trajectories.push_back({"dead reckoning (ODOMETRY, aligned at the start)", "#9467bd", 1.0, true, false,
                                  Thinned(AlignToTruthAtStart(in.log.odometry, in.log.truth, evaluation.max_truth_gap_us),
                                          o.track_step)});
  scene.trajectories.push_back({"driven (SIM_TRUTH)", "#000000", 1.5, false, false, Thinned(in.log.truth, o.track_step)});
  scene.trajectories.push_back({"estimated (POSE)", "#d62728", 1.0, false, false, Thinned(in.log.estimates, o.track_step)});

  SvgMarkers stations;
  stations.label = f.log_stations ? "scan stations (TASK_PLAN)" : "stops of the vehicle (no TASK_PLAN)";
  stations.color = "#1f77b4";
  stations.heading_ticks = true;
  stations.size_px = 4.0;
  stations.poses = f.stations;
  for (size_t i = 0; i < f.stations.size(); ++i) stations.texts.push_back(std::to_string(i + 1));
  scene.markers.push_back(std::move(stations));
  if (!in.log.truth.empty()) {
    SvgMarkers start;
    start.label = "start (true pose)";
    start.color = "#000000";
    start.shape = SvgMarkers::Shape::kSquare;
    start.heading_ticks = true;
    start.poses = {in.log.truth.front().pose};
    scene.markers.push_back(std::move(start));
  }
  SvgMarkers targets;
  targets.label = "cut targets";
  targets.color = "#ff7f0e";
  targets.shape = SvgMarkers::Shape::kDiamond;
  targets.heading_ticks = true;
  for (const CutFigures& c : f.cuts) {
    targets.poses.push_back(c.target);
    targets.texts.push_back(c.kind + " " + Fixed(c.truth.median, 2) + " m");
  }
  if (!targets.poses.empty()) scene.markers.push_back(std::move(targets));
  if (f.map.deviation.samples > 0) {
    SvgMarkers worst;
    worst.label = "largest map deviation (" + Fixed(f.map.deviation.max, 2) + " m)";
    worst.color = "#d62728";
    worst.shape = SvgMarkers::Shape::kCross;
    worst.poses = {Pose2(f.map.deviation.worst_point.x(), f.map.deviation.worst_point.y(), 0.0)};
    scene.markers.push_back(std::move(worst));
  }
  return scene;
}

}  // namespace minenav
