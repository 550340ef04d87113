#include "tracker/survey_client_node.h"

#include <utility>

#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"

namespace minenav {
namespace {

std::vector<Pose2> Poses(const std::vector<Station>& stations) {
  std::vector<Pose2> out;
  for (const Station& s : stations) out.push_back(s.pose);
  return out;
}

}  // namespace

void DeclareOptions(ConfigSchema& s, SurveyClientOptions& o) {
  s.AddString("stations", &o.stations, "scan stations CSV (x,y,theta) to visit in order");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t",
               "the vehicle's estimate: the start of each request");
  s.AddChannel("request_channel", &o.request_channel, "publishes", "path_request_t", "a path to the next station");
  s.AddChannel("path_channel", &o.path_channel, "subscribes", "path_t", "the planner's answers");
  s.AddChannel("status_channel", &o.status_channel, "subscribes", "task_status_t",
               "the path tracker's progress (task_id = request_id)");
  s.AddDouble("rate", &o.rate, "Hz", "how often the client looks at what is due", 0.1, 100.0);
  s.AddDouble("clearance", &o.clearance, "m", "clearance asked of the planner", 0.0, 2.0);
  s.AddDouble("position_tolerance", &o.position_tolerance, "m", "goal position tolerance asked of the planner", 0.001,
              5.0);
  s.AddDouble("heading_tolerance", &o.heading_tolerance, "rad", "goal heading tolerance asked of the planner", 0.0001,
              3.0);
  s.AddBool("allow_reverse", &o.allow_reverse, "the planner may reverse (multi-point maneuvers)");
  s.AddBool("allow_unknown", &o.allow_unknown,
            "the planner may plan through space no scan has seen (a survey that explores); false = seen free space only");
  s.AddBool("exit_when_done", &o.exit_when_done, "stop the process after the last station");
  const OptionScope r = OptionScope(s).Nested("requests");
  r.AddDouble("dwell", &o.requests.dwell, "s", "time standing still at each station (for the ladar's scans)", 0.0,
              600.0);
  r.AddDouble("answer_timeout", &o.requests.answer_timeout, "s", "time to wait for the PATH of a request", 0.1, 3600.0);
  r.AddInt("max_attempts", &o.requests.max_attempts, "requests per station before it is skipped", 1, 100);
  r.AddDouble("retry_delay", &o.requests.retry_delay, "s",
              "from a failed attempt (no path, no answer, the tracker's FAILED) to the next request", 0.0, 600.0);
}

std::vector<Station> LoadClientStations(const SurveyClientOptions& o) {
  if (o.stations.empty()) throw UsageError("--stations is required");
  return LoadStationsCsv(o.stations);
}

SurveyClientNode::SurveyClientNode(NodeRuntime& runtime, SurveyClientOptions options,
                                   const std::vector<Station>& stations)
    : runtime_(runtime),
      options_(std::move(options)),
      requests_(Poses(stations), options_.requests, runtime.NowUtime()) {
  MINENAV_LOG(kInfo) << "surveying " << stations.size() << " stations from " << options_.stations;
  Subscribe<pose_estimate_t>(runtime_.bus(), options_.pose_channel, [this](const pose_estimate_t& m) {
    const PoseEstimate e = FromLcm(m);
    if (e.converged) pose_ = e.pose;
  });
  Subscribe<path_t>(runtime_.bus(), options_.path_channel, [this](const path_t& m) {
    requests_.OnPath(m.request_id, m.feasible, m.status, runtime_.NowUtime());
  });
  Subscribe<task_status_t>(runtime_.bus(), options_.status_channel, [this](const task_status_t& m) {
    requests_.OnStatus(m.task_id, m.state, m.message, runtime_.NowUtime());
  });
  runtime_.AddTimer(1.0 / options_.rate, [this](int64_t now) { Tick(now); });
}

void SurveyClientNode::Tick(int64_t now) {
  if (pose_ && !requests_.Finished()) {
    if (const std::optional<StationRequests::Request> r = requests_.Update(now)) {
      path_request_t m{};
      m.utime = now;
      m.request_id = r->request_id;
      m.start = ToLcm(*pose_);
      m.goal = ToLcm(r->goal);
      m.position_tolerance = options_.position_tolerance;
      m.heading_tolerance = options_.heading_tolerance;
      m.allow_reverse = options_.allow_reverse;
      m.allow_unknown = options_.allow_unknown;
      m.clearance = options_.clearance;
      Publish(runtime_.bus(), options_.request_channel, m);
      MINENAV_LOG(kInfo) << requests_.message();
    }
  }
  runtime_.SetStatus(heartbeat_t::OK, pose_ ? requests_.message() : "waiting for a pose on " + options_.pose_channel);
  if (requests_.Finished() && options_.exit_when_done) {
    MINENAV_LOG(kInfo) << "all stations visited (" << requests_.skipped() << " skipped)";
    runtime_.RequestStop();
  }
}

}  // namespace minenav
