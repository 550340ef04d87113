// log_tool survey and log_tool generate: commands that make inputs and logs from the
// simulator (sim/, sensor_driver/) without a bus.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_tool_commands.h"
#include "sim/survey.h"
#include "sim/changing_world.h"
#include "sim/mine_generator.h"
#include "sim/scenario.h"
#include "sim/mockup_generator.h"

namespace minenav {

namespace {

struct SurveyFlags {
  std::string stations_path, out, truth_out;
  std::string sensor = "typhoon";
  int points = 0;
  int64_t seed = 1;
  std::string pose_noise, drift;
  std::string scan_channel = "LADAR_SCAN", odometry_channel = "ODOMETRY", truth_channel = "SIM_TRUTH";
  std::string world_channel = "SIM_WORLD", map_channel = "LINE_MAP";
  std::string line_map = "none";  // none | first | each
  bool quiet = false;
  std::string config_world;  // --world flags are taken out before parsing; this gets a config file's `world =`
};

LadarModel SensorFor(const std::string& sensor, int points) {
  if (sensor == "cyclone") return LadarModel::Cyclone(points > 0 ? points : 2048);
  LadarModel m = LadarModel::Typhoon();
  if (points > 0) {
    m.num_points = points;
    m.angular_resolution = 0.0;  // a full revolution: 2 pi / points
  }
  return m;
}

// Declares every survey option. The sensor-model options take the chosen sensor's values
// as defaults, so --help --sensor cyclone shows Cyclone's.
void DeclareSurveyOptions(ConfigSchema* s, SurveyFlags* f, SurveyOptions* o) {
  s->AddString("world", &f->config_world,
               "world segments JSON (required; repeat for several worlds, chosen per station by the stations CSV column 'world')");
  s->AddString("stations", &f->stations_path, "stations CSV x,y,theta[,world] (required)");
  s->AddString("out", &f->out, "LCM log to write (required)");
  s->AddString("truth_out", &f->truth_out, "poses CSV of the true pose of each scan (utime,x,y,theta)");
  s->AddString("sensor", &f->sensor, "sensor model", {"typhoon", "cyclone"});
  s->AddInt("points", &f->points, "readings per scan (0 = the sensor's default, 2048)", 0, 1 << 20);
  s->AddInt64("seed", &f->seed, "random seed (ladar noise, initial estimates)", 0);
  s->AddString("pose_noise", &f->pose_noise,
               "initial estimates = truth + N(0, sigma) per station: 'sx,sy,stheta' in m,m,rad (stheta may be '3.33deg')");
  s->AddString("drift", &f->drift,
               "initial estimates = dead reckoning along the stations: 'scale,heading_drift_per_m,noise[,rotation_noise]' "
               "(fraction, rad/m, m/sqrt(m), rad/sqrt(m); default rotation_noise = noise)");
  LadarModel& m = o->sensor;
  s->AddDouble("min_range", &m.min_range, "m", "sensor: minimum range", 0.0);
  s->AddDouble("max_range", &m.max_range, "m", "sensor: maximum range", 0.0);
  s->AddDouble("range_sigma", &m.range_sigma, "m", "sensor: std of range noise", 0.0);
  s->AddDouble("range_resolution", &m.range_resolution, "m", "sensor: range quantisation (0 = none)", 0.0);
  s->AddDouble("start_angle", &m.start_angle, "rad", "sensor: bearing of reading 0");
  s->AddDouble("angular_resolution", &m.angular_resolution, "rad",
               "sensor: angle between readings (0 = 2 pi / points)");
  s->AddDouble("beam_divergence", &m.beam_divergence, "rad", "sensor: horizontal beam divergence", 0.0);
  s->AddDouble("mixed_pixel_probability", &m.mixed_pixel_probability, "",
               "sensor: chance a beam straddling an occlusion edge reports a mixed range", 0.0, 1.0);
  s->AddDouble("mixed_pixel_min_gap", &m.mixed_pixel_min_gap, "m",
               "sensor: range jump inside a beam footprint that counts as an edge", 0.0);
  s->AddDouble("scan_rate", &m.scan_rate, "Hz", "sensor: revolutions per second (sets scan_duration)", 0.0);
  s->AddString("sensor_id", &m.sensor_id, "sensor id written into each scan");
  s->AddDouble("sensor_x", &o->sensor_offset.x, "m", "sensor offset in the vehicle frame: x");
  s->AddDouble("sensor_y", &o->sensor_offset.y, "m", "sensor offset in the vehicle frame: y");
  s->AddDouble("sensor_theta", &o->sensor_offset.theta, "rad", "sensor offset in the vehicle frame: heading");
  s->AddInt64("start_utime", &o->start_utime, "utime of the first scan [us]", 0);
  s->AddDouble("station_interval", &o->station_interval, "s", "time between the scans of consecutive stations",
               1e-6, 1e6);
  s->AddChannel("scan_channel", &f->scan_channel, "writes", "minenav.ladar_scan_t", "scans");
  s->AddChannel("odometry_channel", &f->odometry_channel, "writes", "minenav.odometry_t",
                "initial pose estimates, same utime as the scan");
  s->AddChannel("truth_channel", &f->truth_channel, "writes", "minenav.vehicle_truth_t", "true poses");
  s->AddChannel("world_channel", &f->world_channel, "writes", "minenav.line_map_t",
                "the world the scans were cast in, when it becomes active (first station, and each change)");
  s->AddChannel("map_channel", &f->map_channel, "writes", "minenav.line_map_t", "surveyed map (see --line-map)");
  s->AddString("line_map", &f->line_map,
               "what the map channel carries: none; first = the first station's world once (a map surveyed "
               "before the changes); each = every world when it becomes active, like the world channel",
               {"none", "first", "each"});
  s->AddBool("quiet", &f->quiet, "no progress on stderr");
  s->AddHelpEpilog(
      "Example:\n"
      "  log_tool survey --world mine.json --stations st.csv --sensor typhoon --points 2048 \\\n"
      "      --pose-noise 0.33,0.33,3.33deg --seed 7 --out survey.lcm --truth-out truth.csv\n"
      "Without --pose-noise or --drift the initial estimates equal truth. Scan k has\n"
      "utime = start_utime + k * station_interval and scan_id = k; ODOMETRY (seq k) and\n"
      "SIM_TRUTH (seq k) carry the same utime and precede the scan in the log.\n"
      "A changing world: repeat --world and give the stations CSV a column 'world' (x,y,theta,world;\n"
      "an index into the --world list, default 0). SIM_WORLD (version 1, 2, ... per activation, name\n"
      "'world K: FILE') is written with the utime of the first scan in each newly active world,\n"
      "before that scan's ODOMETRY.\n");
}

void ParseInitialEstimates(const SurveyFlags& f, SurveyOptions* o) {
  if (!f.pose_noise.empty() && !f.drift.empty()) throw UsageError("give --pose-noise or --drift, not both");
  if (!f.pose_noise.empty()) {
    const auto v = ParseNumberList(f.pose_noise, "--pose-noise", 3);
    for (double x : v)
      if (x < 0.0) throw UsageError("--pose-noise: '" + f.pose_noise + "': sigmas must be >= 0");
    o->estimate = InitialEstimateKind::kPoseNoise;
    o->pose_noise = {v[0], v[1], v[2]};
  } else if (!f.drift.empty()) {
    const auto v = ParseNumberList(f.drift, "--drift", 0);
    if (v.size() != 3 && v.size() != 4)
      throw UsageError("--drift: '" + f.drift + "' has " + std::to_string(v.size()) +
                       " values, expected scale,heading_drift_per_m,noise[,rotation_noise]");
    if (v[2] < 0.0 || (v.size() == 4 && v[3] < 0.0)) throw UsageError("--drift: '" + f.drift + "': noise must be >= 0");
    o->estimate = InitialEstimateKind::kDrift;
    o->drift.scale_error = v[0];
    o->drift.heading_drift_per_metre = v[1];
    o->drift.translation_noise = v[2];
    o->drift.rotation_noise = v.size() == 4 ? v[3] : v[2];
  }
}

bool HelpOrPrint(const std::vector<std::string>& args) {
  for (const auto& a : args)
    if (a == "--help" || a == "-h" || a == "--print-config") return true;
  return false;
}

}  // namespace

int RunSurveyCommand(const std::vector<std::string>& raw_args) {
  std::vector<std::string> args = ExpandBareBoolFlags(raw_args, {"quiet"});
  std::vector<std::string> world_paths = TakeRepeatedFlag(&args, "world");
  const std::string summary =
      "Simulates a ladar survey offline (thesis 5.2.1): one scan at each station of a stations CSV,\n"
      "in a world of line segments, written to an LCM log with LADAR_SCAN, ODOMETRY (initial pose\n"
      "estimates) and SIM_TRUTH, plus the true poses as a poses CSV. No bus. Deterministic per seed.";

  // Pass 1 finds the sensor (defaults of the sensor options depend on it); pass 2 parses
  // everything with those defaults, so flags and --config values override them.
  SurveyFlags flags;
  SurveyOptions options;
  {
    std::vector<std::string> first = args;
    std::erase_if(first, [](const std::string& a) { return a == "--help" || a == "-h" || a == "--print-config"; });
    ConfigSchema pass1("log_tool survey", summary);
    DeclareSurveyOptions(&pass1, &flags, &options);
    try {
      pass1.Parse(first);
    } catch (const UsageError&) {
      if (!HelpOrPrint(args)) throw;  // --help must work even next to incomplete flags
    }
  }
  const std::string sensor = flags.sensor;
  const int points = flags.points;
  flags = SurveyFlags{};
  options = SurveyOptions{};
  options.sensor = SensorFor(sensor, points);
  ConfigSchema schema("log_tool survey", summary);
  DeclareSurveyOptions(&schema, &flags, &options);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  options.seed = static_cast<uint64_t>(flags.seed);
  ParseInitialEstimates(flags, &options);
  // Flags --world were taken out before parsing; a `world = FILE` line of a --config
  // file lands here and comes first.
  if (!flags.config_world.empty()) world_paths.insert(world_paths.begin(), flags.config_world);
  if (world_paths.empty()) throw UsageError("--world is required (see --help)");
  if (flags.stations_path.empty()) throw UsageError("--stations is required (see --help)");
  RequireOutputPath(flags.out, "--out");
  if (const std::string why = ValidateSurveyOptions(options); !why.empty()) throw UsageError(why);
  std::vector<std::string> inputs = world_paths;
  inputs.push_back(flags.stations_path);
  CheckOutputIsNotInput("--out", flags.out, inputs);
  // The log is written as OUT.partial first: that must not be an input either.
  CheckOutputIsNotInput("--out (written first as OUT.partial)", flags.out + ".partial", inputs);
  CheckOutputIsNotInput("--truth-out", flags.truth_out, inputs);

  std::vector<std::vector<Segment>> worlds;
  for (const auto& p : world_paths) {
    worlds.push_back(LoadSegmentsJson(p));
    if (worlds.back().empty()) throw InputError(p + ": the world has no segments");
  }
  const std::vector<Station> stations = LoadStationsCsv(flags.stations_path);
  if (stations.empty()) throw InputError(flags.stations_path + ": no stations");

  const auto t0 = std::chrono::steady_clock::now();
  LogWriter writer(flags.out);
  std::vector<StampedPose> truth_rows;
  // Progress at most once a second, so short surveys stay quiet.
  double last_report = 0.0;
  const auto progress = [&](int done, int total) {
    if (flags.quiet) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s - last_report < 1.0) return;
    last_report = s;
    std::fprintf(stderr, "log_tool survey: %d/%d stations (%.1f s)\n", done, total, s);
  };
  int64_t world_version = 0;  // activations so far: increases whenever the world changes
  try {
    RunSurvey(
        worlds, stations, options,
        [&](const SurveyRecord& r) {
          if (r.world_changed) {
            const auto w = static_cast<size_t>(r.world);
            const std::string name = "world " + std::to_string(r.world) + ": " + world_paths[w];
            ++world_version;
            writer.WriteMessage(flags.world_channel, r.utime, SegmentsToLcm(worlds[w], r.utime, world_version, name));
            if (flags.line_map == "each" || (flags.line_map == "first" && r.index == 0))
              writer.WriteMessage(flags.map_channel, r.utime, SegmentsToLcm(worlds[w], r.utime, world_version, name));
          }
          OdometryReading odo;
          odo.utime = r.utime;
          odo.seq = r.index;
          odo.pose = r.estimate;
          odo.covariance = r.estimate_covariance;
          TruthReading truth;
          truth.utime = r.utime;
          truth.seq = r.index;
          truth.pose = r.truth;
          writer.WriteMessage(flags.odometry_channel, r.utime, ToLcm(odo));
          writer.WriteMessage(flags.truth_channel, r.utime, ToLcm(truth));
          writer.WriteMessage(flags.scan_channel, r.utime, ToLcm(r.scan));
          truth_rows.push_back({r.utime, r.truth});
        },
        progress);
  } catch (const InputError& e) {
    throw InputError(flags.stations_path + ": " + e.what());
  }
  if (!flags.truth_out.empty()) SavePosesCsv(flags.truth_out, truth_rows);
  try {
    writer.Close();
  } catch (...) {
    if (!flags.truth_out.empty()) std::remove(flags.truth_out.c_str());
    throw;
  }
  if (!flags.quiet)
    std::fprintf(stderr, "log_tool survey: %zu scans of %d points in %.2f s -> %s%s%s\n", stations.size(),
                 options.sensor.num_points,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), flags.out.c_str(),
                 flags.truth_out.empty() ? "" : ", truth -> ", flags.truth_out.c_str());
  return 0;
}

namespace {

// A changing-world scenario: world k goes to world_out with '{}' replaced by k.
int WriteChangingWorld(const ChangingWorldScenario& sc, const std::string& world_out, const std::string& stations_out,
                       const std::string& map_out) {
  if (!map_out.empty()) throw UsageError("--map-out is only for --kind mockup");
  const size_t brace = world_out.find("{}");
  if (sc.worlds.size() > 1 && brace == std::string::npos)
    throw UsageError("--world-out: '" + world_out + "' needs '{}' for the world index (" + sc.name + " has " +
                     std::to_string(sc.worlds.size()) + " worlds), e.g. " + sc.name + "_{}.json");
  std::vector<std::string> paths;
  for (size_t k = 0; k < sc.worlds.size(); ++k) {
    std::string path = world_out;
    if (brace != std::string::npos) path.replace(brace, 2, std::to_string(k));
    RequireOutputPath(path, "--world-out");
    paths.push_back(path);
  }
  for (size_t k = 0; k < sc.worlds.size(); ++k) SaveSegmentsJson(paths[k], sc.worlds[k]);
  SaveStationsCsv(stations_out, sc.stations);
  std::string survey = "log_tool survey";
  for (const auto& p : paths) survey += " --world " + p;
  std::fprintf(stderr,
               "log_tool generate: %s: %zu worlds -> %s; %zu stations -> %s\n"
               "survey it with:\n  %s --stations %s --out %s.lcm\n",
               sc.name.c_str(), sc.worlds.size(), world_out.c_str(), sc.stations.size(), stations_out.c_str(),
               survey.c_str(), stations_out.c_str(), sc.name.c_str());
  return 0;
}

}  // namespace

int RunGenerateCommand(const std::vector<std::string>& args) {
  std::string kind = "mine", world_out, stations_out, map_out;
  int64_t seed = 1;
  int stations = 0;
  MineOptions mine;
  ResearchMineOptions research;
  double heading_variation = 0.6;
  int loop_row = 0, loop_col = 0;
  std::string summary =
      "Writes a generated world (segments JSON) and survey stations (CSV) for log_tool survey:\n"
      "  mine      room-and-pillar mine of thesis 5.2.1, serpentine survey (default 42 stations)\n"
      "  research  research-mine style (5.3): narrow entries, irregular pillars, cribs (33)\n"
      "  mockup    indoor mockup corridor of 2.2 with clutter not in the map, Table 1's 16 stations\n"
      "  loop      the mine, with stations around one pillar closing a loop (24)\n"
      "A changing world (thesis 4.8, sim/changing_world.h): several worlds, one file each (--world-out\n"
      "with '{}' standing for the world index), and stations with a 'world' column:";
  std::vector<std::string> kinds = ScenarioKinds();
  for (const ChangingWorldScenario& sc : AllChangingWorldScenarios()) {
    summary += "\n  " + sc.name + std::string(sc.name.size() < 17 ? 17 - sc.name.size() : 1, ' ') + sc.description;
    kinds.push_back(sc.name);
  }
  ConfigSchema schema("log_tool generate", summary);
  schema.AddString("kind", &kind, "what to generate", kinds);
  schema.AddInt64("seed", &seed, "random seed", 0);
  schema.AddString("world_out", &world_out, "world segments JSON to write (required)");
  schema.AddString("stations_out", &stations_out, "stations CSV to write (required)");
  schema.AddString("map_out", &map_out, "mockup only: the surveyed map without clutter (segments JSON)");
  schema.AddInt("stations", &stations, "number of stations (0 = the kind's default; ignored for mockup)", 0, 100000);
  schema.AddInt("rows", &mine.pillar_rows, "mine/loop: pillar rows", 1, 1000);
  schema.AddInt("cols", &mine.pillar_cols, "mine/loop: pillar columns", 1, 1000);
  schema.AddDouble("pillar_size", &mine.pillar_size, "m", "mine/loop: pillar side", 0.1);
  schema.AddDouble("room_width", &mine.room_width, "m", "mine/loop: room width", 0.1);
  schema.AddDouble("max_segment_length", &mine.max_segment_length, "m", "mine/loop: split walls below this", 0.01);
  schema.AddDouble("midpoint_displacement", &mine.midpoint_displacement, "m",
                   "mine/loop: first midpoint displacement (halves per split)", 0.0);
  schema.AddDouble("heading_variation", &heading_variation, "rad", "stations: random heading offset bound", 0.0);
  schema.AddInt("loop_row", &loop_row, "loop: pillar row to go around", 0);
  schema.AddInt("loop_col", &loop_col, "loop: pillar column to go around", 0);
  schema.AddHelpEpilog(
      "Examples:\n"
      "  log_tool generate --kind mine --seed 3 --world-out mine.json --stations-out st.csv\n"
      "  log_tool generate --kind doors_open --world-out doors_{}.json --stations-out st.csv\n"
      "      (writes doors_0.json, doors_1.json and prints the log_tool survey command for them)\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  RequireOutputPath(world_out, "--world-out");
  RequireOutputPath(stations_out, "--stations-out");
  if (!map_out.empty() && kind != "mockup") throw UsageError("--map-out is only for --kind mockup");
  const auto built_in_end = kinds.begin() + static_cast<std::ptrdiff_t>(ScenarioKinds().size());
  if (std::find(kinds.begin(), built_in_end, kind) == built_in_end)
    return WriteChangingWorld(ChangingWorldScenarioByName(kind), world_out, stations_out, map_out);

  ScenarioOptions g;
  g.kind = kind;
  g.seed = static_cast<uint64_t>(seed);
  g.mine = mine;
  g.research = research;
  g.stations = stations;
  g.heading_variation = heading_variation;
  g.loop_row = loop_row;
  g.loop_col = loop_col;
  if (const std::string why = ValidateScenarioOptions(g); !why.empty()) throw UsageError(why);
  const GeneratedScenario generated = GenerateScenario(g);
  const std::vector<Segment>& world = generated.world;
  const std::vector<Station>& st = generated.stations;
  const std::vector<Segment> map = kind == "mockup" ? generated.map : std::vector<Segment>{};
  SaveSegmentsJson(world_out, world);
  SaveStationsCsv(stations_out, st);
  if (!map_out.empty()) SaveSegmentsJson(map_out, map);
  std::fprintf(stderr, "log_tool generate: %s: %zu segments -> %s, %zu stations -> %s\n", kind.c_str(), world.size(),
               world_out.c_str(), st.size(), stations_out.c_str());
  return 0;
}

}  // namespace minenav
