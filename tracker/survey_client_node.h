#pragma once
// survey_client as a node: the StationRequests (station_requests.h) on the bus. It asks the
// path planner for a path to each scan station in turn (PATH_REQUEST, start = the latest
// converged POSE), follows the planner's PATH answers and the path tracker's TASK_STATUS of
// its requests, and stops the process after the last station when asked to. It never
// steers (path_tracker does) and uses the fleet's own estimates only. The process (survey_client_main.cc)
// only declares these options and wires the node.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/node_runtime.h"
#include "tracker/station_requests.h"

namespace minenav {

struct SurveyClientOptions {
  std::string stations;  // CSV x,y,theta
  std::string pose_channel = "POSE";
  std::string request_channel = "PATH_REQUEST";
  std::string path_channel = "PATH";
  std::string status_channel = "TASK_STATUS";
  double rate = 2.0;                 // Hz
  double clearance = 0.1;            // m, asked of the planner
  double position_tolerance = 0.05;  // m, asked of the planner
  double heading_tolerance = 0.0175; // rad, asked of the planner
  bool allow_reverse = true;
  bool allow_unknown = false;  // the planner may plan through space no scan has seen (exploring)
  bool exit_when_done = true;
  StationRequestOptions requests;
};

void DeclareOptions(ConfigSchema& schema, SurveyClientOptions& o);
// The stations of --stations (required).
std::vector<Station> LoadClientStations(const SurveyClientOptions& o);

class SurveyClientNode {
 public:
  SurveyClientNode(NodeRuntime& runtime, SurveyClientOptions options, const std::vector<Station>& stations);
  int Run() { return runtime_.Run(); }

 private:
  void Tick(int64_t now);

  NodeRuntime& runtime_;
  SurveyClientOptions options_;
  StationRequests requests_;
  std::optional<Pose2> pose_;
};

}  // namespace minenav
