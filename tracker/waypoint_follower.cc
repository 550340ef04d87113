#include "tracker/waypoint_follower.h"

#include <algorithm>
#include <cmath>

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

}  // namespace minenav
