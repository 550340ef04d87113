#pragma once
// The picture of a finished mission (render/svg_render.h): the true walls at the start (light)
// and at the end (dark: the cuts show), the final contour map, what the map shows free (and
// what it wrongly shows free, and the free space it never saw), the planned paths sampled along
// their motions, the driven track (SIM_TRUTH), the estimated track (POSE) and dead reckoning
// (ODOMETRY), the scan stations, the cut faces with the requested new face, where the map is
// worst; the headline figures as notes. Plain C++ (no LCM, no I/O).

#include <string>
#include <vector>

#include "evaluation/mission_evaluation.h"
#include "render/svg_render.h"

namespace minenav {

struct MissionPictureOptions {
  std::string title = "MINENAV mission";
  double path_step = 0.1;    // m between samples along a planned path's pieces (arcs, straight moves)
  double track_step = 0.05;  // m: a track keeps a pose this far from the last one kept
  bool free_space = true;    // draw the explored-area grid's cells
  bool odometry = true;      // draw ODOMETRY (aligned at its start)
  SvgRenderOptions render = WideLegend();  // the drawing's size; the legend wider than render's default

  static SvgRenderOptions WideLegend() {
    SvgRenderOptions r;
    r.legend_width_px = 420.0;
    return r;
  }
};

// The poses along a path: the start, then every piece sampled at most `step` m (or 0.1 rad of
// a turn in place) apart, ending on each piece's end.
std::vector<Pose2> SamplePath(const PlannedPath& path, double step);

SvgScene MissionScene(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& evaluation,
                      const MissionPictureOptions& options = {});

}  // namespace minenav
