// Fuzz target: ladar_driver's simulation node (sensor_driver/ladar_driver_node.h) with a hostile
// world (SIM_WORLD) and hostile true poses (SIM_TRUTH) (fuzz/node_fuzz.h): every scan it
// publishes must be one its receivers accept.

#include "fuzz/node_fuzz.h"
#include "sensor_driver/ladar_driver_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("ladar_driver");
  h->ExpectOutput<ladar_scan_t>("LADAR_SCAN");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  static const LadarDriverOptions options;  // Typhoon, 2048 points at 10 Hz; the world from SIM_WORLD
  static const LadarSimulationSetup setup = ResolveLadarDriver(options, NodeOptions{});
  LadarSimulationNode node(h->runtime(), options, setup);
  h->Feed(data, size, {"SIM_WORLD", "SIM_TRUTH"});
  return 0;
}
