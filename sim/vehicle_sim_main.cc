// vehicle_sim: the locomotion emulator (thesis App. D, 6.4) as a process: DRIVE_COMMAND in;
// SIM_TRUTH, ODOMETRY, SIM_WORLD and LINE_MAP out, in a world that may change while the
// fleet runs (thesis 4.8). The node and what it does are in sim/vehicle_sim_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "sim/vehicle_sim_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> world_flags;
  VehicleSimNodeOptions options;
  return RunNodeProcess(
      "vehicle_sim", "Skid-steer miner simulator: DRIVE_COMMAND in; SIM_TRUTH, ODOMETRY, SIM_WORLD, LINE_MAP out.",
      args,
      [&](ConfigSchema& s) {
        DeclareOptions(s, options);
        world_flags = TakeWorldFlags(&args);  // --world repeats for a changing world
      },
      [&](NodeRuntime& runtime) {
        SimScenario scenario = PrepareScenario(options.sim, world_flags);
        runtime.Start();
        VehicleSimNode node(runtime, options, std::move(scenario));
        return node.Run();
      });
}
