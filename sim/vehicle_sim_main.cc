// vehicle_sim: the locomotion emulator (thesis App. D, 6.4): a skid-steer miner driven by
// DRIVE_COMMAND in a simulated line-segment world. Publishes the true pose (SIM_TRUTH),
// dead-reckoned odometry with drift (ODOMETRY), the world the ladar sees (SIM_WORLD) and
// the surveyed map estimators may use (LINE_MAP; for the indoor mockup it lacks the
// clutter, thesis 2.2). The vehicle stops by itself when commands go stale.
//
// A changing world (thesis 4.8): --world may be repeated and --world-change-at gives the
// times (s since the first tick) at which world k+1 replaces world k, e.g. a door opens
// while the fleet runs. SIM_WORLD is published at once, before the SIM_TRUTH sample of that
// tick, so the ladar (which ray-casts the latest SIM_WORLD) casts every scan whose utime
// is later than the previous truth sample in the new world. LINE_MAP stays the first world
// (a map surveyed before the changes) unless --line-map each.
//
// Time: each tick integrates the motion over the clock time since the previous tick (live:
// wall clock; batch over a log of commands: log time), so a batch run is deterministic.
// A command's age is measured from when it was received, not from its own utime, so a
// sender with a skewed clock cannot keep the vehicle moving or stop it early.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

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
#include "sim/scenario.h"
#include "sim/world.h"

namespace minenav {
namespace {

struct VehicleSimOptions {
  std::string world;              // JSON file; "" = generate (on the command line: repeatable)
  std::string world_change_at;    // "T1,T2,..." s since the first tick; one per extra --world
  std::string line_map = "first"; // first | each: what LINE_MAP carries in a changing world
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
  s.AddString("world", &o.world,
              "world JSON file ({\"segments\": [[x1,y1,x2,y2],...]}); empty = --generate. Repeat the flag for a "
              "world that changes while running (see --world-change-at)");
  s.AddString("world_change_at", &o.world_change_at,
              "[s since the first tick, comma-separated, increasing] when world 2, 3, ... of the repeated --world "
              "replaces the previous one; one time per extra --world");
  s.AddString("line_map", &o.line_map,
              "what LINE_MAP carries when the world changes: first = the first world (surveyed before the "
              "changes), each = the current world",
              {"first", "each"});
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
              "the vehicle's own stale limit: a command older than this or its own timeout, whichever is shorter, "
              "is stale and the vehicle stops",
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
      "  vehicle_sim --world closed.json --world open.json --world-change-at 30   (a door opens at 30 s)\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
}

struct Scenario {
  std::vector<Segment> world;  // what the ladar sees first
  std::vector<Segment> map;    // the surveyed map
  Pose2 start;
  std::string name;
  // A changing world: later_worlds[i] replaces the world at change_at_us[i] (us since the
  // first tick), named later_names[i].
  std::vector<std::vector<Segment>> later_worlds;
  std::vector<std::string> later_names;
  std::vector<int64_t> change_at_us;
};

// Takes every --world FILE / --world=FILE out of the arguments (the flag may repeat).
std::vector<std::string> TakeWorldFlags(std::vector<std::string>* args) {
  std::vector<std::string> values, rest;
  for (size_t i = 0; i < args->size(); ++i) {
    const std::string& a = (*args)[i];
    if (a == "--world") {
      if (i + 1 >= args->size()) throw UsageError("--world needs a file");
      values.push_back((*args)[++i]);
    } else if (a.rfind("--world=", 0) == 0) {
      values.push_back(a.substr(8));
    } else {
      rest.push_back(a);
    }
  }
  *args = std::move(rest);
  return values;
}

// --world-change-at: one time per world after the first, > 0 and strictly increasing.
std::vector<int64_t> ParseChangeTimes(const std::string& text, size_t world_count) {
  if (world_count <= 1) {
    if (!text.empty()) throw UsageError("--world-change-at needs more than one --world");
    return {};
  }
  if (text.empty())
    throw UsageError(std::to_string(world_count) + " --world files need --world-change-at with " +
                     std::to_string(world_count - 1) + " time(s)");
  const std::vector<double> t = ParseNumberList(text, "--world-change-at", 0);
  if (t.size() != world_count - 1)
    throw UsageError("--world-change-at: '" + text + "' has " + std::to_string(t.size()) + " time(s), expected " +
                     std::to_string(world_count - 1) + " (one per --world after the first)");
  std::vector<int64_t> us;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || t[i] <= 0.0 || t[i] > 1e7)
      throw UsageError("--world-change-at: '" + text + "': times must be in (0, 1e7] s");
    if (i > 0 && t[i] <= t[i - 1]) throw UsageError("--world-change-at: '" + text + "': times must increase");
    us.push_back(std::llround(t[i] * 1e6));
  }
  return us;
}

Scenario BuildScenario(const VehicleSimOptions& o, const std::vector<std::string>& world_files) {
  Scenario sc;
  std::optional<Pose2> first_station;
  sc.change_at_us = ParseChangeTimes(o.world_change_at, world_files.size());
  if (!world_files.empty()) {
    sc.world = World::Load(world_files.front()).Segments();
    if (sc.world.empty()) throw InputError(world_files.front() + ": the world has no segments");
    sc.map = sc.world;
    sc.name = world_files.front();
    for (size_t k = 1; k < world_files.size(); ++k) {
      sc.later_worlds.push_back(World::Load(world_files[k]).Segments());
      if (sc.later_worlds.back().empty()) throw InputError(world_files[k] + ": the world has no segments");
      sc.later_names.push_back(world_files[k]);
    }
  } else {
    ScenarioOptions g;
    g.kind = o.generate;
    g.seed = static_cast<uint64_t>(o.seed);
    g.mine.pillar_rows = g.research.pillar_rows = o.pillar_rows;
    g.mine.pillar_cols = g.research.pillar_cols = o.pillar_cols;
    g.mine.pillar_size = o.pillar_size;
    g.mine.room_width = o.room_width;
    if (const std::string why = ValidateScenarioOptions(g); !why.empty()) throw UsageError(why);
    GeneratedScenario generated = GenerateScenario(g);
    sc.world = std::move(generated.world);
    sc.map = std::move(generated.map);
    first_station = generated.stations.front().pose;
    sc.name = generated.name;
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
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> world_files = TakeWorldFlags(&args);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  // Flags beat a config file's `world =` line, as for every other option.
  if (world_files.empty() && !o.world.empty()) world_files.push_back(o.world);
  if (std::string why = ValidateSkidSteerOptions(o.vehicle); !why.empty()) throw UsageError(why);
  if (std::string why = ValidateOdometryErrorOptions(o.odometry); !why.empty()) throw UsageError(why);

  const Scenario sc = BuildScenario(o, world_files);
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
  std::string world_name = sc.name;
  int64_t map_version = 0;  // LINE_MAP's version with --line-map each: +1 per change
  const auto publish_world = [&](int64_t now) {
    Publish(bus, o.world_channel,
            SegmentsToLcm(world.Segments(), now, static_cast<int64_t>(world.version()), world_name));
    if (o.line_map == "each")
      Publish(bus, o.map_channel, SegmentsToLcm(world.Segments(), now, map_version, world_name));
    else
      Publish(bus, o.map_channel, SegmentsToLcm(sc.map, now, 0, sc.name + " (surveyed map)"));
  };

  // The changing world: a change is applied by the first timer (world or motion) that
  // fires at or after its time, and published at once. True if it changed.
  std::optional<int64_t> first_tick;
  size_t next_change = 0;
  const auto change_world = [&](int64_t now) {
    if (!first_tick) first_tick = now;
    bool changed = false;
    while (next_change < sc.change_at_us.size() && now - *first_tick >= sc.change_at_us[next_change]) {
      world.ReplaceSegments(world.Ids(), sc.later_worlds[next_change]);
      world_name = sc.later_names[next_change];
      ++map_version;
      ++next_change;
      changed = true;
    }
    if (!changed) return false;
    MINENAV_LOG(kInfo) << "world changed at " << static_cast<double>(now - *first_tick) * 1e-6 << " s to "
                       << world_name << ": " << world.size() << " segments, version " << world.version();
    publish_world(now);
    return true;
  };
  runtime.AddTimer(o.map_period, [&](int64_t now) {
    if (!change_world(now)) publish_world(now);
  });

  std::optional<int64_t> last_tick;
  int64_t seq = 0;
  bool was_stale = true;
  runtime.AddTimer(1.0 / o.rate, [&](int64_t now) {
    change_world(now);
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
