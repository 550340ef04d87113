// iconic_pose_estimator: the iconic pose estimators of thesis chapter 3 as a process.
//
// Batch (--log IN.lcm): reads LADAR_SCAN and ODOMETRY (and LINE_MAP / CONTOUR_MAP) from
// the log as fast as it can and, with --poses-out EST.csv, writes one pose per scan
// (utime,x,y,theta,status): the estimate when it converged, else the initial estimate marked
// not_converged.
//   iconic_pose_estimator --log IN.lcm [--map MAP.json] --mode MODE --poses-out EST.csv
// Live (no --log): subscribes LADAR_SCAN, ODOMETRY and a map (--map FILE, line_map_t on
// LINE_MAP or contour_map_t on CONTOUR_MAP), publishes pose_estimate_t on POSE_IPE per
// scan and a HEARTBEAT.
//
// Initial estimate of a scan (--initial auto): in batch, an ODOMETRY reading with the
// scan's exact utime is the scan's initial estimate in the map frame (offline surveys,
// DESIGN.md); otherwise (and always live, where odometry drifts) the last converged
// estimate moved by the odometry increment since that scan (odometry interpolated at the
// scan's utime), or the odometry pose itself for the first scan. A scan waits until
// odometry at or after its utime has arrived.

#include <memory>
#include <optional>
#include <string>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/map_updates.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_estimation_node.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"
#include "pose_estimator/iconic/iconic_estimator.h"

namespace minenav {
namespace {

struct ProcessOptions {
  std::string map;
  std::string map_channel = "LINE_MAP";
  std::string contour_channel = "CONTOUR_MAP";
  ScanEstimationOptions estimation = [] {
    ScanEstimationOptions o;
    o.initial = "auto";
    o.pose_channel = "POSE_IPE";
    return o;
  }();
  IconicEstimatorOptions estimator;
};

void DeclareOptions(ConfigSchema& s, ProcessOptions& p) {
  s.AddString("map", &p.map, "surveyed line map JSON ({\"segments\": ...}); empty = from LINE_MAP or CONTOUR_MAP");
  DeclareScanEstimationOptions(s, &p.estimation, {"auto", "odometry", "chained"}, "ipe");
  const OptionScope estimator(s);
  DeclareOptions(estimator, p.estimator);
  // The flat flags of before the options nested (issue 12).
  estimator.Nested("match").AddFlatAliases({"initial_threshold", "min_threshold", "epsilon_translation",
                                            "epsilon_rotation", "max_iterations", "min_correspondences", "loss",
                                            "loss_scale", "reject_open_ends"});
  estimator.Nested("correspondence").AddFlatAliases({"method", "cell_size"});
  estimator.Nested("partial").AddFlatAliases({"break_distance"});
  estimator.Nested("fit").AddFlatAliases({"segment_length"}, "fit_");
  estimator.Nested("simultaneous").AddFlatAliases({"max_pair_distance", "point_stride", "every_overlapping_scan"});
  s.AddChannel("map_channel", &p.map_channel, "subscribes", "line_map_t", "surveyed map when --map is empty");
  s.AddChannel("contour_channel", &p.contour_channel, "subscribes", "contour_map_t", "contour map as a line map when --map is empty");
  s.AddHelpEpilog(R"(Examples:
  iconic_pose_estimator --log survey.lcm --map mine.json --mode surveyed --poses-out est.csv
  iconic_pose_estimator --log survey.lcm --mode simultaneous --poses-out est.csv
  iconic_pose_estimator --map mine.json                               (live)
)");
}

// Contours as segments; a compressed map is inflated and validated first
// (common/node/contour_map_conversions.h).
int Run(NodeRuntime& runtime, const ProcessOptions& p) {
  const IconicEstimatorOptions& eo = p.estimator;
  if (const std::string why = ValidateIconicMatchOptions(eo.match); !why.empty()) throw UsageError(why);
  const bool batch = !runtime.options().log.empty();
  if (eo.mode == IconicMode::kSimultaneous && !batch)
    throw UsageError("--mode simultaneous needs the whole sequence: use it with --log");
  if (eo.mode != IconicMode::kSurveyed && !p.map.empty())
    MINENAV_LOG(kWarn) << "--map is only used by --mode surveyed; ignored";

  std::unique_ptr<IconicEstimator> estimator = std::make_unique<IconicEstimator>(eo);
  if (eo.mode == IconicMode::kSurveyed && !p.map.empty()) {
    const std::vector<Segment> segments = LoadSegmentsJson(p.map);
    if (const std::string why = estimator->SetMap(segments); !why.empty()) throw InputError(p.map + ": " + why);
    MINENAV_LOG(kInfo) << "map " << p.map << ": " << estimator->map_size() << " segments";
  }
  runtime.Start();
  Bus& bus = runtime.bus();

  std::optional<MapUpdates> map_updates;  // outlives the handlers below
  if (eo.mode == IconicMode::kSurveyed && p.map.empty()) {
    map_updates.emplace(bus, p.map_channel, p.contour_channel,
                        [&](const std::vector<Segment>& segments, const std::string& what) {
                          auto fresh = std::make_unique<IconicEstimator>(eo);
                          if (const std::string why = fresh->SetMap(segments); !why.empty())
                            throw InputError(what + ": " + why);
                          estimator = std::move(fresh);
                          MINENAV_LOG(kInfo) << "map from " << what << ": " << estimator->map_size() << " segments";
                        });
    map_updates->SetRateBound(runtime.clock(), kIconicMapRebuildIntervalUs);
  }

  ScanEstimationNode node(runtime, p.estimation, "ipe",
                          [&](const LadarScan& scan, const Pose2& initial, std::string*) -> std::optional<MatchResult> {
                            if (map_updates) map_updates->HandOnDue();  // a map that waited (rate bound)
                            return estimator->AddScan(scan, initial);  // its core is what POSE_IPE carries
                          });
  node.set_label(ToString(eo.mode));
  if (eo.mode == IconicMode::kSimultaneous) {
    node.EstimateAllAtEnd([&](const std::vector<LadarScan>& scans, const std::vector<Pose2>& initial) {
      const std::vector<IconicMatchResult> results = EstimateSequence(scans, initial, {}, eo);
      return std::vector<MatchResult>(results.begin(), results.end());
    });
  }
  return node.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  minenav::ProcessOptions options;
  return minenav::RunNodeProcess(
      "iconic_pose_estimator", "Iconic pose estimator (thesis ch. 3): scans + odometry [+ map] -> POSE_IPE.", argc,
      argv, [&](minenav::ConfigSchema& s) { DeclareOptions(s, options); },
      [&](minenav::NodeRuntime& runtime) { return Run(runtime, options); });
}
