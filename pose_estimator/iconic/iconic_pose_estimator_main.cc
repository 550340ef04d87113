// iconic_pose_estimator: the iconic pose estimators of thesis chapter 3 as a process.
//
// Batch (--log IN.lcm): reads LADAR_SCAN and ODOMETRY (and LINE_MAP / CONTOUR_MAP) from
// the log as fast as it can and, with --poses-out EST.csv, writes one pose per scan
// (utime,x,y,theta): the estimate when it converged, else the initial estimate.
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
#include "common/node/node_runtime.h"
#include "common/node/scan_estimation_node.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"
#include "pose_estimator/iconic/iconic_estimator.h"

namespace minenav {
namespace {

struct ProcessOptions {
  std::string map;
  std::string mode = "surveyed";
  std::string method = "lookup";
  std::string loss = "none";
  std::string map_channel = "LINE_MAP";
  std::string contour_channel = "CONTOUR_MAP";
  ScanEstimationOptions estimation = [] {
    ScanEstimationOptions o;
    o.initial = "auto";
    o.pose_channel = "POSE_IPE";
    return o;
  }();
};

void Declare(ConfigSchema& s, ProcessOptions& p, IconicEstimatorOptions& e) {
  s.AddString("map", &p.map, "surveyed line map JSON ({\"segments\": ...}); empty = from LINE_MAP or CONTOUR_MAP");
  s.AddString("mode", &p.mode,
              "surveyed (3.1, needs a map), scan-map (3.2), first-scan (3.3), all-previous (3.4), "
              "simultaneous (3.5, batch only)",
              {"surveyed", "scan-map", "first-scan", "all-previous", "simultaneous"});
  DeclareScanEstimationOptions(s, &p.estimation, {"auto", "odometry", "chained"}, "ipe");
  s.AddString("method", &p.method, "correspondence: brute (Cox), grid (Gonzalez), lookup (thesis 3.1.1)",
              {"brute", "grid", "lookup"});
  IconicMatchOptions& m = e.match;
  s.AddDouble("initial_threshold", &m.initial_threshold, "m", "correspondence threshold of the first iteration", 0.01, 100.0);
  s.AddDouble("min_threshold", &m.min_threshold, "m", "floor of the shrinking threshold (~3 sigma of range noise)", 0.001, 100.0);
  s.AddDouble("epsilon_translation", &m.epsilon_translation, "m", "convergence: largest x/y step", 1e-9, 1.0);
  s.AddDouble("epsilon_rotation", &m.epsilon_rotation, "rad", "convergence: largest heading step", 1e-12, 1.0);
  s.AddInt("max_iterations", &m.max_iterations, "Gauss-Newton iteration limit", 1, 10000);
  s.AddInt("min_correspondences", &m.min_correspondences, "fewer matched points = no estimate", 3, 1000000);
  s.AddString("loss", &p.loss, "robust loss: none, huber, cauchy", {"none", "huber", "cauchy"});
  s.AddDouble("loss_scale", &m.loss_scale, "m", "scale of the robust loss", 1e-4, 10.0);
  s.AddBool("reject_open_ends", &m.reject_open_ends, "skip points nearest to the open end of a polyline");
  s.AddDouble("cell_size", &e.correspondence.cell_size, "m", "grid cell of a surveyed/fit map; 0 = automatic", 0.0, 10.0);
  s.AddDouble("scan_map_cell_size", &e.scan_map_cell_size, "m", "grid cell of maps made of raw scans", 0.0, 10.0);
  s.AddDouble("break_distance", &e.partial.break_distance, "m", "gap that splits a scan into partial scans", 0.01, 100.0);
  s.AddDouble("fit_segment_length", &e.fit.segment_length, "m", "segment length of polylines fit to a scan (scan-map)", 0.05, 100.0);
  s.AddDouble("max_pair_distance", &e.max_pair_distance, "m", "simultaneous: scans farther apart are not paired", 0.0, 1e6);
  s.AddInt("point_stride", &e.point_stride, "simultaneous: use every k-th point", 1, 1000);
  s.AddBool("every_overlapping_scan", &e.every_overlapping_scan,
            "simultaneous: a residual per overlapping scan (A.3) rather than for the nearest only");
  s.AddChannel("map_channel", &p.map_channel, "subscribes", "line_map_t", "surveyed map when --map is empty");
  s.AddChannel("contour_channel", &p.contour_channel, "subscribes", "contour_map_t", "contour map as a line map when --map is empty");
  s.AddHelpEpilog(
      "Examples:\n"
      "  iconic_pose_estimator --log survey.lcm --map mine.json --mode surveyed --poses-out est.csv\n"
      "  iconic_pose_estimator --log survey.lcm --mode simultaneous --poses-out est.csv\n"
      "  iconic_pose_estimator --map mine.json                               (live)\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
}

// Contours as segments; a compressed map is inflated and validated first
// (common/node/contour_map_conversions.h).
std::vector<Segment> ContourMapSegments(const contour_map_t& m) {
  std::vector<Segment> out;
  for (const ContourPolyline& c : ContourMapFromLcm(m).contours) {
    for (size_t i = 1; i < c.points.size(); ++i) out.emplace_back(c.points[i - 1], c.points[i]);
    if (c.closed && c.points.size() > 2) out.emplace_back(c.points.back(), c.points.front());
  }
  return out;
}

int Main(int argc, char** argv) {
  ConfigSchema schema("iconic_pose_estimator",
                      "Iconic pose estimator (thesis ch. 3): scans + odometry [+ map] -> POSE_IPE.");
  NodeRuntime runtime("iconic_pose_estimator", schema);
  ProcessOptions p;
  IconicEstimatorOptions eo;
  Declare(schema, p, eo);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  ParseIconicMode(p.mode, &eo.mode);
  ParseCorrespondenceMethod(p.method, &eo.correspondence.method);
  ParseRobustLoss(p.loss, &eo.match.loss);
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

  int64_t line_version = -1, contour_version = -1;  // outlive the handlers below
  if (eo.mode == IconicMode::kSurveyed && p.map.empty()) {
    auto set_map = [&](std::vector<Segment> segments, const std::string& what) {
      auto fresh = std::make_unique<IconicEstimator>(eo);
      if (const std::string why = fresh->SetMap(segments); !why.empty()) throw InputError(what + ": " + why);
      estimator = std::move(fresh);
      MINENAV_LOG(kInfo) << "map from " << what << ": " << estimator->map_size() << " segments";
    };
    Subscribe<line_map_t>(bus, p.map_channel, [&, set_map](const line_map_t& m) {
      if (m.version == line_version) return;
      set_map(SegmentsFromLcm(m), p.map_channel + " '" + m.name + "' version " + std::to_string(m.version));
      line_version = m.version;
    });
    Subscribe<contour_map_t>(bus, p.contour_channel, [&, set_map](const contour_map_t& m) {
      if (m.version == contour_version) return;
      set_map(ContourMapSegments(m), p.contour_channel + " version " + std::to_string(m.version));
      contour_version = m.version;
    });
  }

  ScanEstimationNode node(runtime, p.estimation, "ipe",
                          [&](const LadarScan& scan, const Pose2& initial, std::string*) -> std::optional<MatchResult> {
                            return estimator->AddScan(scan, initial);  // its core is what POSE_IPE carries
                          });
  node.set_label(p.mode);
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
  return minenav::RunNodeMain("iconic_pose_estimator", [&] { return minenav::Main(argc, argv); });
}
