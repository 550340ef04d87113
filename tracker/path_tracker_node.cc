#include "tracker/path_tracker_node.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/pose_at_time.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/path_message.h"

namespace minenav {
namespace {

std::string Seconds(double s) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(2);
  os << s;
  return os.str();
}

double Age(int64_t now, int64_t then) { return static_cast<double>(TimeGap(now, then)) * 1e-6; }

bool SamePose(const pose2d_t& a, const pose2d_t& b) { return a.x == b.x && a.y == b.y && a.theta == b.theta; }

// The same path (start and pieces, exactly as sent), whatever its stamp and status: a repeat.
bool SamePath(const path_t& a, const path_t& b) {
  if (a.feasible != b.feasible || a.num_segments != b.num_segments || !SamePose(a.start, b.start)) return false;
  for (size_t k = 0; k < a.segments.size() && k < b.segments.size(); ++k) {
    const path_segment_t &x = a.segments[k], &y = b.segments[k];
    if (x.motion != y.motion || !SamePose(x.end, y.end) || x.radius != y.radius || x.speed != y.speed) return false;
  }
  return a.segments.size() == b.segments.size();
}

}  // namespace

void DeclareOptions(ConfigSchema& s, PathTrackerNodeOptions& o) {
  s.AddChannel("path_channel", &o.path_channel, "subscribes", "path_t", "paths to track (the path planner's)");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t",
               "pose estimates in the map frame (POSE: the contour mapper; POSE_IPE, POSE_FPE also serve)");
  s.AddChannel("odometry_channel", &o.odometry_channel, "subscribes", "odometry_t", "odometry between estimates");
  s.AddChannel("map_channel", &o.map_channel, "subscribes", "contour_map_t",
               "the map the commanded motion is checked against and the speed regulated by");
  s.AddChannel("line_map_channel", &o.line_map_channel, "subscribes", "line_map_t",
               "a line map used the same way (a surveyed map); empty = none");
  s.AddChannel("drive_channel", &o.drive_channel, "publishes", "drive_command_t", "drive commands at --rate");
  s.AddChannel("status_channel", &o.status_channel, "publishes", "task_status_t",
               "the path's state (task_id = request_id): taken, stopped, resumed, done, failed, blocked");
  s.AddDouble("rate", &o.rate, "Hz", "control rate (one DRIVE_COMMAND per tick)", 1.0, 100.0);
  s.AddDouble("pose_timeout", &o.pose_timeout, "s",
              "no trusted pose estimate for this long (by scan stamps): STOP until one comes", 0.1, 3600.0);
  s.AddDouble("odometry_timeout", &o.odometry_timeout, "s", "no odometry for this long: STOP until it comes", 0.05,
              60.0);
  s.AddDouble("path_max_age", &o.path_max_age, "s", "a path planned longer ago than this is abandoned", 1.0, 1e6);
  s.AddDouble("vehicle_width", &o.vehicle_width, "m", "the footprint rectangle's width (without --footprint)", 0.1,
              100.0);
  s.AddDouble("vehicle_length", &o.vehicle_length, "m", "the footprint rectangle's length (without --footprint)", 0.1,
              100.0);
  s.AddString("footprint", &o.footprint, "footprint JSON {\"footprint\": [[x, y], ...]} (m, vehicle frame); empty = the rectangle");
  DeclareOptions(OptionScope(s).Nested("tracker"), o.tracker);
  DeclareOptions(OptionScope(s).Nested("prediction"), o.prediction);
}

Footprint LoadTrackerFootprint(const PathTrackerNodeOptions& o) {
  if (const std::string why = ValidatePathTrackerOptions(o.tracker); !why.empty()) throw UsageError("tracker." + why);
  if (const std::string why = ValidatePosePredictorOptions(o.prediction); !why.empty())
    throw UsageError("prediction." + why);
  if (o.tracker.command_timeout < 1.0 / o.rate)
    throw UsageError("tracker.command_timeout is shorter than one control period (1 / rate): the vehicle would stop between commands");
  if (o.pose_timeout < o.odometry_timeout)
    MINENAV_LOG(kWarn) << "pose_timeout is shorter than odometry_timeout: the pose watchdog decides";
  if (o.footprint.empty()) return Footprint::Rectangle(o.vehicle_width, o.vehicle_length);
  const Footprint f = ParseFootprintJson(ReadFile(o.footprint), o.footprint);
  if (const std::string why = ValidateFootprint(f); !why.empty()) throw UsageError(o.footprint + ": " + why);
  return f;
}

PathTrackerNode::PathTrackerNode(NodeRuntime& runtime, PathTrackerNodeOptions options, Footprint footprint)
    : runtime_(runtime),
      options_(std::move(options)),
      footprint_(std::move(footprint)),
      tracker_(options_.tracker, footprint_),
      predictor_(options_.prediction) {
  Bus& bus = runtime_.bus();
  Subscribe<odometry_t>(bus, options_.odometry_channel, [this](const odometry_t& m) {
    predictor_.AddOdometry(FromLcm(m));
    if (const std::optional<EstimateVerdict> v = predictor_.TakeDeferredVerdict()) Report(*v);
  });
  Subscribe<pose_estimate_t>(bus, options_.pose_channel,
                             [this](const pose_estimate_t& m) { Report(predictor_.AddEstimate(FromLcm(m))); });
  Subscribe<path_t>(bus, options_.path_channel, [this](const path_t& m) {
    const int64_t now = runtime_.NowUtime();
    if (last_status_ && m.request_id == last_status_->task_id) {
      // A repeat (or a cancel) of the active or last finished request; only a different path
      // for the active request goes on: the planner's replan (same request_id, new path).
      const bool active = request_id_ && *request_id_ == m.request_id;
      if (!active || !m.feasible || (active_path_ && SamePath(m, *active_path_))) return Repeated(m, now);
    }
    PathMessage p;
    try {
      p = PathFromLcm(m, options_.tracker.turn_radius);
    } catch (const InputError& e) {
      MINENAV_LOG(kWarn) << options_.path_channel << ": refused: " << e.what();
      request_id_ = m.request_id;
      PublishStatus(now, task_status_t::FAILED, 0.0f, std::string("refused: ") + e.what());
      tracker_.Cancel(e.what());
      request_id_.reset();
      return;
    }
    if (!p.feasible) {
      MINENAV_LOG(kInfo) << options_.path_channel << ": request " << p.request_id << " has no path (" << p.status
                         << "): nothing to track";
      return;
    }
    if (request_id_ && *request_id_ != p.request_id)
      PublishStatus(now, task_status_t::CANCELED, 0.0f, "replaced by the path of request " + std::to_string(p.request_id));
    const bool replanned = request_id_ && *request_id_ == p.request_id;
    request_id_ = p.request_id;
    path_utime_ = p.utime;
    progress_ = 0.0f;
    active_path_ = m;
    const TrackState s = tracker_.SetPath(p.path, p.speeds);
    MINENAV_LOG(kInfo) << (replanned ? "replanned path" : "path") << " of request " << p.request_id << ": "
                       << tracker_.message();
    if (s == TrackState::kActive) {
      PublishStatus(now, task_status_t::ACTIVE, 0.0f, (replanned ? "replanned path taken: " : "") + tracker_.message());
    } else {
      PublishStatus(now, task_status_t::FAILED, 0.0f, tracker_.message());
      request_id_.reset();
    }
  });
  map_worker_ = std::make_unique<BackgroundWorker<MapJob, BuiltMap>>(1, [this](MapJob& job) {
    BuiltMap b;
    b.map = std::make_shared<TrackerMap>(job.segments, footprint_, options_.tracker.collision_margin,
                                         options_.tracker.turn_radius);
    b.what = std::move(job.what);
    b.segments = job.segments.size();
    return b;
  });
  maps_ = std::make_unique<MapUpdates>(
      bus, options_.line_map_channel, options_.map_channel,
      [this](const std::vector<Segment>& segments, const std::string& what) {
        if (const std::optional<MapJob> dropped = map_worker_->Push({segments, what}))
          MINENAV_LOG(kDebug) << dropped->what << ": replaced by a newer map before it was built";
      });
  runtime_.AddTimer(1.0 / options_.rate, [this](int64_t now) { Tick(now); });
}

PathTrackerNode::~PathTrackerNode() { map_worker_->Stop(); }

void PathTrackerNode::TakeMaps() {
  std::vector<BuiltMap> built = map_worker_->TakeOutbox();
  for (auto it = built.rbegin(); it != built.rend(); ++it) {  // the newest usable one
    if (!it->map->error().empty()) {
      MINENAV_LOG(kWarn) << it->what << ": not used (" << it->map->error() << ")";
      continue;
    }
    MINENAV_LOG(kInfo) << it->what << ": " << it->segments << " segments to check the motion against";
    tracker_.SetMap(std::move(it->map));
    ++maps_applied_;
    return;
  }
}

void PathTrackerNode::Report(const EstimateVerdict& v) {
  if (v.jump) {
    MINENAV_LOG(kWarn) << options_.pose_channel << ": " << v.reason;
    last_report_ = v.reason;
    if (request_id_) PublishStatus(runtime_.NowUtime(), task_status_t::ACTIVE, 0.0f, v.reason);
  } else if (!v.trusted) {
    MINENAV_LOG(kDebug) << options_.pose_channel << ": " << v.reason;
  }
}

void PathTrackerNode::Repeated(const path_t& m, int64_t now) {
  if (!m.feasible && request_id_ && *request_id_ == m.request_id) {
    const std::string why = "canceled by the sender";
    tracker_.Cancel(why);
    MINENAV_LOG(kInfo) << "path " << m.request_id << ": " << why;
    PublishStatus(now, task_status_t::CANCELED, progress_, why);
    request_id_.reset();
    stopped_because_.clear();
    return;
  }
  // The same request again (the sender repeats until acknowledged): nothing changes; its
  // latest status, stamped now, is the acknowledgement.
  MINENAV_LOG(kDebug) << options_.path_channel << ": request " << m.request_id << " repeated: status re-published";
  task_status_t s = *last_status_;
  s.utime = now;
  if (request_id_ && *request_id_ == s.task_id) s.progress = progress_;
  Publish(runtime_.bus(), options_.status_channel, s);
}

void PathTrackerNode::PublishStatus(int64_t now, int8_t state, float progress, const std::string& message) {
  task_status_t m{};
  m.utime = now;
  m.plan_id = 0;
  m.task_id = request_id_.value_or(-1);
  m.state = state;
  m.progress = progress;
  m.message = message;
  Publish(runtime_.bus(), options_.status_channel, m);
  last_status_ = m;
}

std::string PathTrackerNode::Staleness(int64_t now) const {
  const std::optional<int64_t> pose = predictor_.last_trusted_utime();
  const std::optional<int64_t> odo = predictor_.last_odometry_utime();
  if (!pose) return "no trusted pose estimate yet on " + options_.pose_channel;
  if (!odo) return "no odometry yet on " + options_.odometry_channel;
  if (*pose < now && Age(now, *pose) > options_.pose_timeout)
    return "pose stale: " + Seconds(Age(now, *pose)) + " s since the last trusted estimate (limit " +
           Seconds(options_.pose_timeout) + " s)";
  if (*odo < now && Age(now, *odo) > options_.odometry_timeout)
    return "odometry stale: " + Seconds(Age(now, *odo)) + " s since the last reading (limit " +
           Seconds(options_.odometry_timeout) + " s)";
  return "";
}

void PathTrackerNode::Tick(int64_t now) {
  TakeMaps();
  DriveCommand command;
  command.timeout = options_.tracker.command_timeout;
  std::string heartbeat;
  int8_t health = heartbeat_t::OK;
  if (request_id_ && tracker_.state() == TrackState::kActive) {
    if (path_utime_ < now && Age(now, path_utime_) > options_.path_max_age) {
      const std::string why = "path stale: planned " + Seconds(Age(now, path_utime_)) + " s ago (limit " +
                              Seconds(options_.path_max_age) + " s); abandoned";
      tracker_.Cancel(why);
      MINENAV_LOG(kWarn) << why;
      PublishStatus(now, task_status_t::FAILED, 0.0f, why);
      request_id_.reset();
      heartbeat = why;
      health = heartbeat_t::WARN;
    } else if (const std::string stale = Staleness(now); !stale.empty()) {
      if (stopped_because_.empty()) {
        MINENAV_LOG(kWarn) << "stopped: " << stale;
        PublishStatus(now, task_status_t::ACTIVE, 0.0f, "stopped: " + stale);
      }
      stopped_because_ = stale;
      heartbeat = "stopped: " + stale;
      health = heartbeat_t::WARN;
    } else {
      if (!stopped_because_.empty()) {
        MINENAV_LOG(kInfo) << "resumed (" << stopped_because_ << " no longer)";
        PublishStatus(now, task_status_t::ACTIVE, 0.0f, "resumed");
        stopped_because_.clear();
      }
      const TrackStep step = tracker_.Update(*predictor_.Predict());
      command = step.command;
      progress_ = static_cast<float>(step.progress);
      heartbeat = "path " + std::to_string(*request_id_) + ": " + step.message;
      if (step.finished_now) {
        const bool done = step.state == TrackState::kDone;
        if (done)
          MINENAV_LOG(kInfo) << "path " << *request_id_ << ": " << step.message;
        else
          MINENAV_LOG(kWarn) << "path " << *request_id_ << ": " << step.message;
        PublishStatus(now, done ? task_status_t::DONE : task_status_t::FAILED, static_cast<float>(step.progress),
                      step.message);
        request_id_.reset();
        if (!done) health = heartbeat_t::WARN;
      }
    }
  } else {
    stopped_because_.clear();
    heartbeat = "idle: " + tracker_.message();
    if (const std::string stale = Staleness(now); !stale.empty()) heartbeat = "idle; " + stale;
  }
  if (!last_report_.empty() && health == heartbeat_t::OK) {
    heartbeat += "; last report: " + last_report_;
  }
  command.utime = now;
  command.seq = seq_++;
  Publish(runtime_.bus(), options_.drive_channel, ToLcm(command));
  runtime_.SetStatus(health, heartbeat);
}

}  // namespace minenav
