#pragma once
// The coordinator (thesis 6.1, Figure 41: what TCA did for MINENAV): it executes the mission
// as a behaviour tree (coordinator/behavior_tree.h) whose leaves it dispatches to the fleet,
// and it obeys the operator.
//
//   mission     sequence: wait for the fleet (every required HEARTBEAT ready), explore (scan
//               stations chosen one at a time by the task planner until it says no reachable
//               frontier remains), plan the advance (the task planner's subtasks: into
//               position, box cut, reposition, slab cut, back out), then the subtasks, each
//               under a retry; the subtree of the advance is grafted when its plan arrives.
//   a drive     PATH_REQUEST from the latest pose estimate to the task's target; the planner's
//               PATH forwarded to the tracker on DRIVE_PATH; done when the tracker's
//               TASK_STATUS says DONE. The tracker's TASK_STATUS of the path is the
//               acknowledgement; a replanned PATH of the same request is forwarded too.
//   a cut       CUT_TASK to the cutter (depth, face line); done on its TASK_STATUS DONE.
//   planning    while subtask n executes, the path of subtask n+1 is requested from where n
//   ahead       will end (6.2.2: "the effective planning time is usually zero"); it is used
//               when n ends within `preplan_tolerance` of that pose and at most
//               `preplan_max_age` after it was planned, else planned anew.
//   commands    every command carries an id and is re-sent every `resend_period` until it is
//               acknowledged (PATH, TASK_PLAN, TASK_STATUS of that id), so a lost message costs a
//               resend and a repeat is harmless; no answer in `answer_timeout`: the leaf fails.
//   appendages  a driving subtask waits until CUTTER_STATE says the drum is off and the boom up
//               (the only state to tram in, 6.2.1), when a cutter reports at all.
//   heartbeats  a required process silent for `heartbeat_timeout` (or in ERROR) while the
//               mission runs stops the vehicle (running subtasks halted) and waits; when it is
//               back the halted subtask starts afresh from where the vehicle is; not back within
//               `recovery_timeout`: the mission fails, the vehicle stopped, and says why.
//   operator    start, pause (halt, vehicle stopped), resume (the halted subtask afresh), abort
//               (halt, stopped, ABORTED), e-stop (halt, STOP commands every tick, ESTOPPED until
//               resume or abort). A repeated command (same seq) is ignored.
//
// Plain C++: events in (with the clock's time), outputs collected until TakeOutputs(); no LCM,
// no clock, no threads. coordinator_node.h puts it on the bus.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "coordinator/behavior_tree.h"
#include "coordinator/heartbeat_watch.h"
#include "planner/task.h"

namespace minenav {

class OptionScope;

struct CoordinatorOptions {
  std::string mission_id = "mission";
  // Processes whose HEARTBEAT must be ready before the mission starts and while it runs.
  // (comma-separated; "name" or "name/instance").
  std::string required = "vehicle_sim,ladar_driver,contour_mapper,path_planner,path_tracker,task_planner,cutter";
  bool explore = true;             // survey the unknown section first
  int max_stations = 30;           // scan stations at most
  int max_failed_stations = 3;     // consecutive stations not reached (or not decided: the task planner's FAILED): the exploration fails
  double station_dwell = 2.0;      // s standing at each station (scans for the mapper)
  bool advance = true;             // then advance an entry
  std::string face;                // "x,y,theta": a point in front of the face to advance and the direction of advance
  double depth = 1.0;              // m, how far to advance the face
  double clearance = 0.1;          // m, asked of the planners
  double position_tolerance = 0.1; // m, path goals
  double heading_tolerance = 0.035;// rad, path goals
  int drive_attempts = 3;          // a drive is planned anew from where the vehicle is, at most this often
  int cut_attempts = 1;            // a cut that fails is not repeated blindly
  int plan_attempts = 2;           // task planner requests (advance) before the mission fails
  double retry_delay = 3.0;        // s between a failed attempt and the next (the world settles, the map catches up)
  double resend_period = 2.0;      // s between repeats of an unacknowledged command
  double answer_timeout = 30.0;    // s for a planner's answer or a process's acknowledgement
  double ready_timeout = 60.0;     // s for the fleet to be ready after start
  double heartbeat_timeout = 3.0;  // s of silence after which a process is lost
  double recovery_timeout = 60.0;  // s a lost process has to come back before the mission fails
  bool preplan = true;             // plan subtask n+1 while n executes
  double preplan_tolerance = 0.3;  // m (and that over 3 m in rad): a pre-planned path is used this close to its start
  double preplan_max_age = 300.0;  // s: an older pre-planned path is planned anew (the tracker abandons at 600 s)
  double cut_end_offset = 0.4;     // m a cut ends behind its start (cutter withdraw_gap - standoff)
  bool auto_start = false;         // start without an operator START
  double max_pose_age = 30.0;      // s: an older pose estimate is not a path's start
};

std::string ValidateCoordinatorOptions(const CoordinatorOptions& o);
// The processes of `required`, in order.
std::vector<std::string> RequiredProcesses(const CoordinatorOptions& o);
// The face of `face` (throws UsageError naming the option when it does not parse).
Pose2 FacePose(const CoordinatorOptions& o);
void DeclareOptions(OptionScope scope, CoordinatorOptions& o);

// mission_status_t's state constants.
enum class MissionState : int8_t {
  kIdle = 0, kRunning = 1, kPaused = 2, kDone = 3, kFailed = 4, kAborted = 5, kEstopped = 6, kWaiting = 7
};
const char* ToString(MissionState s);

// coordinator_command_t's command constants.
enum class OperatorCommand : int8_t { kStart = 0, kPause = 1, kResume = 2, kAbort = 3, kEstop = 4 };
const char* ToString(OperatorCommand c);

// task_status_t's state constants.
enum class TaskState : int8_t { kPending = 0, kActive = 1, kDone = 2, kFailed = 3, kCanceled = 4 };

struct PathAnswer {
  int64_t request_id = 0;
  int64_t utime = 0;     // the path's stamp: a replanned path is newer
  bool feasible = false;
  std::string status;    // one line
  Pose2 start;
  double length = 0.0;   // m
};

struct TaskStatusReport {
  int64_t task_id = 0;
  TaskState state = TaskState::kActive;
  double progress = 0.0;
  std::string message;
};

struct PathRequestOut {
  int64_t request_id = 0;
  Pose2 start, goal;
  double position_tolerance = 0.0, heading_tolerance = 0.0, clearance = 0.0;
  bool allow_reverse = true;
};

struct CutTaskOut {
  int64_t id = 0;         // CUT_TASK seq
  bool cancel = false;    // STOP the cut `id`
  double depth = 0.0;     // m
  Segment face;
};

struct CoordinatorOutputs {
  std::vector<TaskRequest> task_requests;    // TASK_REQUEST
  std::vector<PathRequestOut> path_requests; // PATH_REQUEST
  std::vector<int64_t> forward_paths;        // the PATH of these request ids, on DRIVE_PATH
  std::vector<int64_t> cancel_paths;         // cancel these request ids on DRIVE_PATH
  std::vector<CutTaskOut> cut_tasks;         // CUT_TASK
  bool stop_vehicle = false;                 // a DRIVE_COMMAND STOP now
  std::vector<std::string> log;              // lines for the log (what happened)
};

struct MissionNodeStatus {
  int id = 0, parent = -1;
  std::string name;
  BtStatus state = BtStatus::kIdle;
  int64_t task_id = -1;
};

struct MissionStatus {
  std::string mission_id;
  MissionState state = MissionState::kIdle;
  int64_t current_task_id = -1;
  int tasks_done = 0, tasks_total = 0;
  double progress = 0.0;
  std::string message, waiting_for;
  std::vector<MissionNodeStatus> nodes;
};

// What the mission did, for the report.
struct MissionStats {
  int stations_visited = 0, stations_failed = 0;
  int drives = 0, drives_preplanned = 0, replans = 0, retries = 0, resends = 0;
  int pauses_for_lost_processes = 0;
  std::vector<double> planning_waits;  // s from a drive's start to its path on DRIVE_PATH
  std::vector<std::string> events;     // retried, refused, lost: one line each
};

class Coordinator {
 public:
  // first_id: ids of requests and tasks count up from it (unique per run: e.g. the clock).
  Coordinator(CoordinatorOptions options, int64_t first_id);

  void OnHeartbeat(const HeartbeatSample& hb, int64_t now);
  void OnPose(const Pose2& pose, int64_t utime, int64_t now);
  // The task planner's answer to request_id.
  void OnTaskPlan(int64_t request_id, const TaskPlan& plan, int64_t now);
  void OnPath(const PathAnswer& path, int64_t now);
  void OnTaskStatus(const TaskStatusReport& status, int64_t now);
  void OnCutterState(bool drum_on, bool boom_raised, int64_t now);
  // Returns "" when obeyed, else why not (one line). A repeated seq is ignored ("").
  std::string OnOperator(OperatorCommand command, int64_t seq, int64_t now);
  // Resends, timeouts, the next steps of the tree. Call at a steady rate (10 Hz).
  void Tick(int64_t now);

  CoordinatorOutputs TakeOutputs();
  MissionStatus Status() const;
  MissionState state() const { return state_; }
  bool Finished() const {
    return state_ == MissionState::kDone || state_ == MissionState::kFailed || state_ == MissionState::kAborted;
  }
  const MissionStats& stats() const { return stats_; }
  const BehaviorTree& tree() const { return tree_; }
  const BtState& tree_state() const { return bt_; }
  // The subtasks of the advance plan, once planned.
  const std::vector<Task>& plan_tasks() const { return plan_tasks_; }

 private:
  // What an action leaf of the tree does (BtNode::ref indexes actions_).
  enum class ActionKind { kWaitFleet, kExplore, kPlanAdvance, kTask };
  struct ActionSpec {
    ActionKind kind = ActionKind::kTask;
    Task task;  // kTask
  };
  // A drive in progress (a driving subtask, or the way to a scan station).
  struct Drive {
    enum class Phase { kWaitAppendages, kWaitPose, kRequest, kWaitPath, kSendPath, kDriving, kDone, kFailed };
    Phase phase = Phase::kWaitAppendages;
    Pose2 goal;
    double clearance = 0.0;
    bool allow_reverse = true;
    int64_t request_id = -1;
    int64_t last_sent = 0, since = 0, started = 0;
    int64_t path_utime = 0;
    std::string reason;
  };
  // A running action leaf.
  struct Running {
    int node = -1;
    ActionKind kind = ActionKind::kTask;
    int64_t started = 0;
    int64_t not_before = 0;  // a retry waits until then
    // explore / plan advance: the task planner's request
    int64_t request_id = -1;
    int64_t last_sent = 0, since = 0;
    bool waiting_plan = false;
    // explore: the station under way
    int stations = 0, failed_in_a_row = 0;
    bool dwelling = false;
    int64_t dwell_until = 0;
    // drives and cuts
    std::optional<Drive> drive;
    int64_t cut_id = -1;
    bool cut_acknowledged = false;
    double progress = 0.0;
    std::string message;
  };
  // A path requested ahead for the subtask after the running one.
  struct Preplan {
    int64_t task_id = -1;
    int64_t request_id = -1;
    Pose2 start;
    std::optional<PathAnswer> answer;
    int64_t last_sent = 0;
  };

  int64_t NextId() { return next_id_++; }
  void Log(const std::string& line) { out_.log.push_back(line); }
  void Event(const std::string& line);
  void BuildMission();
  void GraftAdvance(const std::vector<Task>& tasks);
  void Start(int64_t now);
  void StepTree(int64_t now);
  void StartAction(int node, int64_t now);
  void HaltActions(const std::vector<int>& nodes, int64_t now);
  void FinishAction(Running& r, bool success, const std::string& reason, int64_t now);
  // One more station in a row `failures` ("not reached", ...): true when that is
  // max_failed_stations and the exploration has failed, its reason naming `last`.
  bool ExplorationFailedAgain(Running& r, const std::string& failures, const std::string& last, int64_t now);
  void TickAction(Running& r, int64_t now);
  void TickWaitFleet(Running& r, int64_t now);
  void TickPlanRequest(Running& r, TaskRequestKind kind, int64_t now);
  void TickExplore(Running& r, int64_t now);
  void TickCut(Running& r, const Task& task, int64_t now);
  // Advances a drive; true when it ended (phase kDone or kFailed).
  bool TickDrive(Drive& d, int64_t now);
  void BeginDrive(Running& r, const Pose2& goal, double clearance, bool allow_reverse, int64_t task_id, int64_t now);
  void RequestPreplan(const Task& current, int64_t now);
  void CheckHealth(int64_t now);
  void StopEverything(MissionState state, const std::string& why, int64_t now);
  bool PoseFresh(int64_t now) const;
  const Task* NextTaskAfter(int64_t task_id) const;
  Running* RunningWithPath(int64_t request_id);

  CoordinatorOptions options_;
  Pose2 face_;
  int64_t next_id_;
  HeartbeatWatch watch_;
  BehaviorTree tree_;
  BtState bt_;
  std::vector<ActionSpec> actions_;
  std::map<int, Running> running_;  // by tree node
  std::vector<Task> plan_tasks_;
  std::optional<Preplan> preplan_;
  std::map<int64_t, PathAnswer> paths_;  // answers by request id (the latest of each)
  std::map<int64_t, TaskPlan> plans_;    // task planner answers by request id
  std::map<int64_t, TaskStatusReport> statuses_;  // latest TASK_STATUS by task id
  std::set<int64_t> canceling_;          // path requests whose cancel is not yet acknowledged
  MissionState state_ = MissionState::kIdle;
  std::string message_ = "idle: waiting for START";
  std::string waiting_for_;
  std::optional<Pose2> pose_;
  int64_t pose_utime_ = 0, pose_received_ = 0;
  std::optional<bool> cutter_stowed_;
  int64_t last_operator_seq_ = -1;
  int64_t lost_since_ = -1;  // us, when a required process was first found lost (-1: none)
  bool halted_for_loss_ = false;
  CoordinatorOutputs out_;
  MissionStats stats_;
};

}  // namespace minenav
