#pragma once
// The path planner benches' scenarios (bench/planner_bench.cc, bench/planner_ompl_bench.cc):
// mines of 4 x 6 pillars (12 m pillars, 6 m entries by default, walls jittered by the fractal midpoint
// displacement of sim/mine_generator.h) and the maneuvers on them. Faces close some entries
// between two crossings (a wall across the entry, as at a development heading). Scenarios,
// each on every seed's mine:
//   box_cut    from 10-18 m back in the entry up to the face (nose 0.6 m from it), the face
//              a wall across the entry 1 m before the next crossing (an 11 m dead end);
//   slab_cut   at the face, shifted sideways across the entry (one side to the other);
//   back_out   from the face backwards round the corner into the crosscut behind;
//   turn       from an entry 12 m before a crossing into the crosscut, 12 m past it;
//   long_entry along a whole entry (101 m), lateral offset and heading changed at the ends;
//   long       across the section, corner to corner (> 100 m straight-line distance).
// Per seed two maps (the plain mine, and the mine with that seed's faces), each with its
// planner (the poses near a face are nudged until the planner finds them free).

#include <memory>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "planner/footprint.h"
#include "planner/se2_planner.h"

namespace minenav::bench {

// The scenario names in the order the benches print them.
const std::vector<std::string>& PlannerScenarioNames();

struct PlannerRequest {
  std::string scenario;
  const Se2Planner* planner = nullptr;  // one of PlannerScenarios::planners
  Pose2 start, goal;
};

struct PlannerScenarios {
  std::vector<std::unique_ptr<Se2Planner>> planners;
  std::vector<std::vector<Segment>> maps;  // maps[i] is planners[i]'s map
  std::vector<double> setup_s;             // thread CPU s to build planners[i]
  std::vector<PlannerRequest> requests;    // seed by seed: faces, turns, long_entry, long

  // The index into maps of the request's planner.
  size_t MapIndex(const PlannerRequest& request) const;
};

// Mines for seeds 1..seeds, `instances` requests per scenario and mine, walls jittered by
// `displacement` m, entries and crosscuts `room_width` m wide (6 m: a miner turning at a
// crossing has 0.077 m at 45 deg, planner_test; 6.5 m: 0.37 m). Throws std::runtime_error
// when a planner cannot be built.
PlannerScenarios BuildPlannerScenarios(int seeds, int instances, double displacement, const Footprint& footprint,
                                       const Se2PlannerOptions& options, double room_width = 6.0);

}  // namespace minenav::bench
