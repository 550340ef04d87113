#pragma once
// vehicle_sim as a node: the locomotion emulator (thesis App. D, 6.4), a skid-steer miner
// driven by DRIVE_COMMAND in a simulated line-segment world. Publishes the true pose
// (SIM_TRUTH), dead-reckoned odometry with drift (ODOMETRY), the world the ladar sees
// (SIM_WORLD) and the surveyed map estimators may use (LINE_MAP; for the indoor mockup it
// lacks the clutter, thesis 2.2). The vehicle stops by itself when commands go stale.
//
// A changing world (thesis 4.8): --world may be repeated and --world-change-at gives the
// times (s since the first tick) at which world k+1 replaces world k, e.g. a door opens
// while the fleet runs. SIM_WORLD is published at once, before the SIM_TRUTH sample of that
// tick, so the ladar (which ray-casts the latest SIM_WORLD) casts every scan whose utime
// is later than the previous truth sample in the new world. LINE_MAP stays the first world
// (a map surveyed before the changes) unless --line-map each.
//
// Time: each tick integrates the motion over the clock time since the previous tick (live:
// wall clock; batch over a log of commands: log time), so a batch run is deterministic.
// A command's age is measured from when it was received, not from its own utime, so a
// sender with a skewed clock cannot keep the vehicle moving or stop it early.
//
// The cutter appendages (sim/cutterhead.h): CUTTER_COMMAND in, CUTTER_STATE out; every
// DRIVE_COMMAND passes the appendage order constraints first, and when a shear reaches the
// floor the cut is taken out of the world and SIM_WORLD published at once.
//
// The process (vehicle_sim_main.cc) declares the options, prepares the scenario and wires
// the node; the simulation itself is sim/vehicle_sim.h.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "common/vehicle_state.h"
#include "sim/scenario.h"
#include "sim/vehicle_sim.h"

namespace minenav {

struct VehicleSimNodeOptions {
  VehicleSimOptions sim;
  std::string drive_channel = "DRIVE_COMMAND";
  std::string truth_channel = "SIM_TRUTH";
  std::string odometry_channel = "ODOMETRY";
  std::string world_channel = "SIM_WORLD";
  std::string map_channel = "LINE_MAP";
  std::string cutter_command_channel = "CUTTER_COMMAND";
  std::string cutter_state_channel = "CUTTER_STATE";
  double cutter_state_period = 0.2;  // s
};

// Every option: the simulation's (the vehicle as vehicle.*, the odometry as odometry.*, the
// flat --max-forward-speed, --odometry-scale-error, ... as aliases), the channels, the
// examples for --help.
void DeclareOptions(ConfigSchema& schema, VehicleSimNodeOptions& o);

// The scenario of a run, before the bus starts: the worlds of the --world flags (or of a
// config file's `world =` line when no flag gives one) or the generated one; --world-out and
// --map-out written. Throws UsageError / InputError (exit 2).
SimScenario PrepareScenario(const VehicleSimOptions& o, const std::vector<std::string>& world_flags);

class VehicleSimNode {
 public:
  // Subscribes DRIVE_COMMAND and adds the world and motion timers (after runtime.Start()).
  VehicleSimNode(NodeRuntime& runtime, const VehicleSimNodeOptions& options, SimScenario scenario);
  int Run() { return runtime_.Run(); }

 private:
  void PublishWorld(int64_t now);
  // Applies a world change due at `now` and publishes it at once; true if the world changed.
  bool ChangeWorld(int64_t now);
  void Tick(int64_t now);
  void PublishCutterState(int64_t now);

  NodeRuntime& runtime_;
  VehicleSimNodeOptions options_;
  WorldTimeline world_;
  SimulatedVehicle vehicle_;
  std::optional<DriveCommand> command_;  // utime = when it was received
  Cutterhead cutter_;
  std::optional<int64_t> last_tick_;
};

}  // namespace minenav
