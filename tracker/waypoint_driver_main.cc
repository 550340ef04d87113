// waypoint_driver: drives the vehicle through a list of stations (x,y,theta CSV) with
// the WaypointFollower, pausing at each station so the ladar can take a scan there.
// It steers by odometry alone (never SIM_TRUTH); the survey on the fleet's estimates is
// survey_client + path_planner + path_tracker (tracker/README.md).
// The node is tracker/waypoint_driver_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "tracker/waypoint_driver_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  WaypointDriverOptions options;
  return RunNodeProcess(
      "waypoint_driver", "Drives the vehicle through scan stations, pausing at each.", args,
      [&](ConfigSchema& s) {
        options = WaypointDriverDefaults(args);
        DeclareOptions(s, options);
      },
      [&](NodeRuntime& runtime) {
        const std::vector<Station> stations = LoadDriverStations(options);
        runtime.Start();
        WaypointDriverNode node(runtime, options, stations);
        return node.Run();
      });
}
