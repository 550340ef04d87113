// coordinator: the mission's task tree in place of TCA (thesis 6.1): waits for the fleet,
// explores the section station by station, advances an entry by a box cut and a slab cut and
// backs out, dispatching each subtask to the planners, the tracker and the cutter; obeys the
// operator on COORDINATOR_COMMAND. The node is coordinator/coordinator_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "coordinator/coordinator_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  CoordinatorNodeOptions options;
  return RunNodeProcess(
      "coordinator", "Executes the mission's task tree on the fleet (thesis 6.1): explore, box cut, slab cut, back out.",
      args, [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        runtime.Start();
        CoordinatorNode node(runtime, options);
        return node.Run();
      });
}
