#include "tracker/pure_pursuit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angle.h"

namespace minenav {
namespace {

Eigen::Vector2d Heading(double theta) { return {std::cos(theta), std::sin(theta)}; }

// Appends the samples of a driving piece (from `from`, speed limit `limit`) to `run`.
void SamplePiece(const Pose2& from, const MotionPiece& piece, double step, double limit, TrackedRun& run) {
  const int n = std::max(1, static_cast<int>(std::ceil(piece.amount / step)));
  const double s0 = run.arc_length.back();
  for (int i = 1; i <= n; ++i) {
    const double s = piece.amount * static_cast<double>(i) / n;
    run.samples.push_back(i == n ? piece.end : PoseAfter(from, piece.motion, s, piece.radius));
    run.arc_length.push_back(s0 + s);
    run.speed_limit.push_back(limit);
  }
}

}  // namespace

std::vector<TrackedRun> SplitIntoRuns(const PlannedPath& path, double sample_step,
                                      const std::vector<double>& speed_limits) {
  std::vector<TrackedRun> runs;
  Pose2 at = path.start;
  for (size_t k = 0; k < path.pieces.size(); ++k) {
    const MotionPiece& piece = path.pieces[k];
    const double limit = k < speed_limits.size() && speed_limits[k] > 0.0 ? speed_limits[k] : 0.0;
    if (!(piece.amount != 0.0)) {
      at = piece.end;
      continue;
    }
    const int d = DriveDirection(piece.motion);
    if (runs.empty() || runs.back().direction != d || d == 0) {
      if (d == 0 && !runs.empty() && runs.back().direction == 0) {
        runs.back().end = piece.end;  // consecutive turns in place: one target heading
        at = piece.end;
        continue;
      }
      TrackedRun r;
      r.direction = d;
      if (d != 0) {
        r.samples.push_back(at);
        r.arc_length.push_back(0.0);
        r.speed_limit.push_back(limit);
      }
      runs.push_back(std::move(r));
    }
    TrackedRun& run = runs.back();
    if (d != 0) SamplePiece(at, piece, sample_step, limit, run);
    run.end = piece.end;
    run.length = d != 0 ? run.arc_length.back() : 0.0;
    at = piece.end;
  }
  return runs;
}

double SpeedLimitAhead(const TrackedRun& run, int index, double distance) {
  double least = 0.0;
  const size_t n = run.samples.size();
  if (n == 0) return least;
  const size_t first = static_cast<size_t>(std::clamp(index, 0, static_cast<int>(n) - 1));
  for (size_t i = first; i < n && run.arc_length[i] <= run.arc_length[first] + distance; ++i) {
    const double limit = run.speed_limit[i];
    if (limit > 0.0 && (least == 0.0 || limit < least)) least = limit;
  }
  return least;
}

RunProjection ProjectOnRun(const TrackedRun& run, const Eigen::Vector2d& position, int hint, double window) {
  RunProjection p;
  if (run.samples.empty()) return p;
  const int n = static_cast<int>(run.samples.size());
  hint = std::clamp(hint, 0, n - 1);
  const double s_max = run.arc_length[static_cast<size_t>(hint)] + window;
  double best = std::numeric_limits<double>::infinity();
  for (int i = hint; i < n && run.arc_length[static_cast<size_t>(i)] <= s_max; ++i) {
    const double d2 = (run.samples[static_cast<size_t>(i)].translation() - position).squaredNorm();
    if (d2 < best) {
      best = d2;
      p.index = i;
    }
  }
  const Pose2& q = run.samples[static_cast<size_t>(p.index)];
  p.arc_length = run.arc_length[static_cast<size_t>(p.index)];
  const double travel = q.theta + (run.direction < 0 ? kPi : 0.0);
  const Eigen::Vector2d left(-std::sin(travel), std::cos(travel));
  p.cross_track = (position - q.translation()).dot(left);
  const double end_travel = run.end.theta + (run.direction < 0 ? kPi : 0.0);
  p.remaining = (run.end.translation() - position).dot(Heading(end_travel));
  // Far from the end the along-path distance is what remains (the end tangent may point
  // anywhere on a curved run).
  if (run.length - p.arc_length > 1.0) p.remaining = run.length - p.arc_length;
  return p;
}

Eigen::Vector2d LookaheadPoint(const TrackedRun& run, double s, double lookahead) {
  const double target = s + lookahead;
  if (target >= run.length) {
    const double travel = run.end.theta + (run.direction < 0 ? kPi : 0.0);
    return run.end.translation() + (target - run.length) * Heading(travel);
  }
  const auto it = std::lower_bound(run.arc_length.begin(), run.arc_length.end(), target);
  const size_t i = static_cast<size_t>(it - run.arc_length.begin());
  if (i == 0) return run.samples.front().translation();
  const double s0 = run.arc_length[i - 1], s1 = run.arc_length[i];
  const double f = s1 > s0 ? (target - s0) / (s1 - s0) : 0.0;
  return (1.0 - f) * run.samples[i - 1].translation() + f * run.samples[i].translation();
}

double PursuitCurvature(const Pose2& pose, const Eigen::Vector2d& goal, int direction) {
  const Pose2 effective(pose.x, pose.y, pose.theta + (direction < 0 ? kPi : 0.0));
  const Eigen::Vector2d local = effective.inverse() * goal;
  const double d2 = local.squaredNorm();
  if (!(d2 > 1e-12)) return 0.0;
  return 2.0 * local.y() / d2;
}

double BearingInEffectiveFrame(const Pose2& pose, const Eigen::Vector2d& goal, int direction) {
  const Eigen::Vector2d to = goal - pose.translation();
  return NormalizeAngle(std::atan2(to.y(), to.x()) - pose.theta - (direction < 0 ? kPi : 0.0));
}

const char* ToString(QuantisedMotion m) {
  switch (m) {
    case QuantisedMotion::kStraight:
      return "straight";
    case QuantisedMotion::kArcLeft:
      return "arc left";
    case QuantisedMotion::kArcRight:
      return "arc right";
    case QuantisedMotion::kTurnInPlace:
      return "turn in place";
  }
  return "?";
}

QuantisedMotion QuantiseCurvature(double k, double straight_deadband, double turn_in_place_curvature) {
  if (!std::isfinite(k) || std::abs(k) >= turn_in_place_curvature) return QuantisedMotion::kTurnInPlace;
  if (std::abs(k) <= straight_deadband) return QuantisedMotion::kStraight;
  return k > 0 ? QuantisedMotion::kArcLeft : QuantisedMotion::kArcRight;
}

double CurvatureRegulatedSpeed(double speed, double radius, double min_radius) {
  if (radius < min_radius && min_radius > 0.0) return speed * std::max(0.0, radius) / min_radius;
  return speed;
}

double ProximityRegulatedSpeed(double speed, double clearance, double near_distance, double min_factor) {
  if (!(near_distance > 0.0) || clearance >= near_distance) return speed;
  return speed * std::clamp(clearance / near_distance, min_factor, 1.0);
}

double ApproachRegulatedSpeed(double speed, double remaining, double approach_distance, double min_speed) {
  if (!(approach_distance > 0.0) || remaining >= approach_distance) return speed;
  return std::min(speed, std::max(min_speed, speed * std::max(0.0, remaining) / approach_distance));
}

double TurnRateFor(double heading_error, double gain, double min_rate, double max_rate) {
  const double rate = std::clamp(gain * std::abs(heading_error), min_rate, max_rate);
  return std::copysign(rate, heading_error);
}

}  // namespace minenav
