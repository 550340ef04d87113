#pragma once
// The path tracker (thesis 6.4.2; tracker/README.md): pure pursuit (pure_pursuit.h) along
// the runs of a planned path, one Update per control tick with the vehicle's pose, giving the
// drive command and the path's state. Plain C++: no clock (the caller passes the pose it
// has), no LCM.
//
// Per tick, on a driving run:
//   1. project the pose on the run (the nearest sample ahead of the last one);
//   2. the run is done when the pose is within position_tolerance of its end or past it:
//      stop there (a cusp: the next run starts from standstill);
//   3. far off (|cross-track| > max_cross_track) or pointing away (|bearing of the goal
//      point| > max_heading_error, or an arc tighter than turn_in_place_curvature): turn in
//      place towards the goal point until within align_tolerance (a "correction");
//   4. else the curvature to the goal point one lookahead ahead (at least lookahead_time of
//      cruise), quantised;
//   5. the speed: cruise, regulated (slower where the pursuit arc is tighter than
//      regulated_min_radius, near walls, approaching the run's end);
//   6. the commanded motion over collision_time (at least collision_min_distance, at most
//      what is left of the run or turn plus a few cm or a degree, but never less than the
//      stopping distance from the last commanded speed at `deceleration`) is checked
//      against the map with the planner's collision checker; a motion that would touch a
//      wall is replaced by another of the same direction (straight, arc left, arc right, the
//      nearest the pursuit curvature first) when that is free, else the vehicle stops and
//      the path is abandoned as blocked, with the reason.
// At a cusp between two driving runs it first turns in place to the next run's start heading
// (within heading_tolerance; skipped when that turn would touch the map). A turn-in-place run
// turns to its end heading. After the last run, the heading is aligned
// to the goal's within heading_tolerance (turning in place, also collision-checked); then the
// path is done, or failed when the pose ended farther than goal_tolerance from the goal.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "common/vehicle_state.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/se2_planner.h"
#include "tracker/pure_pursuit.h"

namespace minenav {

struct PathTrackerOptions {
  double lookahead = 0.6;               // m, goal point distance along the path (the least)
  double lookahead_time = 0.0;          // s, the lookahead grows to cruise_speed x this when longer (0 = fixed)
  double turn_radius = 4.0;             // m, the miner's one turning radius
  double straight_deadband = 0.02;      // 1/m, |curvature| below which the command is straight
  double turn_in_place_curvature = 1.0; // 1/m, |curvature| above which it turns in place first
  double max_cross_track = 0.75;        // m, farther off the path it turns in place towards it first
  double max_heading_error = 0.6;       // rad, goal-point bearing above which it turns in place first
  double align_tolerance = 0.05;        // rad, a correction turn ends within this of the bearing
  double cruise_speed = 0.076;          // m/s, speed on straight stretches (the miner's 3 in/s)
  double turn_rate = 0.05;              // rad/s, largest turn-in-place rate
  double min_turn_rate = 0.005;         // rad/s, least turn-in-place rate (slowing into the target)
  double turn_gain = 1.0;               // 1/s, turn-in-place rate per rad of heading error
  double position_tolerance = 0.02;     // m, a run's end counts as reached this close (along its tangent)
  double heading_tolerance = 0.0087;    // rad, final and turn-in-place heading tolerance (0.5 deg)
  double goal_tolerance = 0.10;         // m, a path that ends farther than this from its goal failed
  bool regulated = true;                // false = plain pure pursuit: cruise everywhere
  double regulated_min_radius = 8.0;    // m, a pursuit arc tighter than this slows down by radius / this
  double near_obstacle_distance = 0.5;  // m, closer to a wall than this the speed scales down
  double min_obstacle_speed_factor = 0.3;  // least fraction of the speed near walls
  double approach_distance = 0.3;       // m, before a stop the speed scales with the distance left
  double min_approach_speed = 0.005;    // m/s, least speed approaching a stop
  double collision_time = 3.0;          // s of the commanded motion checked against the map
  double collision_min_distance = 0.15; // m, least distance checked ahead (rad x 1 m turning)
  double deceleration = 0.1;            // m/s^2, the vehicle's braking (the check covers its stopping distance)
  double collision_margin = 0.0;        // m, clearance the checked motion must keep from the walls
  double sample_step = 0.02;            // m between the path's samples
  double search_window = 1.0;           // m along the run searched for the nearest sample
  // s, validity of each command: two periods at 10 Hz, so a tracker that dies leaves the vehicle
  // stopped within 200 ms of its next command being overdue (issue 16; one late tick is
  // forgiven). bus.vehicle_stops_within_200ms_of_a_loss measures it.
  double command_timeout = 0.2;
};

// "" when usable, else one line naming the option (and, for options that contradict each
// other, what the contradiction is, in words).
std::string ValidatePathTrackerOptions(const PathTrackerOptions& o);

class OptionScope;
void DeclareOptions(OptionScope scope, PathTrackerOptions& o);

// The map the tracker checks its motion against: the planner's collision checker
// (Se2Planner::PieceCollides, FootprintCollisionChecker) and, for the speed regulation, the
// distance from the footprint to the nearest wall (common/segment_index.h).
class TrackerMap {
 public:
  TrackerMap(std::vector<Segment> segments, const Footprint& footprint, double margin, double turn_radius);
  // "" when usable.
  const std::string& error() const { return planner_.setup_error(); }
  bool PieceCollides(const Pose2& from, const MotionPiece& piece) const { return planner_.PieceCollides(from, piece); }
  bool PoseFree(const Pose2& pose) const { return planner_.PoseFree(pose); }
  // m, distance from the footprint at `pose` to the nearest wall, capped at `cap`.
  double Clearance(const Pose2& pose, double cap) const;
  size_t size() const { return planner_.map().size(); }

 private:
  Se2Planner planner_;
  StaticSegmentIndex walls_;
  Footprint footprint_;
  double circumscribed_;
};

enum class TrackState { kIdle, kActive, kDone, kFailed, kBlocked };
const char* ToString(TrackState s);

struct TrackStep {
  DriveCommand command;             // utime and seq are the caller's
  TrackState state = TrackState::kIdle;
  std::string message;              // one line: the reason of a failure or block, or the motion
  QuantisedMotion motion = QuantisedMotion::kStraight;
  double cross_track = 0.0;         // m, on driving runs (0 elsewhere)
  double progress = 0.0;            // 0..1 of the path's length and turns
  bool finished_now = false;        // the state became done / failed / blocked this tick
  double left = 0.0;                // m of the run still to drive (driving runs)
  double curvature = 0.0;           // 1/m, the pursuit curvature before quantising
};

class PathTracker {
 public:
  PathTracker(PathTrackerOptions options, Footprint footprint);

  // A new path replaces the current one. With a map, a path whose pieces collide with it is
  // refused at once (state blocked, the piece named). speed_limits: m/s per piece (path_t's
  // segment speed; 0 = none), or empty: the tracker never drives faster than the limit of the
  // stretch from the vehicle to its goal point and its stopping distance. Returns the state.
  TrackState SetPath(const PlannedPath& path, const std::vector<double>& speed_limits = {});
  // Replaces the map (nullptr: none; then nothing is collision-checked).
  void SetMap(std::shared_ptr<const TrackerMap> map);
  // Forgets the path (the vehicle stops).
  void Cancel(const std::string& why);

  // The command for the vehicle at `pose`.
  TrackStep Update(const Pose2& pose);

  TrackState state() const { return state_; }
  const std::string& message() const { return message_; }
  int corrections() const { return corrections_; }  // turn-in-place corrections so far
  int run_index() const { return run_; }
  size_t run_count() const { return runs_.size(); }
  const PathTrackerOptions& options() const { return options_; }
  const Footprint& footprint() const { return footprint_; }

 private:
  TrackStep Step(const Pose2& pose);
  // m the vehicle may still travel braking from the last commanded speed.
  double StoppingDistance() const;
  TrackStep Stop(const std::string& message) const;
  TrackStep Finish(TrackState state, const std::string& message);
  // nullopt when the commanded motion is free; else the step to take instead: another
  // motion of the same direction that is free, or the block (stop, path abandoned).
  // `left`: what remains of the planned motion (m driving, rad turning); the check covers
  // min(collision_time of the command, left + a small overshoot).
  std::optional<TrackStep> CheckAhead(const Pose2& pose, const TrackStep& step, double left);
  TrackStep Turn(double heading_error, const std::string& what);
  // The turn in place the check ahead covers for a yaw rate and what is left of the turn (rad).
  MotionPiece TurnPiece(const Pose2& pose, double omega, double left) const;
  TrackStep Drive(const Pose2& pose);
  double Progress() const;

  PathTrackerOptions options_;
  Footprint footprint_;
  std::shared_ptr<const TrackerMap> map_;
  PlannedPath path_;
  std::vector<TrackedRun> runs_;
  int run_ = 0;
  int hint_ = 0;
  bool correcting_ = false;
  bool aligning_goal_ = false;
  bool cusp_aligned_ = false;   // the current run's start heading was taken at its cusp
  bool aligning_cusp_ = false;  // turning to it
  int corrections_ = 0;
  double last_speed_ = 0.0;  // m/s, of the last velocity command
  double done_length_ = 0.0;
  double total_length_ = 0.0;
  TrackState state_ = TrackState::kIdle;
  std::string message_;
};

}  // namespace minenav
