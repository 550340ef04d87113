// vehicle_sim: the locomotion emulator (thesis App. D, 6.4): a skid-steer miner driven by
// DRIVE_COMMAND in a simulated line-segment world. Publishes the true pose (SIM_TRUTH),
// dead-reckoned odometry with drift (ODOMETRY), the world the ladar sees (SIM_WORLD) and
// the surveyed map estimators may use (LINE_MAP; for the indoor mockup it lacks the
// clutter, thesis 2.2). The vehicle stops by itself when commands go stale.
//
// Time: each tick integrates the motion over the clock time since the previous tick (live:
// wall clock; batch over a log of commands: log time), so a batch run is deterministic.
// A command's age is measured from when it was received, not from its own utime, so a
// sender with a skewed clock cannot keep the vehicle moving or stop it early.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "common/angle.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/node_runtime.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "sim/mine_generator.h"
#include "sim/mockup_generator.h"
#include "sim/odometry_model.h"
#include "sim/skid_steer.h"
#include "sim/world.h"

namespace minenav {
namespace {

struct VehicleSimOptions {
  std::string world;              // JSON file; "" = generate
  std::string generate = "mine";  // mine | research | mockup
  int64_t seed = 1;
  int pillar_rows = 2;
  int pillar_cols = 3;
  double pillar_size = 12.0;  // m
  double room_width = 6.0;    // m
  std::string world_out;      // save the world JSON here
  std::string map_out;        // save the surveyed map JSON here
  std::string start_pose = "auto";
  double rate = 20.0;              // Hz
  double map_period = 1.0;         // s
  SkidSteerOptions vehicle;
  // A modest wheel-odometry error so ODOMETRY drifts like a real miner's; zero them for
  // perfect dead reckoning.
  OdometryErrorOptions odometry{.scale_error = 0.01,
                                .rotation_scale_error = 0.01,
                                .heading_drift_per_metre = 0.002,
                                .heading_drift_per_second = 0.0,
                                .translation_noise = 0.005,
                                .rotation_noise = 0.002};
  std::string drive_channel = "DRIVE_COMMAND";
  std::string truth_channel = "SIM_TRUTH";
  std::string odometry_channel = "ODOMETRY";
  std::string world_channel = "SIM_WORLD";
  std::string map_channel = "LINE_MAP";
};

void Declare(ConfigSchema& s, VehicleSimOptions& o) {
  s.AddString("world", &o.world, "world JSON file ({\"segments\": [[x1,y1,x2,y2],...]}); empty = --generate");
  s.AddString("generate", &o.generate, "built-in world when --world is empty (thesis 5.2.1, 5.3, 2.2)",
              {"mine", "research", "mockup"});
  s.AddInt64("seed", &o.seed, "seed of the world generator and of the odometry noise", 0);
  s.AddInt("pillar_rows", &o.pillar_rows, "mine/research: pillars along y", 1, 50);
  s.AddInt("pillar_cols", &o.pillar_cols, "mine/research: pillars along x", 1, 50);
  s.AddDouble("pillar_size", &o.pillar_size, "m", "mine: side of the square pillars", 1.0, 100.0);
  s.AddDouble("room_width", &o.room_width, "m", "mine: width of the rooms between pillars", 1.0, 50.0);
  s.AddString("world_out", &o.world_out, "also write the simulated world as JSON to this file");
  s.AddString("map_out", &o.map_out, "also write the surveyed map (LINE_MAP) as JSON to this file");
  s.AddString("start_pose", &o.start_pose,
              "initial vehicle pose 'x,y,theta' (m, m, rad or e.g. 90deg); auto = the generator's "
              "first survey station, or 0,0,0 for --world");
  s.AddDouble("rate", &o.rate, "Hz", "integration and SIM_TRUTH/ODOMETRY publishing rate", 0.1, 1000.0);
  s.AddDouble("map_period", &o.map_period, "s", "republish SIM_WORLD and LINE_MAP this often",
              0.05, 3600.0);
  SkidSteerOptions& v = o.vehicle;
  s.AddDouble("max_forward_speed", &v.max_forward_speed, "m/s", "forward speed limit", 0.0, 10.0);
  s.AddDouble("max_reverse_speed", &v.max_reverse_speed, "m/s", "reverse speed limit (magnitude)", 0.0, 10.0);
  s.AddDouble("turn_radius", &v.turn_radius, "m", "the one turning radius besides turning in place", 0.01, 1000.0);
  s.AddDouble("max_turn_in_place_rate", &v.max_turn_in_place_rate, "rad/s", "yaw rate limit turning in place",
              0.0, 10.0);
  s.AddDouble("max_acceleration", &v.max_acceleration, "m/s^2", "raising |speed|; 0 = instantaneous", 0.0, 100.0);
  s.AddDouble("max_deceleration", &v.max_deceleration, "m/s^2", "lowering |speed|; 0 = instantaneous", 0.0, 100.0);
  s.AddDouble("max_yaw_acceleration", &v.max_yaw_acceleration, "rad/s^2",
              "turning in place; 0 = instantaneous", 0.0, 100.0);
  s.AddDouble("min_speed", &v.min_speed, "m/s", "below this a (v, omega) command turns in place or stops",
              0.0, 1.0);
  s.AddDouble("command_timeout", &v.command_timeout, "s",
              "a command older than its own timeout (or this, if it has none) is stale: the vehicle stops",
              0.001, 3600.0);
  OdometryErrorOptions& e = o.odometry;
  s.AddDouble("odometry_scale_error", &e.scale_error, "fraction", "odometry distance error (0.02 = reads 2% long)",
              -0.5, 0.5);
  s.AddDouble("odometry_rotation_scale_error", &e.rotation_scale_error, "fraction",
              "error of each heading change", -0.5, 0.5);
  s.AddDouble("odometry_heading_drift_per_metre", &e.heading_drift_per_metre, "rad/m",
              "heading drift per metre travelled (signed)", -1.0, 1.0);
  s.AddDouble("odometry_heading_drift_per_second", &e.heading_drift_per_second, "rad/s",
              "heading drift per second (gyro bias)", -1.0, 1.0);
  s.AddDouble("odometry_translation_noise", &e.translation_noise, "m/sqrt(m)",
              "std of the distance error after 1 m", 0.0, 1.0);
  s.AddDouble("odometry_rotation_noise", &e.rotation_noise, "rad/sqrt(rad)",
              "std of the heading error after 1 rad (or 1 m)", 0.0, 1.0);
  s.AddChannel("drive_channel", &o.drive_channel, "subscribes", "drive_command_t", "commands to the vehicle");
  s.AddChannel("truth_channel", &o.truth_channel, "publishes", "vehicle_truth_t", "true pose at --rate");
  s.AddChannel("odometry_channel", &o.odometry_channel, "publishes", "odometry_t",
               "dead-reckoned pose with drift at --rate");
  s.AddChannel("world_channel", &o.world_channel, "publishes", "line_map_t",
               "the world the ladar sees (version = world version)");
  s.AddChannel("map_channel", &o.map_channel, "publishes", "line_map_t",
               "surveyed map for estimators (the mockup's lacks its clutter)");
  s.AddHelpEpilog(
      "Examples:\n"
      "  vehicle_sim --generate mine --seed 7\n"
      "  vehicle_sim --world mine.json --start-pose 3,3,0 --max-forward-speed 0.3\n"
      "  vehicle_sim --log commands.lcm --log-out run.lcm     (batch, deterministic)\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
}

struct Scenario {
  std::vector<Segment> world;  // what the ladar sees
  std::vector<Segment> map;    // the surveyed map
  Pose2 start;
  std::string name;
};

Scenario BuildScenario(const VehicleSimOptions& o) {
  Scenario sc;
  std::optional<Pose2> first_station;
  if (!o.world.empty()) {
    sc.world = World::Load(o.world).Segments();
    sc.map = sc.world;
    sc.name = o.world;
  } else if (o.generate == "mine") {
    MineOptions m;
    m.pillar_rows = o.pillar_rows;
    m.pillar_cols = o.pillar_cols;
    m.pillar_size = o.pillar_size;
    m.room_width = o.room_width;
    m.seed = static_cast<uint64_t>(o.seed);
    const std::string why = ValidateMineOptions(m);
    if (!why.empty()) throw UsageError(why);
    sc.world = GenerateRoomAndPillarMine(m);
    sc.map = sc.world;
    first_station = MineSurveyStations(m).front().pose;
    sc.name = "mine seed " + std::to_string(o.seed);
  } else if (o.generate == "research") {
    ResearchMineOptions m;
    m.pillar_rows = o.pillar_rows;
    m.pillar_cols = o.pillar_cols;
    m.seed = static_cast<uint64_t>(o.seed);
    const std::string why = ValidateResearchMineOptions(m);
    if (!why.empty()) throw UsageError(why);
    sc.world = GenerateResearchMine(m);
    sc.map = sc.world;
    first_station = ResearchMineStations(m).front().pose;
    sc.name = "research mine seed " + std::to_string(o.seed);
  } else {
    const MockupWorld m = GenerateIndoorMockup(static_cast<uint64_t>(o.seed));
    sc.world = m.World();
    sc.map = m.map;
    first_station = m.stations.front().pose;
    sc.name = "indoor mockup seed " + std::to_string(o.seed);
  }
  if (o.start_pose == "auto") {
    sc.start = first_station.value_or(Pose2());
  } else {
    const std::vector<double> p = ParseNumberList(o.start_pose, "--start-pose", 3);
    sc.start = Pose2(p[0], p[1], NormalizeAngle(p[2]));
  }
  return sc;
}

int Main(int argc, char** argv) {
  ConfigSchema schema("vehicle_sim",
                      "Skid-steer miner simulator: DRIVE_COMMAND in; SIM_TRUTH, ODOMETRY, SIM_WORLD, LINE_MAP out.");
  NodeRuntime runtime("vehicle_sim", schema);
  VehicleSimOptions o;
  Declare(schema, o);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (std::string why = ValidateSkidSteerOptions(o.vehicle); !why.empty()) throw UsageError(why);
  if (std::string why = ValidateOdometryErrorOptions(o.odometry); !why.empty()) throw UsageError(why);

  const Scenario sc = BuildScenario(o);
  World world(sc.world);
  if (!o.world_out.empty()) world.Save(o.world_out);
  if (!o.map_out.empty()) World(sc.map).Save(o.map_out);

  runtime.Start();
  MINENAV_LOG(kInfo) << sc.name << ": " << world.size() << " segments, start " << sc.start;
  Bus& bus = runtime.bus();
  SkidSteerVehicle vehicle(o.vehicle, sc.start);
  DeadReckoning odometry(o.odometry, sc.start, static_cast<uint64_t>(o.seed) * 7919 + 1);

  std::optional<DriveCommand> command;  // utime = when it was received
  Subscribe<drive_command_t>(bus, o.drive_channel, [&](const drive_command_t& m) {
    DriveCommand c = FromLcm(m);
    c.utime = runtime.NowUtime();
    command = c;
  });

  // The world first, so a ladar starting with us has it before the first truth sample.
  runtime.AddTimer(o.map_period, [&](int64_t now) {
    Publish(bus, o.world_channel,
            SegmentsToLcm(world.Segments(), now, static_cast<int64_t>(world.version()), sc.name));
    Publish(bus, o.map_channel, SegmentsToLcm(sc.map, now, 0, sc.name + " (surveyed map)"));
  });

  std::optional<int64_t> last_tick;
  int64_t seq = 0;
  bool was_stale = true;
  runtime.AddTimer(1.0 / o.rate, [&](int64_t now) {
    if (last_tick) {
      // Clock time since the last tick, capped so a suspended process does not jump.
      const double dt = std::clamp(static_cast<double>(now - *last_tick) * 1e-6, 0.0, 1.0);
      const MotionIncrement inc = command ? vehicle.Step(dt, *command, now) : vehicle.StepWithoutCommand(dt);
      odometry.AddIncrement(inc);
    }
    last_tick = now;
    if (vehicle.stale() != was_stale) {
      was_stale = vehicle.stale();
      if (was_stale && command) MINENAV_LOG(kInfo) << "commands stale: stopping";
      runtime.SetStatus(heartbeat_t::OK, was_stale ? "idle: no fresh command" : "driving");
    }
    TruthReading truth;
    truth.utime = now;
    truth.seq = seq;
    truth.pose = vehicle.pose();
    truth.v = vehicle.v();
    truth.omega = vehicle.omega();
    Publish(bus, o.truth_channel, ToLcm(truth));
    OdometryReading odo = odometry.Reading(now);
    odo.seq = seq;
    Publish(bus, o.odometry_channel, ToLcm(odo));
    ++seq;
  });

  return runtime.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("vehicle_sim", [&] { return minenav::Main(argc, argv); });
}
