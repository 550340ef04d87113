#include "sim/vehicle_sim.h"

#include <algorithm>
#include <utility>

#include "common/config.h"
#include "common/pose_text.h"

namespace minenav {

void DeclareOptions(OptionScope s, VehicleSimOptions& o) {
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
  s.AddDouble("map_period", &o.map_period, "s", "republish SIM_WORLD and LINE_MAP this often", 0.05, 3600.0);
  DeclareOptions(s.Nested("vehicle"), o.vehicle);
  DeclareOptions(s.Nested("odometry"), o.odometry);
  DeclareOptions(s.Nested("cutterhead"), o.cutterhead);
}

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

ScenarioOptions GeneratorOptions(const VehicleSimOptions& o) {
  ScenarioOptions g;
  g.kind = o.generate;
  g.seed = static_cast<uint64_t>(o.seed);
  g.mine.pillar_rows = g.research.pillar_rows = o.pillar_rows;
  g.mine.pillar_cols = g.research.pillar_cols = o.pillar_cols;
  g.mine.pillar_size = o.pillar_size;
  g.mine.room_width = o.room_width;
  return g;
}

void ValidateVehicleSimOptions(const VehicleSimOptions& o) {
  if (std::string why = ValidateSkidSteerOptions(o.vehicle); !why.empty()) throw UsageError(why);
  if (std::string why = ValidateOdometryErrorOptions(o.odometry); !why.empty()) throw UsageError(why);
  if (std::string why = ValidateCutterheadOptions(o.cutterhead); !why.empty()) throw UsageError(why);
}

std::optional<Pose2> StartPose(const VehicleSimOptions& o) {
  if (o.start_pose == "auto") return std::nullopt;
  return ParsePoseText(o.start_pose, "--start-pose");
}

// --- WorldTimeline

WorldTimeline::WorldTimeline(SimScenario scenario, bool line_map_each)
    : scenario_(std::move(scenario)),
      line_map_each_(line_map_each),
      world_(scenario_.world),
      name_(scenario_.name) {}

bool WorldTimeline::Advance(int64_t now) {
  if (!first_tick_) first_tick_ = now;
  bool changed = false;
  while (next_change_ < scenario_.changes.size() && now - *first_tick_ >= scenario_.changes[next_change_].at_us) {
    const WorldChange& change = scenario_.changes[next_change_];
    world_.ReplaceSegments(world_.Ids(), change.world);
    name_ = change.name;
    ++map_version_;
    ++next_change_;
    changed = true;
  }
  return changed;
}

bool WorldTimeline::Edit(const std::function<bool(minenav::World*)>& edit) {
  if (!edit(&world_)) return false;
  ++map_version_;
  return true;
}

MapSnapshot WorldTimeline::World() const {
  return {world_.Segments(), static_cast<int64_t>(world_.version()), name_};
}

MapSnapshot WorldTimeline::LineMap() const {
  if (line_map_each_) return {world_.Segments(), map_version_, name_};
  return {scenario_.map, 0, scenario_.name + " (surveyed map)"};
}

double WorldTimeline::SecondsSinceStart(int64_t now) const {
  return first_tick_ ? static_cast<double>(now - *first_tick_) * 1e-6 : 0.0;
}

// --- SimulatedVehicle

SimulatedVehicle::SimulatedVehicle(const VehicleSimOptions& o, const Pose2& start)
    : vehicle_(o.vehicle, start), odometry_(o.odometry, start, static_cast<uint64_t>(o.seed) * 7919 + 1) {}

SimulatedVehicle::Tick SimulatedVehicle::Step(int64_t now, const std::optional<DriveCommand>& command) {
  if (last_tick_) {
    const double dt = std::clamp(static_cast<double>(now - *last_tick_) * 1e-6, 0.0, 1.0);
    const MotionIncrement inc = command ? vehicle_.Step(dt, *command, now) : vehicle_.StepWithoutCommand(dt);
    odometry_.AddIncrement(inc);
  }
  last_tick_ = now;
  Tick tick;
  tick.stale = vehicle_.stale();
  tick.stale_changed = tick.stale != was_stale_;
  was_stale_ = tick.stale;
  tick.truth.utime = now;
  tick.truth.seq = seq_;
  tick.truth.pose = vehicle_.pose();
  tick.truth.v = vehicle_.v();
  tick.truth.omega = vehicle_.omega();
  tick.odometry = odometry_.Reading(now);
  tick.odometry.seq = seq_;
  ++seq_;
  return tick;
}

}  // namespace minenav
