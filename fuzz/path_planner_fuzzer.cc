// Fuzz target: path_planner's handlers (planner/path_planner_node.h) with hostile PATH_REQUEST,
// CONTOUR_MAP, DRIVE_PATH and POSE (fuzz/node_fuzz.h): every PATH it sends must be one the
// tracker accepts (a feasible path's motions are checked against their poses). The node is
// live (it searches on its worker thread in batch too): after each message the target waits
// for the answers of the requests so far, each search bounded by the node's deadline (5 s by
// default; 1 s here, so that a search bound that fails shows as a hang of the fuzzer's 10 s).

#include "fuzz/node_fuzz.h"
#include "planner/path_planner_node.h"
#include "planner/planner_batch.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("path_planner");
  h->ExpectOutput<path_t>("PATH");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  PathPlannerNodeOptions options;
  options.deadline = 1.0;
  static const Footprint footprint = Normalized(FootprintFromFlag(PlannerBatchFlags{}.footprint));
  PathPlannerNode node(h->runtime(), options, footprint);
  h->Feed(data, size, {"PATH_REQUEST", "CONTOUR_MAP", "DRIVE_PATH", "POSE"}, 3'000'000, 100'000,
          [&] { h->SpinUntil([&] { return node.answers() >= node.requests(); }, options.deadline + 0.5); });
  return 0;
}
