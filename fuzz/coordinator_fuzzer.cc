// Fuzz target: the coordinator's handlers (coordinator/coordinator_node.h) with hostile
// HEARTBEAT, POSE, TASK_PLAN, PATH, TASK_STATUS, CUTTER_STATE and operator commands
// (fuzz/node_fuzz.h), the mission started at once: every request, cut task, drive command and
// mission status it sends must be one its receivers accept. DRIVE_PATH forwards the planner's
// answers as they came (the tracker checks their motions), so only their numbers are checked.

#include "coordinator/coordinator_node.h"
#include "fuzz/node_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("coordinator");
  h->ExpectOutput<task_request_t>("TASK_REQUEST");
  h->ExpectOutput<path_request_t>("PATH_REQUEST");
  h->ExpectOutput("DRIVE_PATH", [](const uint8_t* bytes, size_t n) {
    path_t m{};
    std::string error;
    if (!DecodeMessage(bytes, static_cast<int>(n), "DRIVE_PATH", &m, &error)) fuzz::Fail("published garbage: " + error);
    try {
      fuzz::CheckAccepted(m, /*check_motions=*/false);
    } catch (const std::exception& e) {
      fuzz::Fail(std::string("published on DRIVE_PATH what the tracker rejects: ") + e.what());
    }
  });
  h->ExpectOutput<cutter_command_t>("CUT_TASK");
  h->ExpectOutput<drive_command_t>("DRIVE_COMMAND");
  h->ExpectOutput<mission_status_t>("MISSION_STATUS");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");  // its own (the fake bus does not loop it back)
  CoordinatorNodeOptions options;
  options.mission.auto_start = true;
  options.mission.face = "15,9,0";
  options.mission.required = "contour_mapper,path_planner,path_tracker,task_planner,cutter";  // as in the seed
  CoordinatorNode node(h->runtime(), options);
  h->Feed(data, size,
         {"HEARTBEAT", "POSE", "TASK_PLAN", "PATH", "TASK_STATUS", "CUTTER_STATE", "COORDINATOR_COMMAND"});
  return 0;
}
