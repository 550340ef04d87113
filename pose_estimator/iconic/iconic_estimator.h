#pragma once
// The five iconic pose estimators of chapter 3 over a sequence of scans, each with an
// initial pose estimate (odometry):
//   kSurveyed      3.1  every scan to a surveyed line map
//   kScanMap       3.2  every scan to polylines fit to the first scan
//   kFirstScan     3.3  every scan to the first scan's raw polylines
//   kAllPrevious   3.4  every scan to the raw polylines of all scans before it
//   kSimultaneous  3.5  all scans to each other at once; the first scan is fixed
// The first scan's pose is taken as given in kScanMap, kFirstScan, kAllPrevious and
// kSimultaneous: it defines the map frame (3.2, 3.3).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/scan.h"
#include "pose_estimator/iconic/correspondence.h"
#include "pose_estimator/iconic/iconic_matcher.h"
#include "pose_estimator/iconic/multi_scan_matcher.h"
#include "pose_estimator/iconic/scan_polylines.h"
#include "pose_estimator/iconic/scan_set_map.h"
#include "pose_estimator/iconic/segment_map.h"

namespace minenav {

enum class IconicMode { kSurveyed, kScanMap, kFirstScan, kAllPrevious, kSimultaneous };
// "surveyed", "scan-map", "first-scan", "all-previous", "simultaneous".
const char* ToString(IconicMode mode);
bool ParseIconicMode(const std::string& text, IconicMode* out);

struct IconicEstimatorOptions {
  IconicMode mode = IconicMode::kSurveyed;
  IconicMatchOptions match;
  // Correspondence structure for a surveyed or fit map; the lookup table's reach is
  // raised to match.initial_threshold if smaller.
  CorrespondenceOptions correspondence;
  SegmentMapOptions map;
  PartialScanOptions partial;
  PolylineFitOptions fit;
  // Lookup table cells for maps made of raw scans (first-scan, all-previous, simultaneous),
  // m. Default 0.1 m; 0 = automatic (finer: faster queries, slower builds).
  double scan_map_cell_size = 0.1;
  // Sequential modes in EstimateSequence: when true, the given initial poses are odometry
  // (a drifting frame) and scan k starts from the last converged estimate composed with the
  // odometry motion since that scan; when false they are used as they are (an offline
  // survey's initial estimates in the map frame). Default false.
  bool chain_odometry = false;
  // Simultaneous mode only. When true, the poses first go through kAllPrevious (scan by
  // scan, which tolerates dead-reckoning error) and the simultaneous adjustment starts
  // from its converged estimates; when false it starts from the given poses. Default true.
  bool seed_simultaneous = true;
  double max_pair_distance = 60.0;  // m
  bool every_overlapping_scan = true;  // see MultiScanOptions
  int point_stride = 1;
  // Convergence of the simultaneous adjustment (MultiScanOptions::epsilon_*), m and rad.
  double simultaneous_epsilon_translation = 1e-3;
  double simultaneous_epsilon_rotation = 1e-4;
};

// The live process (and its fuzz target) takes a map from the bus into a new estimator, i.e. a
// new lookup table (the grassfire over the map's grid, the estimator's dearest step), at most
// once per this interval of its clock: MapUpdates::SetRateBound, the waiting map taken before a
// scan. A changed map on every message then costs a table a second, not a table a message.
inline constexpr int64_t kIconicMapRebuildIntervalUs = 1'000'000;

class OptionScope;
// Declares every field of IconicEstimatorOptions under `scope`: mode, scan_map_cell_size,
// chain_odometry and seed_simultaneous at the scope, the nested structs as match.*,
// correspondence.*, segment_map.*, partial.* and fit.*, and the fields the simultaneous mode
// hands on to MultiScanOptions as simultaneous.* (max_pair_distance, epsilons, ...).
void DeclareOptions(OptionScope scope, IconicEstimatorOptions& o);

// Incremental estimator for modes kSurveyed .. kAllPrevious (one scan at a time, as the
// live process needs). kSimultaneous goes through EstimateSequence.
class IconicEstimator {
 public:
  explicit IconicEstimator(IconicEstimatorOptions options);

  // Sets the surveyed map (kSurveyed). Returns "" or a one-line reason it is unusable.
  std::string SetMap(const std::vector<Segment>& segments);
  bool has_map() const { return map_ != nullptr; }
  int map_size() const { return map_ ? static_cast<int>(map_->segments().size()) : 0; }

  // Estimates the pose of one scan from `initial` (vehicle, map frame).
  IconicMatchResult AddScan(const LadarScan& scan, const Pose2& initial);

  const IconicEstimatorOptions& options() const { return options_; }

 private:
  IconicEstimatorOptions options_;
  std::unique_ptr<CorrespondenceSearch> map_;  // kSurveyed, kScanMap, kFirstScan
  std::unique_ptr<ScanSetMap> scans_;           // kAllPrevious
  int scans_seen_ = 0;
};

// Every mode over a whole sequence; results are in input order. For kSurveyed, `map` is
// the surveyed map (ignored otherwise).
std::vector<IconicMatchResult> EstimateSequence(const std::vector<LadarScan>& scans,
                                                const std::vector<Pose2>& initial_poses,
                                                const std::vector<Segment>& map,
                                                const IconicEstimatorOptions& options);

}  // namespace minenav
