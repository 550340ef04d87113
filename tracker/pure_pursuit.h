#pragma once
// Pure pursuit for the continuous miner as small pure functions (Wallace et al. 1985,
// Coulter 1992, "Implementation of the Pure Pursuit Path Tracking Algorithm"; the speed
// regulation after Macenski et al. 2023, "Regulated Pure Pursuit for Robot Path Tracking",
// Nav2's RegulatedPurePursuitController). Thesis 6.4.2: the correction is an arc then a line;
// the miner has one turning radius besides turning in place, so the arc's curvature is
// quantised to straight, arc left, arc right or turn in place.
//
// A path (planner/motion.h) is tracked as runs: consecutive driving pieces of one direction
// (forward or reverse) form a run, sampled densely; a turn in place between them is a run of
// its own. The vehicle stops at the end of each run (a cusp), so reverse runs are driven
// backwards and the planner's turns in place are made where it planned them.
//
// Frames: poses in the map frame; "effective" heading = the heading the vehicle moves along
// (theta for forward runs, theta + pi for reverse ones).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "planner/motion.h"

namespace minenav {

// One run of a path: a same-direction stretch (direction +1 / -1) sampled every sample_step
// metres, or a turn in place (direction 0) to end.theta.
struct TrackedRun {
  int direction = 0;              // +1 forward, -1 reverse, 0 turn in place
  std::vector<Pose2> samples;     // direction != 0: poses along the run, the first its start, the last `end`
  std::vector<double> arc_length; // m from the run's start, one per sample
  std::vector<double> speed_limit; // m/s, one per sample: the limit of the piece it ends (0 = none)
  Pose2 end;
  double length = 0.0;            // m (0 for a turn in place)
};

// The path's runs, in order (pieces with amount 0 are skipped). sample_step in m (> 0).
// speed_limits: m/s per piece of the path (path_t's segment speed; 0 = none), or empty.
std::vector<TrackedRun> SplitIntoRuns(const PlannedPath& path, double sample_step,
                                      const std::vector<double>& speed_limits = {});
// m/s, the least speed limit of `run` from arc length `from` over the next `distance` m
// (0 = none there).
double SpeedLimitAhead(const TrackedRun& run, int index, double distance);

// The sample of `run` nearest to `position`, searched from index `hint` over the next
// `window` metres of the run (and back to the hint: the vehicle never goes back along a run).
struct RunProjection {
  int index = 0;
  double arc_length = 0.0;   // m from the run's start to the sample
  double cross_track = 0.0;  // m, signed: + left of the run's travel direction
  double remaining = 0.0;    // m to the run's end along its end tangent (< 0: past the end)
};
RunProjection ProjectOnRun(const TrackedRun& run, const Eigen::Vector2d& position, int hint, double window);

// The goal point one lookahead (m) along the run from arc length s; beyond the run's end it
// continues straight along the end's travel direction, so the last metre is tracked as well
// as the rest.
Eigen::Vector2d LookaheadPoint(const TrackedRun& run, double s, double lookahead);

// 1/m, signed (+ counter-clockwise): the curvature of the arc from `pose`, tangent to its
// effective heading, through `goal`: k = 2 y / d^2 with (x, y) the goal in the effective frame
// and d its distance. Moving the vehicle at speed u along its effective heading, the yaw rate
// is k u (so a reverse command is v = -u, omega = k u).
double PursuitCurvature(const Pose2& pose, const Eigen::Vector2d& goal, int direction);

// The goal's bearing (rad) from the effective heading.
double BearingInEffectiveFrame(const Pose2& pose, const Eigen::Vector2d& goal, int direction);

// The motions the miner can make.
enum class QuantisedMotion { kStraight = 0, kArcLeft = 1, kArcRight = 2, kTurnInPlace = 3 };
const char* ToString(QuantisedMotion m);

// The motion for curvature k (1/m): straight when |k| <= straight_deadband, turn in place when
// |k| >= turn_in_place_curvature (the arc would be far tighter than the miner's), else the
// arc towards k's side. Quantising only at the deadband (not half-way to 1/R) makes the
// tracker alternate between a line and the arc, so the mean curvature follows k.
QuantisedMotion QuantiseCurvature(double k, double straight_deadband, double turn_in_place_curvature);

// Nav2 RPP's curvature constraint: speed (m/s) on an arc of radius (m) tighter than
// min_radius (m) scales by radius / min_radius.
double CurvatureRegulatedSpeed(double speed, double radius, double min_radius);
// Slower near obstacles: the speed scales by clearance / near_distance below near_distance
// (m), never below min_factor of it (clearance <= 0 gives min_factor).
double ProximityRegulatedSpeed(double speed, double clearance, double near_distance, double min_factor);
// Slower approaching a stop (a cusp or the goal): speed * remaining / approach_distance
// below approach_distance (m), at least min_speed (m/s) and at most speed.
double ApproachRegulatedSpeed(double speed, double remaining, double approach_distance, double min_speed);
// A turn-in-place yaw rate (rad/s, signed as the error) for a heading error (rad):
// gain * error clamped to [min_rate, max_rate] in magnitude, so the turn slows into the
// target and never overshoots by more than a control period at min_rate.
double TurnRateFor(double heading_error, double gain, double min_rate, double max_rate);

}  // namespace minenav
