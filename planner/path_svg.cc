#include "planner/path_svg.h"

#include <algorithm>
#include <cmath>

namespace minenav {

SvgScene PathScene(const std::vector<Segment>& map, const Footprint& footprint, const PlannedPath& path,
                   const std::string& title, const ContourFreeSpace* space, const FreeSpaceOptions& free_space) {
  SvgScene scene;
  scene.title = title;
  if (space != nullptr) {
    // The known free space: runs of 0.5 m cells along x whose centres KnownFreeSpace holds.
    const KnownFreeSpace known(*space, free_space);
    SvgArea cells{"known free space", "#2ca02c", 0.2, {}};
    constexpr double kCell = 0.5;
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
    for (const Segment& s : map) {
      lo = lo.cwiseMin(s.a).cwiseMin(s.b);
      hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    }
    for (double y = lo.y(); y < hi.y(); y += kCell) {
      double run_start = 0.0;
      bool in_run = false;
      for (double x = lo.x(); x <= hi.x() + kCell; x += kCell) {
        const bool in = x < hi.x() && known.Contains({x + kCell / 2, y + kCell / 2});
        if (in && !in_run) run_start = x;
        if (!in && in_run) cells.polygons.push_back({{run_start, y}, {x, y}, {x, y + kCell}, {run_start, y + kCell}});
        in_run = in;
      }
    }
    scene.areas.push_back(cells);
    scene.lines.push_back({"walls (contours)", "#333333", 1.5, space->walls, {}});
    // Frontiers dashed: one two-pose dashed trajectory each, the first in the legend.
    for (const Segment& fr : space->frontiers)
      scene.trajectories.push_back({scene.trajectories.empty() ? "frontiers (end of what the ladar saw)" : "",
                                    "#d62728",
                                    1.5,
                                    true,
                                    false,
                                    {Pose2(fr.a.x(), fr.a.y(), 0.0), Pose2(fr.b.x(), fr.b.y(), 0.0)}});
  } else {
    scene.lines.push_back({"map", "#333333", 1.5, map, {}});
  }
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
        for (const auto& v : footprint.vertices) outline.points.push_back(q * v);
        footprints.polylines.push_back(outline);
        since_footprint = 0.0;
      }
    }
    from = p.end;
  }
  SvgPolyline start_outline{{}, true};
  for (const auto& v : footprint.vertices) start_outline.points.push_back(path.start * v);
  footprints.polylines.push_back(start_outline);
  scene.lines.push_back(footprints);
  scene.trajectories.push_back(traj);
  return scene;
}

}  // namespace minenav
