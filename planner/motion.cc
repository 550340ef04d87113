#include "planner/motion.h"

#include <cmath>

namespace minenav {

namespace {
constexpr const char* kNames[] = {"forward",       "reverse",          "arc_left",         "arc_right",
                                  "turn_in_place", "arc_left_reverse", "arc_right_reverse"};
}

std::string ToString(Motion motion) {
  const int i = static_cast<int>(motion);
  return i >= 0 && i < 7 ? kNames[i] : "unknown";
}

bool MotionFromString(const std::string& name, Motion& motion) {
  for (int i = 0; i < 7; ++i)
    if (name == kNames[i]) {
      motion = static_cast<Motion>(i);
      return true;
    }
  return false;
}

int DriveDirection(Motion motion) {
  switch (motion) {
    case Motion::kForward:
    case Motion::kArcLeft:
    case Motion::kArcRight: return 1;
    case Motion::kReverse:
    case Motion::kArcLeftReverse:
    case Motion::kArcRightReverse: return -1;
    case Motion::kTurnInPlace: return 0;
  }
  return 0;
}

int TurnSide(Motion motion) {
  if (motion == Motion::kArcLeft || motion == Motion::kArcLeftReverse) return 1;
  if (motion == Motion::kArcRight || motion == Motion::kArcRightReverse) return -1;
  return 0;
}

PieceSampler::PieceSampler(const Pose2& start, Motion motion, double radius)
    : start_(start),
      direction_(DriveDirection(motion)),
      side_(TurnSide(motion)),
      radius_(radius),
      cos_start_(std::cos(start.theta)),
      sin_start_(std::sin(start.theta)) {
  if (side_ != 0) {
    centre_x_ = start.x - side_ * radius * sin_start_;
    centre_y_ = start.y + side_ * radius * cos_start_;
  }
}

PieceSampler::Sample PieceSampler::At(double amount) const {
  Sample q;
  if (direction_ == 0) {  // turn in place
    q.pose = {start_.x, start_.y, start_.theta + amount};
    q.cos_theta = std::cos(q.pose.theta);
    q.sin_theta = std::sin(q.pose.theta);
    return q;
  }
  const double s = direction_ * amount;
  if (side_ == 0) {
    q.pose = {start_.x + s * cos_start_, start_.y + s * sin_start_, start_.theta};
    q.cos_theta = cos_start_;
    q.sin_theta = sin_start_;
    return q;
  }
  const double theta = start_.theta + side_ * s / radius_;
  q.cos_theta = std::cos(theta);
  q.sin_theta = std::sin(theta);
  q.pose = {centre_x_ + side_ * radius_ * q.sin_theta, centre_y_ - side_ * radius_ * q.cos_theta, theta};
  return q;
}

Pose2 PoseAfter(const Pose2& start, Motion motion, double amount, double radius) {
  Pose2 p = PieceSampler(start, motion, radius).At(amount).pose;
  p.theta = NormalizeAngle(p.theta);
  return p;
}

double PlannedPath::Length() const {
  double length = 0.0;
  for (const MotionPiece& p : pieces)
    if (p.motion != Motion::kTurnInPlace) length += p.amount;
  return length;
}

int PlannedPath::Reversals() const {
  int reversals = 0, last = 0;
  for (const MotionPiece& p : pieces) {
    const int d = DriveDirection(p.motion);
    if (d == 0) continue;
    if (last != 0 && d != last) ++reversals;
    last = d;
  }
  return reversals;
}

std::vector<MotionPiece> MergePieces(const std::vector<MotionPiece>& pieces) {
  std::vector<MotionPiece> merged;
  for (const MotionPiece& p : pieces) {
    // A turn in place stays under half a turn, so its end pose says which way it turned.
    const bool too_far = p.motion == Motion::kTurnInPlace &&
                         !merged.empty() && std::abs(merged.back().amount + p.amount) > 0.99 * kPi;
    if (!merged.empty() && merged.back().motion == p.motion && merged.back().radius == p.radius && !too_far) {
      merged.back().amount += p.amount;
      merged.back().end = p.end;
    } else {
      merged.push_back(p);
    }
  }
  return merged;
}

}  // namespace minenav
