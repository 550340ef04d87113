#include "planner/motion_costs.h"

#include <cmath>

#include "common/config.h"
#include "planner/motion.h"

namespace minenav {

double PieceCost(const MotionPiece& piece, int previous_direction, const MotionCosts& costs) {
  const int d = DriveDirection(piece.motion);
  if (d == 0) return costs.turn_in_place_per_rad * std::abs(piece.amount);
  const double change = (previous_direction != 0 && d != previous_direction) ? costs.direction_change : 0.0;
  return piece.amount * (d < 0 ? costs.reverse_factor : 1.0) + change;
}

void DeclareOptions(OptionScope scope, MotionCosts& costs) {
  scope.AddDouble("reverse_factor", &costs.reverse_factor, "", "cost of a metre reversed in metres driven forward", 1.0,
                  100.0);
  scope.AddDouble("turn_in_place_per_rad", &costs.turn_in_place_per_rad, "m/rad", "cost of turning in place", 0.0,
                  1000.0);
  scope.AddDouble("direction_change", &costs.direction_change, "m", "cost of each change between forward and reverse",
                  0.0, 1000.0);
}

}  // namespace minenav
