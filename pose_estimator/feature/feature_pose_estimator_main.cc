// feature_pose_estimator: the feature-based pose estimator (thesis chapter 2) as a process.
//
// Live: subscribes LADAR_SCAN, ODOMETRY and the map (--map FILE, or line_map_t on
// LINE_MAP), publishes one pose_estimate_t on POSE_FPE per scan and a HEARTBEAT.
// Batch (--log IN.lcm): reads the same channels from the log as fast as it can;
// --poses-out EST.csv writes one pose per LADAR_SCAN (utime,x,y,theta), the contract of
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
};

void Declare(ConfigSchema& s, ProcessOptions& p, FeaturePoseEstimatorOptions& e) {
  s.AddString("map", &p.map, "line map JSON ({\"segments\": ...}); empty = take it from --map-channel");
  DeclareScanEstimationOptions(s, &p.estimation, {"odometry", "chained"}, "fpe");
  MatchingOptions& m = e.matching;
  s.AddDouble("angerr", &m.angerr, "rad", "bound on the initial heading error (2.1.5; thesis 5 deg)", 0.0, 1.5);
  s.AddDouble("poserr", &m.poserr, "m", "bound on the initial position error (2.1.5; thesis 1 m)", 0.0, 100.0);
  s.AddDouble("concerr", &m.concerr, "rad", "tolerance on concave angles (thesis 10 deg)", 0.0, 3.0);
  s.AddDouble("disterr", &m.disterr, "m", "tolerance on line distances beyond poserr (thesis 0.5 m)", 0.0, 100.0);
  s.AddDouble("bindisterr", &m.bindisterr, "m", "tolerance of the binary distance constraints (thesis 0.5 m)", 0.0, 100.0);
  s.AddDouble("binangerr", &m.binangerr, "rad", "tolerance of the binary angle constraints (thesis 5 deg)", 0.0, 3.0);
  s.AddDouble("arm_length", &e.extraction.corner.arm_length, "m", "corner operator arm length", 0.05, 10.0);
  s.AddDouble("noise_sigma", &e.extraction.noise_sigma, "m", "range noise of the sensor (line fits)", 0.001, 1.0);
  s.AddDouble("point_sigma", &e.minimization.point_sigma, "m", "range noise of the sensor (feature weights)", 0.001, 1.0);
  s.AddDouble("max_range", &e.prediction.max_range, "m", "feature prediction range limit (also the scan's)", 0.1, 1000.0);
  s.AddInt("min_matches", &e.min_matches, "consistent correspondences needed to call a pose converged", 1, 1000);
  s.AddDouble("min_support", &e.min_support, "1", "fraction of scan points that must lie on the map at the estimate", 0.0, 1.0);
  s.AddChannel("map_channel", &p.map_channel, "subscribes", "line_map_t", "the line map when --map is empty");
  s.AddHelpEpilog(
      "Examples:\n"
      "  feature_pose_estimator --log run.lcm --map mockup.json --poses-out est.csv\n"
      "  feature_pose_estimator --map mockup.json --angerr 45deg       (live)\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
}

int Main(int argc, char** argv) {
  ConfigSchema schema("feature_pose_estimator",
                      "Feature-based pose estimator (thesis ch. 2): scans + odometry + line map -> POSE_FPE.");
  NodeRuntime runtime("feature_pose_estimator", schema);
  ProcessOptions p;
  FeaturePoseEstimatorOptions eo;
  Declare(schema, p, eo);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (const std::string why = ValidateOptions(eo); !why.empty()) throw UsageError(why);
  std::unique_ptr<FeaturePoseEstimator> estimator;
  if (!p.map.empty()) {
    estimator = std::make_unique<FeaturePoseEstimator>(LoadSegmentsJson(p.map), eo);
    MINENAV_LOG(kInfo) << "map " << p.map << ": " << estimator->map().segments.size() << " segments, "
                       << estimator->map().vertices.size() << " vertices";
  }
  runtime.Start();
  if (p.map.empty()) {
    Subscribe<line_map_t>(runtime.bus(), p.map_channel, [&](const line_map_t& m) {
      std::vector<Segment> segments = SegmentsFromLcm(m);
      if (estimator && SameSegments(estimator->map().segments, segments)) return;
      estimator = std::make_unique<FeaturePoseEstimator>(segments, eo);
      MINENAV_LOG(kInfo) << "map from " << p.map_channel << " '" << m.name << "' version " << m.version << ": "
                         << segments.size() << " segments";
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
  return minenav::RunNodeMain("feature_pose_estimator", [&] { return minenav::Main(argc, argv); });
}
