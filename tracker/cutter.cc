#include "tracker/cutter.h"

#include <cmath>
#include <utility>

#include <Eigen/Eigenvalues>

#include "common/angle.h"
#include "common/config.h"
#include "common/odometry_chain.h"
#include "common/pose_at_time.h"

namespace minenav {
namespace {

double Seconds(int64_t later, int64_t earlier) { return static_cast<double>(later - earlier) * 1e-6; }

constexpr int64_t kOdometryKeepUs = 30'000'000;  // odometry kept for predictions
constexpr int64_t kOdometryGapUs = 250'000;      // a pose's time at most this far from odometry

}  // namespace

std::string ValidateCutterOptions(const CutterOptions& o) {
  const double positive[] = {o.reach, o.width, o.boom_top, o.max_face_distance, o.turn_rate, o.approach_speed,
                             o.sump_speed, o.sump_step, o.cusp_speed, o.max_pose_age, o.stall_time,
                             o.state_timeout, o.resend_period, o.command_timeout};
  for (double v : positive)
    if (!std::isfinite(v) || v <= 0.0) return "cutter: reach, width, speeds, distances and times must be positive";
  const double non_negative[] = {o.boom_tolerance, o.max_square_angle, o.heading_tolerance, o.standoff,
                                 o.depth_tolerance, o.cusp_distance, o.stall_distance, o.withdraw_gap};
  for (double v : non_negative)
    if (!std::isfinite(v) || v < 0.0) return "cutter: tolerances and margins must be finite and non-negative";
  if (o.max_cycles < 1) return "cutter: max_cycles must be at least 1";
  return "";
}

void DeclareOptions(OptionScope s, CutterOptions& o) {
  s.AddDouble("reach", &o.reach, "m", "vehicle pose to the front of the drum (the vehicle's cutterhead.reach)", 0.1,
              30.0);
  s.AddDouble("width", &o.width, "m", "drum width: the face is looked for across it", 0.1, 20.0);
  s.AddDouble("boom_top", &o.boom_top, "m", "the boom is raised to this height to tram and to sump", 0.1, 10.0);
  s.AddDouble("boom_tolerance", &o.boom_tolerance, "m", "the boom is at a height within this", 0.0, 1.0);
  s.AddDouble("max_face_distance", &o.max_face_distance, "m",
              "a face farther than this ahead of the drum is out of reach (the cut is refused)", 0.1, 50.0);
  s.AddDouble("max_square_angle", &o.max_square_angle, "rad",
              "the face's normal at most this far off the heading (else refused)", 0.0, 1.6);
  s.AddDouble("heading_tolerance", &o.heading_tolerance, "rad", "squared up to the face within this", 0.0, 0.5);
  s.AddDouble("turn_rate", &o.turn_rate, "rad/s", "turning in place to square up", 0.001, 1.0);
  s.AddDouble("approach_speed", &o.approach_speed, "m/s", "tramming to the face", 0.001, 1.0);
  s.AddDouble("standoff", &o.standoff, "m", "drum front to face when the drum starts", 0.0, 1.0);
  s.AddDouble("sump_speed", &o.sump_speed, "m/s", "driving into the face with the drum turning", 0.001, 1.0);
  s.AddDouble("sump_step", &o.sump_step, "m", "face advance of one sump-shear cycle", 0.01, 5.0);
  s.AddDouble("depth_tolerance", &o.depth_tolerance, "m", "done when the confirmed depth is within this of the target",
              0.0, 1.0);
  s.AddDouble("cusp_distance", &o.cusp_distance, "m", "backed up with the drum turning to remove the cusp", 0.0,
              5.0);
  s.AddDouble("cusp_speed", &o.cusp_speed, "m/s", "backing up over the cusp", 0.001, 1.0);
  s.AddDouble("withdraw_gap", &o.withdraw_gap, "m",
              "at the end of a cut the miner backs out (at approach_speed) until the drum's front is this far before "
              "the face the cut started from; 0 = it stays in the cut",
              0.0, 10.0);
  s.AddDouble("max_pose_age", &o.max_pose_age, "s",
              "a pose estimate older than this while the tracks move stops the cut", 0.1, 600.0);
  s.AddDouble("stall_time", &o.stall_time, "s", "sumping this long with less than stall_distance advance: stall",
              0.1, 3600.0);
  s.AddDouble("stall_distance", &o.stall_distance, "m", "the advance a sump must make within stall_time", 0.0, 5.0);
  s.AddDouble("state_timeout", &o.state_timeout, "s", "no CUTTER_STATE for this long stops the cut", 0.1, 600.0);
  s.AddDouble("resend_period", &o.resend_period, "s", "repeat an unacknowledged cutter command this often", 0.05,
              60.0);
  s.AddDouble("command_timeout", &o.command_timeout, "s", "validity of each DRIVE_COMMAND (two control periods: stopped within 200 ms of a missing one)", 0.01, 10.0);
  s.AddInt("max_cycles", &o.max_cycles, "sump-shear cycles at most per cut", 1, 1000);
}

std::optional<Segment> FindFace(const std::vector<Segment>& map, const Pose2& pose, const CutterOptions& o) {
  constexpr int kRays = 9;
  const double max_range = o.reach + o.max_face_distance;
  std::vector<Eigen::Vector2d> hits;
  for (int k = 0; k < kRays; ++k) {
    const double y = -o.width / 2.0 + o.width * k / (kRays - 1);
    const Eigen::Vector2d origin = pose * Eigen::Vector2d(0.0, 0.95 * y);
    const auto hit = CastRay(origin, pose.theta, map, max_range);
    if (!hit || hit->range < o.reach - 0.5) continue;
    hits.push_back(origin + hit->range * Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta)));
  }
  if (hits.size() < 3) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : hits) mean += p;
  mean /= static_cast<double>(hits.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : hits) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d dir = eig.eigenvectors().col(1);
  double lo = 0.0, hi = 0.0;
  for (const auto& p : hits) {
    lo = std::min(lo, (p - mean).dot(dir));
    hi = std::max(hi, (p - mean).dot(dir));
  }
  if (hi - lo <= 0.0) return std::nullopt;
  return Segment(mean + lo * dir, mean + hi * dir);
}

Cutter::Cutter(CutterOptions options) : options_(std::move(options)) {}

double Cutter::DepthAt(const Pose2& pose) const {
  return (pose * Eigen::Vector2d(options_.reach, 0.0)).dot(normal_) - face_offset_;
}

void Cutter::AddOdometry(const OdometryReading& r) {
  if (!odometry_.empty() && r.utime <= odometry_.back().utime) return;  // out of order: dropped
  odometry_.push_back(r);
  while (!odometry_.empty() && odometry_.back().utime - odometry_.front().utime > kOdometryKeepUs)
    odometry_.pop_front();
}

std::optional<Pose2> Cutter::Predict(const StampedPose& pose) const {
  if (odometry_.empty()) return pose.pose;
  const std::optional<Pose2> then = PoseAtTime(odometry_, pose.utime, kOdometryGapUs);
  if (!then || odometry_.back().utime < pose.utime) return pose.pose;
  OdometryChain chain;
  chain.Trust(pose.pose, *then);
  return chain.Predict(odometry_.back().pose);
}

const char* Cutter::StepName(Step s) {
  switch (s) {
    case Step::kIdle: return "idle";
    case Step::kRaiseBoom: return "raising the boom";
    case Step::kSquare: return "squaring up";
    case Step::kApproach: return "approaching the face";
    case Step::kDrumOn: return "starting the drum";
    case Step::kSump: return "sumping";
    case Step::kShear: return "shearing";
    case Step::kCusp: return "removing the cusp";
    case Step::kRaise: return "raising the boom";
    case Step::kFinish: return "stopping the drum";
    case Step::kWithdraw: return "backing out of the cut";
    case Step::kEnded: return "ended";
  }
  return "?";
}

std::string Cutter::Start(const CutTask& task, const std::optional<StampedPose>& pose, const std::vector<Segment>& map,
                          int64_t now) {
  status_ = CutterStatus{};
  status_.task_id = task.id;
  status_.target = task.depth;
  auto refuse = [&](const std::string& why) {
    status_.state = CutterStatus::State::kFailed;
    status_.message = why;
    step_ = Step::kIdle;
    return why;
  };
  if (!std::isfinite(task.depth) || task.depth <= 0.0) return refuse("refused: the depth of cut must be positive");
  if (!pose) return refuse("refused: no pose estimate yet");
  if (Seconds(now, pose->utime) > options_.max_pose_age)
    return refuse("refused: the pose estimate is " + CutterNumber(Seconds(now, pose->utime), 1) + " s old (limit " +
                  CutterNumber(options_.max_pose_age, 1) + " s)");
  const Pose2 p = Predict(*pose).value_or(pose->pose);
  std::optional<Segment> face = task.face;
  if (!face) face = FindFace(map, p, options_);
  if (!face)
    return refuse("refused: no face in reach: nothing in the map within " + CutterNumber(options_.max_face_distance, 1) +
                  " m ahead of the cutterhead");
  face_ = *face;
  const Eigen::Vector2d d = face_.direction().normalized();
  normal_ = Eigen::Vector2d(-d.y(), d.x());
  if ((face_.a - p.translation()).dot(normal_) < 0.0) normal_ = -normal_;
  face_offset_ = face_.a.dot(normal_);
  heading_ = std::atan2(normal_.y(), normal_.x());
  const double off = std::abs(NormalizeAngle(heading_ - p.theta));
  const double gap = face_offset_ - (p.translation().dot(normal_) + options_.reach);
  // The face must lie ahead of the drum, across part of its width at least: a whole face
  // (a box cut) or the part of one left beside a cut (a slab cut, thesis 6.2.1), measured
  // across the face's normal from the vehicle's centre.
  const Eigen::Vector2d across(-normal_.y(), normal_.x());
  const double a = (face_.a - p.translation()).dot(across), b = (face_.b - p.translation()).dot(across);
  if (std::min(std::max(a, b), options_.width / 2.0) <= std::max(std::min(a, b), -options_.width / 2.0))
    return refuse("refused: no face in reach: the face line does not lie ahead of the vehicle");
  if (gap > options_.max_face_distance)
    return refuse("refused: no face in reach: the face is " + CutterNumber(gap) + " m ahead of the cutterhead (reach " +
                  CutterNumber(options_.max_face_distance) + " m)");
  if (gap < -0.5) return refuse("refused: the cutterhead is already " + CutterNumber(-gap) + " m past the face");
  if (off > options_.max_square_angle)
    return refuse("refused: the face is " + CutterNumber(RadToDeg(off), 1) + " deg off the heading (at most " +
                  CutterNumber(RadToDeg(options_.max_square_angle), 1) + " deg)");
  status_.state = CutterStatus::State::kActive;
  status_.message = "cutting " + CutterNumber(task.depth) + " m";
  started_ = now;
  stop_sent_ = false;
  confirmed_.reset();
  stall_ref_.reset();
  cusp_start_.reset();
  Enter(Step::kRaiseBoom, now);
  return "";
}

void Cutter::Enter(Step step, int64_t now) {
  step_ = step;
  step_since_ = now;
  sent_at_.reset();
  acknowledged_ = false;
  status_.step = StepName(step);
}

void Cutter::Fail(const std::string& why) {
  status_.state = CutterStatus::State::kFailed;
  status_.message = why;
  step_ = Step::kEnded;
  status_.step = StepName(step_);
}

void Cutter::Cancel(const std::string& why) {
  if (!active()) return;
  Fail(why);
  status_.state = CutterStatus::State::kCanceled;
}

std::optional<CutterCommand> Cutter::Send(CutterCommand::Action action, double boom, int64_t now) {
  if (acknowledged_) return std::nullopt;
  if (sent_at_ && Seconds(now, *sent_at_) < options_.resend_period) return std::nullopt;
  sent_at_ = now;
  CutterCommand c;
  c.utime = now;
  c.seq = seq_++;
  c.action = action;
  c.boom_height = boom;
  c.face = face_;
  return c;
}

DriveCommand Cutter::Drive(DriveCommand::Mode mode, double v, double omega, int64_t now) const {
  DriveCommand c;
  c.utime = now;
  c.mode = mode;
  c.v = v;
  c.omega = omega;
  c.timeout = options_.command_timeout;
  return c;
}

Cutter::Output Cutter::Update(int64_t now, const std::optional<StampedPose>& pose,
                              const std::optional<CutterState>& state) {
  using A = CutterCommand::Action;
  using M = DriveCommand::Mode;
  Output out;
  if (step_ == Step::kEnded) {
    // The last word after a cut ends: the tracks stop and the drum stops if it failed.
    if (!stop_sent_) {
      stop_sent_ = true;
      out.drive = Drive(M::kStop, 0, 0, now);
      if (status_.state != CutterStatus::State::kDone) {
        CutterCommand c;
        c.utime = now;
        c.seq = seq_++;
        c.action = A::kStop;
        out.cutter = c;
      }
    }
    return out;
  }
  if (!active()) return out;
  out.drive = Drive(M::kStop, 0, 0, now);

  // Safety first: the appendages' state, refusals, the pose's age while moving.
  if (!state || Seconds(now, state->utime) > options_.state_timeout) {
    if (Seconds(now, started_) > options_.state_timeout) {
      Fail("stopped: no CUTTER_STATE for " + CutterNumber(options_.state_timeout, 1) + " s");
      return Update(now, pose, state);
    }
    return out;
  }
  if (state->message.rfind("refused", 0) == 0 && state->utime > started_) {
    Fail("stopped: the vehicle " + state->message);
    return Update(now, pose, state);
  }
  const bool moving_step = step_ == Step::kSquare || step_ == Step::kApproach || step_ == Step::kSump ||
                           step_ == Step::kCusp || step_ == Step::kWithdraw;
  if (moving_step) {
    const double age = pose ? Seconds(now, pose->utime) : INFINITY;
    if (age > options_.max_pose_age) {
      Fail("stopped: the pose estimate is " + (pose ? CutterNumber(age, 1) + " s" : std::string("missing")) + " old while " +
           StepName(step_) + " (limit " + CutterNumber(options_.max_pose_age, 1) + " s)");
      return Update(now, pose, state);
    }
  }
  const std::optional<Pose2> predicted = pose ? Predict(*pose) : std::nullopt;

  switch (step_) {
    case Step::kRaiseBoom:
      out.cutter = Send(A::kSetBoom, options_.boom_top, now);
      if (state->utime > step_since_ && std::abs(state->boom_height - options_.boom_top) <= options_.boom_tolerance)
        Enter(Step::kSquare, now);
      break;
    case Step::kSquare: {
      const double err = NormalizeAngle(heading_ - predicted->theta);
      if (std::abs(err) <= options_.heading_tolerance) {
        Enter(Step::kApproach, now);
        break;
      }
      const double rate = std::clamp(0.5 * std::abs(err), 0.003, options_.turn_rate);
      out.drive = Drive(M::kTurnInPlace, 0.0, std::copysign(rate, err), now);
      break;
    }
    case Step::kApproach: {
      const double err = NormalizeAngle(heading_ - predicted->theta);
      if (std::abs(err) > 3.0 * options_.heading_tolerance + 0.005) {
        Enter(Step::kSquare, now);
        break;
      }
      const double gap = -DepthAt(*predicted) - options_.standoff;
      if (gap <= 0.0) {
        Enter(Step::kDrumOn, now);
        break;
      }
      out.drive = Drive(M::kVelocity, std::clamp(0.5 * gap, 0.005, options_.approach_speed), 0.0, now);
      break;
    }
    case Step::kDrumOn:
      out.cutter = Send(A::kDrumOn, 0, now);
      if (state->drum_on && state->utime > step_since_) {
        cycle_target_ = std::min(status_.depth + options_.sump_step, status_.target);
        Enter(Step::kSump, now);
      }
      break;
    case Step::kSump: {
      if (!acknowledged_) {
        out.cutter = Send(A::kSump, 0, now);
        if (state->phase == CutterState::Phase::kSumping && sent_at_ && state->utime > *sent_at_) {
          acknowledged_ = true;
          stall_ref_ = *pose;
        }
        break;
      }
      if (DepthAt(*predicted) >= cycle_target_) {
        Enter(Step::kShear, now);
        confirmed_.reset();
        down_since_.reset();
        break;
      }
      if (TranslationDistance(pose->pose, stall_ref_->pose) > options_.stall_distance) {
        stall_ref_ = *pose;
        stall_ref_->utime = now;
      } else if (Seconds(now, stall_ref_->utime) > options_.stall_time) {
        Fail("stopped: the face does not advance: " +
             CutterNumber(TranslationDistance(pose->pose, stall_ref_->pose)) + " m in " + CutterNumber(options_.stall_time, 1) +
             " s of sumping");
        return Update(now, pose, state);
      }
      out.drive = Drive(M::kVelocity, options_.sump_speed, 0.0, now);
      break;
    }
    case Step::kShear: {
      out.cutter = Send(A::kShear, 0, now);
      if (state->phase == CutterState::Phase::kShearing && sent_at_ && state->utime > *sent_at_) acknowledged_ = true;
      // Perception confirms the depth: an estimate of the scan taken after the tracks stopped.
      if (pose && Seconds(pose->utime, step_since_) > 0.5) confirmed_ = DepthAt(pose->pose);
      const bool down = state->phase == CutterState::Phase::kCleaning && state->boom_height <= options_.boom_tolerance;
      if (down && confirmed_) {
        status_.depth = std::max(status_.depth, *confirmed_);
        ++status_.cycles;
        cusp_start_ = pose->pose;
        Enter(Step::kCusp, now);
      } else if (down) {
        // A scan taken after the stop may still be on its way: wait for it as long as a
        // pose may be old, and a second more.
        if (!down_since_) down_since_ = now;
        if (Seconds(now, *down_since_) > options_.max_pose_age + 1.0) {
          Fail("stopped: no pose estimate confirmed the depth after the shear");
          return Update(now, pose, state);
        }
      }
      break;
    }
    case Step::kCusp: {
      const double backed = (cusp_start_->translation() - predicted->translation()).dot(normal_);
      if (backed >= options_.cusp_distance) {
        Enter(Step::kRaise, now);
        break;
      }
      out.drive = Drive(M::kVelocity, -options_.cusp_speed, 0.0, now);
      break;
    }
    case Step::kRaise:
      out.cutter = Send(A::kSetBoom, options_.boom_top, now);
      if (state->utime > step_since_ && std::abs(state->boom_height - options_.boom_top) <= options_.boom_tolerance) {
        if (status_.depth >= status_.target - options_.depth_tolerance) {
          Enter(Step::kFinish, now);
        } else if (status_.cycles >= options_.max_cycles) {
          Fail("stopped: " + std::to_string(status_.cycles) + " cycles reached only " + CutterNumber(status_.depth) +
               " m of " + CutterNumber(status_.target) + " m");
          return Update(now, pose, state);
        } else {
          cycle_target_ = std::min(status_.depth + options_.sump_step, status_.target);
          Enter(Step::kSump, now);
        }
      }
      break;
    case Step::kFinish:
      out.cutter = Send(A::kDrumOff, 0, now);
      if (!state->drum_on && state->utime > step_since_) Enter(Step::kWithdraw, now);
      break;
    case Step::kWithdraw: {
      // The drum's front `withdraw_gap` before the face line the cut started from; a cut
      // that ends nearer (withdraw_gap 0, or a shallow one) ends where it is.
      const double out_by = -DepthAt(*predicted) - options_.withdraw_gap;
      if (out_by < 0.0) {
        out.drive = Drive(M::kVelocity, -std::clamp(-0.5 * out_by, 0.005, options_.approach_speed), 0.0, now);
        break;
      }
      status_.state = CutterStatus::State::kDone;
      status_.message = "cut " + CutterNumber(status_.depth) + " m deep (target " + CutterNumber(status_.target) +
                        " m) in " + std::to_string(status_.cycles) + " cycles";
      step_ = Step::kEnded;
      status_.step = StepName(step_);
      stop_sent_ = true;  // this update's STOP is the last word
      break;
    }
    case Step::kIdle:
    case Step::kEnded:
      break;
  }
  return out;
}

}  // namespace minenav
