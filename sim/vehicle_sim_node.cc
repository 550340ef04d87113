#include "sim/vehicle_sim_node.h"

#include <algorithm>
#include <utility>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "sim/world.h"
#include "tracker/cutter_conversions.h"

namespace minenav {

void DeclareOptions(ConfigSchema& s, VehicleSimNodeOptions& o) {
  const OptionScope root(s);
  DeclareOptions(root, o.sim);
  // The flat flags of before the options nested (issue 12).
  root.Nested("vehicle").AddFlatAliases({"max_forward_speed", "max_reverse_speed", "turn_radius",
                                         "max_turn_in_place_rate", "max_acceleration", "max_deceleration",
                                         "max_yaw_acceleration", "min_speed", "command_timeout"});
  root.Nested("odometry").AddFlatAliases({"scale_error", "rotation_scale_error", "heading_drift_per_metre",
                                          "heading_drift_per_second", "translation_noise", "rotation_noise"},
                                         "odometry_");
  s.AddChannel("drive_channel", &o.drive_channel, "subscribes", "drive_command_t", "commands to the vehicle");
  s.AddChannel("truth_channel", &o.truth_channel, "publishes", "vehicle_truth_t", "true pose at --rate");
  s.AddChannel("odometry_channel", &o.odometry_channel, "publishes", "odometry_t",
               "dead-reckoned pose with drift at --rate");
  s.AddChannel("world_channel", &o.world_channel, "publishes", "line_map_t",
               "the world the ladar sees (version = world version)");
  s.AddChannel("map_channel", &o.map_channel, "publishes", "line_map_t",
               "surveyed map for estimators (the mockup's lacks its clutter)");
  s.AddChannel("cutter_command_channel", &o.cutter_command_channel, "subscribes", "cutter_command_t",
               "commands to the cutter appendages");
  s.AddChannel("cutter_state_channel", &o.cutter_state_channel, "publishes", "cutter_state_t",
               "the appendages: boom, drum, sumped depth, coal removed, refusals");
  s.AddDouble("cutter_state_period", &o.cutter_state_period, "s", "publish CUTTER_STATE this often", 0.01, 60.0);
  s.AddHelpEpilog(R"(Examples:
  vehicle_sim --generate mine --seed 7
  vehicle_sim --world mine.json --start-pose 3,3,0 --max-forward-speed 0.3
  vehicle_sim --log commands.lcm --log-out run.lcm     (batch, deterministic)
  vehicle_sim --world closed.json --world open.json --world-change-at 30   (a door opens at 30 s)
)");
}

SimScenario PrepareScenario(const VehicleSimOptions& o, const std::vector<std::string>& world_flags) {
  ValidateVehicleSimOptions(o);
  // Flags beat a config file's `world =` line, as for every other option.
  std::vector<std::string> files = world_flags;
  if (files.empty() && !o.world.empty()) files.push_back(o.world);
  const std::vector<int64_t> change_at_us = ParseWorldChangeTimes(o.world_change_at, files.size());
  std::vector<NamedWorld> worlds;
  for (const std::string& file : files) worlds.push_back({file, World::Load(file).Segments()});
  SimScenario scenario = MakeSimScenario(worlds, change_at_us, GeneratorOptions(o), StartPose(o));
  if (!o.world_out.empty()) World(scenario.world).Save(o.world_out);
  if (!o.map_out.empty()) World(scenario.map).Save(o.map_out);
  return scenario;
}

VehicleSimNode::VehicleSimNode(NodeRuntime& runtime, const VehicleSimNodeOptions& options, SimScenario scenario)
    : runtime_(runtime),
      options_(options),
      world_(scenario, options.sim.line_map == "each"),
      vehicle_(options.sim, scenario.start),
      cutter_(options.sim.cutterhead, options.sim.cutterhead.max_boom_height) {
  MINENAV_LOG(kInfo) << scenario.name << ": " << world_.size() << " segments, start " << scenario.start;
  Subscribe<drive_command_t>(runtime_.bus(), options_.drive_channel, [this](const drive_command_t& m) {
    DriveCommand c = FromLcm(m);
    c.utime = runtime_.NowUtime();
    command_ = c;
  });
  Subscribe<cutter_command_t>(runtime_.bus(), options_.cutter_command_channel, [this](const cutter_command_t& m) {
    std::string why;
    const std::optional<CutterCommand> c = CutterCommandFromLcm(m, &why);
    if (!c) {
      MINENAV_LOG(kWarn) << options_.cutter_command_channel << ": " << why;
      return;
    }
    cutter_.Command(*c, vehicle_.pose(), runtime_.NowUtime());
    PublishCutterState(runtime_.NowUtime());
  });
  // The world first, so a ladar starting with us has it before the first truth sample.
  runtime_.AddTimer(options_.sim.map_period, [this](int64_t now) {
    if (!ChangeWorld(now)) PublishWorld(now);
  });
  runtime_.AddTimer(1.0 / options_.sim.rate, [this](int64_t now) { Tick(now); });
  runtime_.AddTimer(options_.cutter_state_period, [this](int64_t now) { PublishCutterState(now); });
}

void VehicleSimNode::PublishWorld(int64_t now) {
  const MapSnapshot world = world_.World();
  Publish(runtime_.bus(), options_.world_channel, SegmentsToLcm(world.segments, now, world.version, world.name));
  const MapSnapshot map = world_.LineMap();
  Publish(runtime_.bus(), options_.map_channel, SegmentsToLcm(map.segments, now, map.version, map.name));
}

bool VehicleSimNode::ChangeWorld(int64_t now) {
  if (!world_.Advance(now)) return false;
  MINENAV_LOG(kInfo) << "world changed at " << world_.SecondsSinceStart(now) << " s to " << world_.name() << ": "
                     << world_.size() << " segments, version " << world_.version();
  PublishWorld(now);
  return true;
}

void VehicleSimNode::Tick(int64_t now) {
  ChangeWorld(now);
  std::optional<DriveCommand> command = command_;
  if (command) command = cutter_.FilterDrive(*command, vehicle_.pose(), world_.world(), now);
  const SimulatedVehicle::Tick tick = vehicle_.Step(now, command);
  const double dt = last_tick_ ? std::clamp(static_cast<double>(now - *last_tick_) * 1e-6, 0.0, 1.0) : 0.0;
  last_tick_ = now;
  if (world_.Edit([&](World* w) { return cutter_.Step(dt, tick.truth.pose, w, now); })) {
    MINENAV_LOG(kInfo) << "coal cut: " << world_.size() << " segments, version " << world_.version();
    PublishWorld(now);
  }
  if (tick.stale_changed) {
    if (tick.stale && command_) MINENAV_LOG(kInfo) << "commands stale: stopping";
    runtime_.SetStatus(heartbeat_t::OK, tick.stale ? "idle: no fresh command" : "driving");
  }
  Publish(runtime_.bus(), options_.truth_channel, ToLcm(tick.truth));
  Publish(runtime_.bus(), options_.odometry_channel, ToLcm(tick.odometry));
}

void VehicleSimNode::PublishCutterState(int64_t now) {
  Publish(runtime_.bus(), options_.cutter_state_channel, ToLcm(cutter_.State(now)));
}

}  // namespace minenav
