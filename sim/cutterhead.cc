#include "sim/cutterhead.h"

#include <algorithm>
#include <cmath>

#include "common/config.h"

namespace minenav {
namespace {

bool Moving(const DriveCommand& c) {
  if (c.mode == DriveCommand::Mode::kStop) return false;
  if (c.mode == DriveCommand::Mode::kTurnInPlace) return c.omega != 0.0;
  return c.v != 0.0 || c.omega != 0.0;
}

DriveCommand Stopped(const DriveCommand& c) {
  DriveCommand s = c;
  s.mode = DriveCommand::Mode::kStop;
  s.v = 0.0;
  s.omega = 0.0;
  return s;
}

}  // namespace

std::string ValidateCutterheadOptions(const CutterheadOptions& o) {
  const double values[] = {o.width, o.drum_radius, o.reach, o.max_boom_height, o.tram_height,
                           o.boom_rate, o.shear_time, o.contact_margin, o.refusal_hold};
  for (double v : values)
    if (!std::isfinite(v) || v < 0.0) return "cutterhead options must be finite and non-negative";
  if (o.width <= 0.0 || o.drum_radius <= 0.0 || o.boom_rate <= 0.0 || o.shear_time <= 0.0)
    return "cutterhead.width, drum_radius, boom_rate and shear_time must be positive";
  if (o.tram_height > o.max_boom_height) return "cutterhead.tram_height must not exceed max_boom_height";
  if (2.0 * o.drum_radius > o.reach) return "cutterhead.reach must hold the drum (reach >= 2 drum_radius)";
  return "";
}

void DeclareOptions(OptionScope s, CutterheadOptions& o) {
  s.AddDouble("width", &o.width, "m", "cutterhead drum width across the vehicle (the width of a cut)", 0.1, 20.0);
  s.AddDouble("drum_radius", &o.drum_radius, "m", "cutterhead drum radius", 0.05, 3.0);
  s.AddDouble("reach", &o.reach, "m", "from the vehicle pose to the front of the drum", 0.1, 30.0);
  s.AddDouble("max_boom_height", &o.max_boom_height, "m", "the boom's top above the floor (the seam height)", 0.1,
              10.0);
  s.AddDouble("tram_height", &o.tram_height, "m", "the boom must be at least this high to tram (6.2.1)", 0.0, 10.0);
  s.AddDouble("boom_rate", &o.boom_rate, "m/s", "boom speed when raised or set", 0.001, 10.0);
  s.AddDouble("shear_time", &o.shear_time, "s", "a shear from the top to the floor under gravity", 0.1, 600.0);
  s.AddDouble("contact_margin", &o.contact_margin, "m",
              "a wall this close ahead of the drum touches it (driving into it needs the drum turning)", 0.0, 1.0);
  s.AddDouble("refusal_hold", &o.refusal_hold, "s", "a refusal stays in CUTTER_STATE.message this long", 0.0,
              600.0);
}

Cutterhead::Cutterhead(const CutterheadOptions& options, double initial_boom_height)
    : options_(options),
      boom_(std::clamp(initial_boom_height, 0.0, options.max_boom_height)),
      boom_target_(boom_) {}

void Cutterhead::Refuse(const std::string& why, int64_t now) {
  message_ = "refused " + why;
  message_at_ = now;
}

void Cutterhead::Command(const CutterCommand& c, const Pose2& pose, int64_t now) {
  using A = CutterCommand::Action;
  if (c.action != A::kIdle) engaged_ = true;
  switch (c.action) {
    case A::kIdle:
      return;
    case A::kDrumOn:
      drum_on_ = true;
      break;
    case A::kDrumOff:
      drum_on_ = false;
      if (phase_ == CutterState::Phase::kShearing) boom_target_ = boom_;  // the drum stops: so does the shear
      if (phase_ != CutterState::Phase::kIdle) phase_ = CutterState::Phase::kIdle;
      break;
    case A::kSetBoom: {
      if (!std::isfinite(c.boom_height)) return Refuse("SET_BOOM: the height is not finite", now);
      if (phase_ == CutterState::Phase::kShearing) return Refuse("SET_BOOM: a shear is under way", now);
      boom_target_ = std::clamp(c.boom_height, 0.0, options_.max_boom_height);
      if (phase_ == CutterState::Phase::kCleaning || phase_ == CutterState::Phase::kSumping)
        phase_ = CutterState::Phase::kIdle;
      break;
    }
    case A::kSump:
      if (!drum_on_) return Refuse("SUMP: the drum is not turning", now);
      phase_ = CutterState::Phase::kSumping;
      sump_start_ = pose;
      sumped_ = 0.0;
      break;
    case A::kShear:
      if (!drum_on_) return Refuse("SHEAR: the drum is not turning", now);
      phase_ = CutterState::Phase::kShearing;
      boom_target_ = 0.0;
      break;
    case A::kStop:
      drum_on_ = false;
      boom_target_ = boom_;
      phase_ = CutterState::Phase::kIdle;
      break;
  }
  message_.clear();
}

std::vector<Eigen::Vector2d> Cutterhead::DrumArea(const Pose2& pose, double behind) const {
  const double x1 = options_.reach, x0 = options_.reach - 2.0 * options_.drum_radius - std::max(0.0, behind);
  const double h = options_.width / 2.0;
  return {pose * Eigen::Vector2d(x0, -h), pose * Eigen::Vector2d(x1, -h), pose * Eigen::Vector2d(x1, h),
          pose * Eigen::Vector2d(x0, h)};
}

bool Cutterhead::InContact(const Pose2& pose, const World& world) const {
  // The strip just ahead of the drum's front, a little narrower than the drum (the ribs of
  // its own cut run along its sides).
  const double x0 = options_.reach - 1e-3, x1 = options_.reach + options_.contact_margin;
  const double h = options_.width / 2.0 - 0.05;
  const Eigen::Vector2d c[4] = {pose * Eigen::Vector2d(x0, -h), pose * Eigen::Vector2d(x1, -h),
                                pose * Eigen::Vector2d(x1, h), pose * Eigen::Vector2d(x0, h)};
  const Eigen::Vector2d inside = pose * Eigen::Vector2d((x0 + x1) / 2.0, 0.0);
  const Eigen::Vector2d dir(std::cos(pose.theta), std::sin(pose.theta));
  for (const Segment& s : world.Segments()) {
    for (int k = 0; k < 4; ++k)
      if (SegmentIntersection(s, Segment(c[k], c[(k + 1) % 4]))) return true;
    // Wholly inside the strip: an end point within it.
    const Eigen::Vector2d d = s.a - inside;
    const double along = d.dot(dir), across = std::abs(d.x() * dir.y() - d.y() * dir.x());
    if (std::abs(along) <= (x1 - x0) / 2.0 && across <= h) return true;
  }
  return false;
}

DriveCommand Cutterhead::FilterDrive(const DriveCommand& c, const Pose2& pose, const World& world, int64_t now) {
  if (!Moving(c)) return c;
  if (phase_ == CutterState::Phase::kShearing) {
    Refuse("DRIVE: the tracks stay stopped while shearing", now);
    return Stopped(c);
  }
  const bool backing_with_drum = drum_on_ && c.mode == DriveCommand::Mode::kVelocity && c.v < 0.0;
  if (boom_ < options_.tram_height && !backing_with_drum) {
    Refuse("DRIVE: no tramming with the head down (boom " + CutterNumber(boom_) + " m, below " +
               CutterNumber(options_.tram_height) + " m)",
           now);
    return Stopped(c);
  }
  if (engaged_ && !drum_on_ && c.mode == DriveCommand::Mode::kVelocity && c.v > 0.0 && InContact(pose, world)) {
    Refuse("DRIVE: no sump without the drum turning (the drum touches the face)", now);
    return Stopped(c);
  }
  return c;
}

bool Cutterhead::Step(double dt, const Pose2& pose, World* world, int64_t now) {
  if (!message_.empty() && static_cast<double>(now - message_at_) * 1e-6 > options_.refusal_hold) message_.clear();
  if (phase_ == CutterState::Phase::kSumping && sump_start_) {
    const Eigen::Vector2d dir(std::cos(sump_start_->theta), std::sin(sump_start_->theta));
    sumped_ = std::max(sumped_, (pose.translation() - sump_start_->translation()).dot(dir));
  }
  const double rate =
      phase_ == CutterState::Phase::kShearing ? options_.max_boom_height / options_.shear_time : options_.boom_rate;
  const double step = rate * std::max(0.0, dt);
  if (boom_ < boom_target_) boom_ = std::min(boom_target_, boom_ + step);
  if (boom_ > boom_target_) boom_ = std::max(boom_target_, boom_ - step);
  if (phase_ != CutterState::Phase::kShearing || boom_ > 0.0) return false;
  // The shear reached the floor: the swept plan area is free space now.
  phase_ = CutterState::Phase::kCleaning;
  const double behind = sump_start_ ? sumped_ : 0.0;
  sump_start_.reset();
  if (world == nullptr) return false;
  const double x0 = options_.reach - 2.0 * options_.drum_radius - behind;
  coal_removed_ += SolidArea(*world, pose, x0, options_.reach, options_.width / 2.0, pose.translation());
  const CutResult cut = world->CutRegion(DrumArea(pose, behind), pose.translation());
  return !cut.removed_ids.empty() || !cut.added_ids.empty();
}

CutterState Cutterhead::State(int64_t now) const {
  CutterState s;
  s.utime = now;
  s.phase = phase_;
  s.drum_on = drum_on_;
  s.boom_height = boom_;
  s.sumped_depth = sumped_;
  s.coal_removed = coal_removed_;
  s.message = message_;
  return s;
}

double SolidArea(const World& world, const Pose2& frame, double x0, double x1, double half_width,
                 const Eigen::Vector2d& free_point, double step_x, double step_y) {
  if (!(step_x > 0.0) || !(step_y > 0.0) || !(x1 > x0) || !(half_width > 0.0)) return 0.0;
  const int nx = std::max(1, static_cast<int>(std::ceil((x1 - x0) / step_x)));
  const int ny = std::max(1, static_cast<int>(std::ceil(2.0 * half_width / step_y)));
  const double dx = (x1 - x0) / nx, dy = 2.0 * half_width / ny;
  int solid = 0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const Eigen::Vector2d p = frame * Eigen::Vector2d(x0 + (i + 0.5) * dx, -half_width + (j + 0.5) * dy);
      if (!world.SameSpace(p, free_point)) ++solid;
    }
  return solid * dx * dy;
}

}  // namespace minenav
