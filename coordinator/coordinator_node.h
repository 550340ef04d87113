#pragma once
// coordinator as a node: the Coordinator (coordinator.h) on the bus. The process
// (coordinator_main.cc) only declares these options and wires the node.
//
//   subscribes  HEARTBEAT (heartbeat_t: every process's liveness), POSE (pose_estimate_t: the
//               start of each path; converged estimates only), TASK_PLAN (task_plan_t),
//               PATH (path_t: the planner's answers, kept by request id to forward),
//               TASK_STATUS (task_status_t: the tracker's and the cutter's acknowledgements and
//               progress), CUTTER_STATE (cutter_state_t: drum and boom, for tramming),
//               COORDINATOR_COMMAND (coordinator_command_t: the operator)
//   publishes   TASK_REQUEST (task_request_t), PATH_REQUEST (path_request_t), DRIVE_PATH
//               (path_t: the path the tracker is to drive now, or feasible = false to cancel
//               one), CUT_TASK (cutter_command_t: SUMP with depth and face, STOP to cancel),
//               DRIVE_COMMAND (drive_command_t: STOP when it halts the vehicle, and every tick
//               while e-stopped), MISSION_STATUS (mission_status_t, every status_period and on
//               every change), HEARTBEAT
// It decides on the fleet's own estimates only. With --report-out it writes what the mission did (JSON) when the
// mission ends and at shutdown.

#include <cstdint>
#include <deque>
#include <map>
#include <string>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "coordinator/coordinator.h"
#include "minenav/path_t.hpp"

namespace minenav {

struct CoordinatorNodeOptions {
  std::string heartbeat_in_channel = "HEARTBEAT";
  std::string pose_channel = "POSE";
  std::string task_request_channel = "TASK_REQUEST";
  std::string task_plan_channel = "TASK_PLAN";
  std::string path_request_channel = "PATH_REQUEST";
  std::string path_channel = "PATH";
  std::string drive_path_channel = "DRIVE_PATH";
  std::string status_channel = "TASK_STATUS";
  std::string cut_task_channel = "CUT_TASK";
  std::string cutter_state_channel = "CUTTER_STATE";
  std::string command_channel = "COORDINATOR_COMMAND";
  std::string mission_channel = "MISSION_STATUS";
  std::string drive_channel = "DRIVE_COMMAND";
  double rate = 10.0;                 // Hz: resends, timeouts, the tree
  double status_period = 1.0;         // s between MISSION_STATUS messages (and on every change)
  double boom_stowed_height = 2.3;    // m: CUTTER_STATE's boom at least this high counts as raised
  bool exit_when_done = false;        // stop the process when the mission has ended
  bool progress = false;              // one line on stdout at every change of the mission's status
  std::string report_out;             // JSON: what the mission did ("" = none)
  CoordinatorOptions mission;
};

void DeclareOptions(ConfigSchema& schema, CoordinatorNodeOptions& o);

class CoordinatorNode {
 public:
  // Subscribes and adds the timers (call after runtime.Start()). Throws UsageError on bad options.
  CoordinatorNode(NodeRuntime& runtime, CoordinatorNodeOptions options);
  // The runtime's exit code; 3 (kExitRuntime) when the mission ended FAILED or ABORTED, so a
  // supervisor that ends the fleet with the mission passes the outcome on.
  int Run();
  const Coordinator& coordinator() const { return coordinator_; }

 private:
  void Tick(int64_t now);
  void PublishOutputs(int64_t now);
  void PublishStatus(int64_t now);
  void WriteReport() const;
  void PrintProgress(const MissionStatus& s, int64_t now);

  NodeRuntime& runtime_;
  CoordinatorNodeOptions options_;
  Coordinator coordinator_;
  std::map<int64_t, path_t> paths_;  // the planner's latest answer per request id (the newest kept)
  std::deque<int64_t> path_order_;
  int64_t last_status_ = 0;
  std::string last_status_key_;
  std::string last_progress_;
  bool started_ = false;
  bool report_written_ = false;
  int64_t started_utime_ = 0;
};

}  // namespace minenav
