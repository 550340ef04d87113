#pragma once
// waypoint_driver as a node: the StationTour at --rate on the runtime's clock, steering by
// dead-reckoned odometry, one DRIVE_COMMAND per tick; it stops the process after the last
// station when asked to. It no longer steers by SIM_TRUTH (issue 14: ground truth decides
// nothing about how the vehicle moves); the closed loop on the fleet's estimates is
// survey_client + path_planner + path_tracker. The process (waypoint_driver_main.cc) only
// declares these options and wires the node.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/node_runtime.h"
#include "tracker/station_tour.h"
#include "tracker/waypoint_follower.h"

namespace minenav {

struct WaypointDriverOptions {
  std::string stations;               // CSV x,y,theta
  std::string odometry_channel = "ODOMETRY";
  std::string drive_channel = "DRIVE_COMMAND";
  double rate = 10.0;   // Hz, control rate
  double dwell = 0.5;   // s to stand still at each station
  bool exit_when_done = true;
  WaypointFollowerOptions follower;  // command_timeout: see WaypointDriverDefaults
};

// The defaults for a command line: the commands stay valid for three control periods of
// the --rate it gives (0.3 s at 10 Hz), unless follower.command_timeout says otherwise.
WaypointDriverOptions WaypointDriverDefaults(const std::vector<std::string>& args);

// Every option, the follower's as follower.* (the flat --cruise-speed etc. as aliases).
void DeclareOptions(ConfigSchema& schema, WaypointDriverOptions& o);

// The stations of --stations (required).
std::vector<Station> LoadDriverStations(const WaypointDriverOptions& o);

class WaypointDriverNode {
 public:
  // Subscribes the pose and adds the control timer (call after runtime.Start()).
  WaypointDriverNode(NodeRuntime& runtime, WaypointDriverOptions options, const std::vector<Station>& stations);
  int Run() { return runtime_.Run(); }

 private:
  void Tick(int64_t now);

  NodeRuntime& runtime_;
  WaypointDriverOptions options_;
  StationTour tour_;
  std::optional<Pose2> pose_;
  int64_t seq_ = 0;
};

}  // namespace minenav
