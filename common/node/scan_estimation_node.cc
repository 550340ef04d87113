#include "common/node/scan_estimation_node.h"

#include <cmath>
#include <utility>

#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/cpu_time.h"
#include "common/pose_estimate.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {

void DeclareScanEstimationOptions(ConfigSchema& s, ScanEstimationOptions* o,
                                  const std::vector<std::string>& initial_choices, const std::string& source) {
  s.AddString("poses_out", &o->poses_out, "batch: write one pose per scan to this CSV (utime,x,y,theta,status)");
  s.AddString("initial", &o->initial,
              "initial estimate: odometry (the odometry pose at the scan's utime), chained (the last "
              "converged estimate moved by odometry since), auto (batch: odometry stamped exactly with "
              "the scan, else chained)",
              initial_choices);
  s.AddDouble("max_odometry_gap", &o->max_odometry_gap, "s",
              "farthest odometry reading from a scan's utime that may serve for it", 0.0, 3600.0);
  s.AddChannel("scan_channel", &o->scan_channel, "subscribes", "ladar_scan_t", "scans");
  s.AddChannel("odometry_channel", &o->odometry_channel, "subscribes", "odometry_t", "initial estimates");
  s.AddChannel("pose_channel", &o->pose_channel, "publishes", "pose_estimate_t",
               "one estimate per scan (source " + source + ")");
}

ScanEstimationNode::ScanEstimationNode(NodeRuntime& runtime, ScanEstimationOptions options, std::string source,
                                       EstimateFn estimate)
    : runtime_(runtime),
      options_(std::move(options)),
      source_(std::move(source)),
      estimate_(std::move(estimate)),
      sync_({.max_odometry_gap_us = std::llround(options_.max_odometry_gap * 1e6)}) {
  if (!options_.poses_out.empty() && !runtime_.batch()) throw UsageError("--poses-out needs --log (batch mode)");
  CheckOutputIsNotInput("--poses-out", options_.poses_out, {runtime_.options().log});
  Bus& bus = runtime_.bus();
  Subscribe<odometry_t>(bus, options_.odometry_channel, [this](const odometry_t& m) {
    if (!sync_.AddOdometry(FromLcm(m)))
      MINENAV_LOG(kWarn) << options_.odometry_channel << " time went back: history cleared";
    Drain(false);
  });
  Subscribe<ladar_scan_t>(bus, options_.scan_channel, [this](const ladar_scan_t& m) {
    LadarScan scan = FromLcm(m);
    if (const std::string why = ValidateScan(scan); !why.empty()) throw InputError("invalid scan: " + why);
    if (!sync_.AddScan(std::move(scan))) {
      MINENAV_LOG(kWarn) << "scans waiting for odometry: dropping the oldest";
      ++skipped_;
    }
    Drain(false);
  });
  runtime_.OnShutdown([this] { Finish(); });
}

int ScanEstimationNode::Run() { return runtime_.Run(); }

void ScanEstimationNode::Drain(bool at_shutdown) {
  for (const SyncedScan& s : sync_.TakeReady(at_shutdown)) Process(s);
}

void ScanEstimationNode::Process(const SyncedScan& synced) {
  const LadarScan& scan = synced.scan;
  if (!synced.odometry) {
    ++skipped_;
    MINENAV_LOG(kWarn) << "scan " << scan.scan_id << " at " << scan.utime << ": no odometry within "
                       << options_.max_odometry_gap << " s; skipped";
    runtime_.SetStatus(heartbeat_t::WARN, "no odometry for a scan");
    return;
  }
  const Pose2& odometry = *synced.odometry;
  const bool chain = options_.initial == "chained" ||
                     (options_.initial == "auto" && !(synced.exact && runtime_.batch()));
  const Pose2 initial = chain ? chain_.Predict(odometry) : odometry;
  if (estimate_all_) {
    deferred_scans_.push_back(scan);
    deferred_initial_.push_back(initial);
    chain_.Trust(initial, odometry);
    return;
  }
  std::string why;
  const double cpu0 = ThreadCpuSeconds();
  const std::optional<MatchResult> match = estimate_(scan, initial, &why);
  const double cpu_seconds = ThreadCpuSeconds() - cpu0;
  if (!match) {
    ++skipped_;
    MINENAV_LOG(kWarn) << "scan " << scan.scan_id << ": " << why << "; skipped";
    runtime_.SetStatus(heartbeat_t::WARN, why);
    return;
  }
  if (match->converged) chain_.Trust(match->pose, odometry);
  Answer(scan, initial, *match, cpu_seconds);
}

void ScanEstimationNode::Answer(const LadarScan& scan, const Pose2& initial, const MatchResult& match,
                                double cpu_seconds) {
  const PoseEstimate e = MakePoseEstimate(match, scan.utime, scan.scan_id, source_, cpu_seconds);
  ++estimated_;
  Publish(runtime_.bus(), options_.pose_channel, ToLcm(e));
  if (e.converged) {
    ++converged_;
    runtime_.SetStatus(heartbeat_t::OK, "");
  } else {
    MINENAV_LOG(kDebug) << "scan " << scan.scan_id << ": " << e.status;
    runtime_.SetStatus(heartbeat_t::WARN, "last scan: " + e.status);
  }
  // The poses file holds the estimate when it converged, else the initial estimate marked
  // not_converged (a scorer leaves it out: it is no estimate).
  poses_.push_back({scan.utime, e.converged ? e.pose : initial, EstimatorPoseStatus(e.converged)});
}

void ScanEstimationNode::Finish() {
  Drain(true);
  if (estimate_all_ && !deferred_scans_.empty()) {
    const double cpu0 = ThreadCpuSeconds();
    const std::vector<MatchResult> results = estimate_all_(deferred_scans_, deferred_initial_);
    const double per_scan = (ThreadCpuSeconds() - cpu0) / static_cast<double>(deferred_scans_.size());
    for (size_t k = 0; k < results.size() && k < deferred_scans_.size(); ++k)
      Answer(deferred_scans_[k], deferred_initial_[k], results[k], per_scan);
    if (!results.empty() && !results.back().converged)
      MINENAV_LOG(kWarn) << "estimate of the whole sequence: " << results.back().status;
  }
  if (!options_.poses_out.empty()) {
    // A run that ended before the end of its log keeps what it has under a name that says so.
    const std::string path = runtime_.interrupted() ? options_.poses_out + ".partial" : options_.poses_out;
    SavePosesCsv(path, poses_);
    MINENAV_LOG(kInfo) << "wrote " << poses_.size() << " poses to " << path;
  }
  MINENAV_LOG(kInfo) << estimated_ << " scans estimated" << (label_.empty() ? "" : " (" + label_ + ")") << ", "
                     << converged_ << " converged, " << skipped_ << " skipped";
}

}  // namespace minenav
