#pragma once
// The node both pose estimators are (thesis chapters 2 and 3 as processes): each scan is
// paired with odometry (ScanOdometrySync), given an initial estimate (the odometry pose at
// the scan's utime, or the last converged estimate moved by the odometry since:
// OdometryChain), estimated by the library, and answered with one pose_estimate_t; a
// skipped or unconverged scan shows in HEARTBEAT; --poses-out is written at the end of a
// batch run. The process around it only declares its estimator's options and says how to
// estimate one scan.
//
//   ScanEstimationOptions o{.pose_channel = "POSE_FPE"};
//   DeclareScanEstimationOptions(schema, &o, {"odometry", "chained"});
//   ... parse, runtime.Start() ...
//   ScanEstimationNode node(runtime, o, "fpe", [&](const LadarScan& scan, const Pose2& initial,
//                                                  std::string* why) -> std::optional<MatchResult> {...});
//   return node.Run();

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_odometry_sync.h"
#include "common/match_result.h"
#include "common/odometry_chain.h"
#include "common/scan.h"

namespace minenav {

struct ScanEstimationOptions {
  std::string poses_out;           // batch: one pose per scan (utime,x,y,theta,status) at the end
  // odometry: the odometry pose at the scan's utime; chained: the last converged estimate
  // moved by the odometry since; auto: in batch an odometry reading stamped exactly with
  // the scan's utime is its initial estimate (offline surveys), otherwise chained.
  std::string initial = "odometry";
  double max_odometry_gap = 1.0;   // s, farthest odometry reading that may serve a scan
  std::string scan_channel = "LADAR_SCAN";
  std::string odometry_channel = "ODOMETRY";
  std::string pose_channel = "POSE";
};

// Registers poses_out, initial (one of `initial_choices`), max_odometry_gap and the scan,
// odometry and pose channels; `source` names the estimates ("fpe", "ipe").
void DeclareScanEstimationOptions(ConfigSchema& schema, ScanEstimationOptions* options,
                                  const std::vector<std::string>& initial_choices, const std::string& source);

class ScanEstimationNode {
 public:
  // Estimates one scan from `initial`. nullopt = not estimated (e.g. no map yet): *why
  // says why. The node makes the published estimate of it (MakePoseEstimate) with the
  // scan's utime and id, the node's source and the CPU time the call took.
  using EstimateFn =
      std::function<std::optional<MatchResult>(const LadarScan& scan, const Pose2& initial, std::string* why)>;
  // Estimates a whole sequence at once (IPE's simultaneous mode, batch only).
  using EstimateAllFn =
      std::function<std::vector<MatchResult>(const std::vector<LadarScan>& scans, const std::vector<Pose2>& initial)>;

  // Subscribes on runtime.bus() (call after runtime.Start()). Throws UsageError for
  // --poses-out without --log.
  ScanEstimationNode(NodeRuntime& runtime, ScanEstimationOptions options, std::string source, EstimateFn estimate);

  // Collects every scan with its initial estimate and estimates them all at the end.
  void EstimateAllAtEnd(EstimateAllFn estimate_all) { estimate_all_ = std::move(estimate_all); }
  // Words for the summary line ("3 scans estimated (<label>), ..."), e.g. the mode.
  void set_label(std::string label) { label_ = std::move(label); }

  // runtime.Run(): until the end of the log, a signal or --run-for.
  int Run();

  int64_t scans_estimated() const { return estimated_; }
  int64_t scans_converged() const { return converged_; }
  int64_t scans_skipped() const { return skipped_; }

 private:
  void Process(const SyncedScan& synced);
  void Drain(bool at_shutdown);
  void Answer(const LadarScan& scan, const Pose2& initial, const MatchResult& match, double cpu_seconds);
  void Finish();

  NodeRuntime& runtime_;
  ScanEstimationOptions options_;
  std::string source_;
  std::string label_;
  EstimateFn estimate_;
  EstimateAllFn estimate_all_;
  ScanOdometrySync sync_;
  OdometryChain chain_;
  std::vector<StampedPose> poses_;
  std::vector<LadarScan> deferred_scans_;
  std::vector<Pose2> deferred_initial_;
  int64_t estimated_ = 0, converged_ = 0, skipped_ = 0;
};

}  // namespace minenav
