#pragma once
// path_tracker as a node: the PathTracker (path_tracker.h) on the bus. It subscribes PATH
// (path_t), the pose estimates (POSE, the contour mapper's, by default), ODOMETRY and the map
// (CONTOUR_MAP; LINE_MAP too when line_map_channel is given), and publishes DRIVE_COMMAND at
// --rate, TASK_STATUS (task_id = the path's request_id) when a path is taken, done, failed,
// abandoned or blocked, and when the watchdog stops or releases the vehicle, and HEARTBEAT.
// It steers by the fleet's own pose estimate (POSE) only.
//
// Repeat-safe (a coordinator re-sends each path on DRIVE_PATH until acknowledged): a path_t
// whose request_id is the active path's with the same path (start and pieces; its stamp and
// status may differ), or the last finished one's, changes nothing and is answered by
// re-publishing that path's latest TASK_STATUS; feasible = false with the active request_id
// cancels it (STOP, TASK_STATUS CANCELED "canceled by the sender"). A different path with the
// active request_id is the planner's replan (path_planner publishes it with the same id): it
// replaces the active path. A path of another request replaces the active one (CANCELED
// "replaced by ...").
//
// The pose it steers by is PosePredictor's: the latest trusted estimate composed with the
// odometry since. Watchdog, checked every tick while a path is active:
//   * no trusted estimate for pose_timeout s (by the estimates' scan stamps), or no odometry
//     for odometry_timeout s: STOP, TASK_STATUS ACTIVE "stopped: <why>", HEARTBEAT WARN with
//     the same line; the path resumes when both are fresh again ("resumed");
//   * the path older than path_max_age s (its utime): abandoned, TASK_STATUS FAILED.
// The tick runs at --rate (10 Hz: at most 100 ms after a limit passes, the STOP is out).
// A new map (CONTOUR_MAP, or the line map) is turned into the tracker's collision map
// (TrackerMap: the planner's checker and a segment index) on a BackgroundWorker, so the
// control tick never waits for a large map; the tick takes the newest one built (a map that
// arrives while another is built replaces the one waiting).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "common/config.h"
#include "common/node/background_worker.h"
#include "common/node/map_updates.h"
#include "common/node/node_runtime.h"
#include "minenav/path_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/footprint.h"
#include "tracker/path_tracker.h"
#include "tracker/pose_predictor.h"

namespace minenav {

struct PathTrackerNodeOptions {
  std::string path_channel = "PATH";
  std::string pose_channel = "POSE";
  std::string odometry_channel = "ODOMETRY";
  std::string map_channel = "CONTOUR_MAP";
  std::string line_map_channel;  // "" = none
  std::string drive_channel = "DRIVE_COMMAND";
  std::string status_channel = "TASK_STATUS";
  double rate = 10.0;              // Hz
  double pose_timeout = 12.0;      // s without a trusted estimate -> STOP
  double odometry_timeout = 0.5;   // s without odometry -> STOP
  double path_max_age = 600.0;     // s: an older path is abandoned
  double idle_stop_time = 1.0;     // s of STOPs after a path ends (or at the start); then silent
  double vehicle_width = 3.3;      // m
  double vehicle_length = 10.0;    // m
  std::string footprint;           // JSON file {"footprint": [[x, y], ...]}; "" = the rectangle
  PathTrackerOptions tracker;
  PosePredictorOptions prediction;
};

void DeclareOptions(ConfigSchema& schema, PathTrackerNodeOptions& o);
// Throws UsageError for options that contradict each other; reads the footprint file.
Footprint LoadTrackerFootprint(const PathTrackerNodeOptions& o);

class PathTrackerNode {
 public:
  // Subscribes and adds the control timer (call after runtime.Start()).
  PathTrackerNode(NodeRuntime& runtime, PathTrackerNodeOptions options, Footprint footprint);
  ~PathTrackerNode();
  int Run() { return runtime_.Run(); }

  const PathTracker& tracker() const { return tracker_; }
  // Maps built on the worker and taken by the control tick so far.
  int64_t maps_applied() const { return maps_applied_; }

 private:
  void Tick(int64_t now);
  // The newest collision map the worker built, if any, into the tracker.
  void TakeMaps();
  // Logs a verdict on an estimate; a jump also goes out on TASK_STATUS and HEARTBEAT.
  void Report(const EstimateVerdict& v);
  void PublishStatus(int64_t now, int8_t state, float progress, const std::string& message);
  // A path_t of the active or last finished request: a cancel, or a repeat to acknowledge.
  void Repeated(const path_t& m, int64_t now);
  // "" when pose and odometry are fresh, else why not.
  std::string Staleness(int64_t now) const;

  NodeRuntime& runtime_;
  PathTrackerNodeOptions options_;
  Footprint footprint_;
  PathTracker tracker_;
  PosePredictor predictor_;
  std::unique_ptr<MapUpdates> maps_;
  std::optional<int64_t> request_id_;  // the active path's
  std::optional<task_status_t> last_status_;  // the latest of the active or last finished path
  std::optional<path_t> active_path_;          // the message of the active (or last) path
  float progress_ = 0.0f;              // of the active path, at the last tick
  int64_t path_utime_ = 0;
  std::string stopped_because_;         // the watchdog's reason while it holds the vehicle
  std::string last_report_;             // the latest pose report (jumps) for the heartbeat
  int64_t seq_ = 0;
  std::optional<int64_t> idle_since_;  // when the tracker last became idle (no active path)
  int64_t maps_applied_ = 0;
  struct MapJob {
    std::vector<Segment> segments;
    std::string what;
  };
  struct BuiltMap {
    std::shared_ptr<TrackerMap> map;
    std::string what;
    size_t segments = 0;
  };
  // Builds collision maps off the node thread (reads options_ and footprint_ only, which do
  // not change). Last: stopped and destroyed first.
  std::unique_ptr<BackgroundWorker<MapJob, BuiltMap>> map_worker_;
};

}  // namespace minenav
