#pragma once
// vehicle_sim's simulation, plain C++ (the node in vehicle_sim_node.h publishes it): the
// options, the scenario they make, the world over time (a changing world, thesis 4.8) and
// the miner stepped over clock time with its dead-reckoned odometry (App. D, 6.4).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/vehicle_state.h"
#include "sim/cutterhead.h"
#include "sim/odometry_model.h"
#include "sim/scenario.h"
#include "sim/skid_steer.h"
#include "sim/world.h"

namespace minenav {

struct VehicleSimOptions {
  std::string world;              // JSON file; "" = generate (on the command line: repeatable)
  std::string world_change_at;    // "T1,T2,..." s since the first tick; one per extra --world
  std::string line_map = "first"; // first | each: what LINE_MAP carries in a changing world
  std::string generate = "mine";  // mine | research | mockup
  int64_t seed = 1;               // of the generator and (derived) of the odometry noise
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
  // The cutter appendages (thesis 6.4.1; sim/cutterhead.h); the boom starts at its top.
  CutterheadOptions cutterhead;
};

class OptionScope;
// Declares every field under `scope`, the vehicle as vehicle.* and the odometry as
// odometry.*.
void DeclareOptions(OptionScope scope, VehicleSimOptions& o);

// Takes every --world FILE / --world=FILE out of `args` (the flag repeats for a changing
// world, which a schema's one value per key cannot hold). Throws UsageError for a --world
// without a file.
std::vector<std::string> TakeWorldFlags(std::vector<std::string>* args);

// The generator's options for --generate (the pillar counts serve mine and research alike).
ScenarioOptions GeneratorOptions(const VehicleSimOptions& o);
// Throws UsageError when the kinematics or the odometry model are unusable.
void ValidateVehicleSimOptions(const VehicleSimOptions& o);
// --start-pose: nullopt for auto (the generator's first station, 0,0,0 for --world).
std::optional<Pose2> StartPose(const VehicleSimOptions& o);

// A segment list as it goes out on a channel.
struct MapSnapshot {
  std::vector<Segment> segments;
  int64_t version = 0;
  std::string name;
};

// The world over time: the first world, replaced by each change once its time (since the
// first Advance, the first tick) has come.
class WorldTimeline {
 public:
  // line_map_each: LINE_MAP carries the current world (version +1 per change) rather than
  // the surveyed map (version 0) of before the changes.
  WorldTimeline(SimScenario scenario, bool line_map_each);
  // Applies every change due at clock time `now` (us). True if the world changed.
  bool Advance(int64_t now);
  MapSnapshot World() const;    // what the ladar sees (version = World::version())
  MapSnapshot LineMap() const;  // the estimators' map
  // s since the first Advance.
  double SecondsSinceStart(int64_t now) const;
  size_t size() const { return world_.size(); }
  uint64_t version() const { return world_.version(); }
  const std::string& name() const { return name_; }
  // The world the ladar sees, and an edit of it in place (the cutter taking coal): `edit`
  // returns whether it changed the world (LINE_MAP follows with --line-map each).
  const minenav::World& world() const { return world_; }
  bool Edit(const std::function<bool(minenav::World*)>& edit);

 private:
  SimScenario scenario_;
  bool line_map_each_;
  minenav::World world_;
  std::string name_;
  int64_t map_version_ = 0;
  size_t next_change_ = 0;
  std::optional<int64_t> first_tick_;
};

// The miner stepped over clock time: exact skid-steer kinematics under the latest command,
// dead-reckoned odometry with the error model (seeded from the options' seed).
class SimulatedVehicle {
 public:
  SimulatedVehicle(const VehicleSimOptions& o, const Pose2& start);
  struct Tick {
    TruthReading truth;
    OdometryReading odometry;
    bool stale = true;           // no fresh command: the vehicle stops
    bool stale_changed = false;  // since the previous tick (the first tick counts from stale)
  };
  // Integrates the motion since the previous tick (capped at 1 s, so a suspended process
  // does not jump) under `command`, whose utime is when it was received, at time `now`.
  Tick Step(int64_t now, const std::optional<DriveCommand>& command);
  // The true pose now (after the last Step).
  const Pose2& pose() const { return vehicle_.pose(); }

 private:
  SkidSteerVehicle vehicle_;
  DeadReckoning odometry_;
  std::optional<int64_t> last_tick_;
  int64_t seq_ = 0;
  bool was_stale_ = true;
};

}  // namespace minenav
