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
//   storage   the visited states, 40 bytes each, found by their (x, y, heading) cell in an
//             open-addressing table (state_table.h).
// Bounded by SearchLimits (expansions, stored states, stop callback); every answer says why.

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "planner/clearance_field.h"
#include "planner/corridor_route.h"
#include "planner/footprint.h"
#include "planner/footprint_collision.h"
#include "planner/grid_dijkstra.h"
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
  int collision_discs = 8;        // discs of the polygon's cover for the field's quick decisions. Default 8.
  // Heuristic: true adds the cheapest obstacle-free analytic shot's cost (a strong guide
  // towards the goal heading, but the shots are a subset of all paths, so it may overestimate);
  // false uses an admissible closed-form bound instead (FreeSpaceLowerBound). Default true.
  bool shot_heuristic = true;
  int cached_goals = 4;           // goals whose 2-D heuristic is kept between requests. Default 4.
  int analytic_shot_interval = 5;       // expansions between analytic shots (1 = every one). Default 5.
  double analytic_shot_max_length = 150.0;  // m, longer shots are not tried. Default 150.
  // Shots dearer than this times the cheapest shot are not tried (loops and detours: they
  // would cost collision checks and rarely win). Default 1.2.
  double analytic_shot_max_cost_ratio = 1.2;
  // m per 45 degrees: > 0 replaces the 2-D distance by LazyHeadingGridDistances over (cell,
  // heading in 45-degree steps; reversing at costs.reverse_factor) whose turns cost this
  // much where the centre has room (clearance >= the mean of the polygon's inscribed and
  // circumscribed radii + margin: the crossings), 4 times that elsewhere: the search follows
  // corridors with few turns instead of flooding every crossing of a staircase of equal 2-D
  // length. Not a lower bound (the vehicle's arcs turn at no extra cost): the search is then
  // not admissible. 0 = off. Default 0.
  double heuristic_turn_cost = 0.0;
  // With heuristic_turn_cost > 0: a request whose (cell, axis) path turns plans leg by leg
  // through waypoints in the middle of the path's straight runs (centred across the corridor,
  // heading along the run), each leg searched with at most corridor_leg_expansions; a leg
  // that fails falls back to the whole search. Not optimal (the waypoints are fixed). Default
  // true.
  bool corridor_waypoints = true;
  int corridor_leg_expansions = 100000;  // expansions a leg may take. Default 100,000.
  // A hierarchical first attempt (corridor_route.h): the 2-D route from start to goal over
  // (cell, 45-degree heading) with turns charged corridor_route_turn_cost, a waypoint
  // corridor_route_lead before and after each of its turns (centred across the entry, heading
  // along it); the straight legs between are analytic shots, each turn a local search of at
  // most corridor_turn_expansions. When a leg fails, Plan goes on as without it. Default true.
  bool corridor_route = true;
  double corridor_route_turn_cost = 6.0;  // m per 45 degrees of the route's turns. Default 6.
  double corridor_route_lead = 12.0;      // m of route before and after a turn's waypoints. Default 12.
  // m: requests whose goal is nearer the start than this are not routed (a maneuver at a
  // face: the full search is fast there, and the route's cusps in side arms would lengthen
  // its path many times). Default 50.
  double corridor_route_min_distance = 50.0;
  double corridor_route_resolution = 1.0;  // m, cells of the route's grid. Default 1.
  int corridor_turn_expansions = 5000;    // expansions a leg of the route may take. Default 5,000.
  MotionCosts costs;

  bool operator==(const Se2PlannerOptions&) const = default;  // every field equal (Se2PlannerCache)
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
  int64_t memory_bytes = 0; // the search's storage when it ended: its states, their table and the open list
  int64_t shots_tried = 0;  // analytic shots checked for collision
  CollisionCounters collisions;
};

class Se2Planner {
 public:
  // Builds the walls (the map's segments and the four sides of their bounding box: the map
  // ends there), the segment index, the clearance field and the collision checker. Bad
  // options or footprint: every Plan() answers kInvalidRequest with the reason.
  Se2Planner(std::vector<Segment> map, Footprint footprint, Se2PlannerOptions options);

  // Not to be called from two threads at once on one planner (it keeps the heuristics of
  // recent goals, the swept primitives and the collision counters).
  Se2PlanResult Plan(const Pose2& start, const Pose2& goal, const SearchLimits& limits = {}) const;
  // The waypoints a Plan would go through (tests, bench).
  std::vector<Pose2> Waypoints(const Pose2& start, const Pose2& goal) const {
    return setup_error_.empty() ? CorridorWaypoints(start, goal) : std::vector<Pose2>{};
  }
  // The corridor route's waypoints a Plan with corridor_route would go through (tests, bench).
  std::vector<Pose2> TurnWaypoints(const Pose2& start, const Pose2& goal) const {
    return setup_error_.empty() ? RouteWaypoints(start, goal) : std::vector<Pose2>{};
  }

  // Is the pose clear of the walls with the requested clearance (plus the sampling half-step)?
  bool PoseFree(const Pose2& pose) const;
  // The options of a planner for which `pose` is free, so that a vehicle standing there (it
  // stopped short where the map grew around it, or a cut's ribs are beside it) leaves with the
  // clearance it has: these options when the pose is free; else the clearance the pose has
  // from the walls less the sampling half-step (rounded down to 5 mm); within that half-step
  // of a wall, clearance 0 and a collision step fine enough (at least kLeastCollisionStep)
  // that the pose is free. nullopt when the footprint touches a wall, or comes within half
  // the least step of one: never planned in contact.
  std::optional<Se2PlannerOptions> LeavingOptions(const Pose2& pose) const;
  static constexpr double kLeastCollisionStep = 0.002;  // m
  // Does any checked pose along the piece, driven from `from`, collide?
  bool PieceCollides(const Pose2& from, const MotionPiece& piece) const;

  // "" when the planner is usable.
  const std::string& setup_error() const { return setup_error_; }
  const Se2PlannerOptions& options() const { return options_; }
  const Footprint& footprint() const { return footprint_; }
  const std::vector<Segment>& map() const { return map_; }
  Eigen::Vector2d map_min() const { return map_min_; }
  Eigen::Vector2d map_max() const { return map_max_; }

 // One primitive from one heading: the poses to check along it, relative to its start
  // position, no farther apart than collision_step for any point of the polygon.
  struct SweptPose {
    double dx, dy, theta, cos_theta, sin_theta;
  };
  struct SweptPrimitive {
    std::vector<SweptPose> poses;  // the last is the end pose
    double spacing = 0.0;          // m the farthest point of the polygon moves between poses
    int end_heading = 0;           // heading bin of the end pose
  };

 private:
  // The most cells of the clearance field (2^25: 1.1 km square at 0.2 m); a larger map is
  // refused as a setup error (a hostile map message's coordinates, issue 16).
  static constexpr double kMaxFieldCells = 33554432.0;

  std::string CheckPose(const Pose2& pose, const std::string& what) const;
  // The whole search from start to goal (Plan without the corridor waypoints). `shot_only`:
  // the request's checks and the analytic shot from the start only (kNoPath when none is free).
  Se2PlanResult Search(const Pose2& start, const Pose2& goal, const SearchLimits& limits,
                       bool shot_only = false) const;
  // The corridor waypoints between start and goal (empty when the axis path has no turn, or
  // no waypoint is free).
  std::vector<Pose2> CorridorWaypoints(const Pose2& start, const Pose2& goal) const;
  // The corridor route's waypoints (corridor_route): before and after each turn.
  std::vector<Pose2> RouteWaypoints(const Pose2& start, const Pose2& goal) const;
  // The (cell, heading) route from start to goal with turns at turn_cost m per 45 degrees.
  // On the field's cells, or on route_grid_'s (`coarse`); the steps' cells are the field's.
  std::vector<RouteStep> Route(const Pose2& start, const Pose2& goal, double turn_cost, bool coarse) const;
  // The pose at the centre of `cell` moved across its heading (x or y) to the cell of most
  // clearance within 5 m, with that heading.
  Pose2 CentredPose(GridCell cell, int heading) const;
  // The cell of most clearance across `heading` (x or y; diagonals: `cell`) within 5 m.
  GridCell CentredCell(GridCell cell, int heading) const;
  // Leg by leg through the waypoints, each leg at most leg_expansions: kFound with the chained
  // path, kStopped when the caller's limits stopped a leg, else kNoPath with the legs' work
  // (no waypoints: kNoPath and no work).
  Se2PlanResult PlanThrough(const Pose2& start, const std::vector<Pose2>& waypoints, const Pose2& goal,
                            const SearchLimits& limits, int64_t leg_expansions) const;
  // The swept primitives for headings phase + k * bin, k = 0 .. heading_bins - 1 (cached for
  // the last phase asked).
  const std::vector<SweptPrimitive>& PrimitivesFor(double phase) const;
  // The 2-D distances to the goal cell (cached for the last cached_goals goals).
  LazyGridDistances& DistancesTo(GridCell goal) const;
  // The (cell, heading) costs to the goal's state with turns at turn_cost m per 45 degrees
  // (cached with the 2-D distances' count).
  LazyHeadingGridDistances& HeadingDistancesTo(GridCell goal, int heading, double turn_cost) const;

  std::vector<Segment> map_;
  Footprint footprint_;
  Se2PlannerOptions options_;
  std::string setup_error_;
  Eigen::Vector2d map_min_ = Eigen::Vector2d::Zero(), map_max_ = Eigen::Vector2d::Zero();
  std::unique_ptr<StaticSegmentIndex> walls_;
  std::unique_ptr<ClearanceField> field_;
  std::unique_ptr<FootprintCollisionChecker> checker_;
  OccupancyGrid centre_cells_;  // the field's cells where the vehicle's centre may be
  std::vector<uint8_t> roomy_cells_;  // centre cells with room to turn (heuristic_turn_cost)
  RouteGrid route_grid_;              // the corridor route's coarse cells (corridor_route)
  mutable std::deque<std::unique_ptr<LazyHeadingGridDistances>> route_distances_;  // most recent first
  double largest_clearance_ = 0.0;
  mutable double primitives_phase_ = std::numeric_limits<double>::quiet_NaN();
  mutable std::vector<SweptPrimitive> primitives_;  // [heading * 8 + primitive]
  mutable std::deque<std::unique_ptr<LazyGridDistances>> goal_distances_;  // most recent first
  mutable std::deque<std::unique_ptr<LazyHeadingGridDistances>> goal_heading_distances_;  // most recent first
};

}  // namespace minenav
