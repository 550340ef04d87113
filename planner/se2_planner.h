#pragma once
// The SE(2) search for the miner's polygon on a segment map (thesis 6.2.2): hybrid A* over
// (x, y, heading) in the manner of Dolgov et al., "Path Planning for Autonomous Vehicles in
// Unknown Semi-structured Environments" (IJRR 2010) and Nav2 Smac Hybrid-A*:
//   motions   straight forward and back, arcs at the one turning radius both ways and both
//             directions, turning in place (one heading bin); each step of a straight move
//             or arc is as long as the arc that turns one heading bin, so arcs end on bins;
//   costs     metres driven, reversing, turning in place and changing direction (MotionCosts);
//   heuristic the larger of the cheapest obstacle-free analytic shot (analytic_shot.h) and a
//             2-D Dijkstra distance from the goal over the cells where the vehicle's centre
//             can be at all (clearance field >= inscribed radius + margin): dead ends are not
//             searched blindly, and a goal no corridor leads to is known before searching;
//   goal      reached by an analytic shot, tried every analytic_shot_interval expansions
//             and checked for collision along its whole length;
//   collision FootprintCollisionChecker at poses no farther apart than collision_step along
//             every motion (for every point of the polygon), against the map's walls with the
//             requested clearance plus half that step, so the polygon swept between the
//             checked poses keeps the requested clearance;
//   storage   the visited states in a hash map of (x, y, heading) cells.
// Bounded by SearchLimits (expansions, stored states, stop callback); every answer says why.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "planner/clearance_field.h"
#include "planner/footprint.h"
#include "planner/footprint_collision.h"
#include "planner/motion.h"
#include "planner/motion_costs.h"
#include "planner/occupancy_grid.h"
#include "planner/search_limits.h"

namespace minenav {

class OptionScope;

struct Se2PlannerOptions {
  double turn_radius = 4.0;       // m, the one turning radius besides 0 (sim/skid_steer.h's miner). Default 4.
  double clearance = 0.0;         // m, least distance from the polygon to any wall. Default 0.
  int heading_bins = 72;          // heading cells per turn (5 degrees). Default 72.
  double xy_resolution = 0.1;     // m, side of the (x, y) cells of the visited-state hash. Default 0.1.
  double field_resolution = 0.2;  // m, cells of the clearance field and the 2-D heuristic. Default 0.2.
  double collision_step = 0.05;   // m, most any point of the polygon moves between checked poses. Default 0.05.
  int analytic_shot_interval = 5;       // expansions between analytic shots (1 = every one). Default 5.
  double analytic_shot_max_length = 30.0;  // m, longer shots are not tried. Default 30.
  MotionCosts costs;
};

// "" when usable, else one line naming the option.
std::string ValidateOptions(const Se2PlannerOptions& options);
// turn_radius, clearance, heading_bins, ..., costs.* (costs nested under "costs").
void DeclareOptions(OptionScope scope, Se2PlannerOptions& options);

struct Se2PlanResult {
  SearchStatus status = SearchStatus::kNoPath;
  std::string reason;       // one line: why there is no path, or which bound stopped the search
  PlannedPath path;         // when found: pieces from start to goal, consecutive equal motions merged
  double cost = 0.0;        // the MotionCosts cost of the path
  int64_t expansions = 0;
  int64_t states = 0;       // states stored (memory)
  int64_t shots_tried = 0;  // analytic shots checked for collision
  CollisionCounters collisions;
};

class Se2Planner {
 public:
  // Builds the walls (the map's segments and the four sides of their bounding box: the map
  // ends there), the segment index, the clearance field and the collision checker. Bad
  // options or footprint: every Plan() answers kInvalidRequest with the reason.
  Se2Planner(std::vector<Segment> map, Footprint footprint, Se2PlannerOptions options);

  Se2PlanResult Plan(const Pose2& start, const Pose2& goal, const SearchLimits& limits = {}) const;

  // Is the pose clear of the walls with the requested clearance (plus the sampling half-step)?
  bool PoseFree(const Pose2& pose) const;
  // Does any checked pose along the piece, driven from `from`, collide?
  bool PieceCollides(const Pose2& from, const MotionPiece& piece) const;

  // "" when the planner is usable.
  const std::string& setup_error() const { return setup_error_; }
  const Se2PlannerOptions& options() const { return options_; }
  const Footprint& footprint() const { return footprint_; }
  const std::vector<Segment>& map() const { return map_; }
  Eigen::Vector2d map_min() const { return map_min_; }
  Eigen::Vector2d map_max() const { return map_max_; }

 private:
  std::string CheckPose(const Pose2& pose, const std::string& what) const;

  std::vector<Segment> map_;
  Footprint footprint_;
  Se2PlannerOptions options_;
  std::string setup_error_;
  Eigen::Vector2d map_min_ = Eigen::Vector2d::Zero(), map_max_ = Eigen::Vector2d::Zero();
  std::unique_ptr<StaticSegmentIndex> walls_;
  std::unique_ptr<ClearanceField> field_;
  std::unique_ptr<FootprintCollisionChecker> checker_;
  OccupancyGrid centre_cells_;  // the field's cells where the vehicle's centre may be
  double largest_clearance_ = 0.0;
};

}  // namespace minenav
