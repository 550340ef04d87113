#include "tracker/station_tour.h"

namespace minenav {
namespace {

std::vector<Waypoint> StopAtEach(const std::vector<Pose2>& stations) {
  std::vector<Waypoint> out;
  for (const Pose2& pose : stations) out.push_back({pose, true});
  return out;
}

}  // namespace

StationTour::StationTour(const WaypointFollowerOptions& follower, const std::vector<Pose2>& stations, double dwell_s)
    : follower_(follower, StopAtEach(stations)),
      command_timeout_(follower.command_timeout),
      dwell_us_(static_cast<int64_t>(dwell_s * 1e6)),
      station_count_(static_cast<int>(stations.size())) {}

StationTour::Step StationTour::Update(int64_t now, const std::optional<Pose2>& pose) {
  Step step;
  step.command.timeout = command_timeout_;  // a stop, unless the follower says otherwise
  if (!pose || now < dwell_until_) return step;
  step.command = follower_.Update(*pose);
  step.arrived = follower_.JustArrived();
  if (step.arrived) dwell_until_ = now + dwell_us_;
  return step;
}

}  // namespace minenav
