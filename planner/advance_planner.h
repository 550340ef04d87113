#pragma once
// Advancing a section (thesis 6.1, 6.2.1, Figure 40): "a corridor is extended by executing
// two parallel cuts: the box cut and the slab cut. The miner must precisely maneuver into
// position before the box cut, then maneuver to reposition for the slab cut. After the slab
// cut, the miner must back out to make way for the roof bolter."
//
// From the entry's geometry (entry_geometry.h), the vehicle's footprint, the cutter's reach
// and drum width and the desired depth, PlanAdvance makes the subtasks
//
//   MOVE      into position for the box cut: squared to the face (heading = the face's
//             normal, as the cutter squares up), on the `box_cut_side` of the entry, the
//             vehicle's side (or the drum's end, whichever sticks out more) clearance +
//             side_margin from the rib where it comes nearest over the vehicle's length and
//             `approach_length` behind it (so the vehicle can back straight out: walls
//             wander), the drum's front clearance + standoff from the nearest face point
//             across the vehicle's width;                                         STOWED
//   BOX_CUT   from there with the drum standoff from the face (where the cutter starts its
//             sump), `depth` deep, drum width wide; the face as the drum meets it; CUTTING
//   MOVE      to reposition: the same beside the other rib (the path planner's multi-point
//             maneuver; checked from the box cut's MOVE pose: the vehicle trams straight
//             back out of the cut it just made);                                  STOWED
//   SLAB_CUT  the rest of the entry's width, same depth;                          CUTTING
//   BACK_OUT  back out of the last cut along the entry's axis (straight back when the face
//             is square), squared to the face still, the drum's front bolter_gap behind the
//             advanced face, reversing allowed;                                   STOWED
//
// each depending on the one before. An entry wider than the box cut and one slab cut can
// cover (two drum widths plus the margins) gets more slab cuts, evenly spaced; one whose
// width leaves no room beside the box cut gets the box cut alone, centred (and when it is
// narrower than the drum, the box cut is the whole width: the plan's reason says so).
// Between the ribs the cuts leave clearance + side_margin uncut on each side (0.55 m with the
// defaults: the room the path planner needs to turn the 10 m miner one heading bin there).
//
// Every driving goal is checked: in the known free space (contour maps), and reachable by
// the path planner (Se2Planner on the same map: walls and frontiers, the same footprint and
// the request's clearance) from where the task before leaves the vehicle. A goal that is not
// makes the plan FAILED with the planner's reason.
//
// Plain C++: no LCM, clock or I/O.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "planner/entry_geometry.h"
#include "planner/footprint.h"
#include "planner/se2_planner.h"
#include "planner/se2_planner_cache.h"
#include "planner/search_limits.h"
#include "planner/task.h"
#include "planner/task_map.h"
#include "tracker/cutter.h"

namespace minenav {

class OptionScope;

struct AdvanceOptions {
  double reach = CutterOptions{}.reach;  // m, vehicle pose to the drum's front (the cutter's cutter.reach). Default 5.
  double drum_width = CutterOptions{}.width;  // m, the drum's width (the cutter's cutter.width). Default 3.3.
  // m, drum front to face where a cut starts (the cutter's cutter.standoff). Default 0.1.
  double standoff = CutterOptions{}.standoff;
  // m between the vehicle's side (or the drum's end) and a rib at a cut, beyond the clearance:
  // room to turn. The path planner turns in heading bins (5 degrees by default) and the 10 m
  // miner's ends swing 0.44 m for one bin: with less, a vehicle beside a rib can only drive
  // straight along it, and the reposition to the other rib has no path unless a crossing
  // behind gives room. The cuts leave clearance + side_margin of coal at each rib. Default 0.45.
  double side_margin = 0.45;
  // m behind the vehicle at a cut over which the rib's nearest point counts: the vehicle can
  // back this far straight out of its cutting position. Default 10.
  double approach_length = 10.0;
  // "right" or "left" (looking at the face): where the box cut goes. Default right.
  std::string box_cut_side = "right";
  // m, the drum's front to the advanced face after backing out: the room the roof bolter
  // needs in front of the miner. Default 12.
  double bolter_gap = 12.0;
  double max_depth = 10.0;  // m: deeper requests are refused (the cutter's 20 cycles of 0.5 m). Default 10.
  int max_slab_cuts = 4;    // an entry that needs more is refused. Default 4.
  int64_t maneuver_expansions = 300'000;  // expansions each maneuver check may take. Default 300,000.
  EntryOptions entry;
};

// "" when usable, else one line naming the option.
std::string ValidateOptions(const AdvanceOptions& options);
// reach, drum_width, standoff, side_margin, approach_length, box_cut_side, bolter_gap, max_depth, max_slab_cuts,
// maneuver_expansions, entry.*.
void DeclareOptions(OptionScope scope, AdvanceOptions& options);

struct AdvanceRequest {
  Pose2 vehicle;                                        // where the vehicle is (map frame)
  Eigen::Vector2d face_hint = Eigen::Vector2d::Zero();  // m, a point in front of the face
  double direction = 0.0;                               // rad, the direction of advance
  double depth = 0.0;                                   // m, how far to advance the face
  double clearance = 0.0;                               // m, the maneuvers keep this from the walls
};

// One driving goal checked by the path planner.
struct ManeuverCheck {
  size_t task = 0;  // index in plan.tasks
  Pose2 start, goal;
  Se2PlanResult result;
};

struct AdvanceResult {
  TaskPlan plan;
  std::optional<EntryGeometry> entry;    // when the entry was found
  std::vector<ManeuverCheck> maneuvers;  // the checks made (the last one failed when the plan did)
  // Set when the vehicle stood within the request's clearance of a wall: the clearance its
  // first maneuver was checked with (what it has, Se2Planner::LeavingOptions).
  std::optional<double> leaving_clearance;
};

// `planners`: where the path planners on this map are kept between requests (null: built
// for this request alone).
AdvanceResult PlanAdvance(const TaskMap& map, const Footprint& footprint, const AdvanceRequest& request,
                          const AdvanceOptions& options, const Se2PlannerOptions& planner_options,
                          const SearchLimits& limits = {}, Se2PlannerCache* planners = nullptr);

}  // namespace minenav
