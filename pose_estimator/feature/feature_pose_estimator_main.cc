// feature_pose_estimator: the feature-based pose estimator (thesis chapter 2) as a process.
//
// Live: subscribes LADAR_SCAN, ODOMETRY and the map (--map FILE, or line_map_t on
// LINE_MAP), publishes one pose_estimate_t on POSE_FPE per scan and a HEARTBEAT.
// Batch (--log IN.lcm): reads the same channels from the log as fast as it can;
// --poses-out EST.csv writes one pose per LADAR_SCAN (utime,x,y,theta,status), the contract of
// the iconic estimator's batch mode.
//
// Initial estimate of a scan: the ODOMETRY reading with the scan's utime (interpolated
// between the two readings around it when there is no exact one). With --initial chained
// it is instead the last converged estimate moved by the odometry increment since then
// (live runs, where odometry drifts). A scan waits until odometry at or after its utime
// has arrived; at shutdown the waiting scans use the newest reading if it is close enough.
#include <memory>
#include <optional>
#include <string>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/map_updates.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_estimation_node.h"
#include "minenav/line_map_t.hpp"
#include "pose_estimator/feature/feature_pose_estimator.h"

namespace minenav {
namespace {

struct ProcessOptions {
  std::string map;
  std::string map_channel = "LINE_MAP";
  ScanEstimationOptions estimation = [] {
    ScanEstimationOptions o;
    o.pose_channel = "POSE_FPE";
    return o;
  }();
  FeaturePoseEstimatorOptions estimator;
};

void DeclareOptions(ConfigSchema& s, ProcessOptions& p) {
  s.AddString("map", &p.map, "line map JSON ({\"segments\": ...}); empty = take it from --map-channel");
  DeclareScanEstimationOptions(s, &p.estimation, {"odometry", "chained"}, "fpe");
  const OptionScope estimator(s);
  DeclareOptions(estimator, p.estimator);
  // The flat flags of before the options nested (issue 12).
  estimator.Nested("matching").AddFlatAliases({"angerr", "poserr", "concerr", "disterr", "bindisterr", "binangerr"});
  estimator.Nested("extraction").Nested("corner").AddFlatAliases({"arm_length"});
  estimator.Nested("extraction").AddFlatAliases({"noise_sigma"});
  estimator.Nested("minimization").AddFlatAliases({"point_sigma"});
  estimator.Nested("prediction").AddFlatAliases({"max_range"});
  s.AddChannel("map_channel", &p.map_channel, "subscribes", "line_map_t", "the line map when --map is empty");
  s.AddHelpEpilog(R"(Examples:
  feature_pose_estimator --log run.lcm --map mockup.json --poses-out est.csv
  feature_pose_estimator --map mockup.json --angerr 45deg       (live)
)");
}

int Run(NodeRuntime& runtime, const ProcessOptions& p) {
  const FeaturePoseEstimatorOptions& eo = p.estimator;
  if (const std::string why = ValidateOptions(eo); !why.empty()) throw UsageError(why);
  std::unique_ptr<FeaturePoseEstimator> estimator;
  if (!p.map.empty()) {
    estimator = std::make_unique<FeaturePoseEstimator>(LoadSegmentsJson(p.map), eo);
    MINENAV_LOG(kInfo) << "map " << p.map << ": " << estimator->map().segments.size() << " segments, "
                       << estimator->map().vertices.size() << " vertices";
  }
  runtime.Start();
  std::optional<MapUpdates> map_updates;  // outlives the handlers below
  if (p.map.empty()) {
    map_updates.emplace(runtime.bus(), p.map_channel, "",
                        [&](const std::vector<Segment>& segments, const std::string& what) {
                          estimator = std::make_unique<FeaturePoseEstimator>(segments, eo);
                          MINENAV_LOG(kInfo) << "map from " << what << ": " << segments.size() << " segments";
                        });
  }
  ScanEstimationNode node(runtime, p.estimation, "fpe",
                          [&](const LadarScan& scan, const Pose2& initial, std::string* why) -> std::optional<MatchResult> {
                            if (!estimator) {
                              *why = "no map yet";
                              return std::nullopt;
                            }
                            return estimator->Estimate(scan, initial);  // its core is what POSE_FPE carries
                          });
  return node.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  minenav::ProcessOptions options;
  return minenav::RunNodeProcess(
      "feature_pose_estimator",
      "Feature-based pose estimator (thesis ch. 2): scans + odometry + line map -> POSE_FPE.", argc, argv,
      [&](minenav::ConfigSchema& s) { DeclareOptions(s, options); },
      [&](minenav::NodeRuntime& runtime) { return Run(runtime, options); });
}
