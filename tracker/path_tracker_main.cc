// path_tracker: pure pursuit along the path planner's PATH on the fleet's pose estimates
// (POSE) predicted with ODOMETRY between them, checked against the map (CONTOUR_MAP); one
// DRIVE_COMMAND per tick, TASK_STATUS per path. The node is tracker/path_tracker_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "tracker/path_tracker_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  PathTrackerNodeOptions options;
  return RunNodeProcess(
      "path_tracker", "Tracks the planner's paths on the pose estimates (pure pursuit, thesis 6.4.2).", args,
      [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        const Footprint footprint = LoadTrackerFootprint(options);
        runtime.Start();
        PathTrackerNode node(runtime, options, footprint);
        return node.Run();
      });
}
