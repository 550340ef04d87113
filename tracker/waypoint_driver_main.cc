// waypoint_driver: drives the vehicle through a list of stations (x,y,theta CSV) with
// the WaypointFollower, pausing at each station so the ladar can take a scan there.
// It is the survey demo's driver; the pure-pursuit path_tracker replaces it later.

#include <cstdio>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/node_runtime.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tracker/waypoint_follower.h"

namespace minenav {
namespace {

struct DriverOptions {
  std::string stations;                  // CSV x,y,theta
  std::string pose_source = "truth";     // truth | odometry
  std::string truth_channel = "SIM_TRUTH";
  std::string odometry_channel = "ODOMETRY";
  std::string drive_channel = "DRIVE_COMMAND";
  double rate = 10.0;                    // Hz, control rate
  double dwell = 0.5;                    // s to stand still at each station
  bool exit_when_done = true;
  WaypointFollowerOptions follower;
};

void Register(ConfigSchema& s, DriverOptions& o) {
  s.AddString("stations", &o.stations, "scan stations CSV (x,y,theta) to visit in order");
  s.AddString("pose_source", &o.pose_source,
              "which pose to steer by: simulator ground truth or dead-reckoned odometry",
              {"truth", "odometry"});
  s.AddChannel("truth_channel", &o.truth_channel, "subscribes", "vehicle_truth_t",
               "vehicle pose when pose_source = truth");
  s.AddChannel("odometry_channel", &o.odometry_channel, "subscribes", "odometry_t",
               "vehicle pose when pose_source = odometry");
  s.AddChannel("drive_channel", &o.drive_channel, "publishes", "drive_command_t", "drive commands");
  s.AddDouble("rate", &o.rate, "Hz", "control rate", 1.0, 100.0);
  s.AddDouble("dwell", &o.dwell, "s", "time to stand still at each station", 0.0, 600.0);
  s.AddBool("exit_when_done", &o.exit_when_done, "stop the process after the last station");
  s.AddDouble("cruise_speed", &o.follower.cruise_speed, "m/s", "forward speed on straight legs", 0.001, 5.0);
  s.AddDouble("turn_rate", &o.follower.turn_rate, "rad/s", "yaw rate when turning in place", 0.001, 3.0);
  s.AddDouble("position_tolerance", &o.follower.position_tolerance, "m", "station reached inside this radius",
              0.001, 10.0);
  s.AddDouble("heading_tolerance", &o.follower.heading_tolerance, "rad", "final heading tolerance", 0.001, 1.0);
  s.AddDouble("align_tolerance", &o.follower.align_tolerance, "rad",
              "heading error above which the vehicle stops and turns in place", 0.001, 1.5);
}

int Main(int argc, char** argv) {
  ConfigSchema schema("waypoint_driver", "Drives the vehicle through scan stations, pausing at each.");
  DriverOptions o;
  Register(schema, o);
  NodeRuntime runtime("waypoint_driver", schema);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (o.stations.empty()) throw UsageError("--stations is required");
  o.follower.command_timeout = 3.0 / o.rate;

  std::vector<Waypoint> waypoints;
  for (const Station& st : LoadStationsCsv(o.stations)) waypoints.push_back({st.pose, true});
  WaypointFollower follower(o.follower, waypoints);
  MINENAV_LOG(kInfo) << "driving through " << waypoints.size() << " stations from " << o.stations;

  runtime.Start();
  bool have_pose = false;
  Pose2 pose;
  if (o.pose_source == "truth") {
    Subscribe<vehicle_truth_t>(runtime.bus(), o.truth_channel, [&](const vehicle_truth_t& m) {
      pose = FromLcm(m).pose;
      have_pose = true;
    });
  } else {
    Subscribe<odometry_t>(runtime.bus(), o.odometry_channel, [&](const odometry_t& m) {
      pose = FromLcm(m).pose;
      have_pose = true;
    });
  }

  int64_t seq = 0;
  int64_t dwell_until = 0;
  runtime.AddTimer(1.0 / o.rate, [&](int64_t now) {
    DriveCommand c;
    c.timeout = o.follower.command_timeout;
    if (have_pose && now >= dwell_until) {
      c = follower.Update(pose);
      if (follower.JustArrived()) {
        MINENAV_LOG(kInfo) << "station " << follower.CurrentIndex() << "/" << waypoints.size() << " reached at "
                           << pose;
        dwell_until = now + static_cast<int64_t>(o.dwell * 1e6);
      }
    }
    c.utime = now;
    c.seq = seq++;
    Publish(runtime.bus(), o.drive_channel, ToLcm(c));
    if (follower.Done() && now >= dwell_until && o.exit_when_done) {
      MINENAV_LOG(kInfo) << "all stations visited";
      runtime.RequestStop();
    }
  });
  return runtime.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("waypoint_driver", [&] { return minenav::Main(argc, argv); });
}
