// Fuzz target: feature_pose_estimator's handlers (common/node/scan_estimation_node.h with the
// FeaturePoseEstimator, wired as feature_pose_estimator_main.cc wires it without --map: the map
// from LINE_MAP through MapUpdates) with hostile LADAR_SCAN, ODOMETRY and LINE_MAP
// (fuzz/node_fuzz.h): every POSE_FPE it sends must be one its receivers accept.

#include <memory>
#include <optional>

#include "common/node/map_updates.h"
#include "common/node/scan_estimation_node.h"
#include "fuzz/node_fuzz.h"
#include "pose_estimator/feature/feature_pose_estimator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const auto h = fuzz::NodeFuzzHarness::Live("feature_pose_estimator");
  h->ExpectOutput<pose_estimate_t>("POSE_FPE");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  const FeaturePoseEstimatorOptions options;
  std::unique_ptr<FeaturePoseEstimator> estimator;
  MapUpdates maps(h->bus(), "LINE_MAP", "", [&](const std::vector<Segment>& segments, const std::string&) {
    estimator = std::make_unique<FeaturePoseEstimator>(segments, options);
  });
  ScanEstimationOptions estimation;
  estimation.pose_channel = "POSE_FPE";
  ScanEstimationNode node(h->runtime(), estimation, "fpe",
                          [&](const LadarScan& scan, const Pose2& initial, std::string* why) -> std::optional<MatchResult> {
                            if (!estimator) {
                              *why = "no map yet";
                              return std::nullopt;
                            }
                            return estimator->Estimate(scan, initial);
                          });
  h->Feed(data, size, {"LADAR_SCAN", "ODOMETRY", "LINE_MAP"});
  return 0;
}
