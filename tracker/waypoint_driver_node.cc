#include "tracker/waypoint_driver_node.h"

#include <utility>

#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/odometry_t.hpp"

namespace minenav {
namespace {

constexpr int kCommandPeriods = 3;  // a command outlives this many control periods

std::vector<Pose2> Poses(const std::vector<Station>& stations) {
  std::vector<Pose2> out;
  for (const Station& s : stations) out.push_back(s.pose);
  return out;
}

}  // namespace

WaypointDriverOptions WaypointDriverDefaults(const std::vector<std::string>& args) {
  WaypointDriverOptions o;
  double rate = o.rate;
  if (const std::optional<std::string> given = PeekOption(args, "rate")) {
    try {
      rate = ParseNumber(*given, "--rate");
    } catch (const UsageError&) {
      // Parse() will say what is wrong with it.
    }
  }
  if (rate > 0.0) o.follower.command_timeout = kCommandPeriods / rate;
  return o;
}

void DeclareOptions(ConfigSchema& s, WaypointDriverOptions& o) {
  s.AddString("stations", &o.stations, "scan stations CSV (x,y,theta) to visit in order");
  s.AddChannel("odometry_channel", &o.odometry_channel, "subscribes", "odometry_t",
               "the pose steered by (dead-reckoned; it drifts)");
  s.AddChannel("drive_channel", &o.drive_channel, "publishes", "drive_command_t", "drive commands");
  s.AddDouble("rate", &o.rate, "Hz",
              "control rate; the commands stay valid for 3 periods unless follower.command_timeout is given", 1.0,
              100.0);
  s.AddDouble("dwell", &o.dwell, "s", "time to stand still at each station (for the ladar's scans)", 0.0, 600.0);
  s.AddBool("exit_when_done", &o.exit_when_done, "stop the process after the last station");
  const OptionScope follower = OptionScope(s).Nested("follower");
  DeclareOptions(follower, o.follower);
  // The flat flags of before the options nested (issue 12).
  follower.AddFlatAliases({"cruise_speed", "turn_rate", "position_tolerance", "heading_tolerance", "align_tolerance"});
}

std::vector<Station> LoadDriverStations(const WaypointDriverOptions& o) {
  if (o.stations.empty()) throw UsageError("--stations is required");
  return LoadStationsCsv(o.stations);
}

WaypointDriverNode::WaypointDriverNode(NodeRuntime& runtime, WaypointDriverOptions options,
                                       const std::vector<Station>& stations)
    : runtime_(runtime), options_(std::move(options)), tour_(options_.follower, Poses(stations), options_.dwell) {
  MINENAV_LOG(kInfo) << "driving through " << stations.size() << " stations from " << options_.stations;
  Subscribe<odometry_t>(runtime_.bus(), options_.odometry_channel,
                        [this](const odometry_t& m) { pose_ = FromLcm(m).pose; });
  runtime_.AddTimer(1.0 / options_.rate, [this](int64_t now) { Tick(now); });
}

void WaypointDriverNode::Tick(int64_t now) {
  const StationTour::Step step = tour_.Update(now, pose_);
  if (step.arrived)
    MINENAV_LOG(kInfo) << "station " << tour_.station() << "/" << tour_.station_count() << " reached at " << *pose_;
  DriveCommand c = step.command;
  c.utime = now;
  c.seq = seq_++;
  Publish(runtime_.bus(), options_.drive_channel, ToLcm(c));
  if (options_.exit_when_done && tour_.Finished(now)) {
    MINENAV_LOG(kInfo) << "all stations visited";
    runtime_.RequestStop();
  }
}

}  // namespace minenav
