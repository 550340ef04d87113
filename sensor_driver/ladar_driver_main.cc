// ladar_driver: publishes 360 deg scans on LADAR_SCAN (thesis 4.2, 5.2.1, App. B, C).
//
// Simulation mode (default): ray-casts the world (--world FILE, or the line_map_t on
// SIM_WORLD that vehicle_sim publishes) from the vehicle's true pose (SIM_TRUTH) with
// LadarSimulator, at the sensor's scan rate. Scans are scheduled on the truth stream's
// clock: scan k is stamped t0 + k / scan_rate (t0 = the first truth sample) and is made
// as soon as a truth sample at or after that time arrives, from the pose interpolated
// between the two samples around it. So a scan's pose is never extrapolated, and a batch
// run over a log of SIM_TRUTH makes exactly the scans the live run made. The whole
// revolution is cast from the pose at the scan's utime (the motion during one 0.1 s
// revolution is under 1 cm at the miner's speed). scan_id counts published scans from 0.
//
// Replay mode (--replay LOG): republishes the LADAR_SCAN events of a log (e.g. a real
// dataset) at the recorded rate (--replay-speed), unchanged; scans that do not decode are
// counted as bad and skipped.

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "common/angle.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/node/node_runtime.h"
#include "common/segment_index.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "sensor_driver/ladar_model.h"
#include "sensor_driver/ladar_simulator.h"
#include "sensor_driver/scan_schedule.h"

namespace minenav {
namespace {

// Sensor-model overrides are strings so that "" can mean "the sensor's own value".
struct ModelOverrides {
  std::string sensor_id, min_range, max_range, start_angle, angular_resolution, range_resolution,
      range_sigma, beam_divergence, mixed_pixel_probability, mixed_pixel_min_gap, scan_rate;
  int points = 0;
};

struct LadarDriverOptions {
  std::string sensor = "typhoon";
  ModelOverrides model;
  std::string sensor_pose = "0,0,0";
  int64_t seed = 1;
  std::string world;
  double truth_buffer = 5.0;    // s
  double max_truth_gap = 1.0;   // s
  std::string replay;
  double replay_speed = 1.0;
  std::string truth_channel = "SIM_TRUTH";
  std::string world_channel = "SIM_WORLD";
  std::string scan_channel = "LADAR_SCAN";
};

void Declare(ConfigSchema& s, LadarDriverOptions& o) {
  s.AddString("sensor", &o.sensor, "sensor model: K2T Typhoon (App. C) or CMU Cyclone (App. B)",
              {"typhoon", "cyclone"});
  ModelOverrides& m = o.model;
  s.AddInt("points", &m.points, "readings per revolution; 0 = the sensor's (typhoon 2048, cyclone 2048)", 0,
           1 << 20);
  const std::string sensor_default = "; empty = the sensor's";
  s.AddString("sensor_id", &m.sensor_id, "sensor_id in the scans" + sensor_default + " name");
  s.AddString("min_range", &m.min_range, "[m] shorter returns are no return" + sensor_default +
                                             " (typhoon 1.5, cyclone 4)");
  s.AddString("max_range", &m.max_range, "[m] longer returns are no return" + sensor_default +
                                             " (typhoon 45, cyclone 50)");
  s.AddString("start_angle", &m.start_angle, "[rad, or e.g. -180deg] bearing of reading 0" + sensor_default + " (0)");
  s.AddString("angular_resolution", &m.angular_resolution,
              "[rad, or deg] signed step between readings; 0 = 2 pi / points" + sensor_default);
  s.AddString("range_resolution", &m.range_resolution,
              "[m] ranges are rounded to this; 0 = none" + sensor_default + " (typhoon 0.044, cyclone 0.1)");
  s.AddString("range_sigma", &m.range_sigma,
              "[m] std of Gaussian range noise" + sensor_default + " (typhoon 0.044, cyclone 0.1)");
  s.AddString("beam_divergence", &m.beam_divergence,
              "[rad] full horizontal beam divergence" + sensor_default + " (typhoon 0.003, cyclone 0.004)");
  s.AddString("mixed_pixel_probability", &m.mixed_pixel_probability,
              "[0..1] chance a footprint straddling an occlusion edge reports a range in between" + sensor_default);
  s.AddString("mixed_pixel_min_gap", &m.mixed_pixel_min_gap,
              "[m] range jump inside a footprint that counts as an edge" + sensor_default + " (0.3)");
  s.AddString("scan_rate", &m.scan_rate, "[Hz] revolutions per second" + sensor_default + " (typhoon 10, cyclone min(5, 7200 / points))");
  s.AddString("sensor_pose", &o.sensor_pose, "sensor pose in the vehicle frame 'x,y,theta' (m, m, rad or deg)");
  s.AddInt64("seed", &o.seed, "seed of the range noise and mixed pixels (scans depend on seed and scan_id only)",
             0);
  s.AddString("world", &o.world, "world JSON file; empty = take the world from --world-channel");
  s.AddDouble("truth_buffer", &o.truth_buffer, "s", "how much SIM_TRUTH history is kept for interpolation", 0.1,
              600.0);
  s.AddDouble("max_truth_gap", &o.max_truth_gap, "s",
              "a gap in SIM_TRUTH longer than this skips the scans in it instead of interpolating", 0.01, 60.0);
  s.AddString("replay", &o.replay, "replay mode: republish the scans of this LCM log at the recorded rate");
  s.AddDouble("replay_speed", &o.replay_speed, "x", "replay speed factor (2 = twice as fast)", 0.01, 1000.0);
  s.AddChannel("truth_channel", &o.truth_channel, "subscribes", "vehicle_truth_t",
               "the vehicle's true pose (simulation mode)");
  s.AddChannel("world_channel", &o.world_channel, "subscribes", "line_map_t",
               "the world to ray-cast when --world is empty (simulation mode)");
  s.AddChannel("scan_channel", &o.scan_channel, "publishes", "ladar_scan_t",
               "scans (replay mode: also the channel read from the log)");
  s.AddHelpEpilog(
      "Examples:\n"
      "  ladar_driver --sensor typhoon --seed 3              (with vehicle_sim running)\n"
      "  ladar_driver --sensor cyclone --points 8192 --range-sigma 0.05 --world mine.json\n"
      "  ladar_driver --log truth.lcm --log-out scans.lcm    (batch over SIM_TRUTH + SIM_WORLD)\n"
      "  ladar_driver --replay dataset.lcm --replay-speed 2\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
}

LadarModel BuildModel(const LadarDriverOptions& o) {
  const ModelOverrides& v = o.model;
  LadarModel m = o.sensor == "cyclone" ? LadarModel::Cyclone(v.points > 0 ? v.points : 2048) : LadarModel::Typhoon();
  if (v.points > 0 && v.points != m.num_points) {
    m.num_points = v.points;
    m.angular_resolution = 0.0;  // 2 pi / points unless given below
  }
  auto number = [](const std::string& text, const char* flag, bool angle, double* out) {
    if (!text.empty()) *out = ParseNumber(text, flag, angle);
  };
  if (!v.sensor_id.empty()) m.sensor_id = v.sensor_id;
  number(v.min_range, "--min-range", false, &m.min_range);
  number(v.max_range, "--max-range", false, &m.max_range);
  number(v.start_angle, "--start-angle", true, &m.start_angle);
  number(v.angular_resolution, "--angular-resolution", true, &m.angular_resolution);
  number(v.range_resolution, "--range-resolution", false, &m.range_resolution);
  number(v.range_sigma, "--range-sigma", false, &m.range_sigma);
  number(v.beam_divergence, "--beam-divergence", true, &m.beam_divergence);
  number(v.mixed_pixel_probability, "--mixed-pixel-probability", false, &m.mixed_pixel_probability);
  number(v.mixed_pixel_min_gap, "--mixed-pixel-min-gap", false, &m.mixed_pixel_min_gap);
  number(v.scan_rate, "--scan-rate", false, &m.scan_rate);
  if (const std::string why = m.Validate(); !why.empty()) throw UsageError("sensor model: " + why);
  return m;
}

int RunSimulation(NodeRuntime& runtime, const LadarDriverOptions& o, const LadarModel& model,
                  const Pose2& sensor_offset) {
  Bus& bus = runtime.bus();
  const LadarSimulator simulator(model, static_cast<uint64_t>(o.seed));
  const int64_t period_us = std::max<int64_t>(1, std::llround(1e6 / model.scan_rate));
  const int64_t buffer_us = std::llround(o.truth_buffer * 1e6);
  const int64_t max_gap_us = std::llround(o.max_truth_gap * 1e6);

  std::unique_ptr<StaticSegmentIndex> grid;
  std::vector<Segment> world_segments;
  if (!o.world.empty()) {
    world_segments = LoadSegmentsJson(o.world);
    grid = std::make_unique<StaticSegmentIndex>(world_segments);
    MINENAV_LOG(kInfo) << "world " << o.world << ": " << world_segments.size() << " segments";
  } else {
    Subscribe<line_map_t>(bus, o.world_channel, [&](const line_map_t& m) {
      std::vector<Segment> segments = SegmentsFromLcm(m);
      if (grid != nullptr && SameSegments(segments, world_segments)) return;
      world_segments = std::move(segments);
      grid = std::make_unique<StaticSegmentIndex>(world_segments);
      MINENAV_LOG(kInfo) << "world from " << o.world_channel << " '" << m.name << "' version " << m.version
                         << ": " << world_segments.size() << " segments";
    });
  }

  ScanSchedule schedule({.period_us = period_us, .history_us = buffer_us, .max_gap_us = max_gap_us});
  int64_t scan_id = 0;
  int64_t skipped_no_world = 0;
  Subscribe<vehicle_truth_t>(bus, o.truth_channel, [&](const vehicle_truth_t& m) {
    ScheduleNote note;
    const std::vector<DueScan> due = schedule.AddTruth(FromLcm(m), &note);
    if (note.restarted)
      MINENAV_LOG(kWarn) << o.truth_channel << " time went back by " << 1e-6 * static_cast<double>(note.went_back_us)
                         << " s: restarting the scan schedule";
    if (note.skipped_scans > 0)
      MINENAV_LOG(kWarn) << o.truth_channel << " gap of " << 1e-6 * static_cast<double>(note.gap_us) << " s: "
                         << note.skipped_scans << " scan times skipped";
    for (const DueScan& d : due) {
      if (grid == nullptr) {
        if (skipped_no_world++ % 50 == 0)
          MINENAV_LOG(kWarn) << "no world yet (waiting for " << o.world_channel << "): scan skipped";
        runtime.SetStatus(heartbeat_t::WARN, "no world");
        continue;
      }
      const LadarScan scan = simulator.Simulate(*grid, d.pose, sensor_offset, d.utime, scan_id++);
      Publish(bus, o.scan_channel, ToLcm(scan));
      runtime.SetStatus(heartbeat_t::OK, "");
    }
  });
  runtime.SetStatus(heartbeat_t::WARN, "waiting for " + o.truth_channel);
  runtime.OnShutdown([&] { MINENAV_LOG(kInfo) << scan_id << " scans published"; });
  return runtime.Run();
}

int RunReplay(NodeRuntime& runtime, const LadarDriverOptions& o) {
  LogReader reader(o.replay);
  Bus& bus = runtime.bus();
  NodeRuntime::InstallSignalHandlers();
  std::optional<int64_t> log_t0, clock_t0;
  int64_t published = 0, bad = 0;
  const int64_t start = runtime.NowUtime();
  const int64_t run_for_us = std::llround(runtime.options().run_for * 1e6);
  auto out_of_time = [&] { return run_for_us > 0 && runtime.NowUtime() - start >= run_for_us; };
  while (!runtime.StopRequested() && !out_of_time()) {
    const LogEvent* e = reader.NextInPlace();
    if (e == nullptr) break;
    if (e->channel != o.scan_channel) continue;
    ladar_scan_t scan{};
    std::string error;
    if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &scan, &error)) {
      bus.ReportBad(e->channel, o.replay + ": " + error);
      ++bad;
      continue;
    }
    if (!log_t0) {
      log_t0 = e->timestamp;
      clock_t0 = runtime.NowUtime();
    }
    const int64_t due =
        *clock_t0 + std::llround(static_cast<double>(e->timestamp - *log_t0) / o.replay_speed);
    // Wait for the recorded time, still serving heartbeats and signals.
    while (!runtime.StopRequested() && !out_of_time() && runtime.NowUtime() < due)
      runtime.SpinOnce(due - runtime.NowUtime());
    if (runtime.StopRequested() || out_of_time()) break;
    bus.Publish(o.scan_channel, e->data.data(), static_cast<int>(e->data.size()));
    bus.CountHandled();
    ++published;
  }
  MINENAV_LOG(kInfo) << "replayed " << published << " scans from " << o.replay << (bad ? ", " : "")
                     << (bad ? std::to_string(bad) + " bad skipped" : "");
  runtime.Shutdown();
  return 0;
}

int Main(int argc, char** argv) {
  ConfigSchema schema("ladar_driver",
                      "Ladar scans on LADAR_SCAN: simulated from SIM_TRUTH and the world, or replayed from a log.");
  NodeRuntime runtime("ladar_driver", schema);
  LadarDriverOptions o;
  Declare(schema, o);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  const LadarModel model = BuildModel(o);
  const std::vector<double> p = ParseNumberList(o.sensor_pose, "--sensor-pose", 3);
  const Pose2 sensor_offset(p[0], p[1], NormalizeAngle(p[2]));
  if (!o.replay.empty() && !runtime.options().log.empty())
    throw UsageError("--replay and --log cannot be used together");
  runtime.Start();
  if (!o.replay.empty()) return RunReplay(runtime, o);
  MINENAV_LOG(kInfo) << model.sensor_id << ": " << model.num_points << " points at " << model.scan_rate
                     << " Hz, " << model.min_range << "-" << model.max_range << " m, sigma "
                     << model.range_sigma << " m";
  return RunSimulation(runtime, o, model, sensor_offset);
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("ladar_driver", [&] { return minenav::Main(argc, argv); });
}
