#include "tracker/path_tracker.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "common/angle.h"
#include "common/config.h"
#include "planner/footprint_collision.h"

namespace minenav {
namespace {

std::string Fixed(double v, int digits = 2) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}

// What the vehicle may go past the end of a planned motion before it stands still: the
// check ahead covers the rest of the motion plus this, not a full collision_time beyond it
// (the planner's path ends 5 deg turns and metres-long straights close to walls on purpose).
constexpr double kDriveOvershoot = 0.05;  // m
constexpr double kTurnOvershoot = 0.02;   // rad

// The planner's motion for a command: direction d (+1, -1, 0) and yaw sign.
Motion MotionOf(int direction, double omega) {
  if (direction == 0) return Motion::kTurnInPlace;
  if (omega == 0.0) return direction > 0 ? Motion::kForward : Motion::kReverse;
  if (direction > 0) return omega > 0 ? Motion::kArcLeft : Motion::kArcRight;
  // Reversing along a left arc turns clockwise (planner/motion.h).
  return omega > 0 ? Motion::kArcRightReverse : Motion::kArcLeftReverse;
}

}  // namespace

std::string ValidatePathTrackerOptions(const PathTrackerOptions& o) {
  if (!(o.lookahead > 0.0)) return "lookahead must be > 0";
  if (!(o.turn_radius > 0.0)) return "turn_radius must be > 0";
  if (!(o.cruise_speed > 0.0)) return "cruise_speed must be > 0";
  if (!(o.turn_rate > 0.0) || !(o.min_turn_rate > 0.0)) return "turn_rate and min_turn_rate must be > 0";
  if (o.min_turn_rate > o.turn_rate) return "min_turn_rate must not exceed turn_rate";
  if (o.straight_deadband >= 1.0 / o.turn_radius)
    return "straight_deadband must be below 1 / turn_radius (else the arc is never chosen)";
  if (o.turn_in_place_curvature <= 1.0 / o.turn_radius)
    return "turn_in_place_curvature must exceed 1 / turn_radius (else the arc is never chosen)";
  if (!(o.sample_step > 0.0)) return "sample_step must be > 0";
  if (o.search_window < o.sample_step) return "search_window must be at least sample_step";
  if (o.goal_tolerance < o.position_tolerance) return "goal_tolerance must be at least position_tolerance";
  return "";
}

void DeclareOptions(OptionScope s, PathTrackerOptions& o) {
  s.AddDouble("lookahead", &o.lookahead, "m", "goal point distance along the path (pure pursuit's lookahead)", 0.05,
              20.0);
  s.AddDouble("lookahead_time", &o.lookahead_time, "s",
              "the lookahead grows to cruise_speed times this when that is longer (Nav2's adaptive lookahead)", 0.0,
              100.0);
  s.AddDouble("turn_radius", &o.turn_radius, "m", "the miner's one turning radius besides turning in place", 0.1,
              100.0);
  s.AddDouble("straight_deadband", &o.straight_deadband, "1/m",
              "pure-pursuit curvature below which the command is straight (else the arc towards it)", 0.0, 10.0);
  s.AddDouble("turn_in_place_curvature", &o.turn_in_place_curvature, "1/m",
              "curvature above which the tracker turns in place towards the goal point first", 0.01, 100.0);
  s.AddDouble("max_cross_track", &o.max_cross_track, "m",
              "farther off the path than this the tracker turns in place towards it first", 0.01, 100.0);
  s.AddDouble("max_heading_error", &o.max_heading_error, "rad",
              "goal-point bearing above which the tracker turns in place first (pointing away)", 0.01, 3.2);
  s.AddDouble("align_tolerance", &o.align_tolerance, "rad", "a correction turn ends this close to the goal point's bearing",
              0.001, 1.0);
  s.AddDouble("cruise_speed", &o.cruise_speed, "m/s", "speed on straight stretches (0.076: the miner's 3 in/s)", 0.001,
              5.0);
  s.AddDouble("turn_rate", &o.turn_rate, "rad/s", "largest turn-in-place yaw rate", 0.001, 3.0);
  s.AddDouble("min_turn_rate", &o.min_turn_rate, "rad/s", "least turn-in-place yaw rate, slowing into the target", 0.0001,
              3.0);
  s.AddDouble("turn_gain", &o.turn_gain, "1/s", "turn-in-place yaw rate per rad of heading error", 0.01, 100.0);
  s.AddDouble("position_tolerance", &o.position_tolerance, "m",
              "a run's end (cusp or goal) counts as reached this close, along its tangent", 0.001, 5.0);
  s.AddDouble("heading_tolerance", &o.heading_tolerance, "rad", "heading tolerance of turns in place and at the goal",
              0.0005, 1.0);
  s.AddDouble("goal_tolerance", &o.goal_tolerance, "m", "a path ending farther than this from its goal has failed",
              0.001, 10.0);
  s.AddBool("regulated", &o.regulated, "regulate the speed (arcs, walls, approach); false = plain pure pursuit");
  s.AddDouble("regulated_min_radius", &o.regulated_min_radius, "m",
              "where the pursuit arc is tighter than this the speed scales by its radius / this (Nav2 RPP)", 0.0, 1000.0);
  s.AddDouble("near_obstacle_distance", &o.near_obstacle_distance, "m",
              "closer to a wall than this the speed scales with the clearance", 0.0, 100.0);
  s.AddDouble("min_obstacle_speed_factor", &o.min_obstacle_speed_factor, "", "least speed fraction near walls", 0.0,
              1.0);
  s.AddDouble("approach_distance", &o.approach_distance, "m",
              "before a cusp or the goal the speed scales with the distance left", 0.0, 100.0);
  s.AddDouble("min_approach_speed", &o.min_approach_speed, "m/s", "least speed approaching a stop", 0.0001, 5.0);
  s.AddDouble("collision_time", &o.collision_time, "s", "time of the commanded motion checked against the map", 0.0,
              60.0);
  s.AddDouble("collision_min_distance", &o.collision_min_distance, "m",
              "least distance checked ahead (in rad, times 1 m, for turns in place)", 0.0, 100.0);
  s.AddDouble("deceleration", &o.deceleration, "m/s^2",
              "the vehicle's braking: the check ahead never covers less than the stopping distance of the last "
              "commanded speed (0.1: vehicle_sim's miner)",
              0.0, 100.0);
  s.AddDouble("collision_margin", &o.collision_margin, "m", "clearance the checked motion must keep from the walls",
              0.0, 10.0);
  s.AddDouble("sample_step", &o.sample_step, "m", "spacing of the path's samples", 0.001, 1.0);
  s.AddDouble("search_window", &o.search_window, "m", "stretch of a run searched ahead for the nearest sample", 0.01,
              100.0);
  s.AddDouble("command_timeout", &o.command_timeout, "s", "validity of each drive command (two control periods: stopped within 200 ms of a missing one)", 0.01, 60.0);
}

TrackerMap::TrackerMap(std::vector<Segment> segments, const Footprint& footprint, double margin, double turn_radius)
    : planner_(segments,
               footprint,
               [&] {
                 Se2PlannerOptions o;
                 o.turn_radius = turn_radius;
                 o.clearance = margin;
                 return o;
               }()),
      walls_(segments),
      footprint_(Normalized(footprint)),
      circumscribed_(CircumscribedRadius(footprint_)) {}

double TrackerMap::Clearance(const Pose2& pose, double cap) const {
  const std::vector<Eigen::Vector2d> world = footprint_.At(pose);
  double best = cap;
  walls_.ForEachNear(pose.translation(), circumscribed_ + cap, [&](int i) {
    const Segment& w = walls_.segments()[static_cast<size_t>(i)];
    for (size_t k = 0; k < world.size(); ++k)
      best = std::min(best, SegmentToSegmentDistance(Segment{world[k], world[(k + 1) % world.size()]}, w));
  });
  return best;
}

const char* ToString(TrackState s) {
  switch (s) {
    case TrackState::kIdle:
      return "idle";
    case TrackState::kActive:
      return "active";
    case TrackState::kDone:
      return "done";
    case TrackState::kFailed:
      return "failed";
    case TrackState::kBlocked:
      return "blocked";
  }
  return "?";
}

PathTracker::PathTracker(PathTrackerOptions options, Footprint footprint)
    : options_(options), footprint_(std::move(footprint)) {}

void PathTracker::SetMap(std::shared_ptr<const TrackerMap> map) { map_ = std::move(map); }

TrackState PathTracker::SetPath(const PlannedPath& path, const std::vector<double>& speed_limits) {
  path_ = path;
  runs_ = SplitIntoRuns(path, options_.sample_step, speed_limits);
  run_ = 0;
  hint_ = 0;
  correcting_ = aligning_goal_ = false;
  cusp_aligned_ = aligning_cusp_ = false;
  corrections_ = 0;
  done_length_ = 0.0;
  total_length_ = 0.0;
  for (const TrackedRun& r : runs_) total_length_ += r.length;
  state_ = TrackState::kActive;
  message_ = "tracking " + std::to_string(path.pieces.size()) + " pieces in " + std::to_string(runs_.size()) + " runs";
  if (map_) {
    Pose2 at = path.start;
    for (size_t k = 0; k < path.pieces.size(); ++k) {
      if (map_->PieceCollides(at, path.pieces[k])) {
        state_ = TrackState::kBlocked;
        message_ = "refused: piece " + std::to_string(k) + " (" + ToString(path.pieces[k].motion) + " to " +
                   Fixed(path.pieces[k].end.x) + ", " + Fixed(path.pieces[k].end.y) + ") collides with the map";
        return state_;
      }
      at = path.pieces[k].end;
    }
  }
  return state_;
}

void PathTracker::Cancel(const std::string& why) {
  runs_.clear();
  state_ = TrackState::kFailed;
  message_ = why;
}

TrackStep PathTracker::Stop(const std::string& message) const {
  TrackStep s;
  s.command.mode = DriveCommand::Mode::kStop;
  s.command.timeout = options_.command_timeout;
  s.state = state_;
  s.message = message;
  s.progress = Progress();
  return s;
}

TrackStep PathTracker::Finish(TrackState state, const std::string& message) {
  state_ = state;
  message_ = message;
  TrackStep s = Stop(message);
  s.finished_now = true;
  if (state == TrackState::kDone) s.progress = 1.0;
  return s;
}

double PathTracker::Progress() const {
  if (runs_.empty()) return state_ == TrackState::kDone ? 1.0 : 0.0;
  if (total_length_ > 0.0) return std::clamp(done_length_ / total_length_, 0.0, 1.0);
  return static_cast<double>(run_) / static_cast<double>(runs_.size());
}

std::optional<TrackStep> PathTracker::CheckAhead(const Pose2& pose, const TrackStep& step, double left) {
  if (!map_ || step.command.mode == DriveCommand::Mode::kStop) return std::nullopt;
  MotionPiece piece;
  std::string what;
  if (step.command.mode == DriveCommand::Mode::kTurnInPlace) {
    piece = TurnPiece(pose, step.command.omega, left);
    what = "turning in place " + Fixed(RadToDeg(piece.amount), 1) + " deg";
  } else {
    const int d = step.command.v >= 0 ? 1 : -1;
    piece.motion = MotionOf(d, step.command.omega);
    const double reach = std::max(options_.collision_min_distance, std::abs(step.command.v) * options_.collision_time);
    piece.amount = std::min(reach, std::max(std::max(0.0, left) + kDriveOvershoot, StoppingDistance()));
    piece.radius = IsArc(piece.motion) ? options_.turn_radius : 0.0;
    what = std::string(ToString(piece.motion)) + " " + Fixed(piece.amount) + " m";
  }
  if (step.command.mode != DriveCommand::Mode::kTurnInPlace)
    piece.end = PoseAfter(pose, piece.motion, piece.amount, piece.radius);
  if (!map_->PieceCollides(pose, piece)) return std::nullopt;
  if (step.command.mode == DriveCommand::Mode::kVelocity) {
    // The commanded motion would touch a wall: the motions of the same direction (straight,
    // arc left, arc right), the nearest the pursuit curvature first, each over the distance
    // checked, then half of it, a quarter, ... down to the least (collision_min_distance, or
    // the stopping distance), driven slower so that collision_time covers only the distance
    // found free. The next tick corrects again. The pursuit's own motion, shortened and
    // slower, comes before another motion at speed: near a wall the tracker keeps converging
    // on the path (slowly) rather than keeping a lateral error it can never take out there.
    const int d = DriveDirection(piece.motion);
    const double speed = std::abs(step.command.v);
    const double commanded = speed > 0.0 ? step.command.omega / speed : 0.0;
    std::vector<double> curvatures = {0.0, 1.0 / options_.turn_radius, -1.0 / options_.turn_radius};
    std::sort(curvatures.begin(), curvatures.end(), [&](double a, double b) {
      return std::abs(a - step.curvature) < std::abs(b - step.curvature);
    });
    const double full = piece.amount;
    // Never shorter than the vehicle needs to stop from the last commanded speed.
    const double least = std::max(options_.collision_min_distance, StoppingDistance() + kDriveOvershoot);
    for (const double k : curvatures) {
      for (double distance = full, last = full + 1.0; distance < last;
           last = distance, distance = std::max(least, 0.5 * distance)) {
        if (distance == full && k == commanded) continue;  // checked above
        MotionPiece other = piece;
        other.motion = MotionOf(d, k);
        other.amount = distance;
        other.radius = IsArc(other.motion) ? options_.turn_radius : 0.0;
        other.end = PoseAfter(pose, other.motion, other.amount, other.radius);
        if (map_->PieceCollides(pose, other)) continue;
        TrackStep s = step;
        const double slower = distance < full ? std::min(speed, distance / std::max(1e-9, options_.collision_time)) : speed;
        s.command.v = d * slower;
        s.command.omega = k * slower;
        s.motion = k == 0.0 ? QuantisedMotion::kStraight : k > 0 ? QuantisedMotion::kArcLeft : QuantisedMotion::kArcRight;
        s.message = what + " would touch the map: " + ToString(other.motion) + " " + Fixed(distance) + " m instead";
        return s;
      }
    }
  }
  return Finish(TrackState::kBlocked, "blocked: " + what + " from " + Fixed(pose.x) + ", " + Fixed(pose.y) +
                                          " would touch the map; stopped short");
}

MotionPiece PathTracker::TurnPiece(const Pose2& pose, double omega, double left) const {
  MotionPiece piece;
  piece.motion = Motion::kTurnInPlace;
  const double reach = std::max(options_.collision_min_distance, std::abs(omega) * options_.collision_time);
  piece.amount = std::copysign(std::min(reach, std::abs(left) + kTurnOvershoot), omega);
  piece.end = PoseAfter(pose, piece.motion, piece.amount, piece.radius);
  return piece;
}

TrackStep PathTracker::Turn(double heading_error, const std::string& what) {
  TrackStep s;
  s.state = state_;
  s.motion = QuantisedMotion::kTurnInPlace;
  s.command.mode = DriveCommand::Mode::kTurnInPlace;
  s.command.omega = TurnRateFor(heading_error, options_.turn_gain, options_.min_turn_rate, options_.turn_rate);
  s.command.timeout = options_.command_timeout;
  s.message = what;
  s.progress = Progress();
  return s;
}

double PathTracker::StoppingDistance() const {
  if (!(options_.deceleration > 0.0)) return 0.0;
  return last_speed_ * last_speed_ / (2.0 * options_.deceleration);
}

TrackStep PathTracker::Update(const Pose2& pose) {
  TrackStep step = Step(pose);
  // A velocity command sets the speed the vehicle may still have; a turn in place means it
  // stopped first (the miner does not turn in place while moving). A stop does not: the
  // vehicle is still braking.
  if (step.command.mode == DriveCommand::Mode::kVelocity) last_speed_ = std::abs(step.command.v);
  if (step.command.mode == DriveCommand::Mode::kTurnInPlace) last_speed_ = 0.0;
  return step;
}

TrackStep PathTracker::Step(const Pose2& pose) {
  if (state_ != TrackState::kActive) return Stop(message_);
  for (int guard = 0; guard < static_cast<int>(runs_.size()) + 3; ++guard) {
    if (run_ >= static_cast<int>(runs_.size())) {
      // Every run driven: align to the goal's heading, then judge the end pose.
      const Pose2 goal = runs_.empty() ? path_.start : runs_.back().end;
      const double heading_error = NormalizeAngle(goal.theta - pose.theta);
      if (std::abs(heading_error) > options_.heading_tolerance) {
        if (!aligning_goal_) ++corrections_;
        aligning_goal_ = true;
        TrackStep t = Turn(heading_error, "aligning to the goal heading");
        if (auto blocked = CheckAhead(pose, t, heading_error)) return *blocked;
        return t;
      }
      const double error = TranslationDistance(pose, goal);
      if (error > options_.goal_tolerance)
        return Finish(TrackState::kFailed, "ended " + Fixed(error, 3) + " m from the goal (tolerance " +
                                               Fixed(options_.goal_tolerance, 3) + " m)");
      done_length_ = total_length_;
      return Finish(TrackState::kDone, "done " + Fixed(error, 3) + " m, " + Fixed(RadToDeg(std::abs(heading_error)), 2) +
                                           " deg from the goal, " + std::to_string(corrections_) + " corrections");
    }
    const TrackedRun& run = runs_[static_cast<size_t>(run_)];
    if (run.direction == 0) {
      const double heading_error = NormalizeAngle(run.end.theta - pose.theta);
      if (std::abs(heading_error) <= options_.heading_tolerance) {
        ++run_;
        hint_ = 0;
        continue;
      }
      TrackStep t = Turn(heading_error, "turn in place of the path");
      if (auto blocked = CheckAhead(pose, t, heading_error)) return *blocked;
      return t;
    }
    if (run_ > 0 && runs_[static_cast<size_t>(run_ - 1)].direction != 0 && !cusp_aligned_) {
      // At a cusp between two driving runs: turn in place to the next run's start heading
      // first. Pure pursuit ends a run with its heading only converging on the end's (the
      // goal point runs on past the end), and a run that starts with an arc as tight as the
      // miner's can never take a heading lag out again while driving it (the pursuit arc is
      // then tighter than the miner can drive). Skipped when the turn would touch the map.
      const double heading_error = NormalizeAngle(run.samples.front().theta - pose.theta);
      if (std::abs(heading_error) > options_.heading_tolerance) {
        TrackStep t = Turn(heading_error, "aligning to the next run's heading at the cusp");
        if (!map_ || !map_->PieceCollides(pose, TurnPiece(pose, t.command.omega, heading_error))) {
          if (!aligning_cusp_) ++corrections_;
          aligning_cusp_ = true;
          return t;
        }
      }
      cusp_aligned_ = true;
      aligning_cusp_ = false;
    }
    const int before = run_;
    TrackStep step = Drive(pose);
    if (run_ != before) {
      // The run ended this tick: one stop at the cusp (or before the goal alignment).
      return Stop("end of run " + std::to_string(run_) + " of " + std::to_string(runs_.size()));
    }
    if (auto instead = CheckAhead(pose, step, step.left))
      return *instead;
    return step;
  }
  return Stop(message_);
}

TrackStep PathTracker::Drive(const Pose2& pose) {
  const TrackedRun& run = runs_[static_cast<size_t>(run_)];
  const int d = run.direction;
  const RunProjection p = ProjectOnRun(run, pose.translation(), hint_, options_.search_window);
  hint_ = p.index;
  if (p.remaining <= options_.position_tolerance) {
    done_length_ += run.length;
    ++run_;
    hint_ = 0;
    correcting_ = false;
    cusp_aligned_ = aligning_cusp_ = false;
    return Stop("run done");
  }
  const double lookahead = std::max(options_.lookahead, options_.lookahead_time * options_.cruise_speed);
  const Eigen::Vector2d goal = LookaheadPoint(run, p.arc_length, lookahead);
  const double bearing = BearingInEffectiveFrame(pose, goal, d);
  const double k = PursuitCurvature(pose, goal, d);
  const bool far = std::abs(p.cross_track) > options_.max_cross_track || std::abs(bearing) > options_.max_heading_error ||
                   std::abs(k) >= options_.turn_in_place_curvature;
  if (correcting_ && std::abs(bearing) <= options_.align_tolerance) correcting_ = false;
  if (!correcting_ && far) {
    correcting_ = true;
    ++corrections_;
  }
  TrackStep s;
  if (correcting_) {
    s = Turn(bearing, "correction: turning towards the path");
  } else {
    s.motion = QuantiseCurvature(k, options_.straight_deadband, options_.turn_in_place_curvature);
    double speed = options_.cruise_speed;
    // The path's own speed limits, over what the vehicle reaches before it could stop.
    const double ahead = std::max(lookahead, StoppingDistance() + options_.cruise_speed * options_.command_timeout);
    if (const double limit = SpeedLimitAhead(run, p.index, ahead); limit > 0.0) speed = std::min(speed, limit);
    const double curvature = s.motion == QuantisedMotion::kArcLeft    ? 1.0 / options_.turn_radius
                             : s.motion == QuantisedMotion::kArcRight ? -1.0 / options_.turn_radius
                                                                      : 0.0;
    if (options_.regulated) {
      // On the path's curvature (the pursuit arc's, at most the miner's), not the quantised
      // command's: alternating line and arc on a straight stretch is not a tight turn.
      const double k_path = std::min(std::abs(k), 1.0 / options_.turn_radius);
      if (k_path > 0.0) speed = CurvatureRegulatedSpeed(speed, 1.0 / k_path, options_.regulated_min_radius);
      if (map_)
        speed = ProximityRegulatedSpeed(speed, map_->Clearance(pose, options_.near_obstacle_distance),
                                        options_.near_obstacle_distance, options_.min_obstacle_speed_factor);
      speed = ApproachRegulatedSpeed(speed, p.remaining, options_.approach_distance, options_.min_approach_speed);
    }
    s.command.mode = DriveCommand::Mode::kVelocity;
    s.command.v = d * speed;
    s.command.omega = curvature * speed;
    s.command.timeout = options_.command_timeout;
    s.message = ToString(s.motion);
  }
  s.state = state_;
  s.curvature = k;
  s.left = correcting_ ? bearing : p.remaining;
  s.cross_track = p.cross_track;
  s.progress = std::clamp((done_length_ + p.arc_length) / std::max(1e-9, total_length_), 0.0, 1.0);
  return s;
}

}  // namespace minenav
