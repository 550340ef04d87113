#include "sensor_driver/ladar_driver_node.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/pose_text.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"

namespace minenav {

void DeclareOptions(ConfigSchema& s, LadarDriverOptions& o) {
  const OptionScope model = OptionScope(s).Nested("model");
  DeclareOptions(model, o.model);
  // The flat flags of before the options nested (issue 12).
  model.AddFlatAliases({"sensor", "points", "sensor_id", "min_range", "max_range", "start_angle",
                        "angular_resolution", "range_resolution", "range_sigma", "beam_divergence",
                        "mixed_pixel_probability", "mixed_pixel_min_gap", "scan_rate"});
  s.AddString("sensor_pose", &o.sensor_pose, "sensor pose in the vehicle frame 'x,y,theta' (m, m, rad or deg)");
  s.AddInt64("seed", &o.seed, "seed of the range noise and mixed pixels (scans depend on seed and scan_id only)", 0);
  s.AddString("world", &o.world, "world JSON file; empty = take the world from --world-channel");
  const OptionScope schedule = OptionScope(s).Nested("schedule");
  DeclareOptions(schedule, o.schedule);
  schedule.AddAlias("truth_buffer", "history");
  schedule.AddAlias("max_truth_gap", "max_gap");
  s.AddString("replay", &o.replay, "replay mode: republish the scans of this LCM log at the recorded rate");
  s.AddDouble("replay_speed", &o.replay_speed, "x", "replay speed factor (2 = twice as fast)", 0.01, 1000.0);
  s.AddChannel("truth_channel", &o.truth_channel, "subscribes", "vehicle_truth_t", "simulation: the true pose");
  s.AddChannel("world_channel", &o.world_channel, "subscribes", "line_map_t", "simulation: the world, if no --world");
  s.AddChannel("scan_channel", &o.scan_channel, "publishes", "ladar_scan_t", "scans (replay: also read from the log)");
  s.AddHelpEpilog(R"(Examples:
  ladar_driver --sensor typhoon --seed 3              (with vehicle_sim running)
  ladar_driver --sensor cyclone --points 8192 --range-sigma 0.05 --world mine.json
  ladar_driver --log truth.lcm --log-out scans.lcm    (batch over SIM_TRUTH + SIM_WORLD)
  ladar_driver --replay dataset.lcm --replay-speed 2
)");
}

LadarSimulationSetup ResolveLadarDriver(const LadarDriverOptions& o, const NodeOptions& node) {
  LadarSimulationSetup setup;
  setup.model = BuildLadarModel(o.model, "model.");
  setup.sensor_offset = ParsePoseText(o.sensor_pose, "--sensor-pose");
  setup.schedule = o.schedule;
  setup.schedule.period_us = std::max<int64_t>(1, std::llround(1e6 / setup.model.scan_rate));
  if (!o.replay.empty() && !node.log.empty()) throw UsageError("--replay and --log cannot be used together");
  return setup;
}

// --- LadarSimulationNode

LadarSimulationNode::LadarSimulationNode(NodeRuntime& runtime, const LadarDriverOptions& options,
                                         const LadarSimulationSetup& setup)
    : runtime_(runtime),
      options_(options),
      simulator_(setup.model, static_cast<uint64_t>(options.seed)),
      sensor_offset_(setup.sensor_offset),
      schedule_(setup.schedule) {
  const LadarModel& m = setup.model;
  MINENAV_LOG(kInfo) << m.sensor_id << ": " << m.num_points << " points at " << m.scan_rate << " Hz, "
                     << m.min_range << "-" << m.max_range << " m, sigma " << m.range_sigma << " m";
  Bus& bus = runtime_.bus();
  if (!options_.world.empty()) {
    SetWorld(LoadSegmentsJson(options_.world));
    MINENAV_LOG(kInfo) << "world " << options_.world << ": " << world_.size() << " segments";
  } else {
    Subscribe<line_map_t>(bus, options_.world_channel, [this](const line_map_t& msg) { OnWorld(msg); });
  }
  Subscribe<vehicle_truth_t>(bus, options_.truth_channel, [this](const vehicle_truth_t& msg) { OnTruth(msg); });
  runtime_.SetStatus(heartbeat_t::WARN, "waiting for " + options_.truth_channel);
  runtime_.OnShutdown([this] { MINENAV_LOG(kInfo) << scan_id_ << " scans published"; });
}

void LadarSimulationNode::SetWorld(std::vector<Segment> segments) {
  world_ = std::move(segments);
  index_ = std::make_unique<StaticSegmentIndex>(world_);
}

void LadarSimulationNode::OnWorld(const line_map_t& m) {
  std::vector<Segment> segments = SegmentsFromLcm(m);
  if (index_ != nullptr && SameSegments(segments, world_)) return;  // the periodic republication
  SetWorld(std::move(segments));
  MINENAV_LOG(kInfo) << "world from " << options_.world_channel << " '" << m.name << "' version " << m.version
                     << ": " << world_.size() << " segments";
}

void LadarSimulationNode::OnTruth(const vehicle_truth_t& m) {
  ScheduleNote note;
  const std::vector<DueScan> due = schedule_.AddTruth(FromLcm(m), &note);
  const std::string& truth = options_.truth_channel;
  if (note.restarted)
    MINENAV_LOG(kWarn) << truth << " time went back by " << 1e-6 * static_cast<double>(note.went_back_us)
                       << " s: restarting the scan schedule";
  if (note.skipped_scans > 0)
    MINENAV_LOG(kWarn) << truth << " gap of " << 1e-6 * static_cast<double>(note.gap_us) << " s: "
                       << note.skipped_scans << " scan times skipped";
  for (const DueScan& d : due) {
    if (index_ == nullptr) {
      if (skipped_no_world_++ % 50 == 0)
        MINENAV_LOG(kWarn) << "no world yet (waiting for " << options_.world_channel << "): scan skipped";
      runtime_.SetStatus(heartbeat_t::WARN, "no world");
      continue;
    }
    const LadarScan scan = simulator_.Simulate(*index_, d.pose, sensor_offset_, d.utime, scan_id_++);
    Publish(runtime_.bus(), options_.scan_channel, ToLcm(scan));
    runtime_.SetStatus(heartbeat_t::OK, "");
  }
}

// --- ScanReplayNode

ScanReplayNode::ScanReplayNode(NodeRuntime& runtime, const LadarDriverOptions& options)
    : runtime_(runtime),
      options_(options),
      reader_(options.replay),
      start_utime_(runtime.NowUtime()),
      run_for_us_(std::llround(runtime.options().run_for * 1e6)) {}

bool ScanReplayNode::OutOfTime() const {
  return run_for_us_ > 0 && runtime_.NowUtime() - start_utime_ >= run_for_us_;
}

bool ScanReplayNode::WaitUntil(int64_t due) {
  // Still serving heartbeats and signals while waiting for the recorded time.
  while (!runtime_.StopRequested() && !OutOfTime() && runtime_.NowUtime() < due)
    runtime_.SpinOnce(due - runtime_.NowUtime());
  return !runtime_.StopRequested() && !OutOfTime();
}

int ScanReplayNode::Run() {
  NodeRuntime::InstallSignalHandlers();
  Bus& bus = runtime_.bus();
  const std::string& channel = options_.scan_channel;
  while (!runtime_.StopRequested() && !OutOfTime()) {
    const LogEvent* e = reader_.NextInPlace();
    if (e == nullptr) break;
    if (e->channel != channel) continue;
    ladar_scan_t scan{};
    std::string error;
    if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &scan, &error)) {
      bus.ReportBad(e->channel, options_.replay + ": " + error);
      ++bad_;
      continue;
    }
    if (!log_t0_) {
      log_t0_ = e->timestamp;
      clock_t0_ = runtime_.NowUtime();
    }
    const int64_t due =
        *clock_t0_ + std::llround(static_cast<double>(e->timestamp - *log_t0_) / options_.replay_speed);
    if (!WaitUntil(due)) break;
    bus.Publish(channel, e->data.data(), static_cast<int>(e->data.size()));
    bus.CountHandled();
    ++published_;
  }
  MINENAV_LOG(kInfo) << "replayed " << published_ << " scans from " << options_.replay << (bad_ ? ", " : "")
                     << (bad_ ? std::to_string(bad_) + " bad skipped" : "");
  runtime_.Shutdown();
  return 0;
}

}  // namespace minenav
