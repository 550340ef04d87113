#include "planner/task_planner_node.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "planner/contour_map_contours.h"

namespace minenav {

// One map as it arrived: a contour map (contours) or a line map (segments).
struct TaskPlannerNode::MapSnapshot {
  bool is_line_map = false;
  int64_t version = 0;
  std::vector<mapper::Contour> contours;
  std::vector<Segment> segments;
  std::string Name() const { return (is_line_map ? "line map version " : "map version ") + std::to_string(version); }
};

struct TaskPlannerNode::Job {
  TaskRequest request;
  std::shared_ptr<const MapSnapshot> map;
  std::vector<Pose2> visited;
  int64_t plan_id = 0;
};

struct TaskPlannerNode::Answer {
  task_plan_t message{};
};

namespace {
// Planners kept per map: the survey's (paths, roomy stations) and the advance's, each with
// the default and a requested clearance, and the leaving ones of a vehicle near a wall.
constexpr size_t kPlannersPerMap = 6;
}  // namespace

// Worker thread only: the task map of the snapshot in force (held, so its address is not
// reused), and the path planners built on it (the survey's paths and stations, the advance's
// maneuvers: a request on the same map with the same clearance builds none).
struct TaskPlannerNode::MapCache {
  std::shared_ptr<const MapSnapshot> snapshot;
  TaskMap map;
  Se2PlannerCache planners{kPlannersPerMap};
};

namespace {

task_plan_t FailedPlan(int64_t plan_id, int64_t request_id, const std::string& mission_id, const std::string& why) {
  TaskPlanMessage m;
  m.plan_id = plan_id;
  m.request_id = request_id;
  m.mission_id = mission_id;
  m.plan.status = PlanStatus::kFailed;
  m.plan.reason = why;
  return TaskPlanToLcm(m);
}

}  // namespace

void DeclareOptions(ConfigSchema& s, TaskPlannerNodeOptions& o) {
  s.AddChannel("request_channel", &o.request_channel, "subscribes", "task_request_t",
               "task requests: SURVEY_NEXT (the next scan station) or ADVANCE (box cut, slab cut, back out)");
  s.AddChannel("map_channel", &o.map_channel, "subscribes", "contour_map_t",
               "the contour map (plain or zlib): its walls and frontiers");
  s.AddChannel("line_map_channel", &o.line_map_channel, "subscribes", "line_map_t",
               "a line map: ADVANCE requests plan on the latest one there (walls only); empty = none");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t",
               "the vehicle's pose estimate: the places the ladar looked from");
  s.AddDouble("first_map_wait", &o.first_map_wait, "s",
              "live: a request that comes before any map within this long of the start is left for its repeat "
              "(a restarted planner gets the map within the mapper's republish period); later: answered 'no map'",
              0.0, 3600.0);
  s.AddChannel("plan_channel", &o.plan_channel, "publishes", "task_plan_t", "the answers, tagged with the request_id");
  s.AddString("footprint", &o.footprint,
              "W,L (m: a rectangle centred on the pose, x along L) or a JSON file {\"footprint\": [[x, y], ...]}");
  s.AddDouble("deadline", &o.deadline, "s", "live: wall time the path-planner searches of one plan may take", 0.001,
              3600.0);
  s.AddDouble("default_clearance", &o.default_clearance, "m", "clearance of a request that gives 0", 0.0, 10.0);
  s.AddDouble("max_clearance", &o.max_clearance, "m", "larger requested clearances are refused", 0.0, 10.0);
  s.AddDouble("trail_spacing", &o.trail_spacing, "m",
              "between the POSE positions kept as places the ladar looked from; 0 = none", 0.0, 1000.0);
  s.AddInt("max_trail", &o.max_trail, "POSE positions kept (the oldest go first)", 1, 1'000'000);
  s.AddInt("plan_queue", &o.queue_capacity, "live: requests that may wait for planning; a full queue drops the oldest",
           1, 1000);
  s.AddInt("answers_kept", &o.answers_kept, "answers remembered by request_id (a repeat is answered from memory)", 1,
           1'000'000);
  s.AddDouble("poll_period", &o.poll_period, "s", "live: period of the look for finished plans", 0.001, 1.0);
  DeclareOptions(OptionScope(s).Nested("advance"), o.advance);
  DeclareOptions(OptionScope(s).Nested("survey"), o.survey);
  DeclareOptions(OptionScope(s), o.planner);
  DeclareOptions(OptionScope(s).Nested("search"), o.search);
  DeclareOptions(OptionScope(s).Nested("free_space"), o.free_space);
}

std::string ValidateOptions(const TaskPlannerNodeOptions& o) {
  if (const std::string e = ValidateOptions(o.advance); !e.empty()) return "advance." + e;
  if (const std::string e = ValidateOptions(o.survey); !e.empty()) return "survey." + e;
  if (const std::string e = ValidateOptions(o.planner); !e.empty()) return e;
  if (const std::string e = ValidateOptions(o.free_space); !e.empty()) return e;
  if (o.default_clearance > o.max_clearance) return "default_clearance must not exceed max_clearance";
  return "";
}

TaskPlannerNode::TaskPlannerNode(NodeRuntime& runtime, TaskPlannerNodeOptions options, Footprint footprint)
    : runtime_(runtime),
      first_map_wait_(options.first_map_wait, runtime.NowUtime(), !runtime.batch()),
      options_(std::move(options)),
      footprint_(std::move(footprint)),
      cache_(std::make_unique<MapCache>()) {
  if (!runtime_.batch())
    worker_ = std::make_unique<BackgroundWorker<Job, Answer>>(static_cast<size_t>(options_.queue_capacity),
                                                              [this](Job& job) { return Plan(job); });
  Subscribe<task_request_t>(runtime_.bus(), options_.request_channel,
                            [this](const task_request_t& m) { OnRequest(m); });
  Subscribe<contour_map_t>(runtime_.bus(), options_.map_channel, [this](const contour_map_t& m) { OnContourMap(m); });
  if (!options_.line_map_channel.empty())
    Subscribe<line_map_t>(runtime_.bus(), options_.line_map_channel, [this](const line_map_t& m) { OnLineMap(m); });
  Subscribe<pose_estimate_t>(runtime_.bus(), options_.pose_channel, [this](const pose_estimate_t& m) {
    const PoseEstimate e = FromLcm(m);
    if (e.converged) OnPose(e.pose);
  });
  if (worker_) runtime_.AddTimer(options_.poll_period, [this](int64_t) { Poll(); });
  runtime_.OnShutdown([this] {
    if (!worker_) return;
    for (const Job& j : worker_->Stop())
      Publish(FailedPlan(j.plan_id, j.request.request_id, j.request.mission_id, "not planned: shutting down"), false);
  });
  runtime_.SetStatus(heartbeat_t::OK, "waiting for " + options_.map_channel);
}

TaskPlannerNode::~TaskPlannerNode() {
  if (worker_) worker_->Stop();
}

void TaskPlannerNode::Publish(task_plan_t plan, bool remember) {
  plan.utime = runtime_.NowUtime();
  ::minenav::Publish(runtime_.bus(), options_.plan_channel, plan);
  ++answers_;
  if (remember && answered_.emplace(plan.request_id, plan).second) {
    answered_order_.push_back(plan.request_id);
    while (answered_order_.size() > static_cast<size_t>(options_.answers_kept)) {
      answered_.erase(answered_order_.front());
      answered_order_.pop_front();
    }
  }
  runtime_.SetStatus(heartbeat_t::OK, (contour_map_ ? contour_map_->Name() : "no map") + ", " +
                                          std::to_string(requests_) + " requests, " + std::to_string(answers_) +
                                          " answers, " + std::to_string(plans()) + " plans, " +
                                          std::to_string(repeats_) + " repeats");
}

void TaskPlannerNode::OnRequest(const task_request_t& m) {
  ++requests_;
  if (const auto it = answered_.find(m.request_id); it != answered_.end()) {
    ++repeats_;  // the coordinator did not hear it: the same plan again
    Publish(it->second, false);
    return;
  }
  if (pending_.count(m.request_id) != 0) return;  // being planned: the answer is coming
  const int64_t plan_id = next_plan_id_++;
  auto refuse = [&](const std::string& why) {
    MINENAV_LOG(kWarn) << "request " << m.request_id << " refused: " << why;
    Publish(FailedPlan(plan_id, m.request_id, m.mission_id, why), true);
  };
  TaskRequest r;
  try {
    r = TaskRequestFromLcm(m);
    if (r.clearance > options_.max_clearance)
      throw InputError("clearance " + FixedNumber(r.clearance) + " m is not in [0, " +
                       FixedNumber(options_.max_clearance) + "] (max_clearance)");
  } catch (const InputError& e) {
    refuse(std::string("invalid request: ") + e.what());
    throw;  // counted in HEARTBEAT messages_bad
  }
  std::shared_ptr<const MapSnapshot> map = contour_map_;
  if (r.kind == TaskRequestKind::kAdvance && line_map_) map = line_map_;
  if (!map && first_map_wait_.LeaveForRepeat(runtime_.NowUtime())) {
    MINENAV_LOG(kInfo) << "request " << r.request_id << ": no map yet, left for its repeat";
    return;
  }
  if (!map) {
    const std::string channels =
        options_.map_channel + (r.kind == TaskRequestKind::kAdvance && !options_.line_map_channel.empty()
                                    ? " or " + options_.line_map_channel
                                    : "");
    refuse("no map: nothing received on " + channels + " yet");
    return;
  }
  Job job{r, map, visited_, plan_id};
  if (r.kind == TaskRequestKind::kSurveyNext) visited_.push_back(r.pose);  // it scanned where it asks from
  if (!worker_) {                                                          // batch: plan here, repeatably
    Publish(Plan(job).message, true);
    return;
  }
  pending_.insert(r.request_id);
  if (std::optional<Job> dropped = worker_->Push(std::move(job))) {
    pending_.erase(dropped->request.request_id);
    Publish(FailedPlan(dropped->plan_id, dropped->request.request_id, dropped->request.mission_id,
                       "dropped: " + std::to_string(options_.queue_capacity) + " newer requests waiting"),
            false);
  }
}

void TaskPlannerNode::OnContourMap(const contour_map_t& m) {
  ContourMapMessage map = ContourMapFromLcm(m);  // throws InputError: counted as a bad message
  if (contour_map_ && map.version == contour_map_->version) return;
  auto snapshot = std::make_shared<MapSnapshot>();
  snapshot->version = map.version;
  snapshot->contours = ContoursOf(std::move(map));
  contour_map_ = std::move(snapshot);
}

void TaskPlannerNode::OnLineMap(const line_map_t& m) {
  std::vector<Segment> segments = SegmentsFromLcm(m);  // throws InputError: counted as a bad message
  if (line_map_ && SameSegments(segments, line_map_->segments)) return;
  auto snapshot = std::make_shared<MapSnapshot>();
  snapshot->is_line_map = true;
  snapshot->version = m.version;
  snapshot->segments = std::move(segments);
  line_map_ = std::move(snapshot);
}

void TaskPlannerNode::OnPose(const Pose2& pose) {
  if (options_.trail_spacing <= 0.0) return;
  if (!visited_.empty() && (visited_.back().translation() - pose.translation()).norm() < options_.trail_spacing) return;
  visited_.push_back(pose);
  if (visited_.size() > static_cast<size_t>(options_.max_trail)) visited_.erase(visited_.begin());
}

void TaskPlannerNode::Poll() {
  for (Answer& a : worker_->TakeOutbox()) {
    pending_.erase(a.message.request_id);
    Publish(std::move(a.message), true);
  }
}

TaskPlannerNode::Answer TaskPlannerNode::Plan(Job& job) {
  const auto t0 = std::chrono::steady_clock::now();
  MapCache& cache = *cache_;
  if (cache.snapshot != job.map) {
    cache.snapshot = job.map;
    cache.map = job.map->is_line_map ? TaskMapFromSegments(job.map->segments)
                                     : TaskMapFromContours(job.map->contours, options_.free_space);
    cache.planners.Clear();
  }
  // The deadline bounds the path planner's searches (live only: batch is repeatable).
  const auto deadline = t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(options_.deadline));
  bool deadline_passed = false;
  SearchLimits limits = options_.search;
  const bool live = worker_ != nullptr;
  limits.stop_requested = [&] {
    if (NodeRuntime::StopSignalled()) return true;
    deadline_passed = live && std::chrono::steady_clock::now() > deadline;
    return deadline_passed;
  };
  const TaskRequest& r = job.request;
  const double clearance = r.clearance > 0.0 ? r.clearance : options_.default_clearance;
  TaskPlanMessage answer;
  answer.plan_id = job.plan_id;
  answer.request_id = r.request_id;
  answer.mission_id = r.mission_id;
  if (r.kind == TaskRequestKind::kAdvance) {
    AdvanceRequest a;
    a.vehicle = r.pose;
    a.face_hint = r.face.translation();
    a.direction = r.face.theta;
    a.depth = r.depth;
    a.clearance = clearance;
    answer.plan = PlanAdvance(cache.map, footprint_, a, options_.advance, options_.planner, limits, &cache.planners).plan;
  } else {
    SurveyRequest s;
    s.vehicle = r.pose;
    s.clearance = clearance;
    s.visited = job.visited;
    const SurveyDecision d = PlanNextStation(cache.map, footprint_, s, options_.survey, options_.planner, limits, &cache.planners);
    for (const StationCandidate& c : d.candidates)
      if (c.planned)
        MINENAV_LOG(kDebug) << "request " << r.request_id << ": candidate " << PoseText(c.pose) << " (bound "
                            << FixedNumber(c.bound, 1) << " m, " << c.expansions << " expansions): "
                            << (c.rejected.empty() ? "reachable, cost " + FixedNumber(c.cost, 1) + " m" : c.rejected);
    answer.plan = d.plan;
  }
  planners_built_ = cache.planners.built();
  if (deadline_passed && answer.plan.status == PlanStatus::kFailed)
    answer.plan.reason =
        "deadline: planning was stopped at " + FixedNumber(options_.deadline, 3) + " s: " + answer.plan.reason;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  MINENAV_LOG(kInfo) << "request " << r.request_id << " (" << ToString(r.kind) << ", " << job.map->Name() << ", "
                     << FixedNumber(ms, 1) << " ms): " << ToString(answer.plan.status) << ": " << answer.plan.reason;
  return Answer{TaskPlanToLcm(answer)};
}

}  // namespace minenav
