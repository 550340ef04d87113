#pragma once
// ladar_driver as nodes (thesis 4.2, 5.2.1, App. B, C): the process
// (ladar_driver_main.cc) declares these options, resolves them and wires one of the two.
//
// LadarSimulationNode ray-casts the world (--world FILE, or the line_map_t on SIM_WORLD
// that vehicle_sim publishes) from the vehicle's true pose (SIM_TRUTH) with LadarSimulator,
// at the sensor's scan rate. Scans are scheduled on the truth stream's clock
// (sensor_driver/scan_schedule.h): scan k is stamped t0 + k / scan_rate (t0 = the first
// truth sample) and is made as soon as a truth sample at or after that time arrives, from
// the pose interpolated between the two samples around it. So a scan's pose is never
// extrapolated, and a batch run over a log of SIM_TRUTH makes exactly the scans the live
// run made. The whole revolution is cast from the pose at the scan's utime (the motion
// during one 0.1 s revolution is under 1 cm at the miner's speed). scan_id counts
// published scans from 0.
//
// ScanReplayNode (--replay LOG) republishes the LADAR_SCAN events of a log (e.g. a real
// dataset) at the recorded rate (--replay-speed), unchanged; scans that do not decode are
// counted as bad and skipped.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/geometry.h"
#include "common/node/event_log.h"
#include "common/node/node_runtime.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "minenav/line_map_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "sensor_driver/ladar_model.h"
#include "sensor_driver/ladar_model_options.h"
#include "sensor_driver/ladar_simulator.h"
#include "sensor_driver/scan_schedule.h"

namespace minenav {

struct LadarDriverOptions {
  LadarModelOptions model;
  ScanScheduleOptions schedule;  // period_us: from the model's scan rate
  std::string sensor_pose = "0,0,0";
  int64_t seed = 1;
  std::string world;
  std::string replay;
  double replay_speed = 1.0;
  std::string truth_channel = "SIM_TRUTH";
  std::string world_channel = "SIM_WORLD";
  std::string scan_channel = "LADAR_SCAN";
};

// Every option: the model as model.*, the schedule as schedule.* (the flat flags of before,
// --sensor, --range-sigma, --truth-buffer ..., as aliases), and the examples for --help.
void DeclareOptions(ConfigSchema& schema, LadarDriverOptions& o);

// What the simulation needs from the options, resolved before the bus starts so that a bad
// value exits 2 at once. Throws UsageError; also for --replay with --log (`node`).
struct LadarSimulationSetup {
  LadarModel model;
  Pose2 sensor_offset;            // the sensor in the vehicle frame
  ScanScheduleOptions schedule;   // with the model's period
};
LadarSimulationSetup ResolveLadarDriver(const LadarDriverOptions& o, const NodeOptions& node);

class LadarSimulationNode {
 public:
  // Loads --world or subscribes the world channel, subscribes the truth (after runtime.Start()).
  LadarSimulationNode(NodeRuntime& runtime, const LadarDriverOptions& options, const LadarSimulationSetup& setup);
  int Run() { return runtime_.Run(); }
  int64_t scans_published() const { return scan_id_; }

 private:
  void SetWorld(std::vector<Segment> segments);
  void OnWorld(const line_map_t& m);
  void OnTruth(const vehicle_truth_t& m);

  NodeRuntime& runtime_;
  LadarDriverOptions options_;
  LadarSimulator simulator_;
  Pose2 sensor_offset_;
  ScanSchedule schedule_;
  std::vector<Segment> world_;
  std::unique_ptr<StaticSegmentIndex> index_;  // null until there is a world
  int64_t scan_id_ = 0;
  int64_t skipped_no_world_ = 0;
};

class ScanReplayNode {
 public:
  // Opens the --replay log (throws InputError when it cannot). After runtime.Start().
  ScanReplayNode(NodeRuntime& runtime, const LadarDriverOptions& options);
  // Republishes the log's scans at the recorded pace until its end, a signal or --run-for,
  // serving heartbeats while it waits; then shuts the runtime down. Returns 0.
  int Run();
  int64_t scans_published() const { return published_; }
  int64_t scans_bad() const { return bad_; }

 private:
  bool OutOfTime() const;
  // Waits until clock time `due`; false when stopped (or out of time) first.
  bool WaitUntil(int64_t due);

  NodeRuntime& runtime_;
  LadarDriverOptions options_;
  LogReader reader_;
  int64_t start_utime_ = 0;
  int64_t run_for_us_ = 0;
  std::optional<int64_t> log_t0_, clock_t0_;  // the first scan's log time and clock time
  int64_t published_ = 0, bad_ = 0;
};

}  // namespace minenav
