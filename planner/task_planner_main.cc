// task_planner: the subtasks of a mission (planner/README.md "Task planner"): answers
// TASK_REQUEST with TASK_PLAN on the live contour map (planner/task_planner_node.h):
// SURVEY_NEXT the next scan station (planner/survey_planner.h), ADVANCE the box cut, slab
// cut(s) and backing out (planner/advance_planner.h). Option parsing and wiring only.

#include <string>
#include <vector>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "planner/planner_batch.h"
#include "planner/task_planner_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  TaskPlannerNodeOptions options;
  return RunNodeProcess(
      "task_planner",
      "Plans the subtasks of a mission on the live contour map: answers TASK_REQUEST with TASK_PLAN. SURVEY_NEXT: "
      "the next scan station (frontiers, intersections, overlap with the map, reachable by the path planner); "
      "ADVANCE: move into position, box cut, reposition, slab cut(s), back out for the roof bolter.",
      args, [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        if (const std::string e = ValidateOptions(options); !e.empty()) throw UsageError(e);
        Footprint footprint = FootprintFromFlag(options.footprint);
        if (const std::string e = ValidateFootprint(footprint); !e.empty()) throw UsageError("--footprint: " + e);
        runtime.Start();
        TaskPlannerNode node(runtime, options, Normalized(std::move(footprint)));
        return node.Run();
      });
}
