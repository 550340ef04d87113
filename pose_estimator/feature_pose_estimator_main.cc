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
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "common/angle.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/pose_at_time.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_odometry_sync.h"
#include "common/pose_estimate.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "pose_estimator/feature_pose_estimator.h"

namespace minenav {
namespace {

struct ProcessOptions {
  std::string map;
  std::string poses_out;
  std::string initial = "odometry";
  double max_odometry_gap = 1.0;  // s
  std::string scan_channel = "LADAR_SCAN";
  std::string odometry_channel = "ODOMETRY";
  std::string map_channel = "LINE_MAP";
  std::string pose_channel = "POSE_FPE";
};

void Declare(ConfigSchema& s, ProcessOptions& p, FeaturePoseEstimatorOptions& e) {
  s.AddString("map", &p.map, "line map JSON ({\"segments\": ...}); empty = take it from --map-channel");
  s.AddString("poses_out", &p.poses_out, "batch: write one pose per scan to this CSV (utime,x,y,theta)");
  s.AddString("initial", &p.initial,
              "initial estimate: the odometry pose at the scan's utime, or the last estimate moved by odometry",
              {"odometry", "chained"});
  s.AddDouble("max_odometry_gap", &p.max_odometry_gap, "s",
              "farthest odometry reading from a scan's utime that may serve as its initial estimate", 0.0, 3600.0);
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
  s.AddChannel("scan_channel", &p.scan_channel, "subscribes", "ladar_scan_t", "scans");
  s.AddChannel("odometry_channel", &p.odometry_channel, "subscribes", "odometry_t", "initial estimates");
  s.AddChannel("map_channel", &p.map_channel, "subscribes", "line_map_t", "the line map when --map is empty");
  s.AddChannel("pose_channel", &p.pose_channel, "publishes", "pose_estimate_t", "one estimate per scan (source fpe)");
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
  if (!p.poses_out.empty() && runtime.options().log.empty()) throw UsageError("--poses-out needs --log (batch mode)");
  std::unique_ptr<FeaturePoseEstimator> estimator;
  if (!p.map.empty()) {
    estimator = std::make_unique<FeaturePoseEstimator>(LoadSegmentsJson(p.map), eo);
    MINENAV_LOG(kInfo) << "map " << p.map << ": " << estimator->map().segments.size() << " segments, "
                       << estimator->map().vertices.size() << " vertices";
  }
  runtime.Start();
  Bus& bus = runtime.bus();
  const int64_t max_gap_us = std::llround(p.max_odometry_gap * 1e6);

  if (p.map.empty()) {
    Subscribe<line_map_t>(bus, p.map_channel, [&](const line_map_t& m) {
      std::vector<Segment> segments = SegmentsFromLcm(m);
      if (estimator && estimator->map().segments.size() == segments.size()) {
        bool same = true;
        for (size_t i = 0; same && i < segments.size(); ++i) {
          same = segments[i].a == estimator->map().segments[i].a && segments[i].b == estimator->map().segments[i].b;
        }
        if (same) return;
      }
      estimator = std::make_unique<FeaturePoseEstimator>(segments, eo);
      MINENAV_LOG(kInfo) << "map from " << p.map_channel << " '" << m.name << "' version " << m.version << ": "
                         << segments.size() << " segments";
    });
  }

  ScanOdometrySync sync({.max_odometry_gap_us = max_gap_us});
  std::vector<StampedPose> poses;
  std::optional<std::pair<Pose2, Pose2>> last;  // (estimate, odometry) of the last converged scan
  int64_t scans = 0, converged = 0, skipped = 0;

  auto process = [&](const SyncedScan& synced) {
    const LadarScan& scan = synced.scan;
    const std::optional<Pose2>& odo = synced.odometry;
    if (!odo) {
      ++skipped;
      MINENAV_LOG(kWarn) << "scan " << scan.scan_id << " at " << scan.utime << ": no odometry within "
                         << p.max_odometry_gap << " s; skipped";
      runtime.SetStatus(heartbeat_t::WARN, "no odometry for a scan");
      return;
    }
    if (!estimator) {
      ++skipped;
      MINENAV_LOG(kWarn) << "scan " << scan.scan_id << ": no map yet; skipped";
      runtime.SetStatus(heartbeat_t::WARN, "no map");
      return;
    }
    Pose2 initial = *odo;
    if (p.initial == "chained" && last) initial = last->first * Between(last->second, *odo);
    const FeaturePoseResult r = estimator->Estimate(scan, initial);
    ++scans;
    PoseEstimate e;
    e.utime = scan.utime;
    e.scan_id = scan.scan_id;
    e.source = "fpe";
    e.pose = r.pose;
    e.covariance = r.covariance;
    e.residual = r.residual;
    e.num_points = r.num_points;
    e.num_inliers = r.used;
    e.iterations = r.iterations;
    e.converged = r.converged;
    e.status = r.reason;
    e.compute_time = r.timings.total();
    Publish(bus, p.pose_channel, ToLcm(e));
    if (r.converged) {
      ++converged;
      last = std::make_pair(r.pose, *odo);
      runtime.SetStatus(heartbeat_t::OK, "");
    } else {
      MINENAV_LOG(kDebug) << "scan " << scan.scan_id << ": " << r.reason;
      runtime.SetStatus(heartbeat_t::WARN, "last scan: " + r.reason);
    }
    // The poses file holds the estimate when it converged, else the initial estimate.
    poses.push_back({scan.utime, r.converged ? r.pose : initial});
  };
  auto drain = [&](bool at_shutdown) {
    for (const SyncedScan& s : sync.TakeReady(at_shutdown)) process(s);
  };

  Subscribe<odometry_t>(bus, p.odometry_channel, [&](const odometry_t& m) {
    if (!sync.AddOdometry(FromLcm(m))) MINENAV_LOG(kWarn) << "ODOMETRY time went back: history cleared";
    drain(false);
  });
  Subscribe<ladar_scan_t>(bus, p.scan_channel, [&](const ladar_scan_t& m) {
    LadarScan scan = FromLcm(m);
    if (const std::string why = ValidateScan(scan); !why.empty()) {
      throw InputError("invalid scan: " + why);
    }
    if (!sync.AddScan(std::move(scan))) {
      MINENAV_LOG(kWarn) << "100 scans waiting for odometry: dropping the oldest";
      ++skipped;
    }
    drain(false);
  });
  runtime.OnShutdown([&] {
    drain(true);
    if (!p.poses_out.empty()) {
      SavePosesCsv(p.poses_out, poses);
      MINENAV_LOG(kInfo) << "wrote " << poses.size() << " poses to " << p.poses_out;
    }
    MINENAV_LOG(kInfo) << scans << " scans estimated, " << converged << " converged, " << skipped << " skipped";
  });
  return runtime.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("feature_pose_estimator", [&] { return minenav::Main(argc, argv); });
}
