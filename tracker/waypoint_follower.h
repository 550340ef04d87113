#pragma once
// Drives a skid-steer vehicle through a list of waypoints the simplest safe way:
// turn in place until facing the next waypoint, then drive straight at it, steering
// gently to cancel drift (thesis 6.4.2 turns in place when far off, then drives lines).
// Used by the survey demo; the full pure-pursuit path tracker builds on this later.

#include <vector>

#include "common/pose2.h"
#include "common/vehicle_state.h"

namespace minenav {

struct WaypointFollowerOptions {
  double cruise_speed = 0.076;       // m/s, forward speed on straight legs
  double turn_rate = 0.1;            // rad/s, yaw rate when turning in place
  double position_tolerance = 0.10;  // m, a waypoint counts as reached inside this radius
  double heading_tolerance = 0.05;   // rad, final heading tolerance at a waypoint
  double align_tolerance = 0.08;     // rad, heading error above which we stop and turn in place
  double steering_gain = 1.0;        // 1/s, yaw rate per rad of heading error while driving
  double command_timeout = 0.5;      // s, validity of each command sent
};

class OptionScope;
// Declares every field of WaypointFollowerOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, WaypointFollowerOptions& o);

struct Waypoint {
  Pose2 pose;
  bool stop_and_align = true;  // turn to pose.theta on arrival (a scan station)
};

class WaypointFollower {
 public:
  enum class Phase { kTurnToWaypoint, kDrive, kAlign, kArrived, kDone };

  WaypointFollower(WaypointFollowerOptions options, std::vector<Waypoint> waypoints);

  // The command for the vehicle at `pose`. Advances through waypoints as they are reached.
  DriveCommand Update(const Pose2& pose);

  // True right after arriving at a stop_and_align waypoint (for one Update call): the
  // caller may take a scan before the next call moves on.
  bool JustArrived() const { return just_arrived_; }
  bool Done() const { return phase_ == Phase::kDone; }
  int CurrentIndex() const { return index_; }
  Phase phase() const { return phase_; }

 private:
  DriveCommand Stop() const;
  DriveCommand Turn(double heading_error) const;

  WaypointFollowerOptions options_;
  std::vector<Waypoint> waypoints_;
  int index_ = 0;
  Phase phase_ = Phase::kTurnToWaypoint;
  bool just_arrived_ = false;
};

}  // namespace minenav
