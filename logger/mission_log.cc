#include "logger/mission_log.h"

#include <cmath>
#include <set>
#include <utility>

#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/heartbeat_conversion.h"
#include "common/node/event_log.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/path_message.h"
#include "planner/task_plan_message.h"

namespace minenav {

namespace {

template <typename Msg>
Msg Decode(const LogEvent& e) {
  Msg m{};
  std::string error;
  if (!DecodeMessage(e.data.data(), static_cast<int>(e.data.size()), e.channel, &m, &error)) throw InputError(error);
  return m;
}

// The path of a path_t; its arcs' radius is the vehicle's turning radius (PathFromLcm checks
// every arc has it and every piece reaches its end pose).
LoggedPath PathFromMessage(const path_t& m) {
  double radius = 1.0;
  for (const path_segment_t& s : m.segments)
    if (s.motion == path_segment_t::ARC_LEFT || s.motion == path_segment_t::ARC_RIGHT ||
        s.motion == path_segment_t::ARC_LEFT_REVERSE || s.motion == path_segment_t::ARC_RIGHT_REVERSE) {
      radius = s.radius;
      break;
    }
  if (!(radius > 0.0) || !std::isfinite(radius)) throw InputError("path: arc radius " + std::to_string(radius));
  LoggedPath p;
  p.utime = m.utime;
  p.request_id = m.request_id;
  p.feasible = m.feasible;
  p.status = m.status;
  if (m.feasible) p.path = PathFromLcm(m, radius).path;
  return p;
}

template <typename Enum>
Enum CheckedState(int value, int max, const char* what) {
  if (value < 0 || value > max) throw InputError(std::string(what) + ": unknown state " + std::to_string(value));
  return static_cast<Enum>(value);
}

class MissionLogReader {
 public:
  MissionLogReader(const MissionLogChannels& c, const MissionLogAuth* auth)
      : c_(c), auth_(auth), verifier_(auth != nullptr ? static_cast<int64_t>(std::llround(auth->max_age * 1e6)) : 1) {}

  void Read(const LogEvent& e) {
    MissionRecord& r = out_.record;
    if (r.events == 0) r.first_utime = e.timestamp;
    r.last_utime = e.timestamp;
    ++r.events;
    if (auth_ != nullptr && auth_->signed_channels.count(e.channel) != 0) {
      const VerifyOutcome v =
          verifier_.Verify(auth_->keys, e.channel, e.data.data(), static_cast<int>(e.data.size()), e.timestamp);
      if (v.result != AuthResult::kAccepted) {
        if (r.auth_refused++ == 0)
          r.first_auth_refused = "event " + std::to_string(e.eventnum) + ", channel " + e.channel + ": " +
                                 AuthResultName(v.result);
        return;
      }
    }
    try {
      Dispatch(e);
    } catch (const InputError& err) {
      ++r.bad_messages;
      if (r.first_bad.empty())
        r.first_bad = "event " + std::to_string(e.eventnum) + " at byte " + std::to_string(e.offset) + ", channel " +
                      e.channel + ": " + err.what();
    }
  }

  MissionLog Finish() {
    if (last_map_) {
      try {
        out_.last_contour_map = ContourMapFromLcm(Decode<contour_map_t>(*last_map_));
      } catch (const InputError& err) {
        ++out_.record.bad_messages;
        if (out_.record.first_bad.empty()) out_.record.first_bad = c_.contour_map + ": " + err.what();
      }
    }
    return std::move(out_);
  }

 private:
  void Dispatch(const LogEvent& e) {
    MissionRecord& r = out_.record;
    const std::string& ch = e.channel;
    if (ch == c_.truth) {
      const TruthReading t = FromLcm(Decode<vehicle_truth_t>(e));
      r.truth.push_back({t.utime, t.pose});
    } else if (ch == c_.pose) {
      const PoseEstimate p = FromLcm(Decode<pose_estimate_t>(e));
      r.estimates.push_back({p.utime, p.pose});
    } else if (ch == c_.odometry) {
      const OdometryReading o = FromLcm(Decode<odometry_t>(e));
      r.odometry.push_back({o.utime, o.pose});
    } else if (ch == c_.world) {
      const line_map_t m = Decode<line_map_t>(e);
      r.worlds.push_back({m.utime, m.version, SegmentsFromLcm(m)});
    } else if (ch == c_.path) {
      r.planner_paths.push_back(PathFromMessage(Decode<path_t>(e)));
    } else if (ch == c_.drive_path) {
      r.drive_paths.push_back(PathFromMessage(Decode<path_t>(e)));
    } else if (ch == c_.task_status) {
      const task_status_t m = Decode<task_status_t>(e);
      r.task_status.push_back(
          {m.utime, m.task_id, CheckedState<TaskState>(m.state, 4, "task_status_t"), m.message});
    } else if (ch == c_.mission_status) {
      const mission_status_t m = Decode<mission_status_t>(e);
      MissionStatusLine s;
      s.utime = m.utime;
      s.state = CheckedState<MissionState>(m.state, 7, "mission_status_t");
      s.message = m.message;
      for (const mission_node_t& n : m.nodes)
        s.nodes.push_back({n.name, CheckedState<BtStatus>(n.state, 3, "mission_node_t")});
      r.mission_status.push_back(std::move(s));
    } else if (ch == c_.task_plan) {
      // A plan answers one request (re-sent answers repeat its plan id); task ids count within a plan.
      const TaskPlanMessage message = TaskPlanFromLcm(Decode<task_plan_t>(e));
      for (const Task& t : message.plan.tasks)
        if (t.kind == TaskKind::kScanStation && stations_.insert({message.plan_id, t.id}).second)
          r.scan_stations.push_back(t.target);
    } else if (ch == c_.heartbeat) {
      r.heartbeats.push_back(HeartbeatSampleFromLcm(Decode<heartbeat_t>(e), e.timestamp));
    } else if (ch == c_.contour_map) {
      last_map_ = e;  // decoded at the end: only the last one is wanted
    }
  }

  const MissionLogChannels& c_;
  MissionLog out_;
  std::set<std::pair<int64_t, int64_t>> stations_;  // (plan id, task id)
  std::optional<LogEvent> last_map_;
  const MissionLogAuth* auth_;
  MessageVerifier verifier_;
};

}  // namespace

MissionLog ReadMissionLog(const std::string& path, const MissionLogChannels& channels, const MissionLogAuth* auth) {
  LogReader reader(path);
  MissionLogReader read(channels, auth);
  std::string damage;
  try {
    while (const LogEvent* e = reader.NextInPlace()) read.Read(*e);
    damage = reader.truncation();
  } catch (const InputError& err) {
    damage = err.what();
  }
  MissionLog log = read.Finish();
  log.record.damage = damage;
  return log;
}

}  // namespace minenav
