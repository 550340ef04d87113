// Fuzz target: task_planner's handlers (planner/task_planner_node.h) with hostile TASK_REQUEST,
// CONTOUR_MAP, LINE_MAP and POSE (fuzz/node_fuzz.h), in batch (the node plans on its own
// thread then, every request answered in order; the expansion budgets bound each search):
// every TASK_PLAN it sends must be one the coordinator accepts.

#include "fuzz/node_fuzz.h"
#include "planner/task_planner_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h =
      fuzz::NodeFuzzHarness::Batch("task_planner", data, size, {"TASK_REQUEST", "CONTOUR_MAP", "LINE_MAP", "POSE"});
  h->ExpectOutput<task_plan_t>("TASK_PLAN");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  TaskPlannerNodeOptions options;
  options.line_map_channel = "LINE_MAP";
  static const Footprint footprint = Normalized(FootprintFromFlag(options.footprint));
  TaskPlannerNode node(h->runtime(), options, footprint);
  node.Run();
  return 0;
}
