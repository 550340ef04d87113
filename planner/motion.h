#pragma once
// The miner's motions and the piecewise paths made of them. Motion values are
// path_segment_t's constants (lcmtypes/path_segment_t.lcm), so a path converts one to one.
//
// Arcs have the vehicle's one turning radius R; *_LEFT arcs turn about a centre on the
// vehicle's left, *_RIGHT about one on its right. Driving forward along a left arc turns the
// heading counter-clockwise, reversing along it turns it clockwise:
//   d = +1 forward, -1 reverse;  dtheta = d s / R (left), -d s / R (right), s = arc length.

#include <cstdint>
#include <string>
#include <vector>

#include "common/pose2.h"

namespace minenav {

enum class Motion : int8_t {
  kForward = 0,
  kReverse = 1,
  kArcLeft = 2,
  kArcRight = 3,
  kTurnInPlace = 4,
  kArcLeftReverse = 5,
  kArcRightReverse = 6,
};

// "forward", "reverse", "arc_left", "arc_right", "turn_in_place", "arc_left_reverse",
// "arc_right_reverse": the motion column of the path CSV.
std::string ToString(Motion motion);
// The inverse of ToString; false for an unknown name.
bool MotionFromString(const std::string& name, Motion& motion);

// +1 for forward motions, -1 for reverse ones, 0 for turning in place.
int DriveDirection(Motion motion);
// +1 for left arcs, -1 for right arcs, 0 otherwise.
int TurnSide(Motion motion);
inline bool IsArc(Motion m) { return TurnSide(m) != 0; }

// One piece of a path: `motion` from the previous pose to `end`.
struct MotionPiece {
  Motion motion = Motion::kForward;
  // m travelled for straight moves and arcs (> 0); rad turned for a turn in place
  // (signed, counter-clockwise positive).
  double amount = 0.0;
  double radius = 0.0;  // m, the arc's radius (0 for straight moves and turns in place)
  Pose2 end;
};

// The pose reached from `start` by `motion` over `amount` (m, or rad for a turn in place)
// on arcs of `radius` (m).
Pose2 PoseAfter(const Pose2& start, Motion motion, double amount, double radius);

// Poses along one piece from its start (the one implementation of the motions' maths;
// PoseAfter is one pose of it, normalised), for collision sweeps: the piece's constants are
// worked out once, so a pose along a straight move costs no trigonometry and one along an
// arc or a turn in place one sine and cosine. Each pose comes with its heading's cosine and
// sine, which the collision checker needs; the heading itself is not normalised (start theta
// plus the turn so far). About the centre at distance R on the arc's side, the heading
// changes by side * d * s / R over s m driven in direction d.
class PieceSampler {
 public:
  struct Sample {
    Pose2 pose;  // theta not normalised
    double cos_theta = 1.0, sin_theta = 0.0;
  };
  PieceSampler(const Pose2& start, Motion motion, double radius);
  // After `amount` of the motion (m, or rad for a turn in place).
  Sample At(double amount) const;

 private:
  Pose2 start_;
  int direction_, side_;
  double radius_;
  double cos_start_, sin_start_;
  double centre_x_ = 0.0, centre_y_ = 0.0;  // of the arc
};

struct PlannedPath {
  Pose2 start;
  std::vector<MotionPiece> pieces;
  // m travelled (turns in place count 0, as in path_t.length).
  double Length() const;
  // Direction changes: forward after reverse or the other way round (turns in place between
  // them do not count as either).
  int Reversals() const;
};

// Consecutive pieces with the same motion and radius joined into one (the search makes
// many short steps of one kind); turns in place only while they stay under 0.99 pi, so
// each turns the shorter way between its end poses.
std::vector<MotionPiece> MergePieces(const std::vector<MotionPiece>& pieces);

}  // namespace minenav
