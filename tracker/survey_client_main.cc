// survey_client: drives a survey through scan stations on the fleet's own planner and
// tracker: PATH_REQUEST to each station, the planner's PATH, the tracker's TASK_STATUS DONE,
// a dwell for the scans, the next station. The node is tracker/survey_client_node.h.

#include <string>
#include <vector>

#include "common/node/node_runtime.h"
#include "tracker/survey_client_node.h"

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  SurveyClientOptions options;
  return RunNodeProcess(
      "survey_client", "Drives a survey through scan stations on the path planner and the path tracker.", args,
      [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        const std::vector<Station> stations = LoadClientStations(options);
        runtime.Start();
        SurveyClientNode node(runtime, options, stations);
        return node.Run();
      });
}
