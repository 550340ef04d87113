#include "coordinator/coordinator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "common/angle.h"
#include "common/config.h"
#include "common/pose_text.h"

namespace minenav {
namespace {

int64_t Us(double seconds) { return std::llround(seconds * 1e6); }

std::string Where(const Pose2& p) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.2f, %.2f, %.1f deg)", p.x, p.y, p.theta * 180.0 / M_PI);
  return buf;
}

std::string Join(const std::vector<std::string>& parts, const char* sep) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

// The pose `distance` m ahead of `p` along its heading.
Pose2 Ahead(const Pose2& p, double distance) {
  return {p.x + distance * std::cos(p.theta), p.y + distance * std::sin(p.theta), p.theta};
}

bool Near(const Pose2& a, const Pose2& b, double tolerance) {
  return std::hypot(a.x - b.x, a.y - b.y) <= tolerance &&
         std::abs(NormalizeAngle(a.theta - b.theta)) * 3.0 <= tolerance;
}

}  // namespace

const char* ToString(MissionState s) {
  switch (s) {
    case MissionState::kIdle: return "IDLE";
    case MissionState::kRunning: return "RUNNING";
    case MissionState::kPaused: return "PAUSED";
    case MissionState::kDone: return "DONE";
    case MissionState::kFailed: return "FAILED";
    case MissionState::kAborted: return "ABORTED";
    case MissionState::kEstopped: return "ESTOPPED";
    case MissionState::kWaiting: return "WAITING";
  }
  return "UNKNOWN";
}

const char* ToString(OperatorCommand c) {
  switch (c) {
    case OperatorCommand::kStart: return "start";
    case OperatorCommand::kPause: return "pause";
    case OperatorCommand::kResume: return "resume";
    case OperatorCommand::kAbort: return "abort";
    case OperatorCommand::kEstop: return "e-stop";
  }
  return "unknown";
}

std::string ValidateCoordinatorOptions(const CoordinatorOptions& o) {
  if (o.mission_id.empty()) return "mission_id must not be empty";
  if (!o.explore && !o.advance) return "nothing to do: explore and advance are both off";
  for (const std::string& p : RequiredProcesses(o))
    if (p.empty()) return "required: an empty process name in '" + o.required + "'";
  if (o.advance) {
    if (o.face.empty()) return "advance: --face x,y,theta is required (a point in front of the face, the direction of advance)";
    try {
      FacePose(o);
    } catch (const UsageError& e) {
      return e.what();
    }
  }
  if (o.depth <= 0.0) return "depth must be > 0";
  return "";
}

std::vector<std::string> RequiredProcesses(const CoordinatorOptions& o) {
  std::vector<std::string> out;
  std::stringstream in(o.required);
  std::string name;
  while (std::getline(in, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    out.push_back(name);
  }
  return out;
}

Pose2 FacePose(const CoordinatorOptions& o) { return ParsePoseText(o.face, "--face"); }

void DeclareOptions(OptionScope s, CoordinatorOptions& o) {
  s.AddString("mission_id", &o.mission_id, "the mission's name on TASK_REQUEST and MISSION_STATUS");
  s.AddString("required", &o.required,
              "processes whose HEARTBEAT must be ready before the start and while the mission runs "
              "(comma-separated; name or name/instance; empty = none)");
  s.AddBool("explore", &o.explore, "survey the unknown section first (scan stations from the task planner)");
  s.AddInt("max_stations", &o.max_stations, "scan stations at most", 1, 10000);
  s.AddInt("max_failed_stations", &o.max_failed_stations, "consecutive stations not reached (or not decided: the task planner answered FAILED) before the exploration fails",
           1, 100);
  s.AddDouble("station_dwell", &o.station_dwell, "s", "time standing at each station for the ladar's scans", 0.0, 600.0);
  s.AddBool("advance", &o.advance, "then advance an entry: box cut, slab cut, back out");
  s.AddString("face", &o.face, "advance: x,y,theta (m, m, rad or NNdeg): a point in front of the face and the direction "
              "of advance");
  s.AddDouble("depth", &o.depth, "m", "how far to advance the face", 0.01, 20.0);
  s.AddDouble("clearance", &o.clearance, "m", "clearance asked of the path and task planners", 0.0, 2.0);
  s.AddDouble("position_tolerance", &o.position_tolerance, "m", "goal position tolerance of every path", 0.001, 5.0);
  s.AddDouble("heading_tolerance", &o.heading_tolerance, "rad", "goal heading tolerance of every path", 0.0001, 3.0);
  s.AddInt("drive_attempts", &o.drive_attempts, "a failed drive is planned anew from where the vehicle is, this often in all",
           1, 100);
  s.AddInt("cut_attempts", &o.cut_attempts, "attempts of a cut (the remaining depth from the face reached)", 1, 10);
  s.AddInt("plan_attempts", &o.plan_attempts, "task planner requests for the advance before the mission fails", 1, 10);
  s.AddDouble("retry_delay", &o.retry_delay, "s",
              "between a failed attempt and the next (the world settles, the map catches up)", 0.0, 600.0);
  s.AddDouble("resend_period", &o.resend_period, "s", "between repeats of an unacknowledged command", 0.05, 60.0);
  s.AddDouble("answer_timeout", &o.answer_timeout, "s",
              "for a planner's answer or a process's acknowledgement before the step fails", 0.1, 3600.0);
  s.AddDouble("ready_timeout", &o.ready_timeout, "s", "for every required process to be ready after START", 0.1, 3600.0);
  s.AddDouble("heartbeat_timeout", &o.heartbeat_timeout, "s", "silence after which a process is lost", 0.1, 600.0);
  s.AddDouble("recovery_timeout", &o.recovery_timeout, "s",
              "a lost process has this long to come back before the mission fails", 0.0, 3600.0);
  s.AddBool("preplan", &o.preplan, "plan the next subtask's path while the current one executes");
  s.AddDouble("preplan_tolerance", &o.preplan_tolerance, "m",
              "a path planned ahead is used when the vehicle is this close to its start (heading: this / 3 m)", 0.0, 5.0);
  s.AddDouble("preplan_max_age", &o.preplan_max_age, "s",
              "a path planned ahead longer ago than this is planned anew: the tracker abandons a path older than "
              "its path_max_age (600 s), and at real speed a cut keeps the next path waiting about that long "
              "(300 s: half of it)",
              1.0, 1e6);
  s.AddDouble("cut_end_offset", &o.cut_end_offset, "m",
              "a cut leaves the vehicle this far behind where it started (the cutter backs out to its withdraw_gap, "
              "it starts at its standoff: their difference; for planning ahead)",
              -5.0, 5.0);
  s.AddBool("auto_start", &o.auto_start, "start the mission without an operator START");
  s.AddDouble("max_pose_age", &o.max_pose_age, "s", "an older pose estimate is not used as a path's start", 0.1, 3600.0);
}

Coordinator::Coordinator(CoordinatorOptions options, int64_t first_id)
    : options_(std::move(options)),
      face_(options_.face.empty() ? Pose2() : FacePose(options_)),
      next_id_(first_id),
      watch_(RequiredProcesses(options_), options_.heartbeat_timeout) {
  BuildMission();
}

void Coordinator::BuildMission() {
  tree_ = BehaviorTree();
  actions_.clear();
  running_.clear();
  plan_tasks_.clear();
  preplan_.reset();
  const int root = tree_.AddSequence(-1, "mission " + options_.mission_id);
  actions_.push_back({ActionKind::kWaitFleet, {}});
  tree_.AddAction(root, "wait for the fleet to be ready", 0);
  if (options_.explore) {
    actions_.push_back({ActionKind::kExplore, {}});
    tree_.AddAction(root, "explore the section", static_cast<int64_t>(actions_.size() - 1));
  }
  if (options_.advance) {
    actions_.push_back({ActionKind::kPlanAdvance, {}});
    const int retry = tree_.AddRetry(root, "plan the advance", options_.plan_attempts);
    char name[96];
    std::snprintf(name, sizeof(name), "plan advancing the face at (%.1f, %.1f) by %.2f m", face_.x, face_.y,
                  options_.depth);
    tree_.AddAction(retry, name, static_cast<int64_t>(actions_.size() - 1));
  }
  bt_ = InitialState(tree_);
}

void Coordinator::GraftAdvance(const std::vector<Task>& tasks) {
  plan_tasks_ = tasks;
  char name[64];
  std::snprintf(name, sizeof(name), "advance the entry by %.2f m", options_.depth);
  const int seq = tree_.AddSequence(0, name);
  for (const Task& t : tasks) {
    actions_.push_back({ActionKind::kTask, t});
    const int attempts = IsCutTask(t.kind) ? options_.cut_attempts : options_.drive_attempts;
    const std::string label = t.description.empty() ? ToString(t.kind) : t.description;
    const int retry = tree_.AddRetry(seq, "retry: " + label, attempts);
    tree_.AddAction(retry, label, static_cast<int64_t>(actions_.size() - 1));
  }
}

void Coordinator::Event(const std::string& line) {
  stats_.events.push_back(line);
  Log(line);
}

bool Coordinator::PoseFresh(int64_t now) const {
  return pose_ && now - pose_received_ <= Us(options_.max_pose_age);
}

// ---------------------------------------------------------------------------------- inputs

void Coordinator::OnHeartbeat(const HeartbeatSample& hb, int64_t now) {
  HeartbeatSample h = hb;
  h.received = now;  // ages are measured on this clock
  watch_.OnHeartbeat(h);
}

void Coordinator::OnPose(const Pose2& pose, int64_t utime, int64_t now) {
  pose_ = pose;
  pose_utime_ = utime;
  pose_received_ = now;
}

void Coordinator::OnTaskPlan(int64_t request_id, const TaskPlan& plan, int64_t) { plans_[request_id] = plan; }

void Coordinator::OnPath(const PathAnswer& path, int64_t) {
  const auto old = paths_.find(path.request_id);
  const bool newer = old != paths_.end() && path.utime > old->second.utime;
  paths_[path.request_id] = path;
  if (preplan_ && preplan_->request_id == path.request_id) preplan_->answer = path;
  // A replanned path of a drive under way goes to the tracker too.
  if (!newer) return;
  if (Running* r = RunningWithPath(path.request_id)) {
    Drive& d = *r->drive;
    if (d.phase == Drive::Phase::kDriving || d.phase == Drive::Phase::kSendPath) {
      if (!path.feasible) return;  // the tracker stops on its own; its FAILED ends the drive
      ++stats_.replans;
      Event("path " + std::to_string(path.request_id) + " replanned by the path planner: " + path.status);
      out_.forward_paths.push_back(path.request_id);
      d.path_utime = path.utime;
    }
  }
}

void Coordinator::OnTaskStatus(const TaskStatusReport& status, int64_t) { statuses_[status.task_id] = status; }

void Coordinator::OnCutterState(bool drum_on, bool boom_raised, int64_t) { cutter_stowed_ = !drum_on && boom_raised; }

std::string Coordinator::OnOperator(OperatorCommand command, int64_t seq, int64_t now) {
  if (seq == last_operator_seq_) return "";
  last_operator_seq_ = seq;
  Log(std::string("operator: ") + ToString(command));
  switch (command) {
    case OperatorCommand::kStart:
      if (state_ == MissionState::kEstopped) return "e-stopped: resume or abort first";
      if (state_ != MissionState::kIdle && !Finished()) return "the mission is already started";
      Start(now);
      return "";
    case OperatorCommand::kPause:
      if (state_ != MissionState::kRunning && state_ != MissionState::kWaiting) return "nothing to pause";
      {
        BtStep step = Halt(tree_, bt_);
        HaltActions(step.halt, now);
        bt_ = std::move(step.state);
      }
      state_ = MissionState::kPaused;
      message_ = "paused by the operator";
      return "";
    case OperatorCommand::kResume:
      if (state_ != MissionState::kPaused && state_ != MissionState::kEstopped) return "not paused";
      state_ = MissionState::kRunning;
      message_ = "resumed by the operator";
      halted_for_loss_ = false;
      lost_since_ = -1;
      StepTree(now);
      return "";
    case OperatorCommand::kAbort:
      if (Finished()) return "the mission has ended already";
      StopEverything(MissionState::kAborted, "aborted by the operator", now);
      return "";
    case OperatorCommand::kEstop:
      StopEverything(MissionState::kEstopped, "e-stop by the operator", now);
      return "";
  }
  return "unknown command";
}

// ---------------------------------------------------------------------------- the tree

void Coordinator::Start(int64_t now) {
  if (state_ != MissionState::kIdle) BuildMission();
  stats_ = MissionStats();
  state_ = MissionState::kWaiting;
  message_ = "started";
  Log("mission " + options_.mission_id + " started");
  StepTree(now);
}

void Coordinator::StepTree(int64_t now) {
  BtStep step = minenav::Tick(tree_, bt_);
  bt_ = std::move(step.state);
  HaltActions(step.halt, now);
  for (const int node : step.start) StartAction(node, now);
  const BtStatus root = bt_.status[0];
  if (root == BtStatus::kSuccess) {
    state_ = MissionState::kDone;
    message_ = "mission done";
    waiting_for_.clear();
    Log("mission " + options_.mission_id + " done");
  } else if (root == BtStatus::kFailure) {
    StopEverything(MissionState::kFailed, "mission failed: " + bt_.reason[0], now);
  }
}

void Coordinator::StopEverything(MissionState state, const std::string& why, int64_t now) {
  BtStep step = Halt(tree_, bt_);
  HaltActions(step.halt, now);
  bt_ = std::move(step.state);
  state_ = state;
  message_ = why;
  waiting_for_.clear();
  out_.stop_vehicle = true;
  Event(why);
}

void Coordinator::StartAction(int node, int64_t now) {
  const BtNode& n = tree_.node(node);
  const ActionSpec& spec = actions_.at(static_cast<size_t>(n.ref));
  Running r;
  r.node = node;
  r.kind = spec.kind;
  r.started = now;
  r.message = n.name;
  const int parent = n.parent;
  if (parent >= 0 && tree_.node(parent).type == BtNodeType::kRetry &&
      bt_.attempts[static_cast<size_t>(parent)] > 0) {
    ++stats_.retries;
    r.not_before = now + Us(options_.retry_delay);
    Event("retrying '" + n.name + "' (attempt " + std::to_string(bt_.attempts[static_cast<size_t>(parent)] + 1) +
          ") in " + std::to_string(static_cast<int>(std::lround(options_.retry_delay))) + " s");
  }
  if (spec.kind == ActionKind::kTask) {
    const Task& t = spec.task;
    Log("subtask " + std::to_string(t.id) + " started: " + n.name);
    if (IsDrivingTask(t.kind)) {
      BeginDrive(r, t.target, t.clearance > 0.0 ? t.clearance : options_.clearance, t.allow_reverse, t.id, now);
    } else if (IsCutTask(t.kind)) {
      r.cut_id = NextId();
      r.since = now;
    }
    RequestPreplan(t, now);
  }
  if (spec.kind != ActionKind::kWaitFleet && state_ == MissionState::kWaiting && !halted_for_loss_)
    state_ = MissionState::kRunning;
  running_[node] = std::move(r);
}

void Coordinator::HaltActions(const std::vector<int>& nodes, int64_t now) {
  for (const int node : nodes) {
    auto it = running_.find(node);
    if (it == running_.end()) continue;
    Running& r = it->second;
    if (r.drive && (r.drive->phase == Drive::Phase::kSendPath || r.drive->phase == Drive::Phase::kDriving)) {
      out_.cancel_paths.push_back(r.drive->request_id);
      canceling_.insert(r.drive->request_id);
    }
    if (r.cut_id >= 0) {
      CutTaskOut c;
      c.id = r.cut_id;
      c.cancel = true;
      out_.cut_tasks.push_back(c);
      // A cut halted part-way continues later from the face it reached (its progress).
      const auto st = statuses_.find(r.cut_id);
      if (st != statuses_.end()) {
        Task& t = actions_.at(static_cast<size_t>(tree_.node(node).ref)).task;
        const double done = std::clamp(st->second.progress, 0.0, 1.0) * t.depth;
        if (done > 0.0) {
          const Eigen::Vector2d dir(std::cos(t.target.theta), std::sin(t.target.theta));
          t.face = Segment(t.face.a + dir * done, t.face.b + dir * done);
          t.target = Ahead(t.target, done);
          t.depth -= done;
          Event("cut " + std::to_string(t.id) + " halted after " + std::to_string(done) + " m; " +
                std::to_string(t.depth) + " m remain");
        }
      }
    }
    Log("halted: " + tree_.node(node).name);
    running_.erase(it);
  }
  if (!nodes.empty()) out_.stop_vehicle = true;
  (void)now;
}

void Coordinator::FinishAction(Running& r, bool success, const std::string& reason, int64_t) {
  const std::string& name = tree_.node(r.node).name;
  if (success) Log("done: " + name + (reason.empty() ? "" : " (" + reason + ")"));
  else Event("failed: " + name + ": " + reason);
  bt_ = Finish(tree_, bt_, r.node, success, reason);
}

// ------------------------------------------------------------------------------- the clock

void Coordinator::Tick(int64_t now) {
  // Cancels are repeated until the tracker or the cutter says the task ended.
  for (auto it = canceling_.begin(); it != canceling_.end();) {
    const auto st = statuses_.find(*it);
    if (st != statuses_.end() && st->second.state != TaskState::kActive && st->second.state != TaskState::kPending) {
      it = canceling_.erase(it);
    } else {
      ++it;
    }
  }
  if (state_ == MissionState::kEstopped) {
    out_.stop_vehicle = true;  // every tick until resume or abort
    return;
  }
  if (state_ != MissionState::kRunning && state_ != MissionState::kWaiting) return;
  CheckHealth(now);
  if (state_ != MissionState::kRunning && state_ != MissionState::kWaiting) return;
  if (halted_for_loss_) return;
  if (preplan_ && !preplan_->answer && now - preplan_->last_sent >= Us(options_.resend_period)) {
    const Task* next = nullptr;
    for (const Task& t : plan_tasks_)
      if (t.id == preplan_->task_id) next = &t;
    if (next) {
      PathRequestOut p;
      p.request_id = preplan_->request_id;
      p.start = preplan_->start;
      p.goal = next->target;
      p.position_tolerance = options_.position_tolerance;
      p.heading_tolerance = options_.heading_tolerance;
      p.clearance = next->clearance > 0.0 ? next->clearance : options_.clearance;
      p.allow_reverse = next->allow_reverse;
      out_.path_requests.push_back(p);
      preplan_->last_sent = now;
    }
  }
  for (int round = 0; round < 4; ++round) {
    std::vector<int> nodes;
    for (const auto& [node, r] : running_) nodes.push_back(node);
    for (const int node : nodes) {
      auto it = running_.find(node);
      if (it != running_.end()) TickAction(it->second, now);
    }
    bool finished = false;
    for (const int node : nodes) {
      if (bt_.status[static_cast<size_t>(node)] != BtStatus::kRunning) {
        running_.erase(node);
        finished = true;
      }
    }
    if (!finished) break;
    StepTree(now);
    if (state_ != MissionState::kRunning && state_ != MissionState::kWaiting) break;
  }
}

void Coordinator::CheckHealth(int64_t now) {
  // While the fleet is first awaited the wait leaf reports; afterwards a lost process halts.
  bool waiting_fleet = false;
  for (const auto& [node, r] : running_) waiting_fleet |= r.kind == ActionKind::kWaitFleet;
  const std::vector<std::string> restarted = watch_.TakeRestarts();
  if (waiting_fleet) return;
  // A required process restarted between two heartbeats (its supervisor is quicker than the
  // heartbeat timeout) has forgotten its command (the tracker its path, the cutter its cut):
  // the running steps are halted and start again, as after a loss and a recovery.
  if (!restarted.empty() && lost_since_ < 0) {
    ++stats_.pauses_for_lost_processes;
    Event("restarted: " + Join(restarted, "; ") + ": the running steps start again");
    BtStep step = Halt(tree_, bt_);
    HaltActions(step.halt, now);
    bt_ = std::move(step.state);
    StepTree(now);
  }
  const std::vector<std::string> not_ready = watch_.NotReady(now);
  if (!not_ready.empty()) {
    if (lost_since_ < 0) {
      lost_since_ = now;
      halted_for_loss_ = true;
      ++stats_.pauses_for_lost_processes;
      Event("vehicle stopped: " + Join(not_ready, "; "));
      BtStep step = Halt(tree_, bt_);
      HaltActions(step.halt, now);
      bt_ = std::move(step.state);
      state_ = MissionState::kWaiting;
    } else if (now - lost_since_ > Us(options_.recovery_timeout)) {
      StopEverything(MissionState::kFailed,
                     "mission failed: " + Join(not_ready, "; ") + "; not back within " +
                         std::to_string(static_cast<int>(options_.recovery_timeout)) + " s",
                     now);
      return;
    }
    waiting_for_ = Join(not_ready, "; ");
    out_.stop_vehicle = true;
    return;
  }
  if (halted_for_loss_) {
    halted_for_loss_ = false;
    lost_since_ = -1;
    state_ = MissionState::kRunning;
    waiting_for_.clear();
    Event("every required process is back: resuming");
    StepTree(now);
  }
}

// ------------------------------------------------------------------------------ the leaves

void Coordinator::TickAction(Running& r, int64_t now) {
  waiting_for_.clear();
  if (now < r.not_before) {
    waiting_for_ = "the retry's delay";
    return;
  }
  switch (r.kind) {
    case ActionKind::kWaitFleet: TickWaitFleet(r, now); break;
    case ActionKind::kExplore: TickExplore(r, now); break;
    case ActionKind::kPlanAdvance: {
      TickPlanRequest(r, TaskRequestKind::kAdvance, now);
      break;
    }
    case ActionKind::kTask: {
      const Task& t = actions_.at(static_cast<size_t>(tree_.node(r.node).ref)).task;
      if (IsCutTask(t.kind)) {
        TickCut(r, t, now);
      } else if (r.drive) {
        if (TickDrive(*r.drive, now)) {
          const bool ok = r.drive->phase == Drive::Phase::kDone;
          FinishAction(r, ok, ok ? "" : r.drive->reason, now);
        } else {
          r.progress = 0.0;
          if (const auto st = statuses_.find(r.drive->request_id); st != statuses_.end()) {
            r.progress = st->second.progress;
            r.message = st->second.message;
          }
        }
      } else {
        // WAIT: a dwell.
        if (now - r.started >= Us(options_.station_dwell)) FinishAction(r, true, "", now);
      }
      break;
    }
  }
}

void Coordinator::TickWaitFleet(Running& r, int64_t now) {
  const std::vector<std::string> not_ready = watch_.NotReady(now);
  if (not_ready.empty()) {
    state_ = MissionState::kRunning;
    FinishAction(r, true, "every required process is ready", now);
    return;
  }
  waiting_for_ = Join(not_ready, "; ");
  if (now - r.started > Us(options_.ready_timeout))
    FinishAction(r, false, "the fleet was not ready within " + std::to_string(static_cast<int>(options_.ready_timeout)) +
                               " s: " + waiting_for_, now);
}

void Coordinator::TickPlanRequest(Running& r, TaskRequestKind kind, int64_t now) {
  if (r.request_id < 0) {
    if (!PoseFresh(now)) {
      waiting_for_ = "a pose estimate";
      return;
    }
    r.request_id = NextId();
    r.since = now;
    r.last_sent = 0;
  }
  const auto answer = plans_.find(r.request_id);
  if (answer == plans_.end()) {
    if (now - r.since > Us(options_.answer_timeout)) {
      const std::string why = "no TASK_PLAN from the task planner in " +
                              std::to_string(static_cast<int>(options_.answer_timeout)) + " s";
      r.request_id = -1;
      FinishAction(r, false, why, now);
      return;
    }
    waiting_for_ = "the task planner's answer to request " + std::to_string(r.request_id);
    if (r.last_sent == 0 || now - r.last_sent >= Us(options_.resend_period)) {
      if (r.last_sent != 0) ++stats_.resends;
      TaskRequest q;
      q.request_id = r.request_id;
      q.mission_id = options_.mission_id;
      q.kind = kind;
      q.pose = *pose_;
      q.face = face_;
      q.depth = options_.depth;
      q.clearance = options_.clearance;
      out_.task_requests.push_back(q);
      r.last_sent = now;
    }
    return;
  }
  const TaskPlan plan = answer->second;
  r.request_id = -1;
  if (kind == TaskRequestKind::kAdvance) {
    if (plan.status != PlanStatus::kOk) {
      FinishAction(r, false, "task planner: " + plan.reason, now);
      return;
    }
    GraftAdvance(plan.tasks);
    FinishAction(r, true, std::to_string(plan.tasks.size()) + " subtasks: " + plan.reason, now);
    return;
  }
  // A survey step.
  if (plan.status == PlanStatus::kComplete) {
    FinishAction(r, true, "exploration complete after " + std::to_string(stats_.stations_visited) +
                              " stations: " + plan.reason, now);
    return;
  }
  if (plan.status == PlanStatus::kFailed) {
    // FAILED is "not decided" (the planner's budget or deadline spent before a station was
    // found; COMPLETE is the answer when there is none): asked again after retry_delay, a
    // station not decided counting as one not reached.
    if (ExplorationFailedAgain(r, "not reached or not decided", "task planner: " + plan.reason, now)) return;
    Event("no station decided (task planner: " + plan.reason + "): asking again in " +
          std::to_string(static_cast<int>(std::lround(options_.retry_delay))) + " s");
    r.not_before = now + Us(options_.retry_delay);
    return;
  }
  const Task& station = plan.tasks.front();
  ++r.stations;
  r.message = "station " + std::to_string(r.stations) + " at " + Where(station.target);
  Log("next scan station " + std::to_string(r.stations) + ": " + Where(station.target) + " (" + plan.reason + ")");
  BeginDrive(r, station.target, station.clearance > 0.0 ? station.clearance : options_.clearance,
             station.allow_reverse, -1, now);
  TickDrive(*r.drive, now);  // the path request goes out now; an end is seen on the next tick
}

bool Coordinator::ExplorationFailedAgain(Running& r, const std::string& failures, const std::string& last,
                                         int64_t now) {
  ++r.failed_in_a_row;
  if (r.failed_in_a_row < options_.max_failed_stations) return false;
  FinishAction(r, false,
               "exploration: " + std::to_string(r.failed_in_a_row) + " stations in a row " + failures +
                   "; the last: " + last,
               now);
  return true;
}

void Coordinator::TickExplore(Running& r, int64_t now) {
  if (r.drive) {
    if (!TickDrive(*r.drive, now)) return;
    if (r.drive->phase == Drive::Phase::kDone) {
      ++stats_.stations_visited;
      r.failed_in_a_row = 0;
      r.dwelling = true;
      r.dwell_until = now + Us(options_.station_dwell);
    } else {
      ++stats_.stations_failed;
      Event("station " + Where(r.drive->goal) + " not reached: " + r.drive->reason);
      const std::string why = r.drive->reason;
      r.drive.reset();
      if (ExplorationFailedAgain(r, "not reached", why, now)) return;
    }
    r.drive.reset();
    return;
  }
  if (r.dwelling) {
    if (now < r.dwell_until) {
      waiting_for_ = "the scans at the station";
      return;
    }
    r.dwelling = false;
  }
  if (stats_.stations_visited + stats_.stations_failed >= options_.max_stations && r.request_id < 0) {
    FinishAction(r, true, "exploration stopped after max_stations = " + std::to_string(options_.max_stations), now);
    return;
  }
  TickPlanRequest(r, TaskRequestKind::kSurveyNext, now);
}

void Coordinator::TickCut(Running& r, const Task& task, int64_t now) {
  const auto st = statuses_.find(r.cut_id);
  if (!r.cut_acknowledged && st != statuses_.end()) r.cut_acknowledged = true;
  if (!r.cut_acknowledged) {
    if (now - r.since > Us(options_.answer_timeout)) {
      FinishAction(r, false, "the cutter did not acknowledge cut " + std::to_string(r.cut_id), now);
      return;
    }
    waiting_for_ = "the cutter's acknowledgement of cut " + std::to_string(r.cut_id);
    if (r.last_sent == 0 || now - r.last_sent >= Us(options_.resend_period)) {
      if (r.last_sent != 0) ++stats_.resends;
      CutTaskOut c;
      c.id = r.cut_id;
      c.depth = task.depth;
      c.face = task.face;
      out_.cut_tasks.push_back(c);
      r.last_sent = now;
    }
    return;
  }
  const TaskStatusReport& s = st->second;
  r.progress = s.progress;
  r.message = s.message;
  if (s.state == TaskState::kDone) FinishAction(r, true, s.message, now);
  else if (s.state == TaskState::kFailed || s.state == TaskState::kCanceled)
    FinishAction(r, false, "cutter: " + s.message, now);
}

void Coordinator::BeginDrive(Running& r, const Pose2& goal, double clearance, bool allow_reverse, int64_t task_id,
                             int64_t now) {
  Drive d;
  d.goal = goal;
  d.clearance = clearance;
  d.allow_reverse = allow_reverse;
  d.started = now;
  d.since = now;
  ++stats_.drives;
  // The path planned ahead while the previous subtask ran, when the vehicle is where it assumed.
  if (preplan_ && task_id >= 0 && preplan_->task_id == task_id) {
    const Preplan p = *preplan_;
    preplan_.reset();
    const bool fresh_path = p.answer && now - p.answer->utime <= Us(options_.preplan_max_age);
    if (p.answer && p.answer->feasible && fresh_path && PoseFresh(now) &&
        Near(*pose_, p.answer->start, options_.preplan_tolerance)) {
      d.request_id = p.request_id;
      d.phase = Drive::Phase::kSendPath;
      d.path_utime = p.answer->utime;
      ++stats_.drives_preplanned;
      Log("subtask " + std::to_string(task_id) + ": the path planned ahead is used (request " +
          std::to_string(p.request_id) + ")");
    } else {
      Log("subtask " + std::to_string(task_id) + ": the path planned ahead is not used (" +
          (!p.answer            ? "no answer yet"
           : !p.answer->feasible ? "it was infeasible: " + p.answer->status
           : !fresh_path         ? "it was planned " + std::to_string(std::llround(static_cast<double>(now - p.answer->utime) * 1e-6)) +
                                       " s ago, over preplan_max_age"
                                 : "the vehicle is " + (pose_ ? Where(*pose_) : std::string("unknown")) +
                                       ", the path starts at " + Where(p.answer->start)) +
          "): planning anew");
    }
  }
  r.drive = d;
}

bool Coordinator::TickDrive(Drive& d, int64_t now) {
  using Phase = Drive::Phase;
  if (d.phase == Phase::kWaitAppendages) {
    if (cutter_stowed_ && !*cutter_stowed_) {
      waiting_for_ = "the cutter's appendages stowed (drum off, boom up) before tramming";
      return false;
    }
    d.phase = Phase::kWaitPose;
  }
  if (d.phase == Phase::kWaitPose) {
    if (!PoseFresh(now)) {
      waiting_for_ = "a pose estimate";
      return false;
    }
    d.phase = Phase::kRequest;
  }
  if (d.phase == Phase::kRequest) {
    d.request_id = NextId();
    d.since = now;
    d.last_sent = 0;
    d.phase = Phase::kWaitPath;
  }
  if (d.phase == Phase::kWaitPath) {
    const auto answer = paths_.find(d.request_id);
    if (answer == paths_.end()) {
      if (now - d.since > Us(options_.answer_timeout)) {
        d.phase = Phase::kFailed;
        d.reason = "no PATH from the path planner in " + std::to_string(static_cast<int>(options_.answer_timeout)) + " s";
        return true;
      }
      waiting_for_ = "the path planner's answer to request " + std::to_string(d.request_id);
      if (d.last_sent == 0 || now - d.last_sent >= Us(options_.resend_period)) {
        if (d.last_sent != 0) ++stats_.resends;
        PathRequestOut p;
        p.request_id = d.request_id;
        p.start = *pose_;
        p.goal = d.goal;
        p.position_tolerance = options_.position_tolerance;
        p.heading_tolerance = options_.heading_tolerance;
        p.clearance = d.clearance;
        p.allow_reverse = d.allow_reverse;
        out_.path_requests.push_back(p);
        d.last_sent = now;
      }
      return false;
    }
    if (!answer->second.feasible) {
      d.phase = Phase::kFailed;
      d.reason = "no path to " + Where(d.goal) + ": " + answer->second.status;
      return true;
    }
    d.path_utime = answer->second.utime;
    d.phase = Phase::kSendPath;
    d.since = now;
    d.last_sent = 0;
  }
  if (d.phase == Phase::kSendPath) {
    if (statuses_.count(d.request_id)) {
      d.phase = Phase::kDriving;
    } else {
      if (d.last_sent == 0) stats_.planning_waits.push_back(static_cast<double>(now - d.started) * 1e-6);
      if (now - d.since > Us(options_.answer_timeout)) {
        d.phase = Phase::kFailed;
        d.reason = "the path tracker did not acknowledge path " + std::to_string(d.request_id);
        return true;
      }
      waiting_for_ = "the path tracker's acknowledgement of path " + std::to_string(d.request_id);
      if (d.last_sent == 0 || now - d.last_sent >= Us(options_.resend_period)) {
        if (d.last_sent != 0) ++stats_.resends;
        out_.forward_paths.push_back(d.request_id);
        d.last_sent = now;
      }
      return false;
    }
  }
  if (d.phase == Phase::kDriving) {
    const TaskStatusReport& s = statuses_.at(d.request_id);
    if (s.state == TaskState::kDone) {
      d.phase = Phase::kDone;
      return true;
    }
    if (s.state == TaskState::kFailed || s.state == TaskState::kCanceled) {
      d.phase = Phase::kFailed;
      d.reason = "path tracker: " + s.message;
      return true;
    }
    return false;
  }
  return d.phase == Phase::kDone || d.phase == Phase::kFailed;
}

// ------------------------------------------------------------------------- planning ahead

const Task* Coordinator::NextTaskAfter(int64_t task_id) const {
  for (size_t i = 0; i + 1 < plan_tasks_.size(); ++i)
    if (plan_tasks_[i].id == task_id) return &plan_tasks_[i + 1];
  return nullptr;
}

void Coordinator::RequestPreplan(const Task& current, int64_t now) {
  if (!options_.preplan) return;
  const Task* next = NextTaskAfter(current.id);
  if (!next || !IsDrivingTask(next->kind)) return;
  Preplan p;
  p.task_id = next->id;
  p.request_id = NextId();
  // Where the current subtask leaves the vehicle: a drive at its target; a cut backed out of,
  // `cut_end_offset` behind where it started.
  p.start = IsCutTask(current.kind) ? Ahead(current.target, -options_.cut_end_offset) : current.target;
  p.last_sent = 0;
  preplan_ = p;
  Log("planning subtask " + std::to_string(next->id) + " ahead from " + Where(p.start));
  (void)now;
}

Coordinator::Running* Coordinator::RunningWithPath(int64_t request_id) {
  for (auto& [node, r] : running_)
    if (r.drive && r.drive->request_id == request_id) return &r;
  return nullptr;
}

// ------------------------------------------------------------------------------- outputs

CoordinatorOutputs Coordinator::TakeOutputs() {
  CoordinatorOutputs out = std::move(out_);
  out_ = CoordinatorOutputs();
  return out;
}

MissionStatus Coordinator::Status() const {
  MissionStatus s;
  s.mission_id = options_.mission_id;
  s.state = state_;
  s.message = message_;
  s.waiting_for = waiting_for_;
  for (int i = 0; i < tree_.size(); ++i) {
    const BtNode& n = tree_.node(i);
    MissionNodeStatus m;
    m.id = i;
    m.parent = n.parent;
    m.name = n.name;
    m.state = bt_.status[static_cast<size_t>(i)];
    if (n.type == BtNodeType::kAction) {
      const ActionSpec& spec = actions_.at(static_cast<size_t>(n.ref));
      if (spec.kind == ActionKind::kTask) {
        m.task_id = spec.task.id;
        ++s.tasks_total;
        if (m.state == BtStatus::kSuccess) ++s.tasks_done;
      }
    }
    s.nodes.push_back(m);
  }
  for (const auto& [node, r] : running_) {
    const ActionSpec& spec = actions_.at(static_cast<size_t>(tree_.node(node).ref));
    if (spec.kind == ActionKind::kTask && s.current_task_id < 0) s.current_task_id = spec.task.id;
    s.progress = r.progress;
    if (state_ == MissionState::kRunning || state_ == MissionState::kWaiting) s.message = r.message;
  }
  return s;
}

}  // namespace minenav
