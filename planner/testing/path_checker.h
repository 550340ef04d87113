#pragma once
// The tests' independent judge of a planned path: its own geometry, none of the planner's
// collision code. A path is a start pose and, per piece, a motion and the pose it ends at
// (what the path CSV holds). The checker
//   * checks that each piece is a motion the vehicle can make between its two poses: a
//     straight move along the heading (forward or back), an arc of exactly the turning radius
//     about a centre on the side the motion names, travelled the way the direction says, or
//     a turn in place (the shorter way round);
//   * samples the polygon densely along every piece (no point of it moves more than
//     sample_step between samples) and measures the distance to every segment of the map by
//     brute force; any sample closer than the clearance is contact.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav::testing {

struct CheckedPiece {
  int motion = 0;  // path_segment_t's constants: 0 forward ... 6 arc right reverse
  Pose2 end;
};

struct PathCheckReport {
  bool ok = false;
  std::string problem;         // the first thing wrong, "" when ok
  double min_clearance = 0.0;  // m, least distance from the sampled polygon to any segment
  double length = 0.0;         // m driven (turns in place count 0)
  int samples = 0;
};

struct PathCheckSettings {
  std::vector<Eigen::Vector2d> polygon;  // vehicle frame
  double turn_radius = 4.0;              // m
  double clearance = 0.0;                // m
  double sample_step = 0.01;             // m
  double pose_tolerance = 1e-5;          // m and rad, for the motion checks
};

// m, least distance from `polygon` (vehicle frame) at `pose` to any segment of `map`, by brute
// force (0 on contact): the same judge, for poses a vehicle drove rather than planned ones.
double PoseClearance(const std::vector<Segment>& map, const std::vector<Eigen::Vector2d>& polygon, const Pose2& pose);

PathCheckReport CheckPath(const std::vector<Segment>& map, const Pose2& start, const std::vector<CheckedPiece>& pieces,
                          const PathCheckSettings& settings);

}  // namespace minenav::testing
