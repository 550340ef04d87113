#pragma once
// What a finished mission left behind, as plain values: the parts of its LCM log that the
// mission report judges (logger/mission_log.h reads them, decoding each channel), and the
// coordinator's own report (coordinator_node.cc WriteReport, `--report-out`). No LCM here:
// evaluation/mission_evaluation.h computes the figures from these. The states are the
// coordinator's own types (MissionState, TaskState, BtStatus, HeartbeatState), which carry
// the messages' constants.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/pose2.h"
#include "coordinator/behavior_tree.h"
#include "coordinator/coordinator.h"
#include "coordinator/heartbeat_watch.h"
#include "planner/motion.h"

namespace minenav {

// One SIM_WORLD: the true world from `utime` on (vehicle_sim republishes it when the
// cutter removes coal).
struct WorldSnapshot {
  int64_t utime = 0;
  int64_t version = 0;
  std::vector<Segment> segments;
};

// One path_t (PATH: the planner's answers; DRIVE_PATH: what the coordinator sent the tracker).
struct LoggedPath {
  int64_t utime = 0;        // the message's stamp
  int64_t request_id = 0;
  bool feasible = false;
  std::string status;       // the planner's one line ("ok: 26.00 m, ... 3.0 ms on map version 1")
  PlannedPath path;         // empty when not feasible (or when its pieces did not decode)
};

// One TASK_STATUS line (the coordinator's TaskState names task_status_t's states).
struct TaskStatusLine {
  int64_t utime = 0;
  int64_t task_id = 0;
  TaskState state = TaskState::kPending;
  std::string message;
};

// One node of the task tree in a MISSION_STATUS (mission_node_t: the behaviour tree's states).
struct MissionNodeLine {
  std::string name;
  BtStatus state = BtStatus::kIdle;
};

// One MISSION_STATUS (the coordinator's MissionState names mission_status_t's states).
struct MissionStatusLine {
  int64_t utime = 0;
  MissionState state = MissionState::kIdle;
  std::string message;
  std::vector<MissionNodeLine> nodes;  // the task tree
};

// The log of a mission, decoded. Poses in log order.
struct MissionRecord {
  std::vector<StampedPose> truth;      // SIM_TRUTH (world frame)
  std::vector<StampedPose> estimates;  // POSE (map frame: the world frame when the mapper starts at the true start pose)
  std::vector<StampedPose> odometry;   // ODOMETRY (odometry frame)
  std::vector<WorldSnapshot> worlds;   // SIM_WORLD in log order: the first is the world at the start
  std::vector<LoggedPath> drive_paths; // DRIVE_PATH
  std::vector<LoggedPath> planner_paths;  // PATH
  std::vector<TaskStatusLine> task_status;
  std::vector<MissionStatusLine> mission_status;
  std::vector<HeartbeatSample> heartbeats;  // utime: the heartbeat's own stamp
  std::vector<Pose2> scan_stations;    // SCAN_STATION targets of TASK_PLAN, in order, each task once
  int64_t first_utime = 0, last_utime = 0;  // event timestamps (us) of the first and last event
  int64_t events = 0;
  int64_t bad_messages = 0;            // on the channels read, messages that did not decode or were invalid
  std::string first_bad;               // one line: the first of them
  int64_t auth_refused = 0;            // read with the fleet's key: messages on signed channels that did
                                       // not verify (forged, replayed, tampered, unsigned): not used
  std::string first_auth_refused;      // one line: the first of them
  std::string damage;                  // "" or where the log is damaged (what was before is used)
};

// One subtask of the coordinator's report.
struct MissionSubtask {
  int64_t id = 0;
  std::string kind;         // "move", "box_cut", "slab_cut", "back_out", ...
  std::string description;
  std::string state;        // the tree node's state at the end ("success", "failure", ...), "" if none
  Pose2 target;             // cuts: squared up to the face, theta = the direction of advance
  double depth = 0.0;       // m, cuts
  double width = 0.0;       // m, cuts
  std::optional<Segment> face;
};

// The coordinator's report (coordinator_node.cc WriteReport).
struct MissionReport {
  std::string mission_id, state, message;
  double seconds = 0.0;  // s from the coordinator's start to the report
  int stations_visited = 0, stations_failed = 0;
  int drives = 0, drives_planned_ahead = 0, replans = 0, retries = 0, resends = 0;
  int pauses_for_lost_processes = 0;
  std::vector<double> planning_waits_s;
  std::vector<std::string> events;
  std::vector<MissionSubtask> subtasks;
};

// Parses the coordinator's report; throws InputError (one line naming `source` and the key)
// when it is not that JSON. Missing counters read as 0, missing lists as empty.
MissionReport ParseMissionReportJson(const std::string& text, const std::string& source);

}  // namespace minenav
