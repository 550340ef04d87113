#include "sim/skid_steer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "common/config.h"

namespace minenav {

namespace {

double Sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

// One interval of constant acceleration: q(t) = q0 + a t for t in [0, duration].
struct Phase {
  double q0 = 0.0;
  double a = 0.0;
  double duration = 0.0;
  double Integral() const { return q0 * duration + 0.5 * a * duration * duration; }
};

// Phases taking q from q0 towards qt within time T: |q| rises at a_up, falls at a_down
// (0 = jumps at once); a sign change passes through 0. Updates q0 to where it ends.
std::vector<Phase> Ramp(double* q0, double qt, double a_up, double a_down, double T) {
  std::vector<Phase> phases;
  double q = *q0;
  for (int guard = 0; guard < 4 && T > 0.0 && q != qt; ++guard) {
    double next;
    double rate;
    if (q != 0.0 && (qt * q < 0.0 || qt == 0.0)) {
      next = 0.0;  // slow down to a stop first
      rate = a_down;
    } else if (std::abs(qt) < std::abs(q)) {
      next = qt;
      rate = a_down;
    } else {
      next = qt;
      rate = a_up;
    }
    if (rate <= 0.0) {
      q = next;
      continue;
    }
    const double t = std::abs(next - q) / rate;
    const double a = Sign(next - q) * rate;
    if (t >= T) {
      phases.push_back({q, a, T});
      q += a * T;
      T = 0.0;
    } else {
      phases.push_back({q, a, t});
      q = next;
      T -= t;
    }
  }
  if (T > 0.0) phases.push_back({q, 0.0, T});
  *q0 = q;
  return phases;
}

}  // namespace

Pose2 ArcDelta(double s, double curvature) {
  const double phi = s * curvature;
  double sinc, versine;  // sin(phi)/phi and (1 - cos(phi))/phi
  if (std::abs(phi) < 1e-4) {
    const double p2 = phi * phi;
    sinc = 1.0 - p2 / 6.0 + p2 * p2 / 120.0;
    versine = phi / 2.0 - phi * p2 / 24.0;
  } else {
    sinc = std::sin(phi) / phi;
    versine = (1.0 - std::cos(phi)) / phi;
  }
  return Pose2(s * sinc, s * versine, NormalizeAngle(phi));
}

std::string ValidateSkidSteerOptions(const SkidSteerOptions& o) {
  std::ostringstream why;
  auto positive = [&](const char* name, double v) {
    if (why.tellp() == 0 && !(v > 0.0 && std::isfinite(v))) why << name << " must be > 0 (got " << v << ")";
  };
  auto non_negative = [&](const char* name, double v) {
    if (why.tellp() == 0 && !(v >= 0.0 && std::isfinite(v))) why << name << " must be >= 0 (got " << v << ")";
  };
  positive("max_forward_speed", o.max_forward_speed);
  non_negative("max_reverse_speed", o.max_reverse_speed);
  positive("turn_radius", o.turn_radius);
  positive("max_turn_in_place_rate", o.max_turn_in_place_rate);
  non_negative("max_acceleration", o.max_acceleration);
  non_negative("max_deceleration", o.max_deceleration);
  non_negative("max_yaw_acceleration", o.max_yaw_acceleration);
  non_negative("min_speed", o.min_speed);
  positive("command_timeout", o.command_timeout);
  return why.str();
}

ClampedCommand ClampDriveCommand(const DriveCommand& command, const SkidSteerOptions& o) {
  ClampedCommand c;
  const double v = command.v, w = command.omega;
  if (!std::isfinite(v) || !std::isfinite(w)) return c;
  auto in_place = [&](double rate) {
    if (rate == 0.0) return c;
    c.motion = SkidSteerMotion::kTurnInPlace;
    c.yaw_rate = std::clamp(rate, -o.max_turn_in_place_rate, o.max_turn_in_place_rate);
    return c;
  };
  switch (command.mode) {
    case DriveCommand::Mode::kStop:
      return c;
    case DriveCommand::Mode::kTurnInPlace:
      return in_place(w);
    case DriveCommand::Mode::kVelocity:
      break;
  }
  if (std::abs(v) < o.min_speed) return in_place(w);
  const double k = w / v;
  const double k_arc = 1.0 / o.turn_radius;
  if (std::abs(k) > 2.0 * k_arc) return in_place(w);
  c.speed = std::clamp(v, -o.max_reverse_speed, o.max_forward_speed);
  if (c.speed == 0.0) return ClampedCommand{};
  if (std::abs(k) < 0.5 * k_arc) {
    c.motion = SkidSteerMotion::kStraight;
    c.curvature = 0.0;
  } else {
    c.motion = SkidSteerMotion::kArc;
    c.curvature = Sign(k) * k_arc;
  }
  return c;
}

SkidSteerVehicle::SkidSteerVehicle(const SkidSteerOptions& options, const Pose2& initial_pose)
    : options_(options), pose_(initial_pose) {}

SkidSteerMotion SkidSteerVehicle::motion() const {
  if (turning_in_place_) return yaw_rate_ != 0.0 ? SkidSteerMotion::kTurnInPlace : SkidSteerMotion::kStopped;
  if (speed_ == 0.0) return SkidSteerMotion::kStopped;
  return curvature_ == 0.0 ? SkidSteerMotion::kStraight : SkidSteerMotion::kArc;
}

MotionIncrement SkidSteerVehicle::Step(double dt, const DriveCommand& command, int64_t now_utime) {
  // The vehicle's own limit caps whatever the command asks for (drive_command_t: "whichever
  // is shorter"): a lost link must stop the vehicle even after a command claiming to stay
  // valid for ever.
  const bool has_own_timeout = command.timeout > 0.0 && std::isfinite(command.timeout);
  const double timeout =
      has_own_timeout ? std::min(command.timeout, options_.command_timeout) : options_.command_timeout;
  const double age = 1e-6 * static_cast<double>(now_utime - command.utime);
  stale_ = age > timeout;
  return Advance(dt, stale_ ? ClampedCommand{} : ClampDriveCommand(command, options_));
}

MotionIncrement SkidSteerVehicle::StepWithoutCommand(double dt) {
  stale_ = true;
  return Advance(dt, ClampedCommand{});
}

MotionIncrement SkidSteerVehicle::Advance(double dt, const ClampedCommand& target) {
  MotionIncrement inc;
  inc.dt = dt;
  if (!(dt > 0.0)) return inc;
  double remaining = dt;
  auto drive = [&](const std::vector<Phase>& phases) {
    for (const Phase& p : phases) {
      const double s = p.Integral();
      const Pose2 d = ArcDelta(s, curvature_);
      inc.delta = inc.delta * d;
      inc.distance += s;
      inc.rotation += s * curvature_;
      remaining -= p.duration;
    }
  };
  auto spin = [&](const std::vector<Phase>& phases) {
    for (const Phase& p : phases) {
      const double r = p.Integral();
      inc.delta = inc.delta * Pose2(0.0, 0.0, NormalizeAngle(r));
      inc.rotation += r;
      remaining -= p.duration;
    }
  };
  const double a_up = options_.max_acceleration, a_down = options_.max_deceleration;
  const double yaw_acc = options_.max_yaw_acceleration;
  for (int guard = 0; guard < 4 && remaining > 1e-12; ++guard) {
    const bool want_spin = target.motion == SkidSteerMotion::kTurnInPlace;
    const bool want_drive = target.motion == SkidSteerMotion::kStraight || target.motion == SkidSteerMotion::kArc;
    if (want_spin && !turning_in_place_ && speed_ != 0.0) {
      // Tracks must stop before they counter-rotate.
      if (a_down > 0.0)
        drive(Ramp(&speed_, 0.0, a_up, a_down, std::min(remaining, std::abs(speed_) / a_down)));
      else
        speed_ = 0.0;
    } else if (want_spin) {
      turning_in_place_ = true;
      speed_ = 0.0;
      spin(Ramp(&yaw_rate_, target.yaw_rate, yaw_acc, yaw_acc, remaining));
    } else if (want_drive && turning_in_place_ && yaw_rate_ != 0.0) {
      if (yaw_acc > 0.0)
        spin(Ramp(&yaw_rate_, 0.0, yaw_acc, yaw_acc, std::min(remaining, std::abs(yaw_rate_) / yaw_acc)));
      else
        yaw_rate_ = 0.0;
    } else if (want_drive) {
      turning_in_place_ = false;
      yaw_rate_ = 0.0;
      curvature_ = target.curvature;
      drive(Ramp(&speed_, target.speed, a_up, a_down, remaining));
    } else if (turning_in_place_) {  // stop
      spin(Ramp(&yaw_rate_, 0.0, yaw_acc, yaw_acc, remaining));
    } else {
      drive(Ramp(&speed_, 0.0, a_up, a_down, remaining));
    }
    if (yaw_rate_ == 0.0 && turning_in_place_ && !want_spin) turning_in_place_ = false;
  }
  pose_ = pose_ * inc.delta;
  return inc;
}

void DeclareOptions(OptionScope scope, SkidSteerOptions& o) {
  scope.AddDouble("max_forward_speed", &o.max_forward_speed, "m/s",
                  "forward speed limit (0.076 m/s: the miner's cruise, about three inches per second, 6.4.2)", 0.0,
                  10.0);
  scope.AddDouble("max_reverse_speed", &o.max_reverse_speed, "m/s", "reverse speed limit, magnitude (0.076 m/s)",
                  0.0, 10.0);
  scope.AddDouble("turn_radius", &o.turn_radius, "m",
                  "the one turning radius besides turning in place: the miner has only one (4 m)", 0.01, 1000.0);
  scope.AddDouble("max_turn_in_place_rate", &o.max_turn_in_place_rate, "rad/s",
                  "yaw rate limit turning in place (0.05 rad/s)", 0.0, 10.0);
  scope.AddDouble("max_acceleration", &o.max_acceleration, "m/s^2",
                  "raising |speed|; 0 = instantaneous (0.05 m/s^2: cruise in 1.5 s)", 0.0, 100.0);
  scope.AddDouble("max_deceleration", &o.max_deceleration, "m/s^2",
                  "lowering |speed|; 0 = instantaneous (0.1 m/s^2: stops within 3 cm from cruise)", 0.0, 100.0);
  scope.AddDouble("max_yaw_acceleration", &o.max_yaw_acceleration, "rad/s^2",
                  "turning in place; 0 = instantaneous (0.05 rad/s^2)", 0.0, 100.0);
  scope.AddDouble("min_speed", &o.min_speed, "m/s",
                  "below this a (v, omega) command turns in place or stops (1 mm/s: a curvature from a smaller "
                  "speed is noise)",
                  0.0, 1.0);
  scope.AddDouble("command_timeout", &o.command_timeout, "s",
                  "the vehicle's own stale limit: a command older than this or its own timeout, whichever is "
                  "shorter, is stale and the vehicle stops, so no sender can keep it driving by one command (0.5 s)",
                  0.001, 3600.0);
}

}  // namespace minenav
