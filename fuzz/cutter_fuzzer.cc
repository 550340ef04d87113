// Fuzz target: the cutter's handlers (tracker/cutter_node.h) with hostile CUT_TASK, POSE,
// ODOMETRY, CUTTER_STATE and CONTOUR_MAP (fuzz/node_fuzz.h): every DRIVE_COMMAND, CUTTER_COMMAND
// and TASK_STATUS it sends must be one its receivers accept.

#include "fuzz/node_fuzz.h"
#include "tracker/cutter_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("cutter");
  h->ExpectOutput<drive_command_t>("DRIVE_COMMAND");
  h->ExpectOutput<cutter_command_t>("CUTTER_COMMAND");
  h->ExpectOutput<task_status_t>("TASK_STATUS");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  CutterNode node(h->runtime(), CutterNodeOptions{});
  h->Feed(data, size, {"CUT_TASK", "POSE", "ODOMETRY", "CUTTER_STATE", "CONTOUR_MAP"});
  return 0;
}
