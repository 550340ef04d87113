#pragma once
// What the SE(2) search minimises: metres driven, with reversing, turning in place and
// changing direction made dearer (Nav2 Smac Hybrid-A* penalises the same three).

namespace minenav {

class OptionScope;
struct MotionPiece;

struct MotionCosts {
  // Cost per metre reversed, as a multiple of a metre driven forward. Default 1.5.
  double reverse_factor = 1.5;
  // m of cost per radian turned in place (the miner's tracks scrub the floor). Default 2.
  double turn_in_place_per_rad = 2.0;
  // m of cost for each change between forward and reverse. Default 3.
  double direction_change = 3.0;

  bool operator==(const MotionCosts&) const = default;
};

// The cost of one piece, driven after motion in direction `previous_direction` (+1
// forward, -1 reverse, 0 none yet: no change penalty).
double PieceCost(const MotionPiece& piece, int previous_direction, const MotionCosts& costs);

// reverse_factor, turn_in_place_per_rad, direction_change.
void DeclareOptions(OptionScope scope, MotionCosts& costs);

}  // namespace minenav
