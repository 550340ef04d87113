// Fuzz target: waypoint_driver's handler (tracker/waypoint_driver_node.h) with hostile ODOMETRY
// (fuzz/node_fuzz.h): every DRIVE_COMMAND it sends must be one the vehicle accepts.

#include "fuzz/node_fuzz.h"
#include "tracker/waypoint_driver_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("waypoint_driver");
  h->ExpectOutput<drive_command_t>("DRIVE_COMMAND");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  const std::vector<Station> stations = {{Pose2(2, 0, 0), 0}, {Pose2(2, 2, 1.57), 0}, {Pose2(0, 0, 3.14), 0}};
  WaypointDriverNode node(h->runtime(), WaypointDriverDefaults({}), stations);
  h->Feed(data, size, {"ODOMETRY"});
  return 0;
}
