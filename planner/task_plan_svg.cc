#include "planner/task_plan_svg.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include "planner/path_svg.h"

namespace minenav {
namespace {

SvgPolyline Outline(const Footprint& footprint, const Pose2& pose) {
  return SvgPolyline{footprint.At(pose), true};
}

// A dashed two-pose trajectory per segment (how PathScene draws frontiers); the first labelled.
void AddDashed(SvgScene& scene, const std::vector<Segment>& segments, const std::string& label,
               const std::string& color) {
  for (size_t k = 0; k < segments.size(); ++k)
    scene.trajectories.push_back(
        {k == 0 ? label : "",
         color,
         1.5,
         true,
         false,
         {Pose2(segments[k].a.x(), segments[k].a.y(), 0.0), Pose2(segments[k].b.x(), segments[k].b.y(), 0.0)}});
}

}  // namespace

SvgScene SurveyScene(const TaskMap& map, const Footprint& footprint, const SurveyRequest& request,
                     const SurveyDecision& d, const std::string& title) {
  const ContourFreeSpace space = map.AsFreeSpace();
  PlannedPath path = d.path;
  if (!d.chosen) path = PlannedPath{request.vehicle, {}};
  SvgScene scene = PathScene(map.Boundary(), footprint, path, title, &space);
  // PathScene drew every frontier dashed red; keep its known free space and walls, redraw the frontiers.
  std::erase_if(scene.trajectories, [](const SvgTrajectory& t) { return t.dashed; });
  std::vector<Segment> open, dropped, short_ones;
  for (const FrontierState& f : d.frontiers) (f.dropped.empty() ? open : dropped).push_back(f.segment);
  for (const Segment& f : map.frontiers)
    if (std::none_of(d.frontiers.begin(), d.frontiers.end(),
                     [&](const FrontierState& s) { return s.segment.a == f.a && s.segment.b == f.b; }))
      short_ones.push_back(f);
  AddDashed(scene, open, "open frontiers", "#d62728");
  AddDashed(scene, dropped, "frontiers seen close up and still open (gaps)", "#7f7f7f");
  AddDashed(scene, short_ones, "gaps shorter than min_frontier_length", "#c7c7c7");
  SvgPointLayer possible{
      "candidate stations (overlap and new area enough, the footprint fits)", "#1f77b4", 2.5, 0.9, {}};
  SvgPointLayer rejected{"rejected candidates (overlap, new area, footprint)", "#aaaaaa", 1.8, 0.7, {}};
  SvgPointLayer crossings{"intersection candidates", "#9467bd", 3.0, 0.9, {}};
  for (const StationCandidate& c : d.candidates) {
    if (c.frontier < 0)
      crossings.points.push_back(c.pose.translation());
    else
      (c.feasible ? possible : rejected).points.push_back(c.pose.translation());
  }
  scene.points.push_back(rejected);
  scene.points.push_back(possible);
  scene.points.push_back(crossings);
  SvgTrajectory visited{"stations visited", "#17becf", 1.0, true, true, request.visited};
  visited.poses.push_back(request.vehicle);
  scene.trajectories.push_back(visited);
  if (d.chosen) {
    const Pose2& chosen = d.candidates[*d.chosen].pose;
    scene.trajectories.push_back({"chosen station", "#2ca02c", 3.0, false, true, {chosen}});
    scene.lines.push_back({"", "#2ca02c", 2.0, {}, {Outline(footprint, chosen)}});
  }
  scene.notes.push_back(d.plan.reason);
  return scene;
}

SvgScene AdvanceScene(const TaskMap& map, const Footprint& footprint, const AdvanceRequest& request,
                      const AdvanceResult& result, const std::string& title) {
  // The walls near the way to the face (kWindow m about the hint and the vehicle): the entry,
  // not the whole mine.
  constexpr double kWindow = 25.0;
  auto near = [&](const Segment& s) {
    for (const Eigen::Vector2d& c : {request.face_hint, request.vehicle.translation()})
      if ((s.a - c).cwiseAbs().maxCoeff() < kWindow || (s.b - c).cwiseAbs().maxCoeff() < kWindow) return true;
    return false;
  };
  TaskMap window;
  window.oriented = map.oriented;
  std::copy_if(map.walls.begin(), map.walls.end(), std::back_inserter(window.walls), near);
  std::copy_if(map.frontiers.begin(), map.frontiers.end(), std::back_inserter(window.frontiers), near);
  const ContourFreeSpace space = window.AsFreeSpace();
  SvgScene scene = PathScene(window.Boundary(), footprint, PlannedPath{request.vehicle, {}}, title,
                             window.oriented ? &space : nullptr);
  std::erase_if(scene.trajectories, [](const SvgTrajectory& t) { return t.poses.size() < 2; });  // no path of its own
  std::erase_if(scene.lines, [](const SvgLineLayer& l) { return l.label == "footprint"; });
  scene.lines.push_back({"the vehicle", "#7f7f7f", 1.2, {}, {Outline(footprint, request.vehicle)}});
  if (result.entry) {
    const EntryGeometry& e = *result.entry;
    scene.lines.push_back({"face found", "#8c564b", 3.0, {e.face}, {}});
    SvgPointLayer ribs{"rib hits", "#8c564b", 1.5, 0.8, {}};
    for (const Eigen::Vector2d& p : e.left_hits) ribs.points.push_back(e.entry_frame * p);
    for (const Eigen::Vector2d& p : e.right_hits) ribs.points.push_back(e.entry_frame * p);
    scene.points.push_back(ribs);
  }
  SvgLineLayer moves{"move goals", "#ff7f0e", 1.2, {}, {}}, cuts{"cuts (drum at the standoff)", "#d62728", 1.2, {}, {}},
      back{"back out", "#2ca02c", 1.2, {}, {}};
  for (const Task& t : result.plan.tasks) {
    SvgLineLayer& layer = t.kind == TaskKind::kMove ? moves : t.kind == TaskKind::kBackOut ? back : cuts;
    layer.polylines.push_back(Outline(footprint, t.target));
    if (t.kind == TaskKind::kBoxCut || t.kind == TaskKind::kSlabCut) cuts.segments.push_back(t.face);
  }
  scene.lines.push_back(moves);
  scene.lines.push_back(cuts);
  scene.lines.push_back(back);
  for (size_t k = 0; k < result.maneuvers.size(); ++k) {
    const ManeuverCheck& m = result.maneuvers[k];
    SvgTrajectory path{k == 0 ? "maneuvers (path planner)" : "", "#1f77b4", 1.5, false, false, {m.start}};
    Pose2 from = m.start;
    for (const MotionPiece& p : m.result.path.pieces) {
      const double extent = p.motion == Motion::kTurnInPlace ? 0.0 : p.amount;
      const int n = std::max(1, static_cast<int>(std::ceil(extent / 0.5)));
      for (int i = 1; i <= n; ++i) path.poses.push_back(PoseAfter(from, p.motion, p.amount * i / n, p.radius));
      from = p.end;
    }
    scene.trajectories.push_back(path);
  }
  scene.notes.push_back(result.plan.reason);
  return scene;
}

}  // namespace minenav
