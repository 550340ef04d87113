#include "planner/path_planner_node.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "planner/contour_map_contours.h"
#include "planner/se2_planner_cache.h"

namespace minenav {

struct PathPlannerNode::MapSnapshot {
  int64_t version = 0;
  std::vector<mapper::Contour> contours;
};

struct PathPlannerNode::Job {
  bool replan = false;             // re-check `active` against the map, replan when blocked
  path_request_t request{};        // what to plan (for a replan: the active path's request)
  std::shared_ptr<const MapSnapshot> map;
  std::optional<Pose2> pose;       // the latest POSE (replan)
  PlannedPath active;              // the path to re-check (replan)
};

struct PathPlannerNode::Answer {
  path_t message{};
  std::optional<PlannedPath> path;  // when feasible: becomes the active path
  path_request_t request{};
  bool publish = true;              // false: a re-check found the path clear
  bool replanned = false;           // the active path was blocked by a new map
};

constexpr size_t kMaxPlannersPerMap = 8;

// Worker thread only.
struct PathPlannerNode::PlannerCache {
  int64_t version = -1;
  std::unique_ptr<ContourFreeSpace> space;
  std::unique_ptr<KnownFreeSpace> known;
  // Planners on this version's boundary (with or without frontiers, or without those through
  // a start) for the options requests asked (clearance, collision step, reverse factor).
  Se2PlannerCache planners{kMaxPlannersPerMap};
};

namespace {
// Answers kept for repeated requests and for DRIVE_PATH (a mission holds a handful at a time).
constexpr size_t kAnswersKept = 64;
// A request that does not allow reversing: a metre reversed costs this many driven forward
// (the largest costs.reverse_factor), and a path that still reverses is refused.
constexpr double kNoReverseFactor = 100.0;

std::string Fixed(double v, int digits = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

std::string Where(const Pose2& p) { return "(" + Fixed(p.x) + ", " + Fixed(p.y) + ", " + Fixed(p.theta) + ")"; }

}  // namespace

void DeclareOptions(ConfigSchema& s, PathPlannerNodeOptions& o) {
  s.AddChannel("request_channel", &o.request_channel, "subscribes", "path_request_t", "live: path requests");
  s.AddChannel("map_channel", &o.map_channel, "subscribes", "contour_map_t",
               "live: the contour map the paths are planned on (plain or zlib)");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t",
               "live: the vehicle's pose estimate (replanning starts there)");
  s.AddChannel("path_channel", &o.path_channel, "publishes", "path_t", "live: the answers, tagged with the request_id");
  s.AddChannel("drive_path_channel", &o.drive_path_channel, "subscribes", "path_t",
               "live: the path being driven (the coordinator's): the one re-checked and replanned when the map changes");
  s.AddDouble("first_map_wait", &o.first_map_wait, "s",
              "live: a request that comes before any map within this long of the start is left for its repeat "
              "(a restarted planner gets the map within the mapper's republish period); later: answered 'no map'",
              0.0, 3600.0);
  s.AddDouble("deadline", &o.deadline, "s", "live: wall time a search may take before it is stopped", 0.001, 3600.0);
  s.AddDouble("default_clearance", &o.default_clearance, "m", "live: clearance of a request that gives 0", 0.0, 10.0);
  s.AddDouble("max_clearance", &o.max_clearance, "m", "live: larger requested clearances are refused", 0.0, 10.0);
  s.AddDouble("max_tolerance", &o.max_tolerance, "m or rad", "live: larger goal tolerances are refused", 0.0, 100.0);
  s.AddDouble("speed", &o.speed, "m/s", "live: speed limit written on every path segment", 0.0, 10.0);
  s.AddInt("search_queue", &o.queue_capacity, "live: searches that may wait; a full queue drops the oldest", 1, 1000);
  s.AddDouble("poll_period", &o.poll_period, "s", "live: period of the look for finished searches", 0.001, 1.0);
  DeclareOptions(OptionScope(s), o.planner);
  DeclareOptions(OptionScope(s).Nested("search"), o.search);
  DeclareOptions(OptionScope(s).Nested("free_space"), o.free_space);
}

std::string ValidateOptions(const PathPlannerNodeOptions& o) {
  if (const std::string e = ValidateOptions(o.planner); !e.empty()) return e;
  if (const std::string e = ValidateOptions(o.free_space); !e.empty()) return e;
  if (o.default_clearance > o.max_clearance) return "default_clearance must not exceed max_clearance";
  return "";
}

std::string ValidateRequest(const path_request_t& r, const PathPlannerNodeOptions& o) {
  auto finite = [](const pose2d_t& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); };
  if (!finite(r.start)) return "start is not finite";
  if (!finite(r.goal)) return "goal is not finite";
  if (!std::isfinite(r.position_tolerance) || r.position_tolerance < 0.0 || r.position_tolerance > o.max_tolerance)
    return "position_tolerance " + Fixed(r.position_tolerance) + " m is not in [0, " + Fixed(o.max_tolerance) + "]";
  if (!std::isfinite(r.heading_tolerance) || r.heading_tolerance < 0.0 || r.heading_tolerance > o.max_tolerance)
    return "heading_tolerance " + Fixed(r.heading_tolerance) + " rad is not in [0, " + Fixed(o.max_tolerance) + "]";
  if (!std::isfinite(r.clearance) || r.clearance < 0.0 || r.clearance > o.max_clearance)
    return "clearance " + Fixed(r.clearance) + " m is not in [0, " + Fixed(o.max_clearance) + "] (max_clearance)";
  return "";
}

PathPlannerNode::PathPlannerNode(NodeRuntime& runtime, PathPlannerNodeOptions options, Footprint footprint)
    : runtime_(runtime),
      first_map_wait_(options.first_map_wait, runtime.NowUtime(), !runtime.batch()),
      options_(std::move(options)),
      footprint_(std::move(footprint)),
      cache_(std::make_unique<PlannerCache>()) {
  worker_ = std::make_unique<BackgroundWorker<Job, Answer>>(static_cast<size_t>(options_.queue_capacity),
                                                            [this](Job& job) { return Handle(job); });
  Subscribe<path_request_t>(runtime_.bus(), options_.request_channel,
                            [this](const path_request_t& m) { OnRequest(m); });
  Subscribe<contour_map_t>(runtime_.bus(), options_.map_channel, [this](const contour_map_t& m) { OnMap(m); });
  if (!options_.drive_path_channel.empty())
    Subscribe<path_t>(runtime_.bus(), options_.drive_path_channel, [this](const path_t& m) { OnDrivePath(m); });
  Subscribe<pose_estimate_t>(runtime_.bus(), options_.pose_channel, [this](const pose_estimate_t& m) {
    const PoseEstimate e = FromLcm(m);
    if (e.converged) pose_ = e.pose;
  });
  runtime_.AddTimer(options_.poll_period, [this](int64_t) { Poll(); });
  runtime_.OnShutdown([this] {
    for (const Job& j : worker_->Stop())
      if (!j.replan) Publish(NoPathToLcm(j.request.request_id, runtime_.NowUtime(), "not planned: shutting down"));
  });
  runtime_.SetStatus(heartbeat_t::OK, "waiting for " + options_.map_channel);
}

PathPlannerNode::~PathPlannerNode() { worker_->Stop(); }

int64_t PathPlannerNode::map_version() const { return map_ ? map_->version : -1; }

void PathPlannerNode::Publish(const path_t& path) {
  ::minenav::Publish(runtime_.bus(), options_.path_channel, path);
  ++answers_;
  runtime_.SetStatus(heartbeat_t::OK, "map version " + std::to_string(map_version()) + ", " + std::to_string(requests_) +
                                          " requests, " + std::to_string(answers_) + " answers, " +
                                          std::to_string(replans_) + " replans");
}

void PathPlannerNode::OnRequest(const path_request_t& request) {
  ++requests_;
  const int64_t now = runtime_.NowUtime();
  if (pending_.count(request.request_id)) return;  // a repeat while its search runs
  if (const auto it = answered_.find(request.request_id); it != answered_.end()) {
    Publish(it->second.message);  // a repeat: the same answer again
    return;
  }
  if (const std::string why = ValidateRequest(request, options_); !why.empty()) {
    MINENAV_LOG(kWarn) << "request " << request.request_id << " refused: " << why;
    Publish(NoPathToLcm(request.request_id, now, "invalid request: " + why));
    return;
  }
  if (!map_) {
    if (first_map_wait_.LeaveForRepeat(now)) {
      MINENAV_LOG(kInfo) << "request " << request.request_id << ": no map yet, left for its repeat";
      return;
    }
    Publish(NoPathToLcm(request.request_id, now, "no map: nothing received on " + options_.map_channel + " yet"));
    return;
  }
  Job job;
  job.request = request;
  job.map = map_;
  pending_.insert(request.request_id);
  if (std::optional<Job> dropped = worker_->Push(std::move(job))) {
    if (!dropped->replan) {
      pending_.erase(dropped->request.request_id);
      Publish(NoPathToLcm(dropped->request.request_id, now,
                          "dropped: " + std::to_string(options_.queue_capacity) + " newer searches waiting"));
    }
  }
}

void PathPlannerNode::OnDrivePath(const path_t& m) {
  follow_drive_path_ = true;
  if (!m.feasible) {
    if (active_ && active_->request.request_id == m.request_id) active_.reset();
    return;
  }
  const auto it = answered_.find(m.request_id);
  if (it != answered_.end() && it->second.path) active_ = it->second.path;
}

void PathPlannerNode::Remember(const Answer& a) {
  const int64_t id = a.request.request_id;
  if (answered_.find(id) == answered_.end()) {
    answered_order_.push_back(id);
    if (answered_order_.size() > kAnswersKept) {
      answered_.erase(answered_order_.front());
      answered_order_.pop_front();
    }
  }
  Answered& stored = answered_[id];
  stored.message = a.message;
  if (a.path) stored.path = Active{a.request, *a.path};
  else stored.path.reset();
}

void PathPlannerNode::OnMap(const contour_map_t& m) {
  ContourMapMessage map = ContourMapFromLcm(m);  // throws InputError: counted as a bad message
  if (map_ && map.version == map_->version) return;
  auto snapshot = std::make_shared<MapSnapshot>();
  snapshot->version = map.version;
  snapshot->contours = ContoursOf(std::move(map));
  map_ = std::move(snapshot);
  MINENAV_LOG(kDebug) << options_.map_channel << " version " << map_->version << ": " << map_->contours.size() << " contours";
  if (!active_) return;
  Job job;
  job.replan = true;
  job.request = active_->request;
  job.map = map_;
  job.pose = pose_;
  job.active = active_->path;
  worker_->Push(std::move(job));
}

void PathPlannerNode::Poll() {
  for (Answer& a : worker_->TakeOutbox()) {
    const int64_t id = a.request.request_id;
    const bool is_active = active_ && active_->request.request_id == id;
    // Without DRIVE_PATH the last feasible answer is the path driven; with it, only a
    // replanned active path replaces the active one.
    if (a.path && (!follow_drive_path_ || is_active)) active_ = Active{a.request, *a.path};
    else if (a.publish && is_active && !a.path) active_.reset();  // blocked and no other path found
    if (a.replanned) ++replans_;
    a.message.utime = runtime_.NowUtime();  // the worker reads no clock
    pending_.erase(id);
    if (a.publish) {
      Remember(a);
      Publish(a.message);
    }
  }
}

PathPlannerNode::Answer PathPlannerNode::Handle(Job& job) {
  const auto t0 = std::chrono::steady_clock::now();
  PlannerCache& cache = *cache_;
  const path_request_t& r = job.request;
  Answer answer;
  answer.request = r;
  if (cache.version != job.map->version || !cache.space) {
    cache.version = job.map->version;
    cache.space = std::make_unique<ContourFreeSpace>(MakeContourFreeSpace(job.map->contours, options_.free_space));
    cache.known = std::make_unique<KnownFreeSpace>(*cache.space, options_.free_space);
    cache.planners.Clear();
  }
  const double clearance = r.clearance > 0.0 ? r.clearance : options_.default_clearance;
  Se2PlannerOptions requested = options_.planner;
  requested.clearance = clearance;
  if (!r.allow_reverse) requested.costs.reverse_factor = std::max(requested.costs.reverse_factor, kNoReverseFactor);
  // The planners of this request (held: the cache may let one go while the request uses it).
  std::vector<std::shared_ptr<const Se2Planner>> held;
  auto planner_with = [&](const std::vector<Segment>& boundary, const Se2PlannerOptions& po) -> const Se2Planner& {
    held.push_back(cache.planners.Get(boundary, footprint_, po));
    planners_built_ = cache.planners.built();
    return *held.back();
  };
  const std::vector<Segment> boundary = cache.space->Boundary(r.allow_unknown);
  const Se2Planner* chosen = &planner_with(boundary, requested);
  const std::string map_name = "map version " + std::to_string(job.map->version);

  Pose2 start = FromLcm(r.start);
  const Pose2 goal = FromLcm(r.goal);
  std::string prefix;
  if (job.replan) {
    // The rest of the active path from the piece nearest the vehicle.
    const PlannedPath& path = job.active;
    const Eigen::Vector2d here = job.pose ? job.pose->translation() : path.start.translation();
    size_t first = 0;
    double best = (path.start.translation() - here).norm();
    Pose2 from = path.start;
    for (size_t k = 0; k < path.pieces.size(); ++k) {
      const MotionPiece& p = path.pieces[k];
      const int n = 20;
      for (int i = 1; i <= n; ++i) {
        const double d = (PoseAfter(from, p.motion, p.amount * i / n, p.radius).translation() - here).norm();
        if (d < best) best = d, first = k;
      }
      from = p.end;
    }
    std::string blocked;
    from = first == 0 ? path.start : path.pieces[first - 1].end;
    for (size_t k = first; k < path.pieces.size() && blocked.empty(); ++k) {
      if (chosen->PieceCollides(from, path.pieces[k]))
        blocked = map_name + " blocks piece " + std::to_string(k + 1) + " of " + std::to_string(path.pieces.size()) +
                  " (" + ToString(path.pieces[k].motion) + " to " + Where(path.pieces[k].end) + ")";
      from = path.pieces[k].end;
    }
    if (blocked.empty()) {
      answer.publish = false;
      return answer;
    }
    answer.replanned = true;
    if (job.pose) start = *job.pose;
    else start = path.start;
    prefix = "replanned: " + blocked + "; from " + Where(start) + ": ";
    MINENAV_LOG(kInfo) << "request " << r.request_id << " " << prefix;
  }

  // The deadline bounds the search; building the free space and the planner for a new map
  // version (bounded by the map's size, done once per version) comes before it.
  const auto search_start = std::chrono::steady_clock::now();
  const auto deadline = search_start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(options_.deadline));
  bool deadline_passed = false;
  SearchLimits limits = options_.search;
  limits.stop_requested = [&] {
    if (NodeRuntime::StopSignalled()) return true;
    deadline_passed = std::chrono::steady_clock::now() > deadline;
    return deadline_passed;
  };

  auto refuse = [&](const std::string& why) {
    answer.message = NoPathToLcm(r.request_id, 0, prefix + why);
    MINENAV_LOG(kInfo) << "request " << r.request_id << ": " << prefix << why;
    return answer;
  };
  // Where the vehicle stands: a frontier through its footprint is no edge of what the ladar
  // saw (it looked from there), and within the clearance of a wall (the map grew around it
  // where it stopped short, or a cut's ribs beside it) it is not stuck: it leaves with the
  // clearance it has, never in contact. The answer says so.
  const KnownFreeSpace* known = cache.known.get();
  std::optional<ContourFreeSpace> own_space;
  std::unique_ptr<KnownFreeSpace> own_known;
  if (chosen->setup_error().empty() && !chosen->PoseFree(start) && !r.allow_unknown) {
    int dropped = 0;
    std::vector<Segment> frontiers = FrontiersAwayFrom(cache.space->frontiers, footprint_.At(start),
                                                       clearance + options_.planner.collision_step, &dropped);
    if (dropped > 0) {
      own_space = ContourFreeSpace{cache.space->walls, std::move(frontiers), 0, 0};
      own_known = std::make_unique<KnownFreeSpace>(*own_space, options_.free_space);
      known = own_known.get();
      chosen = &planner_with(own_space->Boundary(false), requested);
      prefix += std::to_string(dropped) + " frontier(s) through the vehicle's footprint ignored; ";
    }
  }
  if (chosen->setup_error().empty() && !chosen->PoseFree(start)) {
    if (const std::optional<Se2PlannerOptions> leaving = chosen->LeavingOptions(start)) {
      const Se2Planner& relaxed = planner_with(own_space ? own_space->Boundary(false) : boundary, *leaving);
      if (relaxed.PoseFree(start)) {
        prefix += "start within " + Fixed(clearance) + " m of a wall: planned with a clearance of " +
                  Fixed(leaving->clearance) + " m";
        if (leaving->collision_step < requested.collision_step)
          prefix += " (checked every " + Fixed(leaving->collision_step, 3) + " m)";
        prefix += "; ";
        chosen = &relaxed;
      }
    }
  }
  const Se2Planner& planner = *chosen;
  if (!planner.setup_error().empty()) return refuse("invalid request: " + planner.setup_error());
  if (!r.allow_unknown) {
    if (!cache.known->Contains(goal.translation()))
      return refuse("goal " + Where(goal) + " is not in the known free space of " + map_name +
                    " (behind a frontier or unseen; allow_unknown explores)");
    if (!known->Contains(start.translation()))
      return refuse("start " + Where(start) + " is not in the known free space of " + map_name);
  }
  const Se2PlanResult result = planner.Plan(start, goal, limits);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (result.status != SearchStatus::kFound) {
    std::string why = ToString(result.status) + ": " + result.reason;
    if (result.status == SearchStatus::kStopped && deadline_passed)
      why = "deadline: the search was stopped at the deadline of " + Fixed(options_.deadline, 3) + " s after " +
            std::to_string(result.expansions) + " expansions";
    else if (result.status == SearchStatus::kNoPath && !r.allow_unknown)
      why += " (in the known free space; allow_unknown explores)";
    return refuse(why);
  }
  if (!r.allow_reverse)
    for (const MotionPiece& p : result.path.pieces)
      if (DriveDirection(p.motion) < 0)
        return refuse("no_path: every path found reverses (" + ToString(p.motion) + " to " + Where(p.end) +
                      ") and the request does not allow reversing");
  std::ostringstream status;
  status << prefix << "ok: " << Fixed(result.path.Length()) << " m, " << result.path.pieces.size() << " pieces, "
         << result.path.Reversals() << " reversals, " << result.expansions << " expansions, " << Fixed(ms, 1)
         << " ms on " << map_name;
  answer.message = PathToLcm(result.path, r.request_id, 0, options_.speed, status.str());
  answer.path = result.path;
  MINENAV_LOG(kInfo) << "request " << r.request_id << ": " << status.str();
  return answer;
}

}  // namespace minenav
