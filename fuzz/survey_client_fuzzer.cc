// Fuzz target: survey_client's handlers (tracker/survey_client_node.h) with hostile POSE, PATH
// and TASK_STATUS (fuzz/node_fuzz.h): every PATH_REQUEST it sends must be one the planner
// accepts.

#include "fuzz/node_fuzz.h"
#include "tracker/survey_client_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("survey_client");
  h->ExpectOutput<path_request_t>("PATH_REQUEST");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  const std::vector<Station> stations = {{Pose2(10, 0, 0), 0}, {Pose2(10, 10, 1.57), 0}, {Pose2(0, 0, 3.14), 0}};
  SurveyClientNode node(h->runtime(), SurveyClientOptions{}, stations);
  h->Feed(data, size, {"POSE", "PATH", "TASK_STATUS"});
  return 0;
}
