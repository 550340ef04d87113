#pragma once
// Builds the picture of a logged run (svg_render.h) from a log, an optional world and an
// optional map: world walls, map, scans at truth poses (and optionally at odometry
// poses), trajectories truth vs odometry vs every POSE* channel, and error links.

#include <string>
#include <vector>

#include "logger/run_log.h"
#include "render/svg_render.h"

namespace minenav {

struct LogRenderOptions {
  std::vector<std::string> world_paths;  // segments JSON; several = one layer each
  std::string map_path;        // segments JSON or contour-map JSON; "" = none
  std::string scan_channel = "LADAR_SCAN";
  std::string truth_channel = "SIM_TRUTH";
  std::string odometry_channel = "ODOMETRY";
  // Where scans are drawn: "auto" (truth if the log has it, else odometry), "truth",
  // "odometry", "none", or any pose channel name.
  std::string scans_at = "auto";
  bool scans_at_odometry = false;  // also draw scans at odometry poses (second colour)
  int max_points_per_scan = 1024;  // readings kept per scan (evenly strided); 0 = all
  int max_scans = 200;             // scans drawn, evenly spaced over the log; 0 = all
  int64_t max_pose_gap_us = 500000;  // us; interpolate a pose between two at most this far apart
  std::string title;               // default: the log's path
};

struct LogRenderResult {
  SvgScene scene;
  int scans_drawn = 0;
  int scans_without_pose = 0;  // no pose of the chosen track at their utime
};

// Throws InputError for unreadable inputs, or when scans_at names a channel that is not
// in the log.
LogRenderResult BuildLogScene(const std::string& log_path, const LogRenderOptions& options);

// {"contours": [{"closed": false, "points": [[x, y], ...]}, ...]} (DESIGN.md "File
// contracts"). Throws InputError naming the file and entry.
std::vector<SvgPolyline> ParseContoursJson(const std::string& text, const std::string& source_name);

}  // namespace minenav
