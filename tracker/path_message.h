#pragma once
// path_t (lcmtypes/path_t.lcm) <-> the planner's PlannedPath (planner/motion.h). A piece's
// amount is not on the wire: it is recovered from the poses (the distance for straight moves,
// radius times the heading change for arcs, the heading change for turns in place), and the
// piece is checked to be that motion between its poses (PoseAfter within 2 cm and 0.5 deg).
// Throws InputError with one line naming the segment.

#include <cstdint>
#include <string>

#include "minenav/path_t.hpp"
#include "planner/motion.h"

namespace minenav {

struct PathMessage {
  int64_t utime = 0;
  int64_t request_id = 0;
  bool feasible = false;
  std::string status;
  PlannedPath path;
};

// turn_radius (m): arcs must have it (within 1 %).
PathMessage PathFromLcm(const path_t& m, double turn_radius);
// The path as path_t segments (motion, end pose, radius, speed: m/s, every segment's limit)
// tagged with request_id. The same signature as the live path_planner's (planner/
// path_planner_node.h, branch of issue 13): one of the two goes when both are merged.
path_t PathToLcm(const PlannedPath& path, int64_t request_id, int64_t utime, double speed, const std::string& status);

}  // namespace minenav
