#pragma once
// The continuous miner's cutterhead in the simulator (thesis 6.4.1, Figure 43): a drum
// `width` wide of radius `drum_radius` across the front of the miner, its front `reach`
// ahead of the vehicle pose, on a boom that rises at `boom_rate` and falls to the floor by
// gravity in `shear_time` when shearing. It obeys CUTTER_COMMAND (tracker/cutter_messages.h)
// and removes coal from the world: when a shear reaches the floor the plan area the drum
// swept since the SUMP becomes free space (World::CutRegion), so the ladar sees the new face.
//
// The appendage order constraints of 6.2.1 are enforced here, in the vehicle, whatever the
// controller asks; a refused command gets a one-line reason in CutterState::message:
//   - SUMP and SHEAR need the drum turning;
//   - no tramming with the head down: below `tram_height` the tracks may only back up with
//     the drum turning (cusp removal);
//   - the tracks stay stopped while shearing;
//   - the drum cannot be driven into the face without turning (the simulator has no contact
//     model otherwise: a forward command with the drum off and a wall within `contact_margin`
//     ahead of the drum is refused and the vehicle stops). This one holds once the
//     appendages have been commanded (any command but IDLE): a vehicle nobody cuts with
//     keeps the plain kinematics of before (surveys drive the pose, a point, up to walls
//     the 10 m miner's front would be in).
// Plain C++: no LCM, no clock; the node (sim/vehicle_sim_node.h) feeds it.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "common/vehicle_state.h"
#include "sim/world.h"
#include "tracker/cutter_messages.h"

namespace minenav {

struct CutterheadOptions {
  double width = 3.3;          // m, across the vehicle (the cut's width)
  double drum_radius = 0.5;    // m
  double reach = 5.0;          // m from the vehicle pose to the front of the drum (half the 10 m miner)
  double max_boom_height = 2.4;  // m, the boom's top (the seam height)
  double tram_height = 0.5;    // m: below it the miner may not tram
  double boom_rate = 0.2;      // m/s, raising (and lowering on SET_BOOM)
  double shear_time = 12.0;    // s from the top to the floor under gravity
  double contact_margin = 0.02;  // m ahead of the drum where a wall counts as touching it
  double refusal_hold = 2.0;   // s a refusal stays in CutterState::message
};

std::string ValidateCutterheadOptions(const CutterheadOptions& o);

class OptionScope;
void DeclareOptions(OptionScope scope, CutterheadOptions& o);

class Cutterhead {
 public:
  explicit Cutterhead(const CutterheadOptions& options, double initial_boom_height);

  // Applies a command received at `now` with the vehicle (truly) at `pose`. A refusal is
  // kept in the state's message.
  void Command(const CutterCommand& command, const Pose2& pose, int64_t now);
  // The drive command the vehicle obeys: `command` itself, or a STOP (and a refusal in the
  // message) when it breaks an order constraint. `world` is what the drum may touch.
  DriveCommand FilterDrive(const DriveCommand& command, const Pose2& pose, const World& world, int64_t now);
  // Advances the boom over dt with the vehicle at `pose`; when a shear reaches the floor,
  // cuts the swept area out of `world` (free point: the vehicle pose) and adds its solid
  // area to coal_removed. True if the world changed.
  bool Step(double dt, const Pose2& pose, World* world, int64_t now);

  CutterState State(int64_t now) const;
  const CutterheadOptions& options() const { return options_; }
  // The drum's plan rectangle (world frame, counter-clockwise) at `pose`, extended back by
  // `behind` m: what a sump of that depth swept.
  std::vector<Eigen::Vector2d> DrumArea(const Pose2& pose, double behind) const;

 private:
  void Refuse(const std::string& why, int64_t now);
  bool InContact(const Pose2& pose, const World& world) const;

  CutterheadOptions options_;
  CutterState::Phase phase_ = CutterState::Phase::kIdle;
  bool drum_on_ = false;
  bool engaged_ = false;  // a command other than IDLE has come
  double boom_ = 0.0;
  double boom_target_ = 0.0;
  double sumped_ = 0.0;
  double coal_removed_ = 0.0;
  std::optional<Pose2> sump_start_;  // the vehicle pose at the SUMP
  std::string message_;
  int64_t message_at_ = 0;
};

// m^2 of the rectangle [x0, x1] x [-half_width, half_width] in the frame of `frame` that is
// solid in `world` (not in the same space as `free_point`), sampled every `step_x` m along x
// and `step_y` m across.
double SolidArea(const World& world, const Pose2& frame, double x0, double x1, double half_width,
                 const Eigen::Vector2d& free_point, double step_x = 0.01, double step_y = 0.1);

}  // namespace minenav
