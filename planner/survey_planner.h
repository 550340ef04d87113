#pragma once
// The next scan station of a survey of unknown space (thesis 4.6: "Automatic sensor
// placement was not addressed in this thesis ... In the mine, this amounted to taking a scan
// at each 'intersection' and usually halfway between intersections").
//
// From the live contour map (its walls and the frontiers that close the known free space,
// planner/contour_free_space.h), the vehicle's pose and footprint and the stations visited,
// PlanNextStation chooses where to scan next:
//
//   frontiers     the frontiers at least min_frontier_length long. One whose middle a visited
//                 station saw from within looked_distance (nothing in between) and that is
//                 still open is a gap the ladar cannot close (out of range, a crack): dropped.
//   candidates    (a) before each frontier: the points of a square grid (standoff_step) about
//                 its middle, on its free side, min_standoff to max_standoff from the middle,
//                 moved up the clearance to the middle of their corridor (at most 2 m), in the
//                 known free space, at least min_wall_distance from walls and frontiers,
//                 with no wall between them and the frontier's middle (a long
//                 vehicle needs room before a frontier across its entry: the grid reaches
//                 down the entry as well as across it); (b) at intersections: points of a grid
//                 (intersection_spacing) in the known free space from which rays open into at
//                 least three separate arms (an arm: a ray that meets a frontier, or nothing,
//                 or a wall farther than twice the point's clearance), the most open of those
//                 within min_station_spacing of each other. None within min_station_spacing of a
//                 visited station.
//   prediction    from a candidate, prediction_rays rays out to sensor_range against walls and
//                 frontiers: a ray that meets a wall sees the map (overlap), one that meets a
//                 frontier sees unknown space behind it. OVERLAP = wall rays / (wall rays +
//                 frontier rays), the fraction of the station's predicted returns already in
//                 the map, which the mapper matches the scan against (>= min_overlap);
//                 NEW AREA = for each frontier ray, the sector between the frontier and
//                 unknown_depth beyond it (capped at sensor_range): dtheta/2 (r_far^2 - r^2)
//                 (>= min_new_area).
//   reachable     the path planner (Se2Planner on walls + frontiers: the known free space
//                 only, the request's footprint and clearance) from the vehicle's pose; the
//                 candidate's heading is the first of: the vehicle's heading, its opposite,
//                 along the nearest wall both ways (the corridor's axis), facing the frontier
//                 (or the arms), its opposite and square to it, where the footprint keeps
//                 clearance + station_margin (room to turn there again); the others follow
//                 when the first cannot be reached.
//   cost          path cost (m: the planner's cost, metres with reversing and cusps priced)
//                 - area_value x new area (m per m^2). Candidates are planned in order of a
//                 lower bound of the cost (the path length bound: a 2-D Dijkstra over the cells
//                 where the vehicle's centre fits, as the planner's own heuristic; a candidate
//                 no such corridor reaches is not reachable without a plan); planning stops when
//                 no unplanned candidate's bound can beat the best cost found. At most
//                 tries_per_frontier candidates planned per frontier (its best: if they cannot be
//                 reached the others are taken as unreachable too) and max_plans per decision;
//                 a plan that needs more than plan_expansions is "not reachable".
//   the vehicle   a frontier through the vehicle's own footprint is dropped: it stands where
//                 the ladar looked from (WithoutFrontiersAt).
//
// No candidate reachable and no frontier left that a station could still close: COMPLETE,
// with the reason ("no reachable frontier: 3 frontiers left, none reachable: ..."). Plans
// still to try when the budget ran out: FAILED (we do not know).
//
// Plain C++: no LCM, clock or I/O.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/se2_planner.h"
#include "planner/se2_planner_cache.h"
#include "planner/search_limits.h"
#include "planner/task.h"
#include "planner/task_map.h"

namespace minenav {

class OptionScope;

struct SurveyPlannerOptions {
  double sensor_range = 30.0;        // m, the ladar's useful range in the prediction. Default 30.
  int prediction_rays = 360;         // rays cast from a candidate to predict its scan. Default 360.
  double min_overlap = 0.5;          // fraction of a station's predicted returns already in the map. Default 0.5.
  double unknown_depth = 6.0;        // m beyond a frontier counted as new area (a room's width). Default 6.
  double area_value = 0.25;          // m of path cost one m^2 of new area is worth. Default 0.25.
  double min_new_area = 5.0;         // m^2 a station must be expected to see new. Default 5.
  double min_frontier_length = 1.0;  // m: shorter frontiers are gaps, not openings. Default 1.
  double min_standoff = 2.0;         // m from a frontier's middle to the nearest candidate before it. Default 2.
  double max_standoff = 12.0;        // m to the farthest. Default 12.
  double standoff_step = 1.0;        // m, grid of the candidates before one frontier. Default 1.
  // m: a candidate at least this far from every wall and frontier (a scan from the middle of
  // an entry sees its walls square on; one hugging a wall sees it edge-on). Default 1.5.
  double min_wall_distance = 1.5;
  // m: at a station the footprint keeps the request's clearance plus this from walls and
  // frontiers: the 10 m miner's ends swing 0.44 m when it turns one of the path planner's
  // 5-degree heading bins, and the next scans move the walls a few centimetres. Default 0.45.
  double station_margin = 0.45;
  // m between a candidate and any visited station (and between intersections). Default 3.
  double min_station_spacing = 3.0;
  // m: a frontier a visited station saw from this near and still open is dropped. Default 4.
  double looked_distance = 4.0;
  double intersection_spacing = 1.0;  // m, grid of the intersection search; 0 = no intersection candidates. Default 1.
  int max_plans = 24;                 // path plans per decision. Default 24.
  int tries_per_frontier = 2;         // candidates planned per frontier (the intersections count as one). Default 2.
  int64_t plan_expansions = 40'000;   // expansions each plan may take. Default 40,000.
};

// "" when usable, else one line naming the option.
std::string ValidateOptions(const SurveyPlannerOptions& options);
void DeclareOptions(OptionScope scope, SurveyPlannerOptions& options);

struct SurveyRequest {
  Pose2 vehicle;               // where the vehicle is (it has scanned there)
  double clearance = 0.0;      // m, the path keeps this from walls and frontiers
  std::vector<Pose2> visited;  // stations scanned before
};

// What a candidate station would see from `position` (PredictView).
struct PredictedView {
  int wall_rays = 0;      // rays that meet a wall within sensor_range
  int frontier_rays = 0;  // rays that meet a frontier within sensor_range
  double overlap = 0.0;   // wall_rays / (wall_rays + frontier_rays); 0 when neither
  double new_area = 0.0;  // m^2
};

struct StationCandidate {
  Pose2 pose;
  int frontier = -1;      // index in SurveyDecision::frontiers; -1 for an intersection
  double standoff = 0.0;  // m from the frontier's middle (frontier candidates)
  PredictedView view;
  double bound = 0.0;     // m: straight-line distance - area_value x new area
  bool feasible = false;  // passed the prediction (overlap, new area) and the footprint fits
  bool planned = false;
  int64_t expansions = 0;  // the path planner's, over every heading tried
  double path_cost = 0.0;  // m, when reachable
  double cost = 0.0;       // m: path_cost - area_value x new area, when reachable
  std::string rejected;    // why it is no station ("" while it may be)
};

struct FrontierState {
  Segment segment;
  size_t map_index = 0;  // in TaskMap::frontiers
  std::string dropped;   // why no station is looked for before it ("" = open)
};

struct SurveyDecision {
  TaskPlan plan;                         // OK: one SCAN_STATION; COMPLETE or FAILED with the reason
  std::vector<FrontierState> frontiers;  // the map's frontiers at least min_frontier_length long
  int short_frontiers = 0;               // frontiers shorter than that (ignored)
  std::vector<StationCandidate> candidates;
  std::optional<size_t> chosen;  // index into candidates
  PlannedPath path;              // from the vehicle to the chosen station
  int frontiers_at_vehicle = 0;  // frontiers through the vehicle's footprint (dropped)
  int plans = 0;                 // path plans made
  int64_t expansions = 0;        // their expansions
  // m the paths from the vehicle keep: the request's clearance, less when the vehicle stood
  // within it (what it had, Se2Planner::LeavingOptions).
  double path_clearance = 0.0;
};

// `planners`: where the path planners on this map are kept between requests (null: built
// for this request alone).
SurveyDecision PlanNextStation(const TaskMap& map, const Footprint& footprint, const SurveyRequest& request,
                               const SurveyPlannerOptions& options, const Se2PlannerOptions& planner_options,
                               const SearchLimits& limits = {}, Se2PlannerCache* planners = nullptr);

// The prediction of a scan from `position` on `map` (walls and frontiers), as PlanNextStation
// makes it (tests measure the overlap bound with it).
PredictedView PredictView(const TaskMap& map, const Eigen::Vector2d& position, const SurveyPlannerOptions& options);

}  // namespace minenav
