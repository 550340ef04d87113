#pragma once
// The cutter (thesis 6.4.1, Figure 43): the sump-shear cycle as a state machine.
//
//   square up  turn in place until the heading is the face's normal, then tram (boom up,
//              drum off) until the drum's front is `standoff` from the face;
//   sump in    drum on, SUMP, drive into the face at `sump_speed` until the drum's front is
//              `sump_step` deeper (the last sump: the cut's depth);
//   shear down SHEAR: the tracks stop and the boom falls to the floor; meanwhile a pose
//              estimate taken with the tracks stopped confirms the depth reached;
//   cusp       back up `cusp_distance` with the drum turning, then raise the boom;
//   repeat until perception (the pose estimate) confirms the desired depth, then drum off;
//   withdraw  back straight out of the cut until the drum's front is `withdraw_gap` before the
//              face the cut started from: the miner leaves the cut with the cut's walls
//              beside it rather than inside them, so the next path starts in free space.
//
// Squaring up deviates from the thesis, which drives the miner into the wall and lets the
// tracks push until the heading is right: the simulator has no contact forces, so the
// cutter turns in place to the face's normal instead.
//
// Inputs: the pose estimate (POSE; never ground truth) and the odometry since it (the
// prediction between estimates, common/odometry_chain.h), the face line (given, or found in
// the map ahead of the vehicle: FindFace), the appendages' CutterState. Outputs: drive
// commands and cutter commands. It stops safely and says why in one line when the face is
// out of reach, when the face does not advance (stall), when the pose goes stale during a
// sump, when the appendages' state goes stale or the vehicle refuses a command.
//
// Plain C++: no LCM, no clock (times are arguments), no threads, no simulator.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/pose2.h"
#include "common/vehicle_state.h"
#include "tracker/cutter_messages.h"

namespace minenav {

struct CutterOptions {
  double reach = 5.0;              // m, vehicle pose to the front of the drum (the vehicle's cutterhead.reach)
  double width = 3.3;              // m, drum width (the vehicle's cutterhead.width)
  double boom_top = 2.4;           // m, the boom is raised to this (the vehicle's max_boom_height)
  double boom_tolerance = 0.02;    // m
  double max_face_distance = 3.0;  // m: a face farther ahead of the drum is out of reach
  double max_square_angle = 0.6;   // rad: the face's normal at most this far off the heading
  double heading_tolerance = 0.005;  // rad: squared up
  double turn_rate = 0.03;         // rad/s, turning in place to square up
  double approach_speed = 0.05;    // m/s, tramming to the face
  double standoff = 0.1;           // m, drum front to face before the drum starts
  double sump_speed = 0.02;        // m/s
  double sump_step = 0.5;          // m of face advance per sump
  double depth_tolerance = 0.02;   // m: the cut is done when the confirmed depth is within this of the target
  double cusp_distance = 0.3;      // m backed up with the drum turning
  double cusp_speed = 0.03;        // m/s
  double withdraw_gap = 0.5;       // m, drum front to the face the cut started from at the end (0: no withdrawal)
  double max_pose_age = 2.0;       // s: an older pose estimate while moving stops the cut
  double stall_time = 15.0;        // s of sumping ...
  double stall_distance = 0.02;    // m ... with less advance than this is a stall
  double state_timeout = 2.0;      // s without CUTTER_STATE stops the cut
  double resend_period = 1.0;      // s between repeats of an unacknowledged cutter command
  double command_timeout = 0.2;    // s, validity of each drive command (two 10 Hz periods, as the tracker)
  int max_cycles = 20;             // sump-shear cycles at most
};

std::string ValidateCutterOptions(const CutterOptions& o);

class OptionScope;
void DeclareOptions(OptionScope scope, CutterOptions& o);

// A cut: `depth` m into the face, the face line given or (none) found in the map.
struct CutTask {
  int64_t id = 0;
  double depth = 0.0;
  std::optional<Segment> face;
};

// The face ahead of the vehicle in `map`: rays along the heading across the drum's width
// (from the vehicle's centre), hits between the drum's front (less half a metre) and
// max_face_distance beyond it, a least-squares line through them, clipped to the hits.
// None with fewer than three hits.
std::optional<Segment> FindFace(const std::vector<Segment>& map, const Pose2& pose, const CutterOptions& o);

struct CutterStatus {
  enum class State { kIdle = 0, kActive = 1, kDone = 2, kFailed = 3, kCanceled = 4 };
  State state = State::kIdle;
  int64_t task_id = 0;
  std::string step = "idle";   // the cycle's step
  std::string message;         // one line: the reason when failed, a summary when done
  double depth = 0.0;          // m, confirmed depth of cut so far
  double target = 0.0;         // m
  int cycles = 0;              // sump-shear cycles completed
  double progress() const { return target > 0.0 ? std::clamp(depth / target, 0.0, 1.0) : 0.0; }
};

class Cutter {
 public:
  explicit Cutter(CutterOptions options);

  // Starts a cut at `now` from the latest pose estimate: "" when accepted, else the
  // one-line refusal (also the status's message; the status is then kFailed).
  std::string Start(const CutTask& task, const std::optional<StampedPose>& pose, const std::vector<Segment>& map,
                    int64_t now);
  // Ends an active cut (tracks stop, drum off) with `why`: state canceled.
  void Cancel(const std::string& why);

  void AddOdometry(const OdometryReading& reading);

  struct Output {
    std::optional<DriveCommand> drive;    // every update while active, a last STOP when it ends
    std::optional<CutterCommand> cutter;  // when the appendages must be told something
  };
  // One control step at `now` with the latest pose estimate and appendage state.
  Output Update(int64_t now, const std::optional<StampedPose>& pose, const std::optional<CutterState>& state);

  const CutterStatus& status() const { return status_; }
  bool active() const { return status_.state == CutterStatus::State::kActive; }
  const CutterOptions& options() const { return options_; }
  // The face of the active (or last) cut and its unit normal into the coal.
  const Segment& face() const { return face_; }
  // m: how far the drum's front at `pose` lies beyond the face the cut started from.
  double DepthAt(const Pose2& pose) const;

 private:
  enum class Step { kIdle, kRaiseBoom, kSquare, kApproach, kDrumOn, kSump, kShear, kCusp, kRaise, kFinish, kWithdraw, kEnded };
  void Enter(Step step, int64_t now);
  void Fail(const std::string& why);
  std::optional<Pose2> Predict(const StampedPose& pose) const;
  // The command to send for this step: once, then every resend_period until acknowledged.
  std::optional<CutterCommand> Send(CutterCommand::Action action, double boom, int64_t now);
  DriveCommand Drive(DriveCommand::Mode mode, double v, double omega, int64_t now) const;
  static const char* StepName(Step s);

  CutterOptions options_;
  CutterStatus status_;
  Step step_ = Step::kIdle;
  Segment face_;
  Eigen::Vector2d normal_ = Eigen::Vector2d::UnitX();
  double face_offset_ = 0.0;  // face line's offset along normal_
  double heading_ = 0.0;      // desired heading (normal_)
  double cycle_target_ = 0.0;
  int64_t started_ = 0;
  int64_t step_since_ = 0;
  std::optional<int64_t> sent_at_;
  bool acknowledged_ = false;
  bool stop_sent_ = false;
  int64_t seq_ = 0;
  std::optional<double> confirmed_;     // depth confirmed during this shear
  std::optional<int64_t> down_since_;   // the shear reached the floor
  std::optional<StampedPose> stall_ref_;
  std::optional<Pose2> cusp_start_;
  std::deque<OdometryReading> odometry_;
};

}  // namespace minenav
