#include "tracker/waypoint_follower.h"

#include <algorithm>
#include <cmath>

#include "common/config.h"

namespace minenav {

WaypointFollower::WaypointFollower(WaypointFollowerOptions options, std::vector<Waypoint> waypoints)
    : options_(options), waypoints_(std::move(waypoints)) {
  if (waypoints_.empty()) phase_ = Phase::kDone;
}

DriveCommand WaypointFollower::Stop() const {
  DriveCommand c;
  c.mode = DriveCommand::Mode::kStop;
  c.timeout = options_.command_timeout;
  return c;
}

DriveCommand WaypointFollower::Turn(double heading_error) const {
  DriveCommand c;
  c.mode = DriveCommand::Mode::kTurnInPlace;
  // Slow down near the target heading so we do not overshoot by a control period.
  const double rate = std::min(options_.turn_rate, std::abs(heading_error) * 2.0 + 0.01);
  c.omega = std::copysign(rate, heading_error);
  c.timeout = options_.command_timeout;
  return c;
}

DriveCommand WaypointFollower::Update(const Pose2& pose) {
  just_arrived_ = false;
  for (int guard = 0; guard < 4; ++guard) {  // phase changes re-evaluate at once
    if (phase_ == Phase::kDone) return Stop();
    const Waypoint& wp = waypoints_[static_cast<size_t>(index_)];
    const Eigen::Vector2d to_goal = wp.pose.translation() - pose.translation();
    const double distance = to_goal.norm();
    const double bearing_error = NormalizeAngle(std::atan2(to_goal.y(), to_goal.x()) - pose.theta);
    switch (phase_) {
      case Phase::kTurnToWaypoint:
        if (distance <= options_.position_tolerance) {
          phase_ = wp.stop_and_align ? Phase::kAlign : Phase::kArrived;
          continue;
        }
        if (std::abs(bearing_error) <= options_.align_tolerance / 2) {
          phase_ = Phase::kDrive;
          continue;
        }
        return Turn(bearing_error);
      case Phase::kDrive: {
        // Reached, or passed it (the waypoint is now behind us).
        if (distance <= options_.position_tolerance || std::abs(bearing_error) > kPi / 2) {
          phase_ = wp.stop_and_align ? Phase::kAlign : Phase::kArrived;
          continue;
        }
        if (std::abs(bearing_error) > options_.align_tolerance) {
          phase_ = Phase::kTurnToWaypoint;
          continue;
        }
        DriveCommand c;
        c.mode = DriveCommand::Mode::kVelocity;
        // Ease in over the last half metre so we stop inside the tolerance.
        c.v = std::min(options_.cruise_speed, std::max(0.02, distance));
        c.omega = options_.steering_gain * bearing_error * std::min(1.0, c.v / options_.cruise_speed);
        c.timeout = options_.command_timeout;
        return c;
      }
      case Phase::kAlign: {
        const double heading_error = NormalizeAngle(wp.pose.theta - pose.theta);
        if (std::abs(heading_error) <= options_.heading_tolerance) {
          phase_ = Phase::kArrived;
          continue;
        }
        return Turn(heading_error);
      }
      case Phase::kArrived:
        just_arrived_ = wp.stop_and_align;
        ++index_;
        phase_ = index_ >= static_cast<int>(waypoints_.size()) ? Phase::kDone : Phase::kTurnToWaypoint;
        return Stop();
      case Phase::kDone:
        return Stop();
    }
  }
  return Stop();
}

void DeclareOptions(OptionScope scope, WaypointFollowerOptions& o) {
  scope.AddDouble("cruise_speed", &o.cruise_speed, "m/s",
                  "forward speed on straight legs (0.076 m/s: the miner's cruise, three inches per second, 6.4.2)",
                  0.001, 5.0);
  scope.AddDouble("turn_rate", &o.turn_rate, "rad/s",
                  "yaw rate when turning in place, slowed near the target heading (0.1 rad/s)", 0.001, 3.0);
  scope.AddDouble("position_tolerance", &o.position_tolerance, "m",
                  "a station counts as reached inside this radius (0.1 m: well inside what a scan match corrects)",
                  0.001, 10.0);
  scope.AddDouble("heading_tolerance", &o.heading_tolerance, "rad",
                  "final heading tolerance at a station before it counts as reached (0.05 rad, 3 deg)", 0.001, 1.0);
  scope.AddDouble("align_tolerance", &o.align_tolerance, "rad",
                  "heading error above which the vehicle stops and turns in place instead of steering (0.08 rad): "
                  "the miner has one turning radius only",
                  0.001, 1.5);
  scope.AddDouble("steering_gain", &o.steering_gain, "1/s",
                  "yaw rate per rad of heading error while driving, to cancel drift gently (1)", 0.0, 100.0);
  scope.AddDouble("command_timeout", &o.command_timeout, "s",
                  "validity of each command sent: the vehicle stops when no fresh one arrives, so a few "
                  "control periods",
                  0.001, 60.0);
}

}  // namespace minenav
