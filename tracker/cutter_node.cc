#include "tracker/cutter_node.h"

#include <cmath>
#include <utility>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/map_updates.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"
#include "tracker/cutter_conversions.h"

namespace minenav {

void DeclareOptions(ConfigSchema& s, CutterNodeOptions& o) {
  s.AddChannel("task_channel", &o.task_channel, "subscribes", "cutter_command_t",
               "cut tasks: SUMP = cut sump_depth m into the face face_x1..y2 (zero = find it in the map), STOP = "
               "cancel; seq = task id");
  s.AddChannel("pose_channel", &o.pose_channel, "subscribes", "pose_estimate_t", "the pose estimate (never truth)");
  s.AddChannel("odometry_channel", &o.odometry_channel, "subscribes", "odometry_t",
               "odometry: the prediction between pose estimates");
  s.AddChannel("state_channel", &o.state_channel, "subscribes", "cutter_state_t", "the appendages' state");
  s.AddChannel("map_channel", &o.map_channel, "subscribes", "contour_map_t", "the map the face is found in");
  s.AddChannel("drive_channel", &o.drive_channel, "publishes", "drive_command_t",
               "drive commands, only while a cut is active");
  s.AddChannel("command_channel", &o.command_channel, "publishes", "cutter_command_t",
               "commands to the appendages");
  s.AddChannel("status_channel", &o.status_channel, "publishes", "task_status_t",
               "the cut's progress, DONE, or FAILED with the reason");
  s.AddDouble("rate", &o.rate, "Hz", "control rate", 1.0, 100.0);
  DeclareOptions(OptionScope(s).Nested("cutter"), o.cutter);
  s.AddHelpEpilog(R"(Examples:
  cutter                                  (waits for a cut task on CUT_TASK)
  cutter --cutter.sump-step 0.4 --cutter.max-pose-age 3
)");
}

CutterNode::CutterNode(NodeRuntime& runtime, const CutterNodeOptions& options)
    : runtime_(runtime), options_(options), cutter_(options.cutter) {
  if (std::string why = ValidateCutterOptions(options_.cutter); !why.empty()) throw UsageError(why);
  Subscribe<pose_estimate_t>(runtime_.bus(), options_.pose_channel, [this](const pose_estimate_t& m) {
    const PoseEstimate e = FromLcm(m);
    if (e.converged) pose_ = StampedPose{e.utime, e.pose};
  });
  Subscribe<odometry_t>(runtime_.bus(), options_.odometry_channel,
                        [this](const odometry_t& m) { cutter_.AddOdometry(FromLcm(m)); });
  Subscribe<cutter_state_t>(runtime_.bus(), options_.state_channel, [this](const cutter_state_t& m) {
    std::string why;
    std::optional<CutterState> s = CutterStateFromLcm(m, &why);
    if (!s) throw InputError(why);
    // Our own clock: the vehicle's stamp says nothing about how fresh it is here.
    s->utime = runtime_.NowUtime();
    state_ = std::move(s);
  });
  Subscribe<contour_map_t>(runtime_.bus(), options_.map_channel, [this](const contour_map_t& m) {
    map_ = ContourMapSegments(ContourMapFromLcm(m));
  });
  Subscribe<cutter_command_t>(runtime_.bus(), options_.task_channel, [this](const cutter_command_t& m) {
    std::string why;
    const std::optional<CutterCommand> c = CutterCommandFromLcm(m, &why);
    if (!c) throw InputError(why);
    const int64_t now = runtime_.NowUtime();
    if (c->action != CutterCommand::Action::kSump && c->action != CutterCommand::Action::kStop)
      throw InputError(std::string("cut task: action ") + ToString(c->action) + " is not SUMP or STOP");
    OnTask(*c, now);
  });
  runtime_.AddTimer(1.0 / options_.rate, [this](int64_t now) { Tick(now); });
}

void CutterNode::OnTask(const CutterCommand& c, int64_t now) {
  const CutterStatus& st = cutter_.status();
  // The sender repeats a task until it is acknowledged: the repeat of the task under way
  // (or of the last one, ended) is answered with its latest status and changes nothing.
  const bool known = last_status_ && c.seq == last_status_->task_id;
  if (c.action == CutterCommand::Action::kStop) {
    if (cutter_.active() && c.seq == st.task_id) {
      cutter_.Cancel("canceled by the sender");
      MINENAV_LOG(kInfo) << "cut " << st.task_id << ": " << st.message;
      runtime_.SetStatus(heartbeat_t::OK, st.message);
      PublishStatus(now);
    } else if (known) {
      Republish(now);
    } else {
      MINENAV_LOG(kWarn) << "STOP of cut task " << c.seq << " ignored: "
                         << (cutter_.active() ? "cut " + std::to_string(st.task_id) + " is under way"
                                              : std::string("no cut is under way"));
    }
    return;
  }
  if (known) {
    MINENAV_LOG(kDebug) << "cut task " << c.seq << " repeated: status re-published";
    Republish(now);
    return;
  }
  if (cutter_.active()) {
    MINENAV_LOG(kWarn) << "cut task " << c.seq << " ignored: cut " << st.task_id << " is under way";
    return;
  }
  const std::string refused = cutter_.Start(CutTask{c.seq, c.sump_depth, c.face}, pose_, map_, now);
  if (!refused.empty()) {
    MINENAV_LOG(kWarn) << "cut task " << c.seq << " " << refused;
    runtime_.SetStatus(heartbeat_t::WARN, refused);
  } else {
    MINENAV_LOG(kInfo) << "cut task " << c.seq << ": " << st.message;
  }
  PublishStatus(now);
}

void CutterNode::Republish(int64_t now) {
  task_status_t m = *last_status_;
  m.utime = now;
  if (cutter_.active() && m.task_id == cutter_.status().task_id) m.progress = static_cast<float>(cutter_.status().progress());
  Publish(runtime_.bus(), options_.status_channel, m);
}

void CutterNode::PublishStatus(int64_t now) {
  const CutterStatus& st = cutter_.status();
  task_status_t m{};
  m.utime = now;
  m.plan_id = 0;
  m.task_id = st.task_id;
  switch (st.state) {
    case CutterStatus::State::kIdle: m.state = task_status_t::PENDING; break;
    case CutterStatus::State::kActive: m.state = task_status_t::ACTIVE; break;
    case CutterStatus::State::kDone: m.state = task_status_t::DONE; break;
    case CutterStatus::State::kFailed: m.state = task_status_t::FAILED; break;
    case CutterStatus::State::kCanceled: m.state = task_status_t::CANCELED; break;
  }
  m.progress = static_cast<float>(st.progress());
  m.message = st.state == CutterStatus::State::kActive ? st.step + ": " + st.message : st.message;
  Publish(runtime_.bus(), options_.status_channel, m);
  last_status_at_ = now;
  last_status_ = m;
}

void CutterNode::Tick(int64_t now) {
  const bool was_active = cutter_.active();
  Cutter::Output out = cutter_.Update(now, pose_, state_);
  if (out.cutter) Publish(runtime_.bus(), options_.command_channel, ToLcm(*out.cutter));
  if (out.drive) {
    out.drive->seq = drive_seq_++;
    Publish(runtime_.bus(), options_.drive_channel, ToLcm(*out.drive));
  }
  const CutterStatus& st = cutter_.status();
  if (was_active && !cutter_.active()) {
    if (st.state == CutterStatus::State::kDone)
      MINENAV_LOG(kInfo) << "cut " << st.task_id << ": " << st.message;
    else
      MINENAV_LOG(kWarn) << "cut " << st.task_id << ": " << st.message;
    runtime_.SetStatus(st.state == CutterStatus::State::kDone ? heartbeat_t::OK : heartbeat_t::WARN, st.message);
    PublishStatus(now);
  } else if (cutter_.active()) {
    if (st.step != last_step_) runtime_.SetStatus(heartbeat_t::OK, "cutting: " + st.step);
    if (now - last_status_at_ >= 1'000'000) PublishStatus(now);
  }
  last_step_ = st.step;
}

}  // namespace minenav
