#pragma once
// The survey's drive (waypoint_driver): the WaypointFollower through a list of scan
// stations, standing still for a while at each so the ladar can take its scans there.
// One Update per control tick, on the caller's clock; plain C++ (the node publishes).

#include <cstdint>
#include <optional>
#include <vector>

#include "common/pose2.h"
#include "common/vehicle_state.h"
#include "tracker/waypoint_follower.h"

namespace minenav {

class StationTour {
 public:
  // `dwell_s`: how long the vehicle stands still at each station after reaching it.
  StationTour(const WaypointFollowerOptions& follower, const std::vector<Pose2>& stations, double dwell_s);

  struct Step {
    DriveCommand command;  // utime and seq are the caller's to fill in
    bool arrived = false;  // this step reached a station (station() is its index)
  };
  // The command at clock time `now` (us) for the vehicle at `pose`. Without a pose yet, or
  // while dwelling, the vehicle is told to stand still.
  Step Update(int64_t now, const std::optional<Pose2>& pose);

  // Every station reached and the last dwell over.
  bool Finished(int64_t now) const { return follower_.Done() && now >= dwell_until_; }
  int station() const { return follower_.CurrentIndex(); }
  int station_count() const { return station_count_; }

 private:
  WaypointFollower follower_;
  double command_timeout_ = 0.0;  // s
  int64_t dwell_us_ = 0;
  int64_t dwell_until_ = 0;  // us; no dwell before the first arrival
  int station_count_ = 0;
};

}  // namespace minenav
