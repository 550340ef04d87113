// ladar_driver: publishes 360 deg scans on LADAR_SCAN (thesis 4.2, 5.2.1, App. B, C),
// simulated from SIM_TRUTH and the world, or replayed from a log (--replay). The nodes and
// what they do are in sensor_driver/ladar_driver_node.h.

#include "common/node/node_runtime.h"
#include "sensor_driver/ladar_driver_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  LadarDriverOptions options;
  return RunNodeProcess(
      "ladar_driver", "Ladar scans on LADAR_SCAN: simulated from SIM_TRUTH and the world, or replayed from a log.",
      argc, argv, [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        const LadarSimulationSetup setup = ResolveLadarDriver(options, runtime.options());
        runtime.Start();
        if (!options.replay.empty()) return ScanReplayNode(runtime, options).Run();
        return LadarSimulationNode(runtime, options, setup).Run();
      });
}
