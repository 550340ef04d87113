// Fuzz target: vehicle_sim's handlers (sim/vehicle_sim_node.h) with hostile DRIVE_COMMAND and
// CUTTER_COMMAND (fuzz/node_fuzz.h): the simulated vehicle must never publish a pose, odometry
// or cutter state its receivers reject (a NaN command driven into the kinematics).

#include "fuzz/node_fuzz.h"
#include "mapper/test_world.h"
#include "sim/vehicle_sim_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("vehicle_sim");
  h->ExpectOutput<vehicle_truth_t>("SIM_TRUTH");
  h->ExpectOutput<odometry_t>("ODOMETRY");
  h->ExpectOutput<line_map_t>("SIM_WORLD");
  h->ExpectOutput<line_map_t>("LINE_MAP");
  h->ExpectOutput<cutter_state_t>("CUTTER_STATE");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  SimScenario scenario;
  scenario.world = mapper::testing::SmallRoomWorld();
  scenario.map = scenario.world;
  scenario.start = Pose2(3.0, 9.0, 0.3);
  scenario.name = "small room";
  VehicleSimNode node(h->runtime(), VehicleSimNodeOptions{}, std::move(scenario));
  h->Feed(data, size, {"DRIVE_COMMAND", "CUTTER_COMMAND"});
  return 0;
}
