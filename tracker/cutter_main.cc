// cutter: the sump-shear cycle (thesis 6.4.1, Figure 43) for cut tasks on CUT_TASK, steering
// by the pose estimate and commanding the appendages. The node is tracker/cutter_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "tracker/cutter_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  CutterNodeOptions options;
  return RunNodeProcess(
      "cutter", "Cuts coal: square up, sump in, shear down, remove the cusp, until the depth is reached.", args,
      [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        if (std::string why = ValidateCutterOptions(options.cutter); !why.empty()) throw UsageError(why);
        runtime.Start();
        CutterNode node(runtime, options);
        return node.Run();
      });
}
