// Fuzz target: iconic_pose_estimator's handlers (common/node/scan_estimation_node.h with the
// IconicEstimator, wired as iconic_pose_estimator_main.cc wires it without --map: the map from
// LINE_MAP or CONTOUR_MAP through MapUpdates, at most a table a second) with hostile LADAR_SCAN, ODOMETRY and maps
// (fuzz/node_fuzz.h): every POSE_IPE it sends must be one its receivers accept.

#include <memory>
#include <optional>

#include "common/node/map_updates.h"
#include "common/node/scan_estimation_node.h"
#include "fuzz/node_fuzz.h"
#include "pose_estimator/iconic/iconic_estimator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("iconic_pose_estimator");
  h->ExpectOutput<pose_estimate_t>("POSE_IPE");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  const IconicEstimatorOptions options;  // surveyed
  auto estimator = std::make_unique<IconicEstimator>(options);
  MapUpdates maps(h->bus(), "LINE_MAP", "CONTOUR_MAP", [&](const std::vector<Segment>& segments, const std::string& what) {
    auto fresh = std::make_unique<IconicEstimator>(options);
    if (const std::string why = fresh->SetMap(segments); !why.empty()) throw InputError(what + ": " + why);
    estimator = std::move(fresh);
  });
  maps.SetRateBound(h->clock(), kIconicMapRebuildIntervalUs);
  ScanEstimationOptions estimation;
  estimation.initial = "auto";
  estimation.pose_channel = "POSE_IPE";
  ScanEstimationNode node(h->runtime(), estimation, "ipe",
                          [&](const LadarScan& scan, const Pose2& initial, std::string*) -> std::optional<MatchResult> {
                            maps.HandOnDue();
                            return estimator->AddScan(scan, initial);
                          });
  h->Feed(data, size, {"LADAR_SCAN", "ODOMETRY", "LINE_MAP", "CONTOUR_MAP"});
  return 0;
}
