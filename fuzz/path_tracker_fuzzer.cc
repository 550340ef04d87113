// Fuzz target: path_tracker's handlers (tracker/path_tracker_node.h) with hostile PATH, POSE,
// ODOMETRY and maps (fuzz/node_fuzz.h): whatever it gets, every DRIVE_COMMAND and TASK_STATUS it
// sends must be one the vehicle and the coordinator accept (finite speeds, known states).

#include "fuzz/node_fuzz.h"
#include "tracker/path_tracker_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("path_tracker");
  h->ExpectOutput<drive_command_t>("DRIVE_COMMAND");
  h->ExpectOutput<task_status_t>("TASK_STATUS");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  PathTrackerNodeOptions options;
  options.line_map_channel = "LINE_MAP";
  PathTrackerNode node(h->runtime(), options, Footprint::Rectangle(options.vehicle_width, options.vehicle_length));
  h->Feed(data, size, {"PATH", "POSE", "ODOMETRY", "CONTOUR_MAP", "LINE_MAP"});
  return 0;
}
