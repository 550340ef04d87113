#include "coordinator/coordinator_node.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/heartbeat_conversion.h"
#include "minenav/coordinator_command_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/path_message.h"
#include "planner/task_plan_message.h"
#include "tracker/cutter_conversions.h"

namespace minenav {
namespace {

// Paths kept to forward: a mission holds a handful at a time; the oldest go first.
constexpr size_t kPathsKept = 64;

int8_t BtStateToLcm(BtStatus s) {
  switch (s) {
    case BtStatus::kIdle: return mission_node_t::IDLE;
    case BtStatus::kRunning: return mission_node_t::RUNNING;
    case BtStatus::kSuccess: return mission_node_t::SUCCESS;
    case BtStatus::kFailure: return mission_node_t::FAILURE;
  }
  return mission_node_t::IDLE;
}

mission_status_t ToLcm(const MissionStatus& s, int64_t utime) {
  mission_status_t m{};
  m.utime = utime;
  m.mission_id = s.mission_id;
  m.state = static_cast<int8_t>(s.state);
  m.current_task_id = s.current_task_id;
  m.tasks_done = s.tasks_done;
  m.tasks_total = s.tasks_total;
  m.progress = static_cast<float>(s.progress);
  m.message = s.message;
  m.waiting_for = s.waiting_for;
  for (const MissionNodeStatus& n : s.nodes) {
    mission_node_t x{};
    x.id = n.id;
    x.parent = n.parent;
    x.name = n.name;
    x.state = BtStateToLcm(n.state);
    x.task_id = n.task_id;
    m.nodes.push_back(x);
  }
  m.num_nodes = static_cast<int32_t>(m.nodes.size());
  return m;
}

const CoordinatorOptions& Validated(const CoordinatorOptions& o) {
  if (const std::string why = ValidateCoordinatorOptions(o); !why.empty()) throw UsageError(why);
  return o;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

void DeclareOptions(ConfigSchema& s, CoordinatorNodeOptions& o) {
  s.AddChannel("heartbeat_in_channel", &o.heartbeat_in_channel, "subscribes", "heartbeat_t",
               "every process's liveness (required processes must be ready)");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t",
               "the fleet's pose estimate: the start of every path");
  s.AddChannel("task_request_channel", &o.task_request_channel, "publishes", "task_request_t",
               "requests to the task planner (next scan station, the advance)");
  s.AddChannel("task_plan_channel", &o.task_plan_channel, "subscribes", "task_plan_t", "the task planner's answers");
  s.AddChannel("path_request_channel", &o.path_request_channel, "publishes", "path_request_t",
               "requests to the path planner");
  s.AddChannel("path_channel", &o.path_channel, "subscribes", "path_t", "the path planner's answers");
  s.AddChannel("drive_path_channel", &o.drive_path_channel, "publishes", "path_t",
               "the path the tracker is to drive now (feasible = false cancels it)");
  s.AddChannel("status_channel", &o.status_channel, "subscribes", "task_status_t",
               "the tracker's and the cutter's acknowledgements and progress");
  s.AddChannel("cut_task_channel", &o.cut_task_channel, "publishes", "cutter_command_t",
               "cuts for the cutter (SUMP: depth and face; STOP: cancel)");
  s.AddChannel("cutter_state_channel", &o.cutter_state_channel, "subscribes", "cutter_state_t",
               "drum and boom: the miner trams only with the drum off and the boom up");
  s.AddChannel("command_channel", &o.command_channel, "subscribes", "coordinator_command_t",
               "the operator: start, pause, resume, abort, e-stop");
  s.AddChannel("mission_channel", &o.mission_channel, "publishes", "mission_status_t",
               "the mission's state, current subtask, what it waits for, the task tree");
  s.AddChannel("drive_channel", &o.drive_channel, "publishes", "drive_command_t",
               "STOP when the coordinator halts the vehicle, every tick while e-stopped");
  s.AddDouble("rate", &o.rate, "Hz", "the coordinator's tick: resends, timeouts, the tree", 1.0, 100.0);
  s.AddDouble("status_period", &o.status_period, "s", "between MISSION_STATUS messages (and on every change)", 0.1,
              60.0);
  s.AddDouble("boom_stowed_height", &o.boom_stowed_height, "m",
              "CUTTER_STATE's boom at least this high counts as raised (the cutter's boom_top 2.4)", 0.0, 10.0);
  s.AddBool("exit_when_done", &o.exit_when_done, "stop the process when the mission has ended (done, failed, aborted)");
  s.AddString("report_out", &o.report_out, "JSON file: what the mission did, written when it ends and at shutdown");
  s.AddBool("progress", &o.progress, "one line on stdout at every change of the mission's status (for a terminal)");
  const OptionScope m = OptionScope(s).Nested("mission");
  DeclareOptions(m, o.mission);
  m.AddFlatAliases({"face", "depth", "explore", "advance", "auto_start", "mission_id", "required", "clearance",
                    "max_stations"});
  s.AddHelpEpilog(R"(Examples:
  coordinator --face 46,3,0 --depth 1.0 --auto-start true      (explore, then advance the face near (46, 3) eastwards)
  coordinator --explore false --face 46,3,0 --depth 0.5        (waits for START on COORDINATOR_COMMAND)
  coordinator --advance false --required contour_mapper,path_planner,path_tracker,task_planner
)");
}

CoordinatorNode::CoordinatorNode(NodeRuntime& runtime, CoordinatorNodeOptions options)
    : runtime_(runtime),
      options_(std::move(options)),
      coordinator_(Validated(options_.mission), runtime.NowUtime()) {
  Bus& bus = runtime_.bus();
  Subscribe<heartbeat_t>(bus, options_.heartbeat_in_channel, [this](const heartbeat_t& m) {
    const int64_t now = runtime_.NowUtime();
    coordinator_.OnHeartbeat(HeartbeatSampleFromLcm(m, now), now);
  });
  Subscribe<pose_estimate_t>(bus, options_.pose_channel, [this](const pose_estimate_t& m) {
    const PoseEstimate e = FromLcm(m);
    if (e.converged) coordinator_.OnPose(e.pose, e.utime, runtime_.NowUtime());
  });
  Subscribe<task_plan_t>(bus, options_.task_plan_channel, [this](const task_plan_t& m) {
    const TaskPlanMessage plan = TaskPlanFromLcm(m);
    coordinator_.OnTaskPlan(plan.request_id, plan.plan, runtime_.NowUtime());
  });
  Subscribe<path_t>(bus, options_.path_channel, [this](const path_t& m) {
    PathAnswer a;
    a.request_id = m.request_id;
    a.utime = m.utime;
    a.feasible = m.feasible;
    a.status = m.status;
    a.start = FromLcm(m.start);
    a.length = m.length;
    if (!std::isfinite(a.length)) throw InputError("path " + std::to_string(m.request_id) + ": length is not finite");
    if (paths_.find(m.request_id) == paths_.end()) {
      path_order_.push_back(m.request_id);
      if (path_order_.size() > kPathsKept) {
        paths_.erase(path_order_.front());
        path_order_.pop_front();
      }
    }
    paths_[m.request_id] = m;
    coordinator_.OnPath(a, runtime_.NowUtime());
  });
  Subscribe<task_status_t>(bus, options_.status_channel, [this](const task_status_t& m) {
    if (m.state < task_status_t::PENDING || m.state > task_status_t::CANCELED)
      throw InputError("task status " + std::to_string(m.task_id) + ": unknown state " + std::to_string(m.state));
    if (!std::isfinite(m.progress)) throw InputError("task status " + std::to_string(m.task_id) + ": progress is not finite");
    TaskStatusReport r;
    r.task_id = m.task_id;
    r.state = static_cast<TaskState>(m.state);
    r.progress = std::clamp(static_cast<double>(m.progress), 0.0, 1.0);
    r.message = m.message;
    coordinator_.OnTaskStatus(r, runtime_.NowUtime());
  });
  Subscribe<cutter_state_t>(bus, options_.cutter_state_channel, [this](const cutter_state_t& m) {
    std::string why;
    const std::optional<CutterState> s = CutterStateFromLcm(m, &why);
    if (!s) throw InputError(why);
    coordinator_.OnCutterState(s->drum_on, s->boom_height >= options_.boom_stowed_height, runtime_.NowUtime());
  });
  Subscribe<coordinator_command_t>(bus, options_.command_channel, [this](const coordinator_command_t& m) {
    if (m.command < coordinator_command_t::START || m.command > coordinator_command_t::LOAD_MISSION)
      throw InputError("operator command: unknown command " + std::to_string(m.command));
    if (m.command == coordinator_command_t::LOAD_MISSION) {
      MINENAV_LOG(kWarn) << "operator command LOAD_MISSION refused: the mission is given by the options";
      return;
    }
    const auto command = static_cast<OperatorCommand>(m.command);
    const std::string refused = coordinator_.OnOperator(command, m.seq, runtime_.NowUtime());
    if (!refused.empty()) MINENAV_LOG(kWarn) << "operator " << ToString(command) << " refused: " << refused;
    PublishOutputs(runtime_.NowUtime());
    PublishStatus(runtime_.NowUtime());
  });
  runtime_.AddTimer(1.0 / options_.rate, [this](int64_t now) { Tick(now); });
  runtime_.OnShutdown([this] { WriteReport(); });
}

int CoordinatorNode::Run() {
  const int code = runtime_.Run();
  const MissionState st = coordinator_.state();
  if (code == 0 && (st == MissionState::kFailed || st == MissionState::kAborted)) return kExitRuntime;
  return code;
}

void CoordinatorNode::Tick(int64_t now) {
  if (!started_) {
    started_ = true;
    started_utime_ = now;
    if (options_.mission.auto_start) coordinator_.OnOperator(OperatorCommand::kStart, -2, now);
  }
  coordinator_.Tick(now);
  PublishOutputs(now);
  PublishStatus(now);
  const MissionStatus st = coordinator_.Status();
  const int8_t health = st.state == MissionState::kFailed ? heartbeat_t::WARN : heartbeat_t::OK;
  runtime_.SetStatus(health, std::string(ToString(st.state)) + ": " + st.message);
  if (coordinator_.Finished()) {
    if (!report_written_) {
      WriteReport();
      report_written_ = true;
    }
    if (options_.exit_when_done) runtime_.RequestStop();
  }
}

void CoordinatorNode::PublishOutputs(int64_t now) {
  CoordinatorOutputs out = coordinator_.TakeOutputs();
  Bus& bus = runtime_.bus();
  for (const std::string& line : out.log) MINENAV_LOG(kInfo) << line;
  for (TaskRequest q : out.task_requests) {
    q.utime = now;
    Publish(bus, options_.task_request_channel, TaskRequestToLcm(q));
  }
  for (const PathRequestOut& r : out.path_requests) {
    path_request_t m{};
    m.utime = now;
    m.request_id = r.request_id;
    m.start = ToLcm(r.start);
    m.goal = ToLcm(r.goal);
    m.position_tolerance = r.position_tolerance;
    m.heading_tolerance = r.heading_tolerance;
    m.allow_reverse = r.allow_reverse;
    m.clearance = r.clearance;
    m.allow_unknown = false;
    Publish(bus, options_.path_request_channel, m);
  }
  for (const int64_t id : out.forward_paths) {
    const auto it = paths_.find(id);
    if (it == paths_.end()) {
      MINENAV_LOG(kWarn) << "path " << id << " to forward is no longer kept";
      continue;
    }
    Publish(bus, options_.drive_path_channel, it->second);
  }
  for (const int64_t id : out.cancel_paths)
    Publish(bus, options_.drive_path_channel, NoPathToLcm(id, now, "canceled by the coordinator"));
  for (const CutTaskOut& c : out.cut_tasks) {
    CutterCommand cmd;
    cmd.utime = now;
    cmd.seq = c.id;
    cmd.action = c.cancel ? CutterCommand::Action::kStop : CutterCommand::Action::kSump;
    cmd.sump_depth = c.depth;
    if (!c.cancel) cmd.face = c.face;
    Publish(bus, options_.cut_task_channel, ToLcm(cmd));
  }
  if (out.stop_vehicle) {
    DriveCommand stop;
    stop.utime = now;
    stop.mode = DriveCommand::Mode::kStop;
    stop.timeout = 2.0 / options_.rate;
    Publish(bus, options_.drive_channel, ToLcm(stop));
  }
}

void CoordinatorNode::PublishStatus(int64_t now) {
  const MissionStatus s = coordinator_.Status();
  // A change of state, subtask or what it waits for is published at once.
  const std::string key = std::string(ToString(s.state)) + "|" + std::to_string(s.current_task_id) + "|" +
                          s.waiting_for + "|" + std::to_string(s.tasks_done) + "|" + std::to_string(s.nodes.size());
  if (key == last_status_key_ && now - last_status_ < std::llround(options_.status_period * 1e6)) return;
  last_status_key_ = key;
  last_status_ = now;
  Publish(runtime_.bus(), options_.mission_channel, ToLcm(s, now));
  if (options_.progress) PrintProgress(s, now);
}

void CoordinatorNode::PrintProgress(const MissionStatus& s, int64_t now) {
  std::string line = std::string(ToString(s.state)) + "  " + s.message;
  if (s.tasks_total > 0) line += "  [subtasks " + std::to_string(s.tasks_done) + "/" + std::to_string(s.tasks_total) + "]";
  if (!s.waiting_for.empty()) line += "  (waiting for " + s.waiting_for + ")";
  if (line == last_progress_) return;
  last_progress_ = line;
  const double t = static_cast<double>(now - started_utime_) * 1e-6;
  std::printf("[%4d:%02d] %s\n", static_cast<int>(t) / 60, static_cast<int>(t) % 60, line.c_str());
  std::fflush(stdout);
}

void CoordinatorNode::WriteReport() const {
  if (options_.report_out.empty()) return;
  const MissionStatus s = coordinator_.Status();
  const MissionStats& st = coordinator_.stats();
  nlohmann::json j;
  j["mission_id"] = s.mission_id;
  j["state"] = ToString(s.state);
  j["message"] = s.message;
  j["seconds"] = static_cast<double>(runtime_.NowUtime() - started_utime_) * 1e-6;
  j["stations_visited"] = st.stations_visited;
  j["stations_failed"] = st.stations_failed;
  j["drives"] = st.drives;
  j["drives_planned_ahead"] = st.drives_preplanned;
  j["replans"] = st.replans;
  j["retries"] = st.retries;
  j["resends"] = st.resends;
  j["pauses_for_lost_processes"] = st.pauses_for_lost_processes;
  j["planning_wait_median_s"] = Median(st.planning_waits);
  j["planning_wait_max_s"] =
      st.planning_waits.empty() ? 0.0 : *std::max_element(st.planning_waits.begin(), st.planning_waits.end());
  j["planning_waits_s"] = st.planning_waits;
  j["events"] = st.events;
  nlohmann::json tasks = nlohmann::json::array();
  for (const Task& t : coordinator_.plan_tasks()) {
    nlohmann::json x;
    x["id"] = t.id;
    x["kind"] = ToString(t.kind);
    x["description"] = t.description;
    x["target"] = {t.target.x, t.target.y, t.target.theta};
    x["depth"] = t.depth;
    x["width"] = t.width;
    if (IsCutTask(t.kind)) x["face"] = {t.face.a.x(), t.face.a.y(), t.face.b.x(), t.face.b.y()};
    for (const MissionNodeStatus& n : s.nodes)
      if (n.task_id == t.id) x["state"] = ToString(n.state);
    tasks.push_back(x);
  }
  j["subtasks"] = tasks;
  try {
    WriteFileAtomically(options_.report_out, j.dump(2) + "\n");
  } catch (const std::exception& e) {
    MINENAV_LOG(kError) << "report not written: " << e.what();
  }
}

}  // namespace minenav
