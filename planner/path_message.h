#pragma once
// path_t (lcmtypes/path_t.lcm) <-> the planner's PlannedPath (used by the path_planner and
// the path_tracker nodes) (planner/motion.h). A piece's
// amount is not on the wire: it is recovered from the poses (the distance for straight moves,
// radius times the heading change for arcs, the heading change for turns in place), and the
// piece is checked to be that motion between its poses (PoseAfter within 2 cm and 0.5 deg).
// Throws InputError with one line naming the segment.

#include <cstdint>
#include <string>
#include <vector>

#include "minenav/path_t.hpp"
#include "planner/motion.h"

namespace minenav {

struct PathMessage {
  int64_t utime = 0;
  int64_t request_id = 0;
  bool feasible = false;
  std::string status;
  PlannedPath path;
  std::vector<double> speeds;  // m/s, each piece's speed limit (the segment's speed; 0 = none)
};

// turn_radius (m): arcs must have it (within 1 %); a segment speed must be finite and >= 0.
PathMessage PathFromLcm(const path_t& m, double turn_radius);
// The path as path_t segments (motion, end pose, radius, speed: m/s, every segment's limit)
// tagged with request_id: what the live path_planner publishes.
path_t PathToLcm(const PlannedPath& path, int64_t request_id, int64_t utime, double speed, const std::string& status);
// The answer without a path (feasible false; status says why).
path_t NoPathToLcm(int64_t request_id, int64_t utime, const std::string& status);

}  // namespace minenav
